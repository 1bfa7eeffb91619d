// All agents at once: each agent's limited cell from the agents within 2R, found with a uniform-grid
// index, computed in parallel (OpenMP), stored compactly in input order.
#pragma once

#include "dvoronoi/cells/certified_clip.hpp"
#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/core/grid_index.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
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
    Method method = Method::Scan;
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
        c.chords_after_check = -1;
        const auto ii = static_cast<std::size_t>(i);
        c.measures_.area = areas[ii];
        c.measures_.perimeter = perimeters[ii];
        c.measures_.centroid = centroids.row(i).transpose();
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

/// Sorts a handful of indices (a cell's neighbours) ascending: each lands at its rank (ties by
/// position), counted without branches. Neighbours come in angular order, where the branches of an
/// insertion sort are unpredictable; measured, this is on par with it or up to ~1% faster per run.
inline void sort_small(Index* first, Index* last) {
    constexpr std::ptrdiff_t kSmall = 12;
    const std::ptrdiff_t n = last - first;
    if (n > kSmall) {
        std::sort(first, last);
        return;
    }
    Index tmp[kSmall];
    for (std::ptrdiff_t a = 0; a < n; ++a) {
        std::ptrdiff_t rank = 0;
        for (std::ptrdiff_t b = 0; b < n; ++b) rank += (first[b] < first[a]) | ((first[b] == first[a]) & (b < a));
        tmp[rank] = first[a];
    }
    std::copy(tmp, tmp + n, first);
}

/// Maps the pages of [p, p + bytes) by one system call (MADV_POPULATE_WRITE, Linux 5.14+) instead
/// of one page fault each; elsewhere, on older kernels or for small buffers it does nothing and the
/// pages fault in as before. Measured: page faults are about a sixth of limited_cells at 1e6 agents
/// (700 MB of results and scratch), and mapping the pages up front takes about a quarter off that.
inline void prefault(const void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    constexpr std::uintptr_t kPage = 4096;
    if (bytes < (std::size_t{1} << 20)) return;
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t lo = (at + kPage - 1) & ~(kPage - 1), hi = (at + bytes) & ~(kPage - 1);
    if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_POPULATE_WRITE);  // a hint: failure is harmless
#else
    (void)p;
    (void)bytes;
#endif
}

/// v.assign(n, value) on prefaulted pages.
template <class T>
void assign_prefaulted(std::vector<T>& v, std::size_t n, const T& value = T()) {
    v.clear();
    v.reserve(n);
    prefault(v.data(), n * sizeof(T));
    v.assign(n, value);
}

/// Where each agent sits in `order` (the grid order the drivers compute in): pos_of[i].
inline std::vector<Index> positions_of(const std::vector<Index>& order) {
    std::vector<Index> pos_of(order.size());
    for (std::size_t pos = 0; pos < order.size(); ++pos) pos_of[static_cast<std::size_t>(order[pos])] = static_cast<Index>(pos);
    return pos_of;
}

/// How many agents ahead the gathers prefetch.
inline constexpr Index kAhead = 16;

/// Reads per-agent results stored by grid position in input order: fn(i, pos, by_pos[pos]) with
/// pos = pos_of[i]. The reads are scattered, so a few agents ahead are prefetched and the misses
/// overlap.
template <class R, class Fn>
void gather_in_input_order(const std::vector<Index>& pos_of, const std::vector<R>& by_pos, Fn&& fn) {
    const auto n = static_cast<Index>(pos_of.size());
    for (Index i = 0; i < n; ++i) {
        if (i + kAhead < n) prefetch(&by_pos[static_cast<std::size_t>(pos_of[static_cast<std::size_t>(i + kAhead)])]);
        const auto pos = static_cast<std::size_t>(pos_of[static_cast<std::size_t>(i)]);
        fn(i, pos, by_pos[pos]);
    }
}

/// Progress of a parallel loop over blocks: counts finished agents, calls the callback from the
/// calling thread (OpenMP thread 0), and turns an exception thrown by the callback (e.g. a Python
/// KeyboardInterrupt) into a cancellation that is rethrown after the parallel region.
class ProgressTracker {
public:
    ProgressTracker(const ProgressFn& progress, Index total) : progress_(progress), total_(total) {}
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
    void block_done(Index agents) {
        const Index now = done_.fetch_add(agents) + agents;
#ifdef _OPENMP
        const bool caller = omp_get_thread_num() == 0;
#else
        const bool caller = true;
#endif
        if (!progress_ || !caller) return;
        try {
            progress_(now, total_);
        } catch (...) {
            failure_ = std::current_exception();
            cancelled_ = true;
        }
    }
    /// After the parallel region: rethrow the callback's exception, if it threw.
    void rethrow_if_failed() const {
        if (failure_) std::rethrow_exception(failure_);
    }
    /// At the very end: the callback sees (total, total).
    void report_all() const {
        if (progress_) progress_(total_, total_);
    }

private:
    const ProgressFn& progress_;
    Index total_;
    std::atomic<Index> done_{0};
    std::atomic<bool> cancelled_{false};
    std::exception_ptr failure_;
};

/// Agents per block of the parallel drivers (the unit of scheduling and of progress reports).
inline constexpr Index kBlock = 2048;

/// OpenMP team size for `blocks` blocks: `threads` (0 = all cores), never more than one thread per
/// block, so small inputs start no team.
inline int thread_team(int threads, Index blocks) {
#ifdef _OPENMP
    const int wanted = threads > 0 ? threads : omp_get_max_threads();
#else
    const int wanted = 1;
    (void)threads;
#endif
    return static_cast<int>(std::min<Index>(wanted, std::max<Index>(blocks, 1)));
}

/// Throws CoincidentError naming the lowest pair (i, j), i < j, of coinciding agents.
inline void require_distinct(const GridIndex& index, const Points& pts) {
    const auto [i, j] = index.first_duplicate();
    if (i < 0) return;
    char at[64];
    std::snprintf(at, sizeof at, "(%.17g, %.17g)", pts(i, 0), pts(i, 1));
    throw CoincidentError("points[" + std::to_string(i) + "] and points[" + std::to_string(j) +
                              "] coincide at " + at + "; their Voronoi cells are undefined",
                          i, j);
}

}  // namespace detail

/// Every agent's limited cell V_i ∩ B(p_i, radius) (the radius-limited Voronoi partition).
///
/// \param threads number of OpenMP threads; 0 = all cores. Results do not depend on it.
/// \param progress optional callback (done, total), called from the calling thread.
/// \throws InputError for a bad radius or non-finite coordinates; CoincidentError for coinciding
///         agents (lowest pair named).
/// \note Scan gives Boundary Scan's cells bit for bit; most are computed by the certified clipping
///       filter of cells/certified_clip.hpp (O(m) per agent in a swarm: the nearest agents shrink
///       the cell, the others fail a one-comparison screen), the rest by Boundary Scan itself
///       (O(m log m)); m = agents within 2R. Chords is O(m^2) per agent in the worst case. The
///       duplicate check is O(n) expected (identical points share a grid cell). Memory O(n m).
///       Thread-safe.
inline LimitedPartition limited_cells(PointsRef points, double radius, Method method = Method::Scan,
                                      int threads = 0, const ProgressFn& progress = nullptr) {
    detail::require_finite_radius(radius);
    detail::require_finite_points(points, "points");
    const Index n = points.rows();
    LimitedPartition out;
    out.radius = radius;
    out.method = method;
    out.points = points;
    detail::assign_prefaulted(out.areas, static_cast<std::size_t>(n));
    detail::assign_prefaulted(out.perimeters, static_cast<std::size_t>(n));
    out.centroids.resize(n, 2);
    detail::prefault(out.centroids.data(), static_cast<std::size_t>(out.centroids.size()) * sizeof(double));
    detail::assign_prefaulted(out.candidates, static_cast<std::size_t>(n));
    if (n == 0) return out;

    const GridIndex index(out.points, 2.0 * radius);
    detail::require_distinct(index, out.points);
    const std::vector<Index>& order = index.grid_order();
    // Agents are processed in grid order, in blocks; each block appends its cells to its own buffers,
    // and every per-agent result is stored by grid position, so the hot loop writes sequentially.
    // One gather pass then lays the results out in input order (sequential writes, independent
    // reads): scattered writes from the hot loop cost a cache miss each at 1e6 agents.
    struct Block {
        std::vector<Piece> pieces;
    };
    const Index block = detail::kBlock;
    const Index nblocks = (n + block - 1) / block;
    const int team = detail::thread_team(threads, nblocks);
    std::vector<Block> blocks(static_cast<std::size_t>(nblocks));
    struct Result {  // one agent's scalars, by grid position
        double area, perimeter, cx, cy;
        Index candidates, pieces, edges, first;  // first: offset of its pieces in its block's buffer
    };
    std::vector<Result> by_pos;
    detail::assign_prefaulted(by_pos, static_cast<std::size_t>(n), Result{});
    detail::ProgressTracker tracker(progress, n);

#pragma omp parallel num_threads(team)
    {
        std::vector<detail::Candidate> cand;
        LimitedCell cell;
        detail::CellWorkspace ws;
        detail::ClipWorkspace clip_ws;
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            if (tracker.cancelled()) continue;
            Block& blk = blocks[static_cast<std::size_t>(b)];
            const Index lo = b * block, hi = std::min(n, lo + block);
            // About six pieces per cell in a swarm: room for seven, so the buffer rarely regrows
            // (each regrowth copies it and faults in fresh pages).
            blk.pieces.reserve(static_cast<std::size_t>(hi - lo) * 7);
            detail::prefault(blk.pieces.data(), blk.pieces.capacity() * sizeof(Piece));
            for (Index pos = lo; pos < hi; ++pos) {
                const auto pp = static_cast<std::size_t>(pos);
                const Vec2 c = index.point_at(pp);
                if (method == Method::Scan) {
                    // Boundary Scan's cell: the certified clipping filter on the candidates as the
                    // query finds them (agents are distinct: checked above), Boundary Scan itself
                    // when the filter gives up. The previous agent's count sets the near radius.
                    clip_ws.start(c, detail::near_first_sq(radius, clip_ws.m));
                    index.for_each_within_at(pp, radius, [&](const Vec2& p, Index j) { clip_ws.add(p, j); });
                    if (!detail::certified_clip_loaded(radius, cell, clip_ws)) {
                        clip_ws.candidates(cand);
                        detail::boundary_scan(c, cand, radius, cell, ws);
                    }
                } else {
                    index.within_at(pp, radius, cand);
                    detail::rcvc(c, cand, radius, cell, ws);
                }
                const CellMeasures m = cell.measures();
                Index edges = 0;
                for (const Piece& p : cell.pieces) edges += p.is_arc() ? 0 : 1;
                by_pos[pp] = {m.area, m.perimeter, m.centroid.x(), m.centroid.y(), cell.candidates,
                              static_cast<Index>(cell.pieces.size()), edges, static_cast<Index>(blk.pieces.size())};
                blk.pieces.insert(blk.pieces.end(), cell.pieces.begin(), cell.pieces.end());
            }
            tracker.block_done(hi - lo);
        }
    }
    tracker.rethrow_if_failed();

    // Lay out the results, the pieces and the neighbour CSR in input order.
    const std::vector<Index> pos_of = detail::positions_of(order);
    detail::assign_prefaulted(out.piece_ptr, static_cast<std::size_t>(n) + 1);
    detail::assign_prefaulted(out.indptr, static_cast<std::size_t>(n) + 1);
    // Where each agent's pieces are, in input order: the piece pass then reads only the pieces at
    // random, not the records again.
    std::vector<const Piece*> piece_src(static_cast<std::size_t>(n));
    detail::gather_in_input_order(pos_of, by_pos, [&](Index i, std::size_t pos, const Result& r) {
        const auto ii = static_cast<std::size_t>(i);
        piece_src[ii] = blocks[pos / static_cast<std::size_t>(block)].pieces.data() + r.first;
        out.areas[ii] = r.area;
        out.perimeters[ii] = r.perimeter;
        out.centroids(i, 0) = r.cx;
        out.centroids(i, 1) = r.cy;
        out.candidates[ii] = r.candidates;
        out.piece_ptr[ii + 1] = out.piece_ptr[ii] + r.pieces;
        out.indptr[ii + 1] = out.indptr[ii] + r.edges;
    });
    const auto total = static_cast<std::size_t>(out.piece_ptr.back());
    detail::assign_prefaulted(out.piece_neighbor, total);
    detail::assign_prefaulted(out.piece_x, total);
    detail::assign_prefaulted(out.piece_y, total);
    detail::assign_prefaulted(out.piece_span, total);
    detail::assign_prefaulted(out.indices, static_cast<std::size_t>(out.indptr.back()));
#pragma omp parallel for num_threads(team) schedule(static)
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        if (i + detail::kAhead < n) {
            const Piece* ahead = piece_src[ii + detail::kAhead];
            for (int line = 0; line < 4; ++line) detail::prefetch(ahead + 2 * line);
        }
        const Piece* src = piece_src[ii];
        auto dst = static_cast<std::size_t>(out.piece_ptr[ii]);
        auto nb = static_cast<std::size_t>(out.indptr[ii]);
        const Index cnt = out.piece_ptr[ii + 1] - out.piece_ptr[ii];
        for (Index k = 0; k < cnt; ++k, ++dst) {
            out.piece_neighbor[dst] = src[k].neighbor;
            out.piece_x[dst] = src[k].start.x();
            out.piece_y[dst] = src[k].start.y();
            out.piece_span[dst] = src[k].arc_span;
            if (!src[k].is_arc()) out.indices[nb++] = src[k].neighbor;
        }
        detail::sort_small(out.indices.data() + out.indptr[ii], out.indices.data() + out.indptr[ii + 1]);
    }
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
