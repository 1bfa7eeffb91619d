// Every robot's Voronoi neighbours from the detection graph (distance-only algorithm of Elwin, Freeman
// & Lynch), in parallel (OpenMP), then optionally the consistency step. Results in input order.
#pragma once

#include "dvoronoi/distances/consistency.hpp"
#include "dvoronoi/distances/voronoi_neighbors.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <vector>

namespace dvoronoi::dist {

/// All robots' answers. Row i of the CSR pair (indptr, indices) starts with robot i's own answer in
/// Delaunay-path order (`path_length[i]` entries); entries the consistency step added follow,
/// ascending (`added[i]` of them).
struct DistanceNeighbors {
    Index n = 0;
    bool consistency = false;         ///< the consistency step was applied
    std::vector<Index> indptr{0};
    std::vector<Index> indices;
    std::vector<char> on_hull;        ///< the robot found an end of its Delaunay path (o = Hull)
    std::vector<Index> path_length;   ///< entries of row i found by the robot itself
    std::vector<Index> added;         ///< entries of row i added by the consistency step
    std::vector<Index> detected;      ///< detection neighbours per robot

    Index size() const noexcept { return n; }
    std::pair<const Index*, const Index*> neighbors(Index i) const {
        if (i < 0 || i >= n)
            throw InputError("robot index " + std::to_string(i) + " out of range [0, " + std::to_string(n) + ")");
        return {indices.data() + indptr[static_cast<std::size_t>(i)], indices.data() + indptr[static_cast<std::size_t>(i) + 1]};
    }
};

namespace detail {
/// The robots in breadth-first order of the detection graph (each component from its lowest index).
inline std::vector<Index> breadth_first_order(const DistanceGraph& g) {
    std::vector<Index> order;
    order.reserve(static_cast<std::size_t>(g.n));
    std::vector<char> seen(static_cast<std::size_t>(g.n), 0);
    for (Index s = 0; s < g.n; ++s) {
        if (seen[static_cast<std::size_t>(s)]) continue;
        seen[static_cast<std::size_t>(s)] = 1;
        order.push_back(s);
        for (std::size_t head = order.size() - 1; head < order.size(); ++head) {  // `order` is the queue
            const Index v = order[head];
            for (Index q = g.indptr[static_cast<std::size_t>(v)]; q < g.indptr[static_cast<std::size_t>(v) + 1]; ++q) {
                const Index w = g.indices[static_cast<std::size_t>(q)];
                if (!seen[static_cast<std::size_t>(w)]) {
                    seen[static_cast<std::size_t>(w)] = 1;
                    order.push_back(w);
                }
            }
        }
    }
    return order;
}
}  // namespace detail

/// VORONOI-NEIGHBORS for every robot of `g`, then (if `consistency`) the consistency step.
///
/// \param threads OpenMP threads, 0 = all cores. Results do not depend on it.
/// \param progress optional (done, total) callback, called from the calling thread.
/// \note O(sum over robots of (sum of detected robots' degrees + |V_i| m_i)); memory O(n + E) plus
///       one m x m table per thread. Thread-safe.
inline DistanceNeighbors neighbors_from_distances(const DistanceGraph& g, bool consistency = true, int threads = 0,
                                                  const ProgressFn& progress = nullptr) {
    const Index n = g.n;
    DistanceNeighbors out;
    out.n = n;
    out.consistency = consistency;
    out.on_hull.assign(static_cast<std::size_t>(n), 1);
    out.path_length.assign(static_cast<std::size_t>(n), 0);
    out.detected.assign(static_cast<std::size_t>(n), 0);
    if (n == 0) return out;
    // Robots are renumbered in breadth-first order of the detection graph and processed in that
    // order: consecutive robots then share most detected robots, whose rows (and scratch entries) sit
    // next to each other in memory. Input order is often random, and building the local tables from
    // scattered rows would otherwise cost as much as the algorithm. Rows keep their entry order, so
    // local indices (and tie-breaking) are those of the one-robot call.
    const std::vector<Index> order = detail::breadth_first_order(g);
    std::vector<Index> rank(static_cast<std::size_t>(n)), ptr(static_cast<std::size_t>(n) + 1, 0), idx(g.indices.size());
    std::vector<double> val(g.values.size());
    for (Index p = 0; p < n; ++p) rank[static_cast<std::size_t>(order[static_cast<std::size_t>(p)])] = p;
    for (Index p = 0; p < n; ++p) {
        const auto i = static_cast<std::size_t>(order[static_cast<std::size_t>(p)]);
        auto dst = static_cast<std::size_t>(ptr[static_cast<std::size_t>(p)]);
        for (Index q = g.indptr[i]; q < g.indptr[i + 1]; ++q, ++dst) {
            idx[dst] = rank[static_cast<std::size_t>(g.indices[static_cast<std::size_t>(q)])];
            val[dst] = g.values[static_cast<std::size_t>(q)];
        }
        ptr[static_cast<std::size_t>(p) + 1] = static_cast<Index>(dst);
    }
    const Index block = ::dvoronoi::detail::kBlock;
    const Index nblocks = (n + block - 1) / block;
    const int team = ::dvoronoi::detail::thread_team(threads, nblocks);
    struct Block {
        std::vector<Index> flat;   // the block's answers, one after another
        std::vector<Index> first;  // per robot of the block: offset of its answer in `flat`
    };
    std::vector<Block> blocks(static_cast<std::size_t>(nblocks));
    ::dvoronoi::detail::ProgressTracker tracker(progress, n);

#pragma omp parallel num_threads(team)
    {
        std::vector<int> slot(static_cast<std::size_t>(n), -1);
        LocalTable t;
        NeighborPath path;
        NeighborWorkspace ws;
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            Block& blk = blocks[static_cast<std::size_t>(b)];
            const Index lo = b * block, hi = std::min(n, lo + block);
            if (tracker.skip(lo)) continue;
            Index pos = lo;
            try {
                for (; pos < hi; ++pos) {
                    const Index i = order[static_cast<std::size_t>(pos)];
                    const auto ii = static_cast<std::size_t>(i);
                    local_table(ptr.data(), idx.data(), val.data(), pos, g.squared, t, slot);
                    voronoi_neighbors(t, path, ws);
                    const Index base = g.indptr[ii];
                    blk.first.push_back(static_cast<Index>(blk.flat.size()));
                    for (int v : path.order) blk.flat.push_back(g.indices[static_cast<std::size_t>(base + v)]);
                    out.on_hull[ii] = path.hull ? 1 : 0;
                    out.path_length[ii] = static_cast<Index>(path.order.size());
                    out.detected[ii] = t.m;
                }
            } catch (...) {
                tracker.fail(pos, order[static_cast<std::size_t>(pos)], "distances: robot ", "");
            }
            tracker.block_done(hi - lo);
        }
    }
    tracker.rethrow_if_failed();

    out.indptr.assign(static_cast<std::size_t>(n) + 1, 0);
    for (Index i = 0; i < n; ++i)
        out.indptr[static_cast<std::size_t>(i) + 1] = out.indptr[static_cast<std::size_t>(i)] + out.path_length[static_cast<std::size_t>(i)];
    out.indices.resize(static_cast<std::size_t>(out.indptr.back()));
    for (Index pos = 0; pos < n; ++pos) {
        const Index i = order[static_cast<std::size_t>(pos)];
        const Block& blk = blocks[static_cast<std::size_t>(pos / block)];
        const Index* src = blk.flat.data() + blk.first[static_cast<std::size_t>(pos % block)];
        std::copy(src, src + out.path_length[static_cast<std::size_t>(i)], out.indices.begin() + out.indptr[static_cast<std::size_t>(i)]);
    }
    if (consistency)
        make_consistent(out.indptr, out.indices, out.added);
    else
        out.added.assign(static_cast<std::size_t>(n), 0);
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi::dist
