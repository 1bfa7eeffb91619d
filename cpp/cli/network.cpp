// `dvoronoi network cc|bd07|bs POINTS --range R`: simulate a sensor network computing its Voronoi
// cells by message passing (CC, BD07, distributed Boundary Scan with optional DV-Hop) and report the
// cells and the transmissions per node and message type.
#include "common.hpp"

#include "dvoronoi/io/network_svg.hpp"
#include "dvoronoi/network/bd07.hpp"
#include "dvoronoi/network/cc.hpp"
#include "dvoronoi/network/delaunay_check.hpp"
#include "dvoronoi/network/distributed_boundary_scan.hpp"
#include "dvoronoi/network/dv_hop.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace dvoronoi::cli {
namespace {

struct NetworkOptions {
    std::string algorithm, points, obstacles, columns, routing = "gpsr", output, svg;
    std::vector<std::string> bounds;  // XMIN YMIN XMAX YMAX, as in every subcommand (or one deprecated "a,b,c,d")
    double range = 0.0, loss = 0.0, radius = 0.0, anchor_fraction = 0.0;
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

nlohmann::json rows(const std::vector<std::int64_t>& flat, std::size_t cols) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t r = 0; cols && r < flat.size() / cols; ++r)
        out.push_back(std::vector<std::int64_t>(flat.begin() + static_cast<std::ptrdiff_t>(r * cols),
                                                flat.begin() + static_cast<std::ptrdiff_t>((r + 1) * cols)));
    return out;
}

nlohmann::json points_json(const Points& p) {
    nlohmann::json out = nlohmann::json::array();
    for (Index i = 0; i < p.rows(); ++i) {
        nlohmann::json r = nlohmann::json::array();
        for (int d = 0; d < 2; ++d) r.push_back(std::isfinite(p(i, d)) ? nlohmann::json(p(i, d)) : nlohmann::json());
        out.push_back(r);
    }
    return out;
}

void csr_json(nlohmann::json& j, const std::vector<std::vector<Index>>& lists, bool sorted) {
    std::vector<Index> indptr{0}, indices;
    for (auto l : lists) {
        if (sorted) std::sort(l.begin(), l.end());
        indices.insert(indices.end(), l.begin(), l.end());
        indptr.push_back(static_cast<Index>(indices.size()));
    }
    j["indptr"] = indptr;
    j["indices"] = indices;
}

int run_network(const NetworkOptions& o) {
    if (!std::isfinite(o.range) || !(o.range > 0.0))
        throw UsageError("--range: must be a positive finite number, got " + show(o.range));
    if (!(o.loss >= 0.0 && o.loss < 1.0)) throw UsageError("--loss: must be in [0, 1), got " + show(o.loss));
    if (o.budget < 0) throw UsageError("--budget: must be >= 0");
    if (!(o.anchor_fraction >= 0.0 && o.anchor_fraction <= 1.0))
        throw UsageError("--anchor-fraction: must be in [0, 1], got " + show(o.anchor_fraction));
    if (o.radius < 0.0 || !std::isfinite(o.radius)) throw UsageError("--radius: must be a positive finite number");
    const bool to_stdout = o.output.empty() || o.output == "-";
    const std::string ext = to_stdout ? ".json" : lower_extension(o.output);
    if (ext != ".json" && ext != ".csv")
        throw UsageError("-o/--output: cannot tell the output format of '" + o.output + "'; use .json or .csv");
    network::CcOptions cc;
    cc.cap_adjacency = !o.no_cap;
    cc.adjacency_cap = o.adjacency_cap;
    cc.forward = !o.no_forward;
    cc.route_discovery = !o.no_route_discovery;
    try {
        cc.routing = network::parse_routing(o.routing);
    } catch (const InputError& e) {
        throw UsageError(std::string("--routing: ") + e.what());
    }
    const bool has_bounds = !o.bounds.empty();
    network::Box box = has_bounds ? parse_bounds(o.bounds) : network::Box{};

    const io::PointFile file = read_points_argument(o.points, o.columns);
    const auto obstacles = o.obstacles.empty() ? std::vector<network::Segment>{} : read_obstacles(o.obstacles);
    std::unique_ptr<io::AtomicFile> out, svg;
    if (!to_stdout) out = open_output(o.output, "-o/--output");
    if (!o.svg.empty()) svg = open_output(o.svg, "--svg");

    network::Network net;
    try {
        net = network::make_network(file.points, o.range, obstacles);
    } catch (const CoincidentError& e) {
        throw InputError(coincident_message(file, e));
    }
    if (!has_bounds && net.size() > 0) {
        box = {net.points.col(0).minCoeff(), net.points.col(1).minCoeff(), net.points.col(0).maxCoeff(),
               net.points.col(1).maxCoeff()};
        if (!(box.xmin < box.xmax)) box.xmin -= 1, box.xmax += 1;
        if (!(box.ymin < box.ymax)) box.ymin -= 1, box.ymax += 1;
    }
    const network::RunOptions run{o.loss, o.seed, o.budget};
    Progress progress("network " + o.algorithm, 1, o.quiet, 1);

    nlohmann::json j;
    j["kind"] = "network_" + o.algorithm;
    j["algorithm"] = o.algorithm;
    j["comm_range"] = o.range;
    j["loss"] = o.loss;
    j["seed"] = o.seed;
    j["points"] = points_json(net.points);
    std::vector<std::array<Index, 2>> links;
    for (Index i = 0; i < net.size(); ++i)
        for (Index k : net.adj[static_cast<std::size_t>(i)])
            if (k > i) links.push_back({i, k});
    j["links"] = links;
    j["blocked_links"] = net.blocked_links;
    nlohmann::json obs = nlohmann::json::array();
    for (const auto& s : obstacles) obs.push_back({s.a.x(), s.a.y(), s.b.x(), s.b.y()});
    j["obstacles"] = obs;
    network::TransmissionCounts counts, dv_counts;
    std::vector<network::Polygon> cells;
    std::vector<char> highlight;
    std::vector<double> areas;
    if (o.algorithm == "cc") {
        const auto r = network::run_cc(net, run, cc);
        counts = r.counts;
        j["lost_messages"] = r.lost;
        j["route_discoveries"] = r.discoveries;
        csr_json(j, r.neighbors, true);
        std::vector<Index> ccw;
        for (const auto& l : r.neighbors) ccw.insert(ccw.end(), l.begin(), l.end());
        j["neighbors_ccw"] = ccw;
        std::vector<bool> hull;
        for (char h : r.on_hull) hull.push_back(h != 0);
        j["on_hull"] = hull;
        highlight = r.on_hull;
        const auto chk = network::delaunay_check(net);
        j["condition"] = chk.condition;
        j["wrong_nodes"] = network::wrong_nodes(chk, r.neighbors, &r.on_hull);
        if (has_bounds) {
            j["bounds"] = {box.xmin, box.ymin, box.xmax, box.ymax};
            for (Index i = 0; i < net.size(); ++i) {
                std::vector<Vec2> nb;
                for (Index k : r.neighbors[static_cast<std::size_t>(i)]) nb.push_back(net.pos(k));
                cells.push_back(network::clipped_cell(net.pos(i), nb, r.neighbors[static_cast<std::size_t>(i)], box));
                areas.push_back(cells.back().area());
            }
            j["areas"] = areas;
        } else {
            j["bounds"] = nullptr;
        }
    } else if (o.algorithm == "bd07") {
        network::Bd07Options bo;
        bo.route_discovery = !o.no_route_discovery;
        const auto r = network::run_bd07(net, box, run, bo);
        counts = r.counts;
        j["lost_messages"] = r.lost;
        j["bounds"] = {box.xmin, box.ymin, box.xmax, box.ymax};
        csr_json(j, r.neighbors, true);
        cells = r.cells;
        for (const auto& c : cells) areas.push_back(c.area());
        j["areas"] = areas;
        j["probes"] = r.probes;
        j["route_discoveries"] = r.discoveries;
    } else {
        const double R = o.radius > 0.0 ? o.radius : 0.5 * o.range;
        Points positions = net.points;
        std::vector<Index> anchors;
        if (o.anchor_fraction > 0.0) {
            const auto k = static_cast<std::size_t>(std::max<double>(1.0, std::round(o.anchor_fraction * static_cast<double>(net.size()))));
            std::vector<Index> all(static_cast<std::size_t>(net.size()));
            for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
            std::mt19937_64 rng(o.seed);
            std::shuffle(all.begin(), all.end(), rng);
            anchors.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(std::min(k, all.size())));
            std::sort(anchors.begin(), anchors.end());
            network::DvHopOptions dvo;
            dvo.synchronous = !o.dv_hop_async;
            dvo.anchors_relay = o.anchors_relay;
            const auto dv = network::run_dv_hop(net, anchors, run, dvo);
            positions = dv.estimates;
            dv_counts = dv.counts;
        }
        const auto r = network::run_distributed_bs(net, positions, R, run);
        counts = r.counts;
        j["lost_messages"] = 0;
        j["positions"] = points_json(positions);
        j["radius"] = R;
        j["indptr"] = r.partition.indptr;
        j["indices"] = r.partition.indices;
        j["areas"] = r.partition.areas;
        j["anchors"] = anchors.empty() ? nlohmann::json() : nlohmann::json(anchors);
        j["dv_hop_types"] = dv_counts.types;
        j["dv_hop_sent"] = rows(dv_counts.sent, dv_counts.types.size());
        j["dv_hop_received"] = rows(dv_counts.received, dv_counts.types.size());
        j["dropped_coincident"] = r.dropped_coincident;
        areas = r.partition.areas;
    }
    progress.finish();
    j["message_types"] = counts.types;
    j["sent"] = rows(counts.sent, counts.types.size());
    j["received"] = rows(counts.received, counts.types.size());
    j["total_transmissions"] = counts.total_sent() + dv_counts.total_sent();
    j["total_deliveries"] = counts.total_received() + dv_counts.total_received();

    std::string text;
    if (ext == ".csv") {
        std::ostringstream cs;
        // The columns of the other writers (io/csv.hpp): 'agent' and the neighbours space-separated, ascending.
        const std::vector<Index> indptr = j["indptr"].get<std::vector<Index>>();
        const std::vector<Index> indices = j["indices"].get<std::vector<Index>>();
        cs << "agent,x,y,neighbors";
        if (!areas.empty()) cs << ",area";
        for (const auto& t : dv_counts.types) cs << ",sent_" << t << ",received_" << t;
        for (const auto& t : counts.types) cs << ",sent_" << t << ",received_" << t;
        cs << '\n';
        cs.precision(17);
        for (Index i = 0; i < net.size(); ++i) {
            const auto ii = static_cast<std::size_t>(i);
            cs << i << ',' << net.pos(i).x() << ',' << net.pos(i).y() << ',';
            for (Index q = indptr[ii]; q < indptr[ii + 1]; ++q)
                cs << (q > indptr[ii] ? " " : "") << indices[static_cast<std::size_t>(q)];
            if (!areas.empty()) cs << ',' << areas[ii];
            for (std::size_t t = 0; t < dv_counts.types.size(); ++t)
                cs << ',' << dv_counts.sent[ii * dv_counts.types.size() + t] << ',' << dv_counts.received[ii * dv_counts.types.size() + t];
            for (std::size_t t = 0; t < counts.types.size(); ++t)
                cs << ',' << counts.sent[ii * counts.types.size() + t] << ',' << counts.received[ii * counts.types.size() + t];
            cs << '\n';
        }
        text = cs.str();
    } else {
        text = j.dump() + "\n";
    }
    const int code = deliver(
        out, svg, [&](std::ostream& os) { os << text; },
        [&](std::ostream& os) { io::write_network_svg(os, net, cells, box, highlight); });
    if (code != 0) return code;
    if (!o.quiet)
        std::cerr << "network " << o.algorithm << ": " << net.size() << " nodes, " << net.link_count() << " links, "
                  << (counts.total_sent() + dv_counts.total_sent()) << " transmissions, "
                  << (counts.total_received() + dv_counts.total_received()) << " link deliveries\n";
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
    sub->add_option("-o,--output", o->output, "output file: .json (the result) or .csv (one row per node: neighbours, area, transmissions (sent_*) and link deliveries (received_*) by type); default JSON on stdout");
    sub->add_option("--svg", o->svg, "also draw the network (cells, links, obstacles) into this SVG file");
    sub->add_flag("-q,--quiet", o->quiet, "no summary on stderr");
    return {sub, [o] { return run_network(*o); }};
}

}  // namespace dvoronoi::cli
