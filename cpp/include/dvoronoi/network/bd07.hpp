// BD07 (Bash & Desnoyers, IPSN 2007, as summarised in the CC paper): every node starts from the
// bounded region as its cell, refined with the locations of its adjacent nodes (the beacons GPSR needs
// anyway); it then probes each vertex of its current cell through GPSR, which delivers the probe to
// the node nearest that vertex; that node replies and the cell is refined with it; new vertices are
// probed in turn. A node stops once it is the nearest node to all its vertices. The result is the
// Voronoi diagram clipped to the region. Beacons are broadcasts (one transmission each); probes and
// replies one transmission per hop. Replies are addressed to a node: where GPSR cannot deliver one
// (obstacles), the same route discovery as CC's takes over (`route_discovery`, not in either paper,
// so that neither algorithm is helped alone); off, the reply is lost.
//
// Exactness: which nodes bound a cell is the exact Delaunay star (as in CC); the clipped polygon and
// the probed points are rounded. A convex cell cut by a node's half-plane has a vertex strictly on the
// node's side, so probing every vertex finds every missing neighbour as long as GPSR delivers to a
// nearest node (true on connected planar graphs, i.e. without obstacles).
#pragma once

#include "dvoronoi/network/cc.hpp"

#include <set>
#include <utility>
#include <vector>

namespace dvoronoi::network {

struct Bd07Options {
    /// Where GPSR cannot deliver a reply, find a route by flooding (cc.hpp: NodeRouter). Off: lost.
    bool route_discovery = true;
};

struct Bd07Result {
    std::vector<std::vector<Index>> neighbors;  ///< nodes across an edge of the clipped cell, ascending
    std::vector<Polygon> cells;                 ///< cells clipped to the region
    TransmissionCounts counts;                  ///< message types: location, probe, reply, discovery
    std::int64_t delivered = 0;
    std::int64_t lost = 0;                      ///< replies that could not be delivered
    std::int64_t discoveries = 0;               ///< route discoveries after GPSR gave up (obstacles only)
    std::int64_t probes = 0;                    ///< vertices probed
};

/// Runs BD07 on the network with the bounded region `box`.
///
/// \throws BudgetExceeded when the run needs more transmissions than `run.budget`.
/// \note Thread-safe (no shared state).
inline Bd07Result run_bd07(const Network& net, const Box& box, const RunOptions& run, const Bd07Options& opt = {}) {
    require_box(box);
    const Index n = net.size();
    enum : std::size_t { kLocation = 0, kProbe = 1, kReply = 2, kDiscovery = 3 };
    struct Msg {
        Index to, about;
        std::size_t kind;
    };
    Simulator<Msg> sim(n, {"location", "probe", "reply", "discovery"}, run);
    const Gpsr gpsr(net);
    detail::NodeRouter router(net, Routing::Gpsr, opt.route_discovery);
    std::vector<Index> flood;
    std::vector<std::pair<Index, Index>> discovery;
    std::vector<detail::CcCell> cells(static_cast<std::size_t>(n));
    std::vector<Polygon> polys(static_cast<std::size_t>(n));
    std::vector<std::set<std::pair<Index, Index>>> probed(static_cast<std::size_t>(n));
    Bd07Result res;
    std::vector<dvoronoi::detail::Candidate> cand;
    DelaunayCell star;
    dvoronoi::detail::DelaunayWorkspace ws;
    std::vector<Index> path;
    std::vector<Vec2> nb;

    const auto reclip = [&](Index s) {
        const auto& cell = cells[static_cast<std::size_t>(s)];
        nb.clear();
        for (Index j : cell.nbrs) nb.push_back(net.pos(j));
        polys[static_cast<std::size_t>(s)] = clipped_cell(net.pos(s), nb, cell.nbrs, box);
    };
    const auto probe_new_vertices = [&](Index s) {
        const Polygon& p = polys[static_cast<std::size_t>(s)];
        const std::size_t m = p.vertices.size();
        for (std::size_t k = 0; k < m; ++k) {
            const std::pair<Index, Index> key{p.edge_label[(k + m - 1) % m], p.edge_label[k]};
            if (!probed[static_cast<std::size_t>(s)].insert(key).second) continue;
            ++res.probes;
            gpsr.route(s, p.vertices[k], path);
            const Index t = path.back();
            if (path.size() > 1) sim.send_along(path, kProbe, Msg{t, s, kProbe});
        }
    };

    for (Index i = 0; i < n; ++i) polys[static_cast<std::size_t>(i)] = box_polygon(box);
    // Beacons: every node broadcasts its location once; its adjacent nodes learn it.
    for (Index s = 0; s < n; ++s)
        sim.broadcast(s, net.adj[static_cast<std::size_t>(s)], kLocation, [&](Index t) { return Msg{t, s, kLocation}; });
    res.delivered += sim.run([&](const Msg& m) {
        detail::refine(m.to, m.about, cells[static_cast<std::size_t>(m.to)], net, cand, star, ws);
    });
    for (Index s = 0; s < n; ++s) reclip(s);
    // Probing.
    for (Index s = 0; s < n; ++s) probe_new_vertices(s);
    res.delivered += sim.run([&](const Msg& m) {
        if (m.kind == kProbe) {
            if (m.to == m.about) return;  // the prober is itself nearest: the vertex is certified
            // m.to is the node nearest the probed vertex; it answers the prober m.about.
            const bool ok = router.route(m.to, m.about, path, flood, discovery);
            for (Index u : flood) sim.count_broadcast(u, net.adj[static_cast<std::size_t>(u)], kDiscovery);
            for (const auto& [u, w] : discovery) sim.count_hop(u, w, kDiscovery);
            if (ok) {
                sim.send_along(path, kReply, Msg{m.about, m.to, kReply});
            } else {
                for (std::size_t h = 0; h + 1 < path.size(); ++h) sim.count_hop(path[h], path[h + 1], kReply);
                ++res.lost;
            }
            return;
        }
        const Index s = m.to;
        if (!detail::refine(s, m.about, cells[static_cast<std::size_t>(s)], net, cand, star, ws)) return;
        reclip(s);
        probe_new_vertices(s);
    });
    res.counts = sim.counts();
    res.discoveries = router.discoveries();
    res.cells = std::move(polys);
    res.neighbors.resize(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        auto& out = res.neighbors[static_cast<std::size_t>(i)];
        for (Index l : res.cells[static_cast<std::size_t>(i)].edge_label)
            if (l >= 0) out.push_back(l);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    }
    return res;
}

}  // namespace dvoronoi::network
