// One network simulation from inputs to a typed result (SPEC "Networks of agents"): build the
// communication graph, run CC, BD07 or the distributed Boundary Scan (after DV-Hop when there are
// anchors), and compute every node's final cell, its area and centroid here, in C++, so the CLI,
// the Python bindings and io/network_json.hpp all read one result.
//
//   const auto r = network::run(points, options);          // std::variant<CcRun, Bd07Run, BsRun>
//   std::visit([](const auto& res) { ... }, r);
//
// Cells are flat counter-clockwise piece cycles, as LimitedPartition's: node i owns pieces
// piece_ptr[i]..piece_ptr[i+1], each starting at (piece_x, piece_y); a piece's piece_neighbor is the
// node across an edge, -1 an arc of the limiting circle (Boundary Scan, sweeping piece_span radians),
// -2..-5 the bottom, right, top and left side of the bounded region (bounded_cell.hpp).
#pragma once

#include "dvoronoi/cells/bisectors.hpp"
#include "dvoronoi/network/bd07.hpp"
#include "dvoronoi/network/cc.hpp"
#include "dvoronoi/network/delaunay_check.hpp"
#include "dvoronoi/network/distributed_boundary_scan.hpp"
#include "dvoronoi/network/dv_hop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <variant>
#include <vector>

namespace dvoronoi::network {

enum class Algorithm { Cc, Bd07, Bs };

inline Algorithm parse_algorithm(const std::string& s) {
    if (s == "cc") return Algorithm::Cc;
    if (s == "bd07") return Algorithm::Bd07;
    if (s == "bs") return Algorithm::Bs;
    throw InputError("algorithm must be \"cc\", \"bd07\" or \"bs\", got \"" + s + "\"");
}

inline const char* algorithm_name(Algorithm a) {
    switch (a) {
        case Algorithm::Cc: return "cc";
        case Algorithm::Bd07: return "bd07";
        default: return "bs";
    }
}

/// Everything one simulation needs besides the node positions.
struct Options {
    Algorithm algorithm = Algorithm::Cc;
    double range = 0.0;                  ///< communication range (a link when |p - q| <= range)
    std::vector<Segment> obstacles;      ///< segments that cut links
    std::optional<Box> bounds;           ///< BD07's region (default: the nodes' bounding box); CC clips to it
    RunOptions run;                      ///< loss, seed, budget
    CcOptions cc;
    Bd07Options bd07;
    double radius = 0.0;                 ///< bs: cell radius; 0 = range / 2
    std::optional<std::vector<Index>> anchors;  ///< bs: anchor nodes (DV-Hop first unless empty)
    double anchor_fraction = 0.0;        ///< bs, without anchors: > 0 picks max(1, round(f n)) anchors with `seed`
    DvHopOptions dv_hop;
    bool verify = true;                  ///< cc, bd07: the exact diagram, Theorem 2's condition, wrong nodes
};

/// Cells as flat piece cycles (see the file comment); a cell without a polygon has no pieces.
struct FlatCells {
    std::vector<Index> piece_ptr{0};
    std::vector<Index> piece_neighbor;
    std::vector<double> piece_x, piece_y, piece_span;
    std::vector<double> areas;  ///< +inf for an unbounded cell
    Points centroids;           ///< NaN for an unbounded cell
};

/// The options that shaped a run besides those a result holds as fields (range, loss, seed,
/// obstacles, bounds, radius, anchors): recorded so that a saved run can be run again (dv.load).
struct Settings {
    std::int64_t budget = 0;  ///< RunOptions::budget (0 = 10^9)
    CcOptions cc;
    Bd07Options bd07;
    DvHopOptions dv_hop;
    bool verify = true;
};

/// What every algorithm reports: its inputs, the graph, the counts and the neighbour relation.
struct RunBase {
    double range = 0.0, loss = 0.0;
    std::uint64_t seed = 0;
    Settings settings;                          ///< the other options of the run
    Points points;                              ///< the nodes, as given
    std::vector<Segment> obstacles;
    std::vector<std::array<Index, 2>> links;    ///< pairs i < j, ascending
    Index blocked_links = 0;                    ///< unit-disk links cut by obstacles
    TransmissionCounts counts;                  ///< transmissions and link deliveries per node and type
    std::int64_t lost = 0;                      ///< messages not delivered
    std::int64_t discoveries = 0;               ///< route discoveries (cc, bd07)
    std::int64_t delivered = 0;                 ///< messages delivered end to end (cc, bd07)
    std::vector<Index> indptr{0}, indices;      ///< neighbours, CSR, ascending per node
    FlatCells cells;

    Index size() const noexcept { return static_cast<Index>(points.rows()); }
    std::int64_t total_transmissions() const { return counts.total_sent(); }
    std::int64_t total_deliveries() const { return counts.total_received(); }
};

/// CC: the complete diagram. Without bounds an interior cell is the polygon of its Voronoi vertices
/// (circumcentres of the node and consecutive neighbours) and a hull cell has none (area +inf).
struct CcRun : RunBase {
    static constexpr Algorithm algorithm = Algorithm::Cc;
    std::vector<Index> neighbors_ccw;   ///< same CSR layout as indices, CC's counter-clockwise order
    std::vector<char> on_hull;
    std::int64_t refinements = 0;
    std::optional<Box> bounds;          ///< the box the cells were clipped to
    std::optional<bool> condition;      ///< Theorem 2's condition (verify)
    std::optional<Index> dt_components; ///< components of the Delaunay edges that are links (verify)
    std::optional<std::vector<Index>> wrong_nodes;  ///< nodes whose answer is not exact (verify)
};

/// BD07: cells clipped to the region, found by GPSR probes.
struct Bd07Run : RunBase {
    static constexpr Algorithm algorithm = Algorithm::Bd07;
    std::optional<Box> bounds;          ///< the region used; none for an empty network without bounds
    std::int64_t probes = 0;
    std::optional<bool> condition;
    std::optional<Index> dt_components;
};

/// Distributed Boundary Scan, after DV-Hop when there are anchors: limited cells around the
/// positions the nodes used.
struct BsRun : RunBase {
    static constexpr Algorithm algorithm = Algorithm::Bs;
    double radius = 0.0;
    Points positions;                   ///< positions used: true ones, or DV-Hop estimates (NaN: none)
    std::vector<double> perimeters;
    std::optional<std::vector<Index>> anchors;
    bool localised = false;             ///< DV-Hop ran (anchors given and not empty)
    std::vector<char> localized;        ///< has a position (all true without DV-Hop)
    std::vector<double> hop_size;       ///< DV-Hop's hop size per node (empty without DV-Hop)
    TransmissionCounts dv_hop_counts;   ///< anchor_flood, hop_size (no types without DV-Hop)
    Index dropped_coincident = 0;

    std::int64_t total_transmissions() const { return counts.total_sent() + dv_hop_counts.total_sent(); }
    std::int64_t total_deliveries() const { return counts.total_received() + dv_hop_counts.total_received(); }
};

using Result = std::variant<CcRun, Bd07Run, BsRun>;

namespace detail {

inline void append_polygon(FlatCells& f, const Polygon& p) {
    for (std::size_t k = 0; k < p.vertices.size(); ++k) {
        f.piece_x.push_back(p.vertices[k].x());
        f.piece_y.push_back(p.vertices[k].y());
        f.piece_neighbor.push_back(p.edge_label[k]);
        f.piece_span.push_back(0.0);
    }
    f.piece_ptr.push_back(static_cast<Index>(f.piece_x.size()));
}

inline FlatCells flat_polygons(const std::vector<Polygon>& polys) {
    FlatCells f;
    f.centroids.resize(static_cast<Eigen::Index>(polys.size()), 2);
    for (std::size_t i = 0; i < polys.size(); ++i) {
        append_polygon(f, polys[i]);
        f.areas.push_back(polys[i].area());
        f.centroids.row(static_cast<Eigen::Index>(i)) = polys[i].centroid().transpose();
    }
    return f;
}

/// CC's unbounded diagram: interior cells from their counter-clockwise neighbours. Vertex k is the
/// circumcentre of (c, ccw[k], ccw[k+1]) (cells/bisectors.hpp's accurate_vertex: within 2^-44 of the
/// exact vertex), and the edge from it lies on the bisector with ccw[k+1]. Area and centroid are
/// taken in the node's frame, so their rounding does not grow with the distance from the origin.
inline FlatCells cc_unbounded_cells(const Network& net, const std::vector<std::vector<Index>>& ccw,
                                    const std::vector<char>& on_hull) {
    FlatCells f;
    const Index n = net.size();
    f.centroids = Points::Constant(n, 2, std::numeric_limits<double>::quiet_NaN());
    f.areas.assign(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
    Polygon local;
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const auto& nb = ccw[ii];
        if (on_hull[ii] || nb.size() < 3) {
            f.piece_ptr.push_back(static_cast<Index>(f.piece_x.size()));
            continue;
        }
        const Vec2 c = net.pos(i);
        // A cell CC reports bounded has a Voronoi vertex between consecutive neighbours (a left
        // turn, exact); should an answer ever lack one, the cell gets no polygon rather than a
        // vertex at infinity.
        bool turns = true;
        for (std::size_t k = 0; k < nb.size() && turns; ++k)
            turns = pred::orient(c, net.pos(nb[k]), net.pos(nb[(k + 1) % nb.size()])) > 0;
        if (!turns) {
            f.piece_ptr.push_back(static_cast<Index>(f.piece_x.size()));
            continue;
        }
        local.vertices.clear();
        local.edge_label.clear();
        for (std::size_t k = 0; k < nb.size(); ++k) {
            const Index a = nb[k], b = nb[(k + 1) % nb.size()];
            local.vertices.push_back(dvoronoi::detail::accurate_vertex(c, net.pos(a), net.pos(b)));
            local.edge_label.push_back(b);
        }
        for (std::size_t k = 0; k < local.vertices.size(); ++k) {
            f.piece_x.push_back(c.x() + local.vertices[k].x());
            f.piece_y.push_back(c.y() + local.vertices[k].y());
            f.piece_neighbor.push_back(local.edge_label[k]);
            f.piece_span.push_back(0.0);
        }
        f.piece_ptr.push_back(static_cast<Index>(f.piece_x.size()));
        f.areas[ii] = local.area();
        f.centroids.row(i) = (c + local.centroid()).transpose();
    }
    return f;
}

inline void csr_ascending(const std::vector<std::vector<Index>>& lists, std::vector<Index>& indptr,
                          std::vector<Index>& indices, std::vector<Index>* as_given = nullptr) {
    indptr.assign(1, 0);
    indices.clear();
    if (as_given) as_given->clear();
    for (const auto& l : lists) {
        if (as_given) as_given->insert(as_given->end(), l.begin(), l.end());
        const auto from = static_cast<std::ptrdiff_t>(indices.size());
        indices.insert(indices.end(), l.begin(), l.end());
        std::sort(indices.begin() + from, indices.end());
        indptr.push_back(static_cast<Index>(indices.size()));
    }
}

/// The nodes' bounding box, widened by 1 where it is flat; [0, 1]^2 without nodes.
inline Box default_box(const Points& p) {
    if (p.rows() == 0) return Box{0, 0, 1, 1};
    Box b{p.col(0).minCoeff(), p.col(1).minCoeff(), p.col(0).maxCoeff(), p.col(1).maxCoeff()};
    if (!(b.xmin < b.xmax)) b.xmin -= 1, b.xmax += 1;
    if (!(b.ymin < b.ymax)) b.ymin -= 1, b.ymax += 1;
    return b;
}

/// `round(fraction n)` anchors (at least one), drawn with `seed`, ascending.
inline std::vector<Index> pick_anchors(Index n, double fraction, std::uint64_t seed) {
    const auto k = static_cast<std::size_t>(std::max<double>(1.0, std::round(fraction * static_cast<double>(n))));
    std::vector<Index> all(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
    std::mt19937_64 rng(seed);
    std::shuffle(all.begin(), all.end(), rng);
    all.resize(std::min(k, all.size()));
    std::sort(all.begin(), all.end());
    return all;
}

inline void fill_base(RunBase& r, const Network& net, const Options& o) {
    r.range = o.range;
    r.loss = o.run.loss;
    r.seed = o.run.seed;
    r.settings = Settings{o.run.budget, o.cc, o.bd07, o.dv_hop, o.verify};
    r.points = net.points;
    r.obstacles = net.obstacles;
    r.blocked_links = net.blocked_links;
    for (Index i = 0; i < net.size(); ++i)
        for (Index j : net.adj[static_cast<std::size_t>(i)])
            if (j > i) r.links.push_back({i, j});
}

inline CcRun run_cc_full(const Network& net, const Options& o) {
    CcRun r;
    fill_base(r, net, o);
    const CcResult cc = run_cc(net, o.run, o.cc);
    r.counts = cc.counts;
    r.lost = cc.lost;
    r.discoveries = cc.discoveries;
    r.delivered = cc.delivered;
    r.refinements = cc.refinements;
    r.on_hull = cc.on_hull;
    csr_ascending(cc.neighbors, r.indptr, r.indices, &r.neighbors_ccw);
    r.bounds = o.bounds;
    if (o.bounds) {
        std::vector<Polygon> polys;
        std::vector<Vec2> nb;
        for (Index i = 0; i < net.size(); ++i) {
            const auto& ids = cc.neighbors[static_cast<std::size_t>(i)];
            nb.clear();
            for (Index k : ids) nb.push_back(net.pos(k));
            polys.push_back(clipped_cell(net.pos(i), nb, ids, *o.bounds));
        }
        r.cells = flat_polygons(polys);
    } else {
        r.cells = cc_unbounded_cells(net, cc.neighbors, cc.on_hull);
    }
    if (o.verify) {
        const auto chk = delaunay_check(net);
        r.condition = chk.condition;
        r.dt_components = chk.components;
        r.wrong_nodes = wrong_nodes(chk, cc.neighbors, &cc.on_hull);
    }
    return r;
}

inline Bd07Run run_bd07_full(const Network& net, const Options& o) {
    Bd07Run r;
    fill_base(r, net, o);
    const Box box = o.bounds ? *o.bounds : default_box(net.points);
    const Bd07Result bd = run_bd07(net, box, o.run, o.bd07);
    r.counts = bd.counts;
    r.lost = bd.lost;
    r.discoveries = bd.discoveries;
    r.delivered = bd.delivered;
    r.probes = bd.probes;
    if (o.bounds || net.size() > 0) r.bounds = box;
    csr_ascending(bd.neighbors, r.indptr, r.indices);
    r.cells = flat_polygons(bd.cells);
    if (o.verify) {
        const auto chk = delaunay_check(net);
        r.condition = chk.condition;
        r.dt_components = chk.components;
    }
    return r;
}

inline BsRun run_bs_full(const Network& net, const Options& o) {
    BsRun r;
    fill_base(r, net, o);
    r.radius = o.radius > 0.0 ? o.radius : 0.5 * o.range;
    if (o.anchors) r.anchors = o.anchors;
    else if (o.anchor_fraction > 0.0) r.anchors = pick_anchors(net.size(), o.anchor_fraction, o.run.seed);
    r.localised = r.anchors && !r.anchors->empty();
    DvHopResult dv;
    if (r.localised) {
        dv = run_dv_hop(net, *r.anchors, o.run, o.dv_hop);
        r.localized = dv.localized;
        r.hop_size = dv.hop_size;
        r.dv_hop_counts = dv.counts;
    } else {
        r.localized.assign(static_cast<std::size_t>(net.size()), 1);
        r.dv_hop_counts.reset(net.size(), {});
    }
    const DistributedBsResult bs = run_distributed_bs(net, r.localised ? dv.estimates : net.points, r.radius, o.run);
    const LimitedPartition& p = bs.partition;
    r.counts = bs.counts;
    r.dropped_coincident = bs.dropped_coincident;
    r.positions = p.points;
    r.indptr = p.indptr;
    r.indices = p.indices;
    r.perimeters = p.perimeters;
    r.cells.piece_ptr = p.piece_ptr;
    r.cells.piece_neighbor = p.piece_neighbor;
    r.cells.piece_x = p.piece_x;
    r.cells.piece_y = p.piece_y;
    r.cells.piece_span = p.piece_span;
    r.cells.areas = p.areas;
    r.cells.centroids = p.centroids;
    return r;
}

}  // namespace detail

/// Checks the options that do not depend on the nodes (the nodes are checked by make_network).
///
/// \throws InputError naming the option.
inline void require_options(const Options& o) {
    dvoronoi::detail::require_finite_radius(o.range, "comm_range");
    require_run_options(o.run);
    if (o.bounds) require_box(*o.bounds);
    if (!(o.radius >= 0.0 && std::isfinite(o.radius)))
        throw InputError("radius must be a positive finite number (0 = comm_range / 2)");
    if (!(o.anchor_fraction >= 0.0 && o.anchor_fraction <= 1.0))
        throw InputError("anchor_fraction must be in [0, 1], got " + std::to_string(o.anchor_fraction));
    if (o.cc.adjacency_cap < 0) throw InputError("adjacency_cap must be >= 0");
}

/// Runs one simulation: the communication graph of `points` and `o.range` (minus the links the
/// obstacles cut), the algorithm `o.algorithm`, and every node's cell with its area and centroid.
///
/// \throws InputError for bad options or nodes, CoincidentError for coinciding nodes,
///         BudgetExceeded when the run needs more transmissions than `o.run.budget`.
/// \note Thread-safe (no shared state). Cost: the algorithm's simulation, plus the exact diagram
///       (voronoi_cells) for cc and bd07 with `verify`.
inline Result run(PointsRef points, const Options& o) {
    require_options(o);
    const Network net = make_network(points, o.range, o.obstacles);
    switch (o.algorithm) {
        case Algorithm::Cc: return detail::run_cc_full(net, o);
        case Algorithm::Bd07: return detail::run_bd07_full(net, o);
        default: return detail::run_bs_full(net, o);
    }
}

/// The base of any result (its inputs, graph, counts and cells).
inline const RunBase& base(const Result& r) {
    return std::visit([](const auto& x) -> const RunBase& { return x; }, r);
}

}  // namespace dvoronoi::network
