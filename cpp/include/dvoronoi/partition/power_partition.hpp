// All agents of a heterogeneous team at once (docs/spec.md, heterogeneous teams): agent i's cell
// W_i = power cell (weights R_i^2) ∩ B(p_i, R_i) from the agents within R_i + R_max (a uniform-grid
// index), in parallel (OpenMP), in input order.
#pragma once

#include "dvoronoi/cells/certified_power_clip.hpp"
#include "dvoronoi/cells/power_boundary_scan.hpp"
#include "dvoronoi/cells/power_cell.hpp"
#include "dvoronoi/cells/power_rcvc.hpp"
#include "dvoronoi/partition/limited_partition.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>
#include <string>
#include <vector>

namespace dvoronoi {

namespace detail {

/// Throws CoincidentError naming the lowest pair (i, j), i < j, of agents with the same position and
/// the same radius (the same position with different radii is allowed: the larger disk holds the
/// cell). O(n log n).
inline void require_distinct_weighted(const Points& pts, const std::vector<double>& radii) {
    std::vector<Index> order(static_cast<std::size_t>(pts.rows()));
    std::iota(order.begin(), order.end(), Index{0});
    const auto key = [&](Index i) {
        return std::make_tuple(pts(i, 0), pts(i, 1), radii[static_cast<std::size_t>(i)], i);
    };
    std::sort(order.begin(), order.end(), [&](Index a, Index b) { return key(a) < key(b); });
    Index bi = -1, bj = -1;
    for (std::size_t t = 0; t + 1 < order.size(); ++t) {
        const Index a = order[t], b = order[t + 1];  // a < b within a run of equal (x, y, R)
        if (pts(a, 0) == pts(b, 0) && pts(a, 1) == pts(b, 1) &&
            radii[static_cast<std::size_t>(a)] == radii[static_cast<std::size_t>(b)] &&
            (bi < 0 || a < bi || (a == bi && b < bj))) {
            // Only the first pair of each run can be lowest: a is the run's smallest index so far.
            bi = a;
            bj = b;
        }
    }
    if (bi < 0) return;
    char at[64];
    std::snprintf(at, sizeof at, "(%.17g, %.17g)", pts(bi, 0), pts(bi, 1));
    throw CoincidentError("points[" + std::to_string(bi) + "] and points[" + std::to_string(bj) + "] coincide at " + at +
                              " with the same radius; their cells are undefined",
                          bi, bj);
}

/// One thread's workspace for heterogeneous cells, and what it computed.
struct PowerScratch {
    explicit PowerScratch(int t) : thread(t) {}
    int thread;
    std::vector<Candidate> cand;
    std::vector<double> cand_r;
    LimitedCell cell;
    PowerWorkspace ws;
    PowerChordWorkspace chord_ws;
    PowerClipWorkspace clip_ws;
    AlgorithmCounts ran;
};

/// The heterogeneous cell of the agent at grid position `pos` (radius r) into s.cell by `method`.
/// `radius_at` holds the radii in grid order, `radii` in input order.
inline void power_cell_at(const GridIndex& index, const std::vector<double>& radius_at,
                          const std::vector<double>& radii, double rmax, std::size_t pos, Method method,
                          PowerScratch& s) {
    const double r = radius_at[pos];
    const Vec2 c = index.point_at(pos);
    const Index self = index.grid_order()[pos];
    // Agents that can shape the cell are closer than r + R_j <= r + R_max; the query radius is half
    // the range, widened so that rounding never drops one (the exact classification of every route
    // discards the extras).
    const double half_range = 0.5 * (r + rmax) * (1.0 + 0x1p-40);
    if (method == Method::Auto) {
        // The certified clipping (agents with the same position and radius were refused before),
        // the exact clipping where it gives up.
        s.clip_ws.start(c, r);
        const Index* order0 = index.grid_order().data();
        index.for_each_batch_within_at(pos, half_range, [&](const double* xs, const double* ys, const Index* ids,
                                                            const std::uint32_t* sel, std::size_t count) {
            const double* rs = radius_at.data() + (ids - order0);  // the batch's grid positions
            s.clip_ws.add_batch(xs, ys, ids, sel, count, [&](std::uint32_t t) { return rs[t]; });
        });
        if (certified_power_clip_loaded(s.cell, s.clip_ws)) {
            ++s.ran.clip;
            return;
        }
        s.cand.clear();
        s.cand_r.clear();
        for (std::size_t t = 0; t < s.clip_ws.m; ++t) {
            s.cand.push_back({Vec2(s.clip_ws.px[t], s.clip_ws.py[t]), s.clip_ws.id[t]});
            s.cand_r.push_back(s.clip_ws.pr[t]);
        }
        power_cell(c, r, s.cand, s.cand_r, s.cell, s.ws, self);
        ++s.ran.power;
        return;
    }
    index.within_at(pos, half_range, s.cand);
    s.cand_r.clear();
    for (const Candidate& q : s.cand) s.cand_r.push_back(radii[static_cast<std::size_t>(q.id)]);
    if (method == Method::Scan) {
        power_boundary_scan(c, r, s.cand, s.cand_r, s.cell, s.chord_ws, self);
        ++s.ran.scan;
    } else {
        power_rcvc(c, r, s.cand, s.cand_r, s.cell, s.chord_ws, self);
        ++s.ran.chords;
    }
}

}  // namespace detail

/// Every agent's cell of a heterogeneous team: W_i = {q in B(p_i, R_i) : power_i(q) <= power_j(q) for
/// all j}, power_j(q) = |q - p_j|^2 - R_j^2 (docs/spec.md, heterogeneous teams). The cells partition the
/// union of the disks; a cell of zero area is empty (no pieces, no neighbours, area 0, centroid at the
/// agent: is_empty(i)).
///
/// With every radius equal this is limited_cells(points, radius, method, threads, progress) itself
/// (the same result, bit for bit; `radii` stays empty). Otherwise, by `method` (the same cells;
/// computed_by counts which algorithm computed each):
///   - Auto: the certified clipping of cells/certified_power_clip.hpp (computed_by.clip), the exact
///     clipping of cells/power_cell.hpp where it gives up (computed_by.power);
///   - Scan: Boundary Scan on the radical axes, cells/power_boundary_scan.hpp (computed_by.scan);
///   - Chords: RCVC on the radical axes, cells/power_rcvc.hpp (computed_by.chords).
///
/// \throws InputError naming `radii` when its length is not n or a radius is not positive and finite;
///         CoincidentError for two agents with the same position and radius (lowest pair named);
///         RangeError as limited_cells (Chords: more than kMaxChordsCandidates radical axes cutting
///         an agent's disk).
/// \note Per agent, m agents within R_i + R_max: O(m) for Auto in a swarm, O(m log m) for Scan when
///       the agent lies in its cell (a few restarts otherwise), O(m^2) for Chords; memory O(n k) for k
///       pieces per cell. Thread-safe. Results do not depend on `threads`.
inline LimitedPartition limited_cells(PointsRef points, const std::vector<double>& radii, Method method = Method::Auto,
                                      int threads = 0, const ProgressFn& progress = nullptr) {
    detail::require_finite_points(points, "points");
    const Index n = points.rows();
    if (static_cast<Index>(radii.size()) != n)
        throw InputError("radius must be a number or one radius per agent: " + std::to_string(radii.size()) +
                         " radii for " + std::to_string(n) + " points");
    detail::require_finite_radii(radii);
    const bool equal = std::all_of(radii.begin(), radii.end(), [&](double R) { return R == radii.front(); });
    if (n == 0 || equal) return limited_cells(points, n == 0 ? 1.0 : radii.front(), method, threads, progress);

    const int team = detail::thread_team(threads, detail::block_count(n));
    LimitedPartition out;
    out.method = method;
    detail::CellColumns columns(out, points, team);
    out.radii = radii;
    const double rmax = *std::max_element(radii.begin(), radii.end());
    out.radius = rmax;

    // Index the agents (cells of R_max: a query scans little beyond its disk). Coinciding positions
    // share a grid cell (O(n) expected); only when some exist are the radii compared (O(n log n)).
    const GridIndex index(out.points, rmax, team);
    if (index.first_duplicate().first >= 0) detail::require_distinct_weighted(out.points, out.radii);
    const std::vector<Index>& order = index.grid_order();
    // The radii in grid order: the fast path reads its candidates' radii next to their positions.
    std::vector<double> radius_at(static_cast<std::size_t>(n));
    for (std::size_t pos = 0; pos < radius_at.size(); ++pos) radius_at[pos] = radii[static_cast<std::size_t>(order[pos])];

    // Every agent's cell, stored as it is computed (see partition/detail/cell_columns.hpp).
    detail::ProgressTracker tracker(progress, n);
    detail::for_each_block(
        n, team, tracker, [](int thread) { return detail::PowerScratch(thread); },
        [&](detail::PowerScratch& s, Index pos) {
            const auto pp = static_cast<std::size_t>(pos);
            detail::power_cell_at(index, radius_at, radii, rmax, pp, method, s);
            const Index ahead = pos + detail::kWriteAhead < n ? order[pp + detail::kWriteAhead] : -1;
            columns.store(order[pp], s.cell, s.thread, ahead);
        },
        [&](Index pos) { return order[static_cast<std::size_t>(pos)]; },
        [&](const detail::PowerScratch& s) { out.computed_by += s.ran; });

    // The pieces and the neighbour CSR in input order.
    columns.stitch();
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
