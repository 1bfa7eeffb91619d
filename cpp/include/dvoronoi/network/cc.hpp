// CC, the completely cooperative algorithm (Núñez-Rodríguez, Xiao, Islam & Alsalih, "A distributed
// algorithm for computing Voronoi diagram in the unit disk graph model", Algorithm 1): every node
// broadcasts its location; a node that learns a location refines its cell with it and, for each new
// vertex of its cell, tells the two other nodes of that vertex about each other. The complete Voronoi
// diagram (unbounded cells included), the Delaunay triangulation and the convex hull come out with no
// further messages. Theorem 2: exact whenever the Delaunay edges that are links form a connected graph.
//
// Exactness: a node's cell is kept combinatorially, as its Voronoi neighbours among the locations it
// knows in counter-clockwise order plus an "unbounded" flag; refinement is the exact Delaunay star of
// the node among its neighbours and the new location (cells/delaunay.hpp: orient2d / incircle with
// exact fallback), after an exact in-circle pre-test that discards a location cutting no vertex of a
// bounded cell. A new vertex is a pair of consecutive neighbours that includes the new one.
//
// Section 2.3's optimisations, each switchable: (1) locations carry the node's adjacency list capped at
// `adjacency_cap` entries (its nearest adjacent nodes) and no notification goes to two nodes one of
// which lists the other; (2) a notification goes to one of the two nodes only (the one nearer to the
// notifying node), which tells the other if the news changed its own cell.
// Locations are broadcasts (one transmission each, one link delivery per neighbour). Notifications
// travel by GPSR (the paper uses it for fairness with BD07) or, optionally, along hop-shortest paths;
// each hop is one transmission. Where GPSR cannot deliver (obstacles make the graph non-planar), a
// route discovery by flooding takes over (NodeRouter; our addition, not in the paper, switchable:
// `route_discovery`), counted separately; without it such a notification is lost.
#pragma once

#include "dvoronoi/cells/delaunay.hpp"
#include "dvoronoi/network/bounded_cell.hpp"
#include "dvoronoi/network/gpsr.hpp"
#include "dvoronoi/network/simulator.hpp"

#include <algorithm>
#include <optional>
#include <vector>

namespace dvoronoi::network {

/// How multi-hop messages travel.
enum class Routing { Gpsr, Shortest };

inline Routing parse_routing(const std::string& s) {
    if (s == "gpsr") return Routing::Gpsr;
    if (s == "shortest") return Routing::Shortest;
    throw InputError("routing must be \"gpsr\" or \"shortest\", got \"" + s + "\"");
}

struct CcOptions {
    bool cap_adjacency = true;   ///< Section 2.3 optimisation 1
    int adjacency_cap = 6;       ///< entries of the adjacency list sent along (the paper: 6)
    bool forward = true;         ///< Section 2.3 optimisation 2: notify one node, let it forward
    Routing routing = Routing::Gpsr;
    /// Where GPSR cannot deliver to a node, find a route by flooding (not in the paper; BD07 has the
    /// same switch). Off: the message is lost (its hops counted), and cells may end wrong.
    bool route_discovery = true;
};

/// The CC result: every node's Voronoi neighbours (counter-clockwise; a hull node's list runs from
/// the neighbour across its incoming ray to the one across its outgoing ray), hull flags, and counts.
struct CcResult {
    std::vector<std::vector<Index>> neighbors;  ///< counter-clockwise per node
    std::vector<char> on_hull;
    TransmissionCounts counts;                  ///< message types: location, notify
    std::int64_t delivered = 0;                 ///< messages delivered (end to end)
    std::int64_t lost = 0;                      ///< messages not delivered (addressee unreachable)
    std::int64_t discoveries = 0;               ///< route discoveries after GPSR gave up (obstacles only)
    std::int64_t refinements = 0;               ///< locations that changed a cell
};

namespace detail {

/// A node's cell as CC keeps it.
struct CcCell {
    std::vector<Index> nbrs;   // counter-clockwise Voronoi neighbours among the known locations
    bool unbounded = true;
    std::vector<Index> touch;  // known nodes whose cells meet this one in a single point (a vertex)
    std::vector<Index> ring;   // nbrs with each touching node inserted at its vertex, counter-clockwise
};

/// Consecutive pairs (a, b) of `list` (cyclic unless the cell is unbounded) that meet at a Voronoi
/// vertex of the cell (orient(c, a, b) > 0).
template <class F>
void for_each_vertex(const Vec2& c, const std::vector<Index>& list, bool unbounded, const Network& net, F&& f) {
    const std::size_t k = list.size();
    if (k < 2) return;
    const std::size_t pairs = unbounded ? k - 1 : k;
    for (std::size_t i = 0; i < pairs; ++i) {
        const Index a = list[i], b = list[(i + 1) % k];
        if (pred::orient(c, net.pos(a), net.pos(b)) > 0) f(a, b);
    }
}

/// Does q lie on the circle through c and the two neighbours of some vertex (it touches the cell
/// there)? Exact.
inline bool touches(const Vec2& c, const CcCell& cell, const Vec2& q, const Network& net) {
    bool on = false;
    for_each_vertex(c, cell.nbrs, cell.unbounded, net, [&](Index a, Index b) {
        if (!on && pred::incircle(c, net.pos(a), net.pos(b), q) == 0) on = true;
    });
    return on;
}

/// The ring: between consecutive neighbours a, b the touching nodes on their circle, in
/// counter-clockwise order around c (the order along the arc from a to b).
inline void build_ring(const Vec2& c, CcCell& cell, const Network& net) {
    cell.ring.clear();
    const std::size_t k = cell.nbrs.size();
    if (cell.touch.empty()) {
        cell.ring = cell.nbrs;
        return;
    }
    std::vector<Index> here;
    for (std::size_t i = 0; i < k; ++i) {
        cell.ring.push_back(cell.nbrs[i]);
        if (k < 2 || (cell.unbounded && i + 1 == k)) continue;
        const Index a = cell.nbrs[i], b = cell.nbrs[(i + 1) % k];
        if (pred::orient(c, net.pos(a), net.pos(b)) <= 0) continue;
        here.clear();
        for (Index x : cell.touch)
            if (pred::incircle(c, net.pos(a), net.pos(b), net.pos(x)) == 0) here.push_back(x);
        std::sort(here.begin(), here.end(), [&](Index x, Index y) { return pred::orient(c, net.pos(x), net.pos(y)) > 0; });
        cell.ring.insert(cell.ring.end(), here.begin(), here.end());
    }
}

/// Refines the cell of node s with node t. Returns true when t became a neighbour (the cell shrank)
/// or a touching node (its cell meets this one at a vertex only).
///
/// Why touching nodes: the paper assumes no four cocircular nodes. Where four or more cells meet at a
/// vertex (lattices), two of them may share an edge whose both ends are such vertices; no third node
/// then has both as consecutive neighbours, and nobody would introduce them. Keeping the nodes that
/// touch a vertex in the counter-clockwise ring and notifying consecutive ring entries sends what any
/// perturbation into general position would send, so Theorem 2 holds on degenerate inputs too (the
/// lattice tests check it against CGAL).
inline bool refine(Index s, Index t, CcCell& cell, const Network& net, std::vector<dvoronoi::detail::Candidate>& cand,
                   DelaunayCell& star, dvoronoi::detail::DelaunayWorkspace& ws) {
    const Vec2 c = net.pos(s);
    if (s == t) return false;
    if (std::find(cell.nbrs.begin(), cell.nbrs.end(), t) != cell.nbrs.end()) return false;
    if (std::find(cell.touch.begin(), cell.touch.end(), t) != cell.touch.end()) return false;
    const Vec2 q = net.pos(t);
    if (!cell.unbounded) {
        // Bounded cell: t cuts it iff some vertex lies strictly inside the circle through c and the
        // vertex's two neighbours and t; it touches it iff none does and one lies on it.
        int most = -1;
        for_each_vertex(c, cell.nbrs, false, net, [&](Index a, Index b) {
            if (most < 1) most = std::max(most, pred::incircle(c, net.pos(a), net.pos(b), q));
        });
        if (most < 0) return false;
        if (most == 0) {
            cell.touch.push_back(t);
            build_ring(c, cell, net);
            return true;
        }
    }
    cand.clear();
    for (Index j : cell.nbrs) cand.push_back({net.pos(j), j});
    for (Index j : cell.touch) cand.push_back({net.pos(j), j});
    cand.push_back({q, t});
    dvoronoi::detail::delaunay_star(c, cand, star, ws);
    const bool is_nbr = std::find(star.neighbors.begin(), star.neighbors.end(), t) != star.neighbors.end();
    std::vector<Index> pool;
    for (const auto& x : cand)
        if (std::find(star.neighbors.begin(), star.neighbors.end(), x.id) == star.neighbors.end()) pool.push_back(x.id);
    cell.nbrs = star.neighbors;
    cell.unbounded = star.on_hull;
    cell.touch.clear();
    for (Index x : pool)
        if (touches(c, cell, net.pos(x), net)) cell.touch.push_back(x);
    build_ring(c, cell, net);
    return is_nbr || std::find(cell.touch.begin(), cell.touch.end(), t) != cell.touch.end();
}

/// Each node's `cap` nearest adjacent nodes, ascending by index (what its messages carry).
inline std::vector<std::vector<Index>> capped_adjacency(const Network& net, int cap) {
    std::vector<std::vector<Index>> out(static_cast<std::size_t>(net.size()));
    for (Index i = 0; i < net.size(); ++i) {
        auto a = net.adj[static_cast<std::size_t>(i)];
        const Vec2 c = net.pos(i);
        const std::size_t keep = std::min<std::size_t>(a.size(), static_cast<std::size_t>(std::max(cap, 0)));
        std::partial_sort(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(keep), a.end(), [&](Index x, Index y) {
            const int s = pred::compare_distance(c, net.pos(x), net.pos(y));
            return s < 0 || (s == 0 && x < y);
        });
        a.resize(keep);
        std::sort(a.begin(), a.end());
        out[static_cast<std::size_t>(i)] = std::move(a);
    }
    return out;
}

/// Routes from node `from` to node `to`: GPSR, or hop-shortest paths (a per-destination BFS cache).
///
/// GPSR alone is not enough with obstacles: the communication graph is then no unit-disk graph,
/// its Gabriel subgraph may keep crossing links, and face routing can loop or end at the wrong
/// node. A node whose packet GPSR cannot deliver then does what on-demand routing protocols do
/// (AODV's route discovery): it floods a route request through its connected component (every
/// node forwards it once to each neighbour), the addressee answers back along the shortest path,
/// and the packet follows that path. The flood is one broadcast per node of the component
/// (`flood`), the answer one transmission per hop (`discovery`), all counted as "discovery", so
/// nothing is lost on a connected network and the cost is honest. With `discover` off, a packet GPSR
/// cannot deliver is lost.
class NodeRouter {
public:
    NodeRouter(const Network& net, Routing r, bool discover = true)
        : net_(net), routing_(r), discover_(discover), parent_(static_cast<std::size_t>(net.size())) {
        if (r == Routing::Gpsr) gpsr_.emplace(net);
    }
    /// False when the message cannot be delivered (different components, or GPSR failed and route
    /// discovery is off). `path` holds the hops the message takes (GPSR's attempt included),
    /// `flood` the nodes that broadcast a route request, `discovery` the hops of the answer.
    bool route(Index from, Index to, std::vector<Index>& path, std::vector<Index>& flood,
               std::vector<std::pair<Index, Index>>& discovery) {
        discovery.clear();
        flood.clear();
        if (from == to) {
            path.assign(1, from);
            return true;
        }
        if (net_.linked(from, to)) {
            path.assign({from, to});
            return true;
        }
        if (!gpsr_) {
            path.assign(1, from);
            return append_shortest(from, to, path);
        }
        if (gpsr_->route(from, net_.pos(to), path) && path.back() == to) return true;
        if (!discover_) return false;
        // GPSR gave up at path.back(): route discovery from there.
        const Index stuck = path.back();
        const auto& comp = component_of(stuck);
        flood.assign(comp.begin(), comp.end());
        const std::size_t before = path.size();
        if (!append_shortest(stuck, to, path)) return false;
        for (std::size_t h = path.size() - 1; h > before - 1; --h) discovery.emplace_back(path[h], path[h - 1]);  // the answer
        ++discoveries_;
        return true;
    }
    const Gpsr* gpsr() const { return gpsr_ ? &*gpsr_ : nullptr; }
    std::int64_t discoveries() const { return discoveries_; }

private:
    /// Appends the hop-shortest path from `from` (already path's last node) to `to`.
    bool append_shortest(Index from, Index to, std::vector<Index>& path) {
        auto& par = parent_[static_cast<std::size_t>(to)];
        if (par.empty()) {
            std::vector<Index> hops;
            bfs(net_.adj, to, par, hops);
            par.push_back(0);  // marks "computed" even for an isolated node
        }
        if (par[static_cast<std::size_t>(from)] < 0) return false;
        for (Index u = from; u != to;) {
            u = par[static_cast<std::size_t>(u)];
            path.push_back(u);
        }
        return true;
    }
    const std::vector<Index>& component_of(Index u) {
        if (comp_id_.empty()) {
            comp_id_ = components(net_.adj);
            Index k = 0;
            for (Index c : comp_id_) k = std::max(k, c + 1);
            members_.assign(static_cast<std::size_t>(k), {});
            for (Index v = 0; v < net_.size(); ++v) members_[static_cast<std::size_t>(comp_id_[static_cast<std::size_t>(v)])].push_back(v);
        }
        return members_[static_cast<std::size_t>(comp_id_[static_cast<std::size_t>(u)])];
    }

    const Network& net_;
    Routing routing_;
    bool discover_;
    std::optional<Gpsr> gpsr_;
    std::vector<std::vector<Index>> parent_;
    std::vector<Index> comp_id_;
    std::vector<std::vector<Index>> members_;
    std::int64_t discoveries_ = 0;
};

}  // namespace detail

/// Runs CC on the network. Every node ends with its exact Voronoi neighbours whenever the Delaunay
/// edges among the links form a connected graph (Theorem 2) and every message is delivered.
///
/// \throws BudgetExceeded when the run needs more transmissions than `run.budget`.
/// \note Complexity: O(messages x k^1.5) for cells of k neighbours. Thread-safe (no shared state).
inline CcResult run_cc(const Network& net, const RunOptions& run, const CcOptions& opt = {}) {
    if (opt.cap_adjacency && opt.adjacency_cap < 0)
        throw InputError("adjacency_cap must be >= 0, got " + std::to_string(opt.adjacency_cap));
    const Index n = net.size();
    enum : std::size_t { kLocation = 0, kNotify = 1, kDiscovery = 2 };
    struct Msg {
        Index to, about;
        bool forward;  // optimisation 2: the receiver tells `about` of itself if the news was new
    };
    Simulator<Msg> sim(n, {"location", "notify", "discovery"}, run);
    detail::NodeRouter router(net, opt.routing, opt.route_discovery);
    const auto capped = opt.cap_adjacency ? detail::capped_adjacency(net, opt.adjacency_cap)
                                          : std::vector<std::vector<Index>>{};
    const auto lists = [&](Index a, Index b) {  // does a's capped list name b, or b's name a?
        if (!opt.cap_adjacency) return false;
        const auto& la = capped[static_cast<std::size_t>(a)];
        const auto& lb = capped[static_cast<std::size_t>(b)];
        return std::binary_search(la.begin(), la.end(), b) || std::binary_search(lb.begin(), lb.end(), a);
    };
    std::vector<detail::CcCell> cells(static_cast<std::size_t>(n));
    CcResult res;
    std::vector<Index> path, flood;
    std::vector<std::pair<Index, Index>> discovery;
    // A message that cannot be delivered (addressee in another component, or GPSR failed without
    // route discovery) costs its hops and is lost.
    const auto send = [&](Index from, Index to, Index about, bool forward) {
        const bool ok = router.route(from, to, path, flood, discovery);
        for (Index u : flood) sim.count_broadcast(u, net.adj[static_cast<std::size_t>(u)], kDiscovery);
        for (const auto& [u, w] : discovery) sim.count_hop(u, w, kDiscovery);
        if (ok) {
            sim.send_along(path, kNotify, Msg{to, about, forward});
        } else {
            for (std::size_t h = 0; h + 1 < path.size(); ++h) sim.count_hop(path[h], path[h + 1], kNotify);
            ++res.lost;
        }
    };
    // Every node broadcasts its location once.
    for (Index s = 0; s < n; ++s)
        sim.broadcast(s, net.adj[static_cast<std::size_t>(s)], kLocation, [&](Index t) { return Msg{t, s, false}; });

    std::vector<dvoronoi::detail::Candidate> cand;
    DelaunayCell star;
    dvoronoi::detail::DelaunayWorkspace ws;
    std::vector<std::pair<Index, Index>> fresh;
    res.delivered = sim.run([&](const Msg& m) {
        const Index s = m.to, t = m.about;
        if (t == s) return;
        auto& cell = cells[static_cast<std::size_t>(s)];
        if (!detail::refine(s, t, cell, net, cand, star, ws)) return;
        ++res.refinements;
        if (m.forward && !lists(s, t)) send(s, t, s, false);
        // New vertices: the pairs of consecutive neighbours that include t.
        fresh.clear();
        detail::for_each_vertex(net.pos(s), cell.ring, cell.unbounded, net, [&](Index a, Index b) {
            if (a == t) fresh.push_back({b, t});
            else if (b == t) fresh.push_back({a, t});
        });
        for (const auto& [x, y] : fresh) {
            if (lists(x, y)) continue;
            if (opt.forward) {
                // Tell the nearer of the two; it tells the other if it did not know.
                const bool x_first = pred::compare_distance(net.pos(s), net.pos(x), net.pos(y)) <= 0;
                if (x_first) send(s, x, y, true);
                else send(s, y, x, true);
            } else {
                send(s, x, y, false);
                send(s, y, x, false);
            }
        }
    });
    res.counts = sim.counts();
    res.discoveries = router.discoveries();
    res.neighbors.resize(static_cast<std::size_t>(n));
    res.on_hull.resize(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        res.neighbors[static_cast<std::size_t>(i)] = cells[static_cast<std::size_t>(i)].nbrs;
        res.on_hull[static_cast<std::size_t>(i)] = cells[static_cast<std::size_t>(i)].unbounded ? 1 : 0;
    }
    return res;
}

}  // namespace dvoronoi::network
