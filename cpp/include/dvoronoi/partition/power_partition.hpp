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
    for (double R : radii) detail::require_finite_radius(R, "radius");
    const bool equal = std::all_of(radii.begin(), radii.end(), [&](double R) { return R == radii.front(); });
    if (n == 0 || equal) return limited_cells(points, n == 0 ? 1.0 : radii.front(), method, threads, progress);

    LimitedPartition out;
    out.method = method;
    out.points = points;
    out.radii = radii;
    const double rmax = *std::max_element(radii.begin(), radii.end());
    out.radius = rmax;
    const Index block = detail::kBlock;
    const Index nblocks = (n + block - 1) / block;
    const int team = detail::thread_team(threads, nblocks);
    const GridIndex index(out.points, rmax, team);  // cells of R_max: a query scans little beyond its disk
    // Coinciding positions share a grid cell (O(n) expected); only when some exist are the radii
    // compared (O(n log n)).
    if (index.first_duplicate().first >= 0) detail::require_distinct_weighted(out.points, out.radii);
    const std::vector<Index>& order = index.grid_order();
    // Each thread appends its cells' pieces to its own list; agent i's run is (thread, offset).
    std::vector<std::vector<Piece>> lists(static_cast<std::size_t>(team));
    std::vector<std::pair<int, std::size_t>> run_of(static_cast<std::size_t>(n));
    const auto un = static_cast<std::size_t>(n);
    out.areas.assign(un, 0.0);
    out.perimeters.assign(un, 0.0);
    out.centroids.resize(n, 2);
    out.candidates.assign(un, 0);
    out.piece_ptr.assign(un + 1, 0);  // counts, summed below
    out.indptr.assign(un + 1, 0);     // the same
    detail::ProgressTracker tracker(progress, n);
    Index by_filter = 0, by_clipping = 0, by_scan = 0, by_chords = 0;
    // The radii in grid order: the fast path reads its candidates' radii next to their positions.
    std::vector<double> radius_at(un);
    for (std::size_t pos = 0; pos < un; ++pos) radius_at[pos] = radii[static_cast<std::size_t>(order[pos])];
    const Index* order0 = order.data();

#pragma omp parallel num_threads(team) reduction(+ : by_filter, by_clipping, by_scan, by_chords)
    {
        std::vector<detail::Candidate> cand;
        std::vector<double> cand_r;
        const int me = detail::thread_id();
        std::vector<Piece>& mine = lists[static_cast<std::size_t>(me)];
        LimitedCell cell;
        detail::PowerWorkspace ws;
        detail::PowerChordWorkspace chord_ws;
        detail::PowerClipWorkspace clip_ws;
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            const Index lo = b * block, hi = std::min(n, lo + block);
            if (tracker.skip(lo)) continue;
            Index pos = lo;
            try {
                for (; pos < hi; ++pos) {
                    const auto pp = static_cast<std::size_t>(pos);
                    const auto i = static_cast<std::size_t>(order[pp]);
                    const double r = radius_at[pp];
                    if (pos + detail::kWriteAhead < n) {  // this agent's results go to scattered places
                        const auto a = static_cast<std::size_t>(order[pp + detail::kWriteAhead]);
                        detail::prefetch_for_write(&out.areas[a]);
                        detail::prefetch_for_write(&out.perimeters[a]);
                        detail::prefetch_for_write(out.centroids.data() + 2 * a);
                        detail::prefetch_for_write(&out.candidates[a]);
                        detail::prefetch_for_write(&out.piece_ptr[a + 1]);
                        detail::prefetch_for_write(&run_of[a]);
                    }
                    // Agents that can shape the cell are closer than r + R_j <= r + R_max; the query
                    // radius is half the range, widened so that rounding never drops one (the exact
                    // classification of every route discards the extras).
                    const double half_range = 0.5 * (r + rmax) * (1.0 + 0x1p-40);
                    const Vec2 c = index.point_at(pp);
                    const auto self = static_cast<Index>(i);
                    if (method == Method::Auto) {
                        // The certified clipping (agents with the same position and radius were
                        // refused above), the exact clipping where it gives up.
                        clip_ws.start(c, r);
                        index.for_each_batch_within_at(pp, half_range, [&](const double* xs, const double* ys, const Index* ids,
                                                                           const std::uint32_t* sel, std::size_t count) {
                            const double* rs = radius_at.data() + (ids - order0);  // the batch's grid positions
                            clip_ws.add_batch(xs, ys, ids, sel, count, [&](std::uint32_t t) { return rs[t]; });
                        });
                        if (detail::certified_power_clip_loaded(cell, clip_ws)) {
                            ++by_filter;
                        } else {
                            cand.clear();
                            cand_r.clear();
                            for (std::size_t t = 0; t < clip_ws.m; ++t) {
                                cand.push_back({Vec2(clip_ws.px[t], clip_ws.py[t]), clip_ws.id[t]});
                                cand_r.push_back(clip_ws.pr[t]);
                            }
                            detail::power_cell(c, r, cand, cand_r, cell, ws, self);
                            ++by_clipping;
                        }
                    } else {
                        index.within_at(pp, half_range, cand);
                        cand_r.clear();
                        for (const detail::Candidate& q : cand) cand_r.push_back(radii[static_cast<std::size_t>(q.id)]);
                        if (method == Method::Scan) {
                            detail::power_boundary_scan(c, r, cand, cand_r, cell, chord_ws, self);
                            ++by_scan;
                        } else {
                            detail::power_rcvc(c, r, cand, cand_r, cell, chord_ws, self);
                            ++by_chords;
                        }
                    }
                    const CellMeasures& m = cell.measures();
                    out.areas[i] = m.area;
                    out.perimeters[i] = m.perimeter;
                    out.centroids(static_cast<Index>(i), 0) = m.centroid.x();
                    out.centroids(static_cast<Index>(i), 1) = m.centroid.y();
                    out.candidates[i] = cell.candidates;
                    run_of[i] = {me, mine.size()};
                    mine.insert(mine.end(), cell.pieces.begin(), cell.pieces.end());
                    out.piece_ptr[i + 1] = static_cast<Index>(cell.pieces.size());
                    Index edges = 0;  // one per neighbour: a chord bounds a convex cell once
                    for (const Piece& p : cell.pieces) edges += p.is_arc() ? 0 : 1;
                    out.indptr[i + 1] = edges;
                }
            } catch (...) {
                tracker.fail(pos, order[static_cast<std::size_t>(pos)]);
            }
            tracker.block_done(hi - lo);
        }
    }
    tracker.rethrow_if_failed();
    out.computed_by.clip = by_filter;
    out.computed_by.power = by_clipping;
    out.computed_by.scan = by_scan;
    out.computed_by.chords = by_chords;

    // Counts to offsets; then each agent's run to its place in input order, and its neighbours
    // sorted, in parallel (runs are read scattered over the threads' lists: a few agents ahead are
    // prefetched so that the misses overlap).
    for (std::size_t i = 0; i < un; ++i) {
        out.piece_ptr[i + 1] += out.piece_ptr[i];
        out.indptr[i + 1] += out.indptr[i];
    }
    const auto total = static_cast<std::size_t>(out.piece_ptr.back());
    out.piece_x.resize(total);
    out.piece_y.resize(total);
    out.piece_span.resize(total);
    out.piece_neighbor.resize(total);
    out.indices.resize(static_cast<std::size_t>(out.indptr.back()));
#pragma omp parallel for num_threads(team) schedule(static)
    for (Index ii = 0; ii < n; ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        if (i + detail::kAhead < un) {
            const auto [ta, aa] = run_of[i + detail::kAhead];
            if (aa < lists[static_cast<std::size_t>(ta)].size()) detail::prefetch(&lists[static_cast<std::size_t>(ta)][aa]);
        }
        const auto [t, at] = run_of[i];
        const auto to = static_cast<std::size_t>(out.piece_ptr[i]);
        const std::size_t len = static_cast<std::size_t>(out.piece_ptr[i + 1]) - to;
        for (std::size_t q = 0; q < len; ++q) {
            const Piece& p = lists[static_cast<std::size_t>(t)][at + q];
            out.piece_x[to + q] = p.start.x();
            out.piece_y[to + q] = p.start.y();
            out.piece_span[to + q] = p.arc_span;
            out.piece_neighbor[to + q] = p.neighbor;
        }
        detail::sorted_edge_neighbors(out.piece_neighbor.data() + to, len, out.indices.data() + out.indptr[i]);
    }
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
