// All agents at once: each agent's limited cell from the agents within 2R, found with a uniform-grid
// index, computed in parallel (OpenMP), stored compactly in input order.
#pragma once

#include "dvoronoi/cells/certified_clip.hpp"
#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/core/grid_index.hpp"
#include "dvoronoi/core/parallel.hpp"
#include "dvoronoi/partition/detail/cell_columns.hpp"
#include "dvoronoi/partition/limited_result.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace dvoronoi {

namespace detail {

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

/// One thread's scratch for limited cells: the candidates, the cell and the workspaces of the
/// three algorithms, and how many cells each computed.
struct LimitedScratch {
    explicit LimitedScratch(int t) : thread(t) {}
    int thread;
    std::vector<Candidate> cand;
    LimitedCell cell;
    CellWorkspace ws;
    ClipWorkspace clip_ws;
    AlgorithmCounts ran;
};

/// The limited cell of the agent at grid position `pos` (centre c) into s.cell by `method`.
inline void limited_cell_at(const GridIndex& index, std::size_t pos, const Vec2& c, double radius, Method method,
                            LimitedScratch& s) {
    if (method == Method::Auto) {
        // Boundary Scan's cell: the certified clipping filter on the candidates as the query finds
        // them (agents are distinct: checked before), Boundary Scan itself when the filter gives up.
        // The previous agent's count sets the near radius.
        s.clip_ws.start(c, near_first_sq(radius, s.clip_ws.m));
        index.for_each_batch_within_at(pos, radius, [&](auto... batch) { s.clip_ws.add_batch(batch...); });
        if (certified_clip_loaded(radius, s.cell, s.clip_ws)) {
            ++s.ran.clip;
        } else {
            s.clip_ws.candidates(s.cand);
            boundary_scan(c, s.cand, radius, s.cell, s.ws);
            ++s.ran.scan;
        }
    } else if (method == Method::Scan) {
        index.within_at(pos, radius, s.cand);
        boundary_scan(c, s.cand, radius, s.cell, s.ws);
        ++s.ran.scan;
    } else {
        index.within_at(pos, radius, s.cand);
        rcvc(c, s.cand, radius, s.cell, s.ws);
        ++s.ran.chords;
    }
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
    const int team = detail::thread_team(threads, detail::block_count(n));
    LimitedPartition out;
    out.radius = radius;
    out.method = method;
    detail::CellColumns columns(out, points, team);
    if (n == 0) return out;

    // Index the agents; cells are computed in grid order, so queries read memory already cached.
    const GridIndex index(out.points, 2.0 * radius, team);
    detail::require_distinct(index, out.points);
    const std::vector<Index>& order = index.grid_order();

    // Every agent's cell, stored as it is computed (see partition/detail/cell_columns.hpp).
    detail::ProgressTracker tracker(progress, n);
    detail::for_each_block(
        n, team, tracker, [](int thread) { return detail::LimitedScratch(thread); },
        [&](detail::LimitedScratch& s, Index pos) {
            const auto pp = static_cast<std::size_t>(pos);
            detail::limited_cell_at(index, pp, index.point_at(pp), radius, method, s);
            const Index ahead = pos + detail::kWriteAhead < n ? order[pp + detail::kWriteAhead] : -1;
            columns.store(order[pp], s.cell, s.thread, ahead);
        },
        [&](Index pos) { return order[static_cast<std::size_t>(pos)]; },
        [&](const detail::LimitedScratch& s) { out.computed_by += s.ran; });

    // The pieces and the neighbour CSR in input order.
    columns.stitch();
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
