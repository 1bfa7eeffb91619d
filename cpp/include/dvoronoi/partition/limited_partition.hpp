// All agents at once: each agent's limited cell from the agents within 2R, found with a uniform-grid
// index, computed in parallel (OpenMP), stored compactly in input order.
#pragma once

#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/core/grid_index.hpp"

#include <algorithm>
#include <atomic>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace dvoronoi {

/// The range-limited Voronoi partition of n agents (the result of limited_cells).
///
/// Cells are stored flat: agent i owns pieces [piece_ptr[i], piece_ptr[i+1]); a piece starts at
/// (piece_x, piece_y), ends where the next piece of the same agent starts (cyclically), and is an edge
/// with neighbour piece_neighbor >= 0 or an arc (kArc) sweeping piece_span radians.
/// Limited neighbours are the CSR pair (indptr, indices), ascending per agent (scipy's layout).
struct LimitedPartition {
    double radius = 0.0;
    Points points;  ///< the agents, as given
    std::vector<Index> piece_ptr{0};
    std::vector<Index> piece_neighbor;
    std::vector<double> piece_x, piece_y, piece_span;
    std::vector<Index> indptr{0};
    std::vector<Index> indices;
    std::vector<double> areas, perimeters;
    Points centroids;
    std::vector<Index> candidates;  ///< agents within 2R examined per agent

    Index size() const noexcept { return static_cast<Index>(points.rows()); }

    /// Agent i's cell, rebuilt from the flat arrays.
    LimitedCell cell(Index i) const {
        check_index(i);
        LimitedCell c;
        c.center = points.row(i).transpose();
        c.radius = radius;
        c.candidates = candidates[static_cast<std::size_t>(i)];
        for (Index k = piece_ptr[i]; k < piece_ptr[i + 1]; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            Piece p;
            p.neighbor = piece_neighbor[kk];
            p.start = Vec2(piece_x[kk], piece_y[kk]);
            p.arc_span = piece_span[kk];
            c.pieces.push_back(p);
        }
        return c;
    }

    /// Limited neighbours of agent i, ascending (a view into `indices`).
    std::pair<const Index*, const Index*> neighbors(Index i) const {
        check_index(i);
        return {indices.data() + indptr[i], indices.data() + indptr[i + 1]};
    }

    void check_index(Index i) const {
        if (i < 0 || i >= size())
            throw InputError("agent index " + std::to_string(i) + " out of range [0, " +
                             std::to_string(size()) + ")");
    }
};

/// Progress callback: called with (agents done, agents total) from the calling thread only.
using ProgressFn = std::function<void(Index, Index)>;

namespace detail {

/// Throws CoincidentError naming the lowest-index pair (i, j), i < j, of coinciding agents.
inline void require_distinct(PointsRef pts) {
    const Index n = pts.rows();
    std::vector<Index> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), Index{0});
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
        if (pts(a, 0) != pts(b, 0)) return pts(a, 0) < pts(b, 0);
        if (pts(a, 1) != pts(b, 1)) return pts(a, 1) < pts(b, 1);
        return a < b;
    });
    Index best_i = -1, best_j = -1;
    for (std::size_t k = 0; k + 1 < order.size(); ++k) {
        const Index a = order[k], b = order[k + 1];
        if (pts(a, 0) == pts(b, 0) && pts(a, 1) == pts(b, 1)) {
            // a < b within a run of equal points; the run's first index pairs with its second.
            if (best_i < 0 || a < best_i || (a == best_i && b < best_j)) { best_i = a; best_j = b; }
        }
    }
    if (best_i >= 0)
        throw CoincidentError("points[" + std::to_string(best_i) + "] and points[" +
                                  std::to_string(best_j) + "] coincide at (" +
                                  std::to_string(pts(best_i, 0)) + ", " +
                                  std::to_string(pts(best_i, 1)) +
                                  "); their Voronoi cells are undefined",
                              best_i, best_j);
}

}  // namespace detail

/// Every agent's limited cell V_i ∩ B(p_i, radius) (the radius-limited Voronoi partition).
///
/// \param threads number of OpenMP threads; 0 = all cores. Results do not depend on it.
/// \param progress optional callback (done, total), called from the calling thread.
/// \throws InputError for a bad radius or non-finite coordinates; CoincidentError for coinciding
///         agents (lowest pair named).
/// \note Complexity O(n m log m) for Scan (m agents within 2R per agent) plus O(n log n) for the
///       duplicate check; memory O(n m). Thread-safe.
inline LimitedPartition limited_cells(PointsRef points, double radius, Method method = Method::Scan,
                                      int threads = 0, const ProgressFn& progress = nullptr) {
    detail::require_finite_radius(radius);
    detail::require_finite_points(points, "points");
    detail::require_distinct(points);
    const Index n = points.rows();
    LimitedPartition out;
    out.radius = radius;
    out.points = points;
    out.areas.assign(static_cast<std::size_t>(n), 0.0);
    out.perimeters.assign(static_cast<std::size_t>(n), 0.0);
    out.centroids.resize(n, 2);
    out.candidates.assign(static_cast<std::size_t>(n), 0);
    if (n == 0) return out;

    const GridIndex index(out.points, 2.0 * radius);
#ifdef _OPENMP
    const int nthreads = threads > 0 ? threads : omp_get_max_threads();
#else
    const int nthreads = 1;
    (void)threads;
#endif
    // Cells are computed in blocks; each block writes its own piece buffers, stitched in order after.
    const Index block = 4096;
    const Index nblocks = (n + block - 1) / block;
    std::vector<LimitedPartition> parts(static_cast<std::size_t>(nblocks));
    std::atomic<Index> done{0};

#pragma omp parallel num_threads(nthreads)
    {
        std::vector<detail::Candidate> cand;
        LimitedCell cell;
        detail::CellWorkspace ws;
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            LimitedPartition& part = parts[static_cast<std::size_t>(b)];
            const Index lo = b * block, hi = std::min(n, lo + block);
            for (Index i = lo; i < hi; ++i) {
                const Vec2 c = out.points.row(i).transpose();
                index.within(out.points, i, radius, cand);
                if (method == Method::Scan)
                    detail::boundary_scan(c, cand, radius, cell, ws);
                else
                    detail::rcvc(c, cand, radius, cell, ws);
                const CellMeasures m = cell.measures();
                const auto ii = static_cast<std::size_t>(i);
                out.areas[ii] = m.area;
                out.perimeters[ii] = m.perimeter;
                out.centroids(i, 0) = m.centroid.x();
                out.centroids(i, 1) = m.centroid.y();
                out.candidates[ii] = cell.candidates;
                const std::size_t first_nb = part.indices.size();
                for (const Piece& p : cell.pieces) {
                    part.piece_neighbor.push_back(p.neighbor);
                    part.piece_x.push_back(p.start.x());
                    part.piece_y.push_back(p.start.y());
                    part.piece_span.push_back(p.arc_span);
                    if (!p.is_arc()) part.indices.push_back(p.neighbor);
                }
                std::sort(part.indices.begin() + static_cast<std::ptrdiff_t>(first_nb),
                          part.indices.end());
                part.piece_ptr.push_back(static_cast<Index>(part.piece_neighbor.size()));
                part.indptr.push_back(static_cast<Index>(part.indices.size()));
            }
            const Index now = done.fetch_add(hi - lo) + (hi - lo);
#ifdef _OPENMP
            if (progress && omp_get_thread_num() == 0) progress(now, n);
#else
            if (progress) progress(now, n);
#endif
        }
    }

    // Stitch the blocks in input order.
    for (const LimitedPartition& part : parts) {
        const Index piece_base = static_cast<Index>(out.piece_neighbor.size());
        const Index nb_base = static_cast<Index>(out.indices.size());
        for (std::size_t k = 1; k < part.piece_ptr.size(); ++k) {
            out.piece_ptr.push_back(piece_base + part.piece_ptr[k]);
            out.indptr.push_back(nb_base + part.indptr[k]);
        }
        out.piece_neighbor.insert(out.piece_neighbor.end(), part.piece_neighbor.begin(),
                                  part.piece_neighbor.end());
        out.piece_x.insert(out.piece_x.end(), part.piece_x.begin(), part.piece_x.end());
        out.piece_y.insert(out.piece_y.end(), part.piece_y.begin(), part.piece_y.end());
        out.piece_span.insert(out.piece_span.end(), part.piece_span.begin(), part.piece_span.end());
        out.indices.insert(out.indices.end(), part.indices.begin(), part.indices.end());
    }
    if (progress) progress(n, n);
    return out;
}

}  // namespace dvoronoi
