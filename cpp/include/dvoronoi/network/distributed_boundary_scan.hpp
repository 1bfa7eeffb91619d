// Distributed Boundary Scan (He, Feng & Ren 2018, Section 4.2): every node broadcasts its position
// once to its adjacent nodes and computes its limited cell (radius R = range / 2, SPEC "Range-limited cell")
// from what it received, with the library's Boundary Scan (cells/limited_cell.hpp). Without obstacles
// the unit-disk links reach every node that can shape the cell (closer than 2R = range), so the cells
// equal the centralised limited_cells; with obstacles a node sees only its linked neighbours.
#pragma once

#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/network/network.hpp"
#include "dvoronoi/network/simulator.hpp"
#include "dvoronoi/partition/limited_partition.hpp"

#include <cmath>
#include <vector>

namespace dvoronoi::network {

struct DistributedBsResult {
    LimitedPartition partition;     ///< cells from the positions the nodes used (NaN rows: no cell)
    TransmissionCounts counts;      ///< message type: position
    Index dropped_coincident = 0;   ///< received positions ignored because they coincide with another
};

/// Runs the distributed Boundary Scan. `positions` are the positions the nodes believe (true ones, or
/// DV-Hop estimates); a node whose row is NaN (not localised) sends nothing and gets an empty cell.
/// Positions that coincide (possible for estimates) are kept once per receiver: the receiver's own
/// first, then the lowest node index; each drop is counted.
///
/// \throws InputError if radius <= 0.
inline DistributedBsResult run_distributed_bs(const Network& net, PointsRef positions, double radius,
                                              const RunOptions& run) {
    dvoronoi::detail::require_finite_radius(radius);
    const Index n = net.size();
    if (positions.rows() != n) throw InputError("positions must have one row per node");
    enum : std::size_t { kPosition = 0 };
    struct Msg {
        Index to, from;
    };
    Simulator<Msg> sim(n, {"position"}, run);
    const auto known = [&](Index i) { return std::isfinite(positions(i, 0)) && std::isfinite(positions(i, 1)); };
    // Every localised node broadcasts its position once (one transmission, a delivery per neighbour).
    for (Index s = 0; s < n; ++s)
        if (known(s)) sim.broadcast(s, net.adj[static_cast<std::size_t>(s)], kPosition, [&](Index t) { return Msg{t, s}; });
    std::vector<std::vector<Index>> heard(static_cast<std::size_t>(n));
    sim.run([&](const Msg& m) { heard[static_cast<std::size_t>(m.to)].push_back(m.from); });

    DistributedBsResult res;
    LimitedPartition& out = res.partition;
    out.radius = radius;
    out.method = Method::Scan;  // Boundary Scan on every node
    out.points = positions;
    out.areas.assign(static_cast<std::size_t>(n), 0.0);
    out.perimeters.assign(static_cast<std::size_t>(n), 0.0);
    out.centroids = Points::Constant(n, 2, std::nan(""));
    out.candidates.assign(static_cast<std::size_t>(n), 0);
    out.piece_ptr.assign(1, 0);
    out.indptr.assign(1, 0);
    Points others;
    std::vector<Index> ids;
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        if (known(i)) {
            auto& h = heard[ii];
            std::sort(h.begin(), h.end());
            ids.clear();
            const Vec2 c = positions.row(i).transpose();
            for (Index j : h) {
                const Vec2 q = positions.row(j).transpose();
                bool dup = q == c;
                for (Index k : ids) dup = dup || positions.row(k).transpose() == q;
                if (dup) ++res.dropped_coincident;
                else ids.push_back(j);
            }
            others.resize(static_cast<Index>(ids.size()), 2);
            for (std::size_t k = 0; k < ids.size(); ++k) others.row(static_cast<Index>(k)) = positions.row(ids[k]);
            const LimitedCell cell = limited_cell(c, others, radius, Method::Scan);  // Boundary Scan
            const CellMeasures& m = cell.measures();
            out.areas[ii] = m.area;
            out.perimeters[ii] = m.perimeter;
            out.centroids.row(i) = m.centroid.transpose();
            out.candidates[ii] = cell.candidates;
            std::vector<Index> nb;
            for (const Piece& p : cell.pieces) {
                const Index g = p.is_arc() ? kArc : ids[static_cast<std::size_t>(p.neighbor)];
                out.piece_neighbor.push_back(g);
                out.piece_x.push_back(p.start.x());
                out.piece_y.push_back(p.start.y());
                out.piece_span.push_back(p.arc_span);
                if (g >= 0) nb.push_back(g);
            }
            std::sort(nb.begin(), nb.end());
            nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
            out.indices.insert(out.indices.end(), nb.begin(), nb.end());
        }
        out.piece_ptr.push_back(static_cast<Index>(out.piece_neighbor.size()));
        out.indptr.push_back(static_cast<Index>(out.indices.size()));
    }
    res.counts = sim.counts();
    return res;
}

}  // namespace dvoronoi::network
