// All agents at once: each agent's limited cell from the agents within 2R, found with a uniform-grid
// index, computed in parallel (OpenMP), stored compactly in input order.
#pragma once

#include "dvoronoi/cells/certified_clip.hpp"
#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/core/grid_index.hpp"
#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>
#include <type_traits>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace dvoronoi {

/// How many cells each algorithm computed in one limited_cells call (they add up to n).
struct AlgorithmCounts {
    Index clip = 0;    ///< the certified clipping filter (cells/certified_clip.hpp; Method::Auto only)
    Index scan = 0;    ///< Boundary Scan (every cell under Method::Scan; the filter's give-ups under Auto)
    Index chords = 0;  ///< RCVC (Method::Chords)
};

/// The range-limited Voronoi partition of n agents (the result of limited_cells).
///
/// Cells are stored flat: agent i owns pieces [piece_ptr[i], piece_ptr[i+1]); a piece starts at
/// (piece_x, piece_y), ends where the next piece of the same agent starts (cyclically), and is an edge
/// with neighbour piece_neighbor >= 0 or an arc (kArc) sweeping piece_span radians.
/// Limited neighbours are the CSR pair (indptr, indices), ascending per agent (scipy's layout).
struct LimitedPartition {
    double radius = 0.0;
    Method method = Method::Auto;
    AlgorithmCounts computed_by;  ///< which algorithm computed how many of the cells
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

namespace detail {

/// Sorts eight values ascending: Batcher's odd-even merge network, 19 compare-exchanges. Each
/// exchange selects by a mask, not a branch: its outcome is a coin flip, and as branches (what
/// the compiler made of std::min/max here) half of them were mispredicted, which took twice the time.
inline void sort8(Index (&v)[8]) {
    const auto exchange = [&v](int a, int b) {
        const Index x = v[a], y = v[b];
        const Index d = (x ^ y) & -static_cast<Index>(y < x);  // x ^ y if they must swap, else 0
        v[a] = x ^ d;
        v[b] = y ^ d;
    };
    exchange(0, 2), exchange(1, 3), exchange(4, 6), exchange(5, 7);
    exchange(0, 4), exchange(1, 5), exchange(2, 6), exchange(3, 7);
    exchange(0, 1), exchange(2, 3), exchange(4, 5), exchange(6, 7);
    exchange(2, 4), exchange(3, 5);
    exchange(1, 4), exchange(3, 6);
    exchange(1, 2), exchange(3, 4), exchange(5, 6);
}

/// Sorts a handful of indices (a cell's neighbours) ascending. Up to eight (the usual case) go
/// through sort8, padded with the largest index; more through std::sort. The values stay in
/// registers: the copies in and out are loops of constant length.
inline void sort_small(Index* first, Index* last) {
    const std::ptrdiff_t n = last - first;
    if (n > 8) {
        std::sort(first, last);
        return;
    }
    Index v[8];
    for (std::ptrdiff_t t = 0; t < 8; ++t) v[t] = t < n ? first[t] : std::numeric_limits<Index>::max();
    sort8(v);
    for (std::ptrdiff_t t = 0; t < 8; ++t)
        if (t < n) first[t] = v[t];
}

/// A cell's limited neighbours from its pieces' neighbours `run` (arcs are negative): the edges'
/// neighbours, ascending, written to out; returns how many. Measured on a swarm of 1e6 agents
/// (about six pieces each): 25 ms, against 46 ms for a filter loop and the branching network.
inline std::size_t sorted_edge_neighbors(const Index* run, std::size_t len, Index* out) {
    if (len > 8) {
        Index* last = out;
        for (std::size_t k = 0; k < len; ++k)
            if (run[k] >= 0) *last++ = run[k];
        std::sort(out, last);
        return static_cast<std::size_t>(last - out);
    }
    constexpr Index kMax = std::numeric_limits<Index>::max();
    Index v[8] = {kMax, kMax, kMax, kMax, kMax, kMax, kMax, kMax};
    std::size_t count = 0;
    for (std::size_t k = 0; k < len; ++k) {
        // An edge is kept (count moves on); an arc leaves the padding in its slot.
        const Index r = run[k];
        const Index arc = -static_cast<Index>(r < 0);  // all ones for an arc
        v[count] = (r & ~arc) | (kMax & arc);
        count += static_cast<std::size_t>(arc + 1);
    }
    sort8(v);
    for (std::size_t t = 0; t < 8; ++t)
        if (t < count) out[t] = v[t];
    return count;
}

/// How many agents ahead the gathers prefetch.
inline constexpr Index kAhead = 16;
/// How many agents ahead a driver prefetches the lines it will write an agent's results to, in
/// input order: one agent is over a microsecond of work, and more lines in flight stall the loads
/// the work needs (measured: 4 ahead beats 2, 8 and 16 by 1-3%; none is 10% slower).
inline constexpr Index kWriteAhead = 4;

/// A piece with a nonzero span (an arc), by its place in the output: the k-th piece of agent's cell.
struct ArcSpan {
    Index agent;
    Index k;
    double span;
};

/// Pieces as the columns of LimitedPartition's piece arrays; a thread appends its cells' pieces here
/// in the order it computes them. Spans are not a column: in a swarm only a few pieces per thousand
/// are arcs, so the arcs are listed apart and written into a zeroed column at the end. That saves
/// a column of fresh pages (at 1e6 agents 48 MB, each page a fault and a zeroing) and a pass that
/// would put it into input order.
struct PieceColumns {
    std::vector<double> x, y;
    std::vector<Index> neighbor;
    std::vector<ArcSpan> arcs;
    std::size_t mapped = 0;  // values up to here are on mapped pages

    Index size() const noexcept { return static_cast<Index>(x.size()); }
    void reserve(std::size_t pieces) {
        x.reserve(pieces);
        y.reserve(pieces);
        neighbor.reserve(pieces);
    }
    void append(Index agent, const std::vector<Piece>& pieces) {
        if (x.size() + pieces.size() > mapped) map_ahead();
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const Piece& p = pieces[k];
            x.push_back(p.start.x());
            y.push_back(p.start.y());
            neighbor.push_back(p.neighbor);
            if (p.arc_span != 0.0) arcs.push_back({agent, static_cast<Index>(k), p.arc_span});
        }
    }
    /// Maps the next pages of the reserved room in one call per column (see prefault).
    void map_ahead() {
        constexpr std::size_t kStep = std::size_t{1} << 17;  // values: 1 MB per column
        const std::size_t to = std::min(x.capacity(), std::max(mapped, x.size()) + kStep);
        if (to <= mapped) return;
        const std::size_t at = std::max(mapped, x.size());
        prefault(x.data() + at, (to - at) * sizeof(double));
        prefault(y.data() + at, (to - at) * sizeof(double));
        prefault(neighbor.data() + at, (to - at) * sizeof(Index));
        mapped = to;
    }
    /// parts[0] followed by parts[1], ... (each freed once appended); up to `team` threads copy
    /// the three columns.
    static PieceColumns concatenate(std::vector<PieceColumns>& parts, int team) {
        PieceColumns all = std::move(parts.front());
        std::size_t more = 0;
        for (std::size_t t = 1; t < parts.size(); ++t) more += parts[t].x.size();
        if (more > 0 && all.x.size() + more <= all.x.capacity())  // the pages the copies land on, by the team
            prefault_together({{all.x.data() + all.x.size(), more * sizeof(double)},
                               {all.y.data() + all.y.size(), more * sizeof(double)},
                               {all.neighbor.data() + all.neighbor.size(), more * sizeof(Index)}},
                              team);
        const auto join = [&](auto column) {
            auto& into = all.*column;
            for (std::size_t t = 1; t < parts.size(); ++t) {
                const auto part = std::move(parts[t].*column);  // freed once appended
                into.insert(into.end(), part.begin(), part.end());
            }
        };
#pragma omp parallel for num_threads(std::min(team, 3)) schedule(static, 1) if (parts.size() > 1)
        for (int c = 0; c < 3; ++c) {
            if (c == 0) join(&PieceColumns::x);
            if (c == 1) join(&PieceColumns::y);
            if (c == 2) join(&PieceColumns::neighbor);
        }
        join(&PieceColumns::arcs);
        return all;
    }
};

/// Puts runs of 8-byte values in CSR order: the run of agent i moves from [from(i), from(i) + len)
/// of `src` to [ptr[i], ptr[i + 1]) of `dst`, len = ptr[i + 1] - ptr[i]; then moved(i, run, len)
/// sees it in its new place. The reads are scattered, so a few agents ahead are prefetched. `src`
/// is read as bytes: it may be another column's storage holding a copy of these values.
template <class T, class From, class Moved>
void move_runs(T* dst, const void* src, const std::vector<Index>& ptr, From&& from, int team, Moved&& moved) {
    static_assert(sizeof(T) == 8 && std::is_trivially_copyable<T>::value, "columns of 8-byte values");
    const auto n = static_cast<Index>(ptr.size()) - 1;
    const auto* old = static_cast<const unsigned char*>(src);
#pragma omp parallel for num_threads(team) schedule(static)
    for (Index i = 0; i < n; ++i) {
        if (i + kAhead < n) prefetch(old + 8 * from(i + kAhead));
        const auto at = static_cast<std::size_t>(ptr[static_cast<std::size_t>(i)]);
        const auto len = static_cast<std::size_t>(ptr[static_cast<std::size_t>(i) + 1]) - at;
        const unsigned char* run = old + 8 * from(i);
        for (std::size_t k = 0; k < len; ++k) std::memcpy(dst + at + k, run + 8 * k, 8);  // a load and a store each
        moved(i, dst + at, len);
    }
}

/// Where each agent sits in `order` (the grid order the drivers compute in): pos_of[i].
inline std::vector<Index> positions_of(const std::vector<Index>& order) {
    std::vector<Index> pos_of(order.size());
    for (std::size_t pos = 0; pos < order.size(); ++pos) pos_of[static_cast<std::size_t>(order[pos])] = static_cast<Index>(pos);
    return pos_of;
}

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

/// Where an agent's run starts while each thread appends runs to its own column: offset * team +
/// thread. Once the columns are joined in thread order (sizes: their lengths before), to_joined
/// turns these places into offsets in the joined column.
inline Index column_place(std::size_t offset, int team, int thread) {
    return static_cast<Index>(offset) * team + thread;
}
inline void to_joined(std::vector<Index>& places, const std::vector<Index>& sizes) {
    const auto team = static_cast<Index>(sizes.size());
    if (team <= 1) return;  // offset * 1 + 0: already the offset
    std::vector<Index> base(sizes.size(), 0);
    for (std::size_t t = 1; t < base.size(); ++t) base[t] = base[t - 1] + sizes[t - 1];
    for (Index& at : places) at = base[static_cast<std::size_t>(at % team)] + at / team;
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
///         agents (lowest pair named); RangeError for a radius outside [kMinRadius, kMaxRadius], and,
///         naming the agent ("points[17]: ..."), for an exact test that over- or underflows
///         (coordinates far outside the exact range of core/expansion.hpp) or a Chords cell with more
///         than kMaxChordsCandidates agents within 2R. The agent named is the first in grid order
///         that fails, whatever the thread count.
/// \note Methods (docs/spec.md, API conventions); all three give the same cells, and
///       `computed_by` counts which algorithm computed each:
///       - Auto (default), our fast path, not a published algorithm: the certified clipping filter of
///         cells/certified_clip.hpp (O(m) per agent in a swarm: the nearest agents shrink the cell,
///         the others fail a one-comparison screen), Boundary Scan where the filter gives up (ties,
///         concurrent bisectors, vertices on the circle: none in a uniform swarm). Bit-identical to
///         Scan's cells.
///       - Scan: Boundary Scan (He, Feng & Ren 2018) on every agent, O(m log m) (it sorts all m
///         bisectors); about twice Auto's time in a uniform swarm.
///       - Chords: RCVC (Guruprasad & Dasgupta 2012) on every agent, O(m^2) in the worst case.
///       m = agents within 2R. The duplicate check is O(n) expected (identical points share a grid
///       cell). Memory O(n m). Thread-safe.
inline LimitedPartition limited_cells(PointsRef points, double radius, Method method = Method::Auto,
                                      int threads = 0, const ProgressFn& progress = nullptr) {
    detail::require_finite_radius(radius);
    detail::require_finite_points(points, "points");
    const Index n = points.rows();
    const Index block = detail::kBlock;
    const Index nblocks = (n + block - 1) / block;
    const int team = detail::thread_team(threads, nblocks);
    LimitedPartition out;
    out.radius = radius;
    out.method = method;
    // The per-agent arrays. All but the points are written in scattered (input) order, so they get
    // huge pages (see advise_huge_pages); the team maps all their pages together first.
    const auto un = static_cast<std::size_t>(n);
    out.points.resize(n, 2);
    out.centroids.resize(n, 2);
    // Where each agent's pieces start: its place in its thread's columns during the loop (see
    // column_place), the offset in the joined columns after it.
    std::vector<Index> source;
    const auto room = [](auto& v, std::size_t size) {
        v.reserve(size);
        detail::advise_huge_pages(v.data(), size * sizeof(v[0]));
        return std::pair<const void*, std::size_t>(v.data(), size * sizeof(v[0]));
    };
    const std::size_t xy_bytes = 2 * un * sizeof(double);
    detail::advise_huge_pages(out.centroids.data(), xy_bytes);
    detail::prefault_together({{out.points.data(), xy_bytes}, {out.centroids.data(), xy_bytes}, room(out.areas, un),
                               room(out.perimeters, un), room(out.candidates, un), room(out.piece_ptr, un + 1),
                               room(out.indptr, un + 1), room(source, un)},
                              team);
    out.points = points;
    out.areas.assign(un, 0.0);
    out.perimeters.assign(un, 0.0);
    out.candidates.assign(un, 0);
    out.piece_ptr.assign(un + 1, 0);  // counts, summed below
    out.indptr.assign(un + 1, 0);
    source.assign(un, 0);
    if (n == 0) return out;

    const GridIndex index(out.points, 2.0 * radius, team);
    detail::require_distinct(index, out.points);
    const std::vector<Index>& order = index.grid_order();
    // Agents are processed in grid order (queries then read memory that is already cached), in
    // blocks. Each agent's scalars and counts go straight to their places in input order (the lines
    // are prefetched for writing a few agents ahead); its pieces are appended to its thread's piece
    // columns, which become the output columns, put into input order one column at a time.
    // Why this layout: a fresh page costs a fault and a zeroing (and on a VM that hands freed memory
    // back to the host, a host fault), so every byte of scratch is paid for; this keeps the scratch
    // to one column of pieces, against three times the pieces' size when they were staged whole.
    std::vector<detail::PieceColumns> columns(static_cast<std::size_t>(team));
    detail::ProgressTracker tracker(progress, n);

#pragma omp parallel num_threads(team)
    {
        const int me = detail::thread_id();
        detail::PieceColumns& mine = columns[static_cast<std::size_t>(me)];
        // About six pieces per cell in a swarm: room for seven per agent. Room that is never written
        // costs address space only; the first thread's columns take the others' in the end.
        mine.reserve(static_cast<std::size_t>(me == 0 ? n : n / team + block) * 7);
        std::vector<detail::Candidate> cand;
        LimitedCell cell;
        detail::CellWorkspace ws;
        detail::ClipWorkspace clip_ws;
        AlgorithmCounts ran;  // this thread's
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            const Index lo = b * block, hi = std::min(n, lo + block);
            if (tracker.skip(lo)) continue;
            Index pos = lo;
            try {
                for (; pos < hi; ++pos) {
                    const auto pp = static_cast<std::size_t>(pos);
                    if (pos + detail::kWriteAhead < n) {
                        const auto a = static_cast<std::size_t>(order[pp + detail::kWriteAhead]);
                        detail::prefetch_for_write(&out.areas[a]);
                        detail::prefetch_for_write(&out.perimeters[a]);
                        detail::prefetch_for_write(out.centroids.data() + 2 * a);
                        detail::prefetch_for_write(&out.candidates[a]);
                        detail::prefetch_for_write(&out.piece_ptr[a + 1]);
                        detail::prefetch_for_write(&out.indptr[a + 1]);
                        detail::prefetch_for_write(&source[a]);
                    }
                    const Vec2 c = index.point_at(pp);
                    if (method == Method::Auto) {
                        // Boundary Scan's cell: the certified clipping filter on the candidates as the
                        // query finds them (agents are distinct: checked above), Boundary Scan itself
                        // when the filter gives up. The previous agent's count sets the near radius.
                        clip_ws.start(c, detail::near_first_sq(radius, clip_ws.m));
                        index.for_each_batch_within_at(pp, radius, [&](auto... batch) { clip_ws.add_batch(batch...); });
                        if (detail::certified_clip_loaded(radius, cell, clip_ws)) {
                            ++ran.clip;
                        } else {
                            clip_ws.candidates(cand);
                            detail::boundary_scan(c, cand, radius, cell, ws);
                            ++ran.scan;
                        }
                    } else if (method == Method::Scan) {
                        index.within_at(pp, radius, cand);
                        detail::boundary_scan(c, cand, radius, cell, ws);
                        ++ran.scan;
                    } else {
                        index.within_at(pp, radius, cand);
                        detail::rcvc(c, cand, radius, cell, ws);
                        ++ran.chords;
                    }
                    const CellMeasures m = cell.measures();
                    const auto i = static_cast<std::size_t>(order[pp]);
                    out.areas[i] = m.area;
                    out.perimeters[i] = m.perimeter;
                    out.centroids(static_cast<Index>(i), 0) = m.centroid.x();
                    out.centroids(static_cast<Index>(i), 1) = m.centroid.y();
                    out.candidates[i] = cell.candidates;
                    Index edges = 0;
                    for (const Piece& p : cell.pieces) edges += p.is_arc() ? 0 : 1;
                    out.piece_ptr[i + 1] = static_cast<Index>(cell.pieces.size());
                    out.indptr[i + 1] = edges;
                    source[i] = detail::column_place(mine.x.size(), team, me);
                    mine.append(static_cast<Index>(i), cell.pieces);
                }
            } catch (...) {
                tracker.fail(pos, order[static_cast<std::size_t>(pos)]);
            }
            tracker.block_done(hi - lo);
        }
#pragma omp critical(dvoronoi_limited_counts)
        {
            out.computed_by.clip += ran.clip;
            out.computed_by.scan += ran.scan;
            out.computed_by.chords += ran.chords;
        }
    }
    tracker.rethrow_if_failed();

    // Counts to offsets; the threads' columns one after another (where each thread's pieces start).
    for (Index i = 0; i < n; ++i) {
        out.piece_ptr[static_cast<std::size_t>(i) + 1] += out.piece_ptr[static_cast<std::size_t>(i)];
        out.indptr[static_cast<std::size_t>(i) + 1] += out.indptr[static_cast<std::size_t>(i)];
    }
    std::vector<Index> sizes;
    for (const detail::PieceColumns& part : columns) sizes.push_back(part.size());
    detail::to_joined(source, sizes);
    detail::PieceColumns all = detail::PieceColumns::concatenate(columns, team);
    // Each column into input order: agent i's pieces move from source[i] to piece_ptr[i]. x goes
    // into fresh storage; the neighbours (of another type) are copied into x's old storage and moved
    // back; y goes into x's old storage; y's old storage, zeroed, takes the arcs' spans. So one
    // column of scratch serves all three.
    const auto from = [&](Index i) { return static_cast<std::size_t>(source[static_cast<std::size_t>(i)]); };
    const auto nothing = [](Index, const void*, std::size_t) {};
    std::vector<double> free_column;
    const auto pieces = all.x.size(), edges = static_cast<std::size_t>(out.indptr.back());
    free_column.reserve(pieces);
    out.indices.reserve(edges);
    detail::prefault_together({{free_column.data(), pieces * sizeof(double)}, {out.indices.data(), edges * sizeof(Index)}}, team);
    free_column.assign(pieces, 0.0);
    out.indices.assign(edges, 0);
    detail::move_runs(free_column.data(), all.x.data(), out.piece_ptr, from, team, nothing);
    std::swap(free_column, all.x);
    std::memcpy(free_column.data(), all.neighbor.data(), all.neighbor.size() * sizeof(Index));
    // Limited neighbours: the edges' neighbours, ascending.
    detail::move_runs(all.neighbor.data(), free_column.data(), out.piece_ptr, from, team,
                      [&](Index i, const Index* run, std::size_t len) {
                          detail::sorted_edge_neighbors(run, len, out.indices.data() + out.indptr[static_cast<std::size_t>(i)]);
                      });
    detail::move_runs(free_column.data(), all.y.data(), out.piece_ptr, from, team, nothing);
    std::swap(free_column, all.y);
    std::fill(free_column.begin(), free_column.end(), 0.0);
    for (const detail::ArcSpan& a : all.arcs)
        free_column[static_cast<std::size_t>(out.piece_ptr[static_cast<std::size_t>(a.agent)] + a.k)] = a.span;
    out.piece_x = std::move(all.x);
    out.piece_y = std::move(all.y);
    out.piece_span = std::move(free_column);
    out.piece_neighbor = std::move(all.neighbor);
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
