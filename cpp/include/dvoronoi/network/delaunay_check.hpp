// The simulator's view from above: the exact Voronoi neighbours of all nodes (centralised, ASR with
// Boundary Scan: partition/voronoi_partition.hpp), Theorem 2's condition (the Delaunay edges that are
// links form a connected graph) and whether a distributed answer matches. Used to report, not to run.
#pragma once

#include "dvoronoi/network/network.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <algorithm>
#include <vector>

namespace dvoronoi::network {

struct DelaunayCheck {
    std::vector<std::vector<Index>> neighbors;  ///< exact Voronoi neighbours, ascending
    std::vector<char> on_hull;
    bool condition = false;                     ///< DT(G') connected (Theorem 2)
    Index components = 0;                       ///< components of DT(G')
};

inline DelaunayCheck delaunay_check(const Network& net) {
    DelaunayCheck out;
    const Index n = net.size();
    const VoronoiPartition vp = voronoi_cells(net.points, AsrInner::Scan, 1);
    out.neighbors.resize(static_cast<std::size_t>(n));
    out.on_hull = vp.on_hull;
    std::vector<std::vector<Index>> dtg(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        const auto [a, b] = vp.neighbors(i);
        out.neighbors[static_cast<std::size_t>(i)].assign(a, b);
        for (const Index* j = a; j != b; ++j)
            if (net.linked(i, *j)) dtg[static_cast<std::size_t>(i)].push_back(*j);
    }
    const auto comp = components(dtg);
    out.components = comp.empty() ? 0 : *std::max_element(comp.begin(), comp.end()) + 1;
    out.condition = out.components <= 1;
    return out;
}

/// Nodes whose computed neighbour set (any order) or hull flag differs from the exact one.
inline std::vector<Index> wrong_nodes(const DelaunayCheck& ref, const std::vector<std::vector<Index>>& nbrs,
                                      const std::vector<char>* on_hull = nullptr) {
    std::vector<Index> bad;
    std::vector<Index> s;
    for (std::size_t i = 0; i < nbrs.size(); ++i) {
        s = nbrs[i];
        std::sort(s.begin(), s.end());
        if (s != ref.neighbors[i] || (on_hull && ((*on_hull)[i] != 0) != (ref.on_hull[i] != 0)))
            bad.push_back(static_cast<Index>(i));
    }
    return bad;
}

}  // namespace dvoronoi::network
