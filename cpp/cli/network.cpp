// `dvoronoi network cc|bd07|bs POINTS --range R`: simulate a sensor network computing its Voronoi
// cells by message passing (CC, BD07, distributed Boundary Scan with optional DV-Hop) and report the
// cells and the transmissions per node and message type.
#include "common.hpp"

#include "dvoronoi/io/network_csv.hpp"
#include "dvoronoi/io/network_geojson.hpp"
#include "dvoronoi/io/network_json.hpp"
#include "dvoronoi/io/network_svg.hpp"
#include "dvoronoi/network/run.hpp"

#include <cmath>
#include <iostream>
#include <memory>
#include <variant>
#include <sstream>
#include <string>
#include <vector>

namespace dvoronoi::cli {
namespace {

struct NetworkOptions {
    std::string algorithm, points, obstacles, columns, routing = "gpsr", output, svg;
    std::vector<std::string> bounds;  // XMIN YMIN XMAX YMAX, as in every subcommand (or one deprecated "a,b,c,d")
    double range = 0.0, loss = 0.0, radius = 0.0, anchor_fraction = 0.0, tolerance = 0.0;
    std::uint64_t seed = 0;
    std::int64_t budget = 0;
    int adjacency_cap = 6;
    bool no_cap = false, no_forward = false, quiet = false;
    bool no_route_discovery = false, dv_hop_async = false, anchors_relay = false;
};

/// --bounds XMIN YMIN XMAX YMAX (the syntax of every subcommand); the older single comma-separated
/// word XMIN,YMIN,XMAX,YMAX is still read so existing scripts keep working.
network::Box parse_bounds(const std::vector<std::string>& words) {
    std::vector<std::string> items = words;
    if (words.size() == 1 && words[0].find(',') != std::string::npos) {
        items.clear();
        std::stringstream ss(words[0]);
        std::string item;
        while (std::getline(ss, item, ',')) items.push_back(item);
    }
    std::string given;
    for (const auto& w : words) given += (given.empty() ? "" : " ") + w;
    std::vector<double> v;
    for (const auto& item : items) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(x))
            throw UsageError("--bounds: expected 4 finite numbers XMIN YMIN XMAX YMAX, got '" + given + "'");
        v.push_back(x);
    }
    if (v.size() != 4)
        throw UsageError("--bounds: expected 4 numbers XMIN YMIN XMAX YMAX, got " + std::to_string(v.size()));
    const network::Box b{v[0], v[1], v[2], v[3]};
    if (!(b.xmin < b.xmax && b.ymin < b.ymax)) throw UsageError("--bounds: need XMIN < XMAX and YMIN < YMAX");
    return b;
}

/// Obstacles: one segment 'x0 y0 x1 y1' per line (the point-file syntax with four fields).
std::vector<network::Segment> read_obstacles(const std::string& path) {
    io::Columns a, b;
    a.x = 0, a.y = 1, b.x = 2, b.y = 3;
    const io::PointFile p = io::read_point_file(path, a), q = io::read_point_file(path, b);
    std::vector<network::Segment> out;
    for (Index k = 0; k < p.points.rows(); ++k) out.push_back({p.points.row(k).transpose(), q.points.row(k).transpose()});
    return out;
}

/// Cells for the picture: the polygons of a run that has them (CC with bounds, BD07).
std::vector<network::Polygon> polygons(const network::RunBase& r) {
    std::vector<network::Polygon> out;
    for (Index i = 0; i < r.size(); ++i) {
        network::Polygon p;
        for (Index k = r.cells.piece_ptr[static_cast<std::size_t>(i)]; k < r.cells.piece_ptr[static_cast<std::size_t>(i) + 1]; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            p.vertices.emplace_back(r.cells.piece_x[kk], r.cells.piece_y[kk]);
            p.edge_label.push_back(r.cells.piece_neighbor[kk]);
        }
        out.push_back(std::move(p));
    }
    return out;
}

int run_network(const NetworkOptions& o) {
    if (!std::isfinite(o.range) || !(o.range > 0.0))
        throw UsageError("--range: must be a positive finite number, got " + show(o.range));
    if (!(o.loss >= 0.0 && o.loss < 1.0)) throw UsageError("--loss: must be in [0, 1), got " + show(o.loss));
    if (o.budget < 0) throw UsageError("--budget: must be >= 0");
    if (!(o.anchor_fraction >= 0.0 && o.anchor_fraction <= 1.0))
        throw UsageError("--anchor-fraction: must be in [0, 1], got " + show(o.anchor_fraction));
    if (o.radius < 0.0 || !std::isfinite(o.radius)) throw UsageError("--radius: must be a positive finite number");
    if (o.adjacency_cap < 0) throw UsageError("--adjacency-cap: must be >= 0");
    if (!std::isfinite(o.tolerance) || o.tolerance < 0.0)
        throw UsageError("--tolerance: must be a finite number >= 0, got " + show(o.tolerance));
    const bool to_stdout = o.output.empty() || o.output == "-";
    const Format format = to_stdout ? Format::Json : output_format(o.output, "-o/--output");
    check_outputs(o.output, o.svg, {{o.points, "POINTS"}, {o.obstacles, "--obstacles"}});
    network::Options opt;
    opt.algorithm = network::parse_algorithm(o.algorithm);
    opt.range = o.range;
    opt.run = network::RunOptions{o.loss, o.seed, o.budget};
    opt.cc.cap_adjacency = !o.no_cap;
    opt.cc.adjacency_cap = o.adjacency_cap;
    opt.cc.forward = !o.no_forward;
    opt.cc.route_discovery = !o.no_route_discovery;
    opt.bd07.route_discovery = !o.no_route_discovery;
    try {
        opt.cc.routing = network::parse_routing(o.routing);
    } catch (const InputError& e) {
        throw UsageError(std::string("--routing: ") + e.what());
    }
    if (!o.bounds.empty()) opt.bounds = parse_bounds(o.bounds);
    opt.radius = o.radius;
    opt.anchor_fraction = o.anchor_fraction;
    opt.dv_hop.synchronous = !o.dv_hop_async;
    opt.dv_hop.anchors_relay = o.anchors_relay;

    const io::PointFile file = read_points_argument(o.points, o.columns);
    if (!o.obstacles.empty()) opt.obstacles = read_obstacles(o.obstacles);
    std::unique_ptr<io::AtomicFile> out, svg;
    if (!to_stdout) out = open_output(o.output, "-o/--output");
    if (!o.svg.empty()) svg = open_output(o.svg, "--svg");

    Progress progress("network " + o.algorithm, 1, o.quiet, 1);
    network::Result result;
    try {
        result = network::run(file.points, opt);
    } catch (const CoincidentError& e) {
        throw InputError(coincident_message(file, e));
    }
    progress.finish();
    const network::RunBase& r = network::base(result);

    std::string text;
    if (format == Format::Csv) {
        std::ostringstream cs;
        io::write_network_csv(cs, result);
        text = cs.str();
    } else if (format == Format::GeoJson) {
        std::ostringstream gs;
        io::write_network_geojson(gs, result, o.tolerance);
        text = gs.str() + "\n";
    } else {
        text = io::network_json_text(result) + "\n";
    }
    // The picture: the links over the cells that are polygons (CC with bounds, BD07), hull nodes
    // highlighted for CC, in the run's box (the nodes' bounding box when none was given).
    network::Network net;
    net.points = r.points;
    net.obstacles = r.obstacles;
    net.adj.assign(static_cast<std::size_t>(r.size()), {});
    for (const auto& l : r.links) {
        net.adj[static_cast<std::size_t>(l[0])].push_back(l[1]);
        net.adj[static_cast<std::size_t>(l[1])].push_back(l[0]);
    }
    const network::Box box = opt.bounds ? *opt.bounds : network::detail::default_box(r.points);
    std::vector<network::Polygon> cells;
    std::vector<char> highlight;
    if (const auto* cc = std::get_if<network::CcRun>(&result)) {
        highlight = cc->on_hull;
        if (cc->bounds) cells = polygons(r);
    } else if (std::holds_alternative<network::Bd07Run>(result)) {
        cells = polygons(r);
    }
    const int code = deliver(
        out, svg, [&](std::ostream& os) { os << text; },
        [&](std::ostream& os) { io::write_network_svg(os, net, cells, box, highlight); });
    if (code != 0) return code;
    const std::int64_t transmissions = std::visit([](const auto& x) { return x.total_transmissions(); }, result);
    const std::int64_t deliveries = std::visit([](const auto& x) { return x.total_deliveries(); }, result);
    if (!o.quiet)
        std::cerr << "network " << o.algorithm << ": " << r.size() << " nodes, " << r.links.size() << " links, "
                  << transmissions << " transmissions, " << deliveries << " link deliveries\n";
    return 0;
}

}  // namespace

Command add_network(CLI::App& parent) {
    auto o = std::make_shared<NetworkOptions>();
    CLI::App* sub = parent.add_subcommand(
        "network",
        "simulate a sensor network computing its Voronoi cells by message passing: cc (complete diagram, "
        "Delaunay graph and hull), bd07 (cells of a bounded region by GPSR probes) or bs (limited cells by "
        "distributed Boundary Scan, optionally after DV-Hop localisation); reports cells and transmissions");
    sub->add_option("ALGORITHM", o->algorithm, "cc, bd07 or bs")->required()->check(CLI::IsMember({"cc", "bd07", "bs"}));
    sub->add_option("POINTS", o->points, "node positions: point file ('x y' per line) or .npy; '-' reads stdin")->required();
    sub->add_option("-r,--range", o->range, "communication range: nodes at distance <= range are linked")->required();
    sub->add_option("--loss", o->loss, "probability that one try over a link fails (repeated and counted)")->capture_default_str();
    sub->add_option("--seed", o->seed, "seed of the delivery order and of link failures")->capture_default_str();
    sub->add_option("--obstacles", o->obstacles, "file of obstacle segments, 'x0 y0 x1 y1' per line");
    sub->add_option("--bounds", o->bounds, "XMIN YMIN XMAX YMAX: BD07's region (default: the points' bounding box); CC clips its cells to it")
        ->expected(1, 4);
    sub->add_option("--budget", o->budget, "most transmissions allowed (0 = 10^9); exceeding it is an error");
    sub->add_flag("--no-cap-adjacency", o->no_cap, "CC: do not send capped adjacency lists (Section 2.3, optimisation 1)");
    sub->add_option("--adjacency-cap", o->adjacency_cap, "CC: adjacency list entries sent along")->capture_default_str();
    sub->add_flag("--no-forward", o->no_forward, "CC: notify both nodes of a new vertex (Section 2.3, optimisation 2 off)");
    sub->add_option("--routing", o->routing, "CC: gpsr or shortest")->check(CLI::IsMember({"gpsr", "shortest"}))->capture_default_str();
    sub->add_flag("--no-route-discovery", o->no_route_discovery,
                  "cc, bd07: where GPSR cannot deliver to a node, lose the message instead of finding a route by flooding");
    sub->add_option("--radius", o->radius, "bs: cell radius (default range / 2)");
    sub->add_option("--anchor-fraction", o->anchor_fraction, "bs: fraction of anchor nodes; the others localise themselves by DV-Hop");
    sub->add_flag("--dv-hop-async", o->dv_hop_async,
                  "bs: DV-Hop floods in random asynchronous order, every improvement passed on (default: "
                  "breadth-first rounds, each node forwards each anchor's flood once)");
    sub->add_flag("--anchors-relay", o->anchors_relay, "bs: anchors forward other anchors' DV-Hop floods (the paper: they do not)");
    sub->add_option("--columns", o->columns, "X,Y: the fields of POINTS holding x and y");
    sub->add_option("-o,--output", o->output,
                    "output file: .json (the result), .geojson (the cells as polygons, Boundary Scan's arcs "
                    "densified; null for a cell without a polygon) or .csv (one row per node: neighbours, area, "
                    "transmissions (sent_*) and link deliveries (received_*) by type); default JSON on stdout");
    sub->add_option("--tolerance", o->tolerance,
                    "GeoJSON: largest distance between an arc and its chords (default 1e-3 of the cell radius)");
    sub->add_option("--svg", o->svg, "also draw the network (cells, links, obstacles) into this SVG file");
    sub->add_flag("-q,--quiet", o->quiet, "no summary on stderr");
    return {sub, [o] { return run_network(*o); }};
}

}  // namespace dvoronoi::cli
