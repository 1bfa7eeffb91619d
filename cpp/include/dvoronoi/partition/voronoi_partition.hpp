// All agents' exact Voronoi cells by Adjust-Sensing-Radius (+ Boundary Scan), each from the agents
// within its current sensing radius found with the grid index, in parallel (OpenMP).
#pragma once

#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/cells/certified_exact_cell.hpp"
#include "dvoronoi/core/convex_hull.hpp"
#include "dvoronoi/partition/asr_schedule.hpp"
#include "dvoronoi/partition/empty_circle_certificate.hpp"
#include "dvoronoi/partition/detail/input_order.hpp"
#include "dvoronoi/partition/limited_partition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace dvoronoi {

namespace detail {
/// The cell of c with the half-planes of `cand` applied, clipped to `region`.
inline ClippedCell clip_to(const Vec2& c, const std::vector<Candidate>& cand, const ConvexRegion& region) {
    std::vector<Vec2> pos;
    std::vector<Index> ids;
    for (const Candidate& q : cand) {
        pos.push_back(q.p);
        ids.push_back(q.id);
    }
    return clip_cell(c, pos, ids, region);
}
}  // namespace detail

/// Exact Voronoi neighbours and hull flags of n agents (the result of voronoi_cells).
struct VoronoiPartition {
    Points points;                    ///< the agents, as given
    std::vector<Index> indptr{0};     ///< Voronoi neighbours (positive-length edges), CSR, ascending
    std::vector<Index> indices;
    std::vector<char> on_hull;        ///< the agent's cell is unbounded
    /// ASR's own numbers per agent, as asr_cell reports them for that agent alone: the limited cells
    /// its radius schedule computes, and the agents within twice its final radius (all others when
    /// the radius never certified the cell). See partition/asr_schedule.hpp.
    std::vector<int> radius_steps;
    std::vector<Index> agents_used;
    ConvexRegion bounds;              ///< the region cells are clipped to (empty: none given)
    /// Per agent: area and centroid of the clipped cell when `bounds` is given (0 and NaN when the
    /// cell misses it), else of the bounded cell (NaN for hull agents).
    std::vector<double> areas;
    Points centroids;
    /// How the cells were found (they add up to n): `one_shot` by one certified clipping at a fixed
    /// radius and `deferred` from the triangulation of the agents it did not certify (AsrInner::Auto),
    /// `asr` by Adjust-Sensing-Radius with the inner step on every radius (AsrInner::Scan and Evt).
    struct ComputedBy {
        Index one_shot = 0, deferred = 0, asr = 0;
    } computed_by;

    Index size() const noexcept { return static_cast<Index>(points.rows()); }

    /// The exact cell of agent i (rebuilt from its Voronoi neighbours, whose half-planes define it;
    /// clipped to `bounds` when given). 	hrows InputError for an index out of range.
    VoronoiCell cell(Index i) const {
        const auto [b, e] = neighbors(i);
        const Vec2 c = points.row(i).transpose();
        std::vector<detail::Candidate> cand;
        for (const Index* j = b; j != e; ++j) cand.push_back({points.row(*j).transpose(), *j});
        VoronoiCell out;
        out.center = c;
        detail::CellWorkspace ws;
        detail::DelaunayWorkspace dws;
        if (cand.empty()) {
            out.on_hull = true;
        } else {
            detail::candidate_cell(c, cand, AsrInner::Scan, ws, dws, out);
        }
        out.radius_steps = radius_steps[static_cast<std::size_t>(i)];
        out.agents_used = agents_used[static_cast<std::size_t>(i)];
        if (!bounds.empty()) {
            out.clipped = detail::clip_to(c, cand, bounds);
            out.is_clipped = true;
        }
        return out;
    }

    /// Voronoi neighbours of agent i, ascending (a view into `indices`).
    std::pair<const Index*, const Index*> neighbors(Index i) const {
        if (i < 0 || i >= size())
            throw InputError("agent index " + std::to_string(i) + " out of range [0, " +
                             std::to_string(size()) + ")");
        return {indices.data() + indptr[static_cast<std::size_t>(i)],
                indices.data() + indptr[static_cast<std::size_t>(i) + 1]};
    }

    /// The Delaunay graph (dual of the Voronoi diagram, positive-length edges only): pairs i < j.
    std::vector<std::pair<Index, Index>> delaunay_edges() const {
        std::vector<std::pair<Index, Index>> out;
        for (Index i = 0; i < size(); ++i)
            for (Index k = indptr[static_cast<std::size_t>(i)]; k < indptr[static_cast<std::size_t>(i) + 1]; ++k)
                if (indices[static_cast<std::size_t>(k)] > i) out.push_back({i, indices[static_cast<std::size_t>(k)]});
        return out;
    }
};

namespace detail {

/// One agent's result, stored by grid position during the passes (the hot loop writes sequentially)
/// and gathered into input order at the end. (Writing the results straight to input order, as
/// limited_cells does, measured slower here.)
struct VoronoiRow {
    double area, cx, cy;
    Index used, count;
    Index first;  // where the neighbours start in the thread's column (column_place)
    std::int16_t steps;
    char hull;
};

/// One thread's scratch.
struct VoronoiScratch {
    explicit VoronoiScratch(int t) : thread(t) {}
    int thread;
    std::vector<Candidate> cand;
    CellWorkspace ws;
    DelaunayWorkspace dws;
    LimitedCell limited;
    VoronoiCell cell;
    ClipWorkspace clip_ws;  // agents are distinct (checked before): the filter may serve
    ExactClip exact;
    std::vector<Index> mine;      // the agent's neighbours
    std::vector<Index> deferred;  // grid positions the one-shot clip did not certify
    std::vector<int> dnb;         // an agent's neighbours in the deferred agents' triangulation
};

/// The Delaunay triangulation of the deferred agents (about 3% of a uniform swarm: a vertex beyond
/// the one-shot radius R, near the swarm's edge, on its hull, or an uncertain clip): agent t's
/// neighbours among them, as indices into the list it was built from. Why the agents within 2R and
/// those neighbours give the exact cell: a neighbour q of such an agent c at distance >= 2R shares
/// with it a Voronoi edge whose points lie at distance >= R from both, so q's cell too has a vertex
/// at R or beyond (or none): q was deferred as well. And a positive-length Voronoi edge means a
/// circle through c and q with every other agent strictly outside; the deferred agents being a
/// subset, c and q are Delaunay neighbours among them too. So the loaded agents and c's neighbours
/// in this triangulation hold all of c's neighbours, and their half-planes cut out exactly its cell.
/// Why: one triangulation of a few percent of the agents replaces, for each deferred agent, a radius
/// schedule whose disks (and empty-circle scans) along the swarm's edge sweep thousands of agents.
class DeferredTriangulation {
public:
    explicit DeferredTriangulation(const std::vector<Vec2>& pts) {
        dim_ = naming_range_error("points", [&] { return dt_.build(pts, /*spatial=*/true); });
        if (dim_ == 1) {  // collinear deferred agents: their order along the line
            line_ = dt_.line_order();
            rank_.resize(line_.size());
            for (std::size_t t = 0; t < line_.size(); ++t) rank_[static_cast<std::size_t>(line_[t])] = static_cast<int>(t);
        }
    }
    void neighbors(int t, std::vector<int>& out) const {
        out.clear();
        if (dim_ == 2) {
            dt_.star(t, out);
        } else if (dim_ == 1) {
            const int k = rank_[static_cast<std::size_t>(t)];
            if (k > 0) out.push_back(line_[static_cast<std::size_t>(k - 1)]);
            if (k + 1 < static_cast<int>(line_.size())) out.push_back(line_[static_cast<std::size_t>(k + 1)]);
        }
    }

private:
    Delaunay dt_;
    int dim_ = -1;
    std::vector<int> line_, rank_;
};

/// The steps every agent's result is made of, over the shared inputs (the index and its grid order,
/// ASR's radius schedule and empty-circle certificate, the inner step, the one-shot radius R, the
/// bounds), writing the rows by grid position and the threads' neighbour columns.
struct VoronoiSteps {
    const Points& points;
    const GridIndex& index;
    const AsrSchedule& schedule;
    const EmptyCircleCertificate& cert;
    AsrInner inner;
    double one_shot;
    const ConvexRegion& bounds;
    int team;
    std::vector<std::vector<Index>> columns{};  // per thread
    std::vector<VoronoiRow> by_pos{};

    /// Room for the rows and, per thread, about seven neighbours per agent (six in a swarm; room
    /// never written costs address space only; the first thread's column takes the others' in the end).
    void size_for(Index n) {
        by_pos.assign(static_cast<std::size_t>(n), VoronoiRow{});
        columns.resize(static_cast<std::size_t>(team));
        for (int t = 0; t < team; ++t)
            columns[static_cast<std::size_t>(t)].reserve(static_cast<std::size_t>(t == 0 ? n : n / team + kBlock) * 7);
    }

    /// The first pass over the agent at grid position `pos`: with `deferring`, one certified clipping
    /// at the one-shot radius, false (put off) when it does not certify the cell; else ASR.
    bool first_pass(VoronoiScratch& sc, Index pos, bool deferring) {
        const auto spos = static_cast<std::size_t>(pos);
        const Vec2 c = index.point_at(spos);
        VoronoiRow r{0.0, 0.0, 0.0, 0, 0, 0, 0, 0};
        sc.mine.clear();
        if (deferring) {
            load_in_range(sc, spos, c, pos % kBlock == 0);
            if (!certified_exact_cell(one_shot, sc.exact, sc.clip_ws)) {
                sc.deferred.push_back(pos);
                return false;
            }
            from_clip(sc, c, r);
        } else {
            by_asr(sc, spos, c, index.grid_order()[spos], r);
        }
        finish(sc, c, spos, r);
        return true;
    }

    /// The cell of deferred agent t (grid position deferred[t]) from the agents strictly within 2R
    /// and its neighbours beyond them in the deferred agents' triangulation (DeferredTriangulation
    /// says why that is exact).
    void deferred_cell(VoronoiScratch& sc, Index t, const std::vector<Index>& deferred, const DeferredTriangulation& dt) {
        const auto spos = static_cast<std::size_t>(deferred[static_cast<std::size_t>(t)]);
        const Vec2 c = index.point_at(spos);
        VoronoiRow r{0.0, 0.0, 0.0, 0, 0, 0, 0, 0};
        sc.mine.clear();
        load_in_range(sc, spos, c, t % kBlock == 0);
        dt.neighbors(static_cast<int>(t), sc.dnb);
        for (int v : sc.dnb) {
            const auto qpos = static_cast<std::size_t>(deferred[static_cast<std::size_t>(v)]);
            const Vec2 q = index.point_at(qpos);
            if (!(pred::within_2r(c, q, one_shot) > 0)) sc.clip_ws.add(q, index.grid_order()[qpos]);
        }
        // A square of 4R first (most of these cells: a vertex a little beyond R), whose corners the
        // clip screens candidates against; then a huge one.
        const double wide = std::ldexp(1.0, 20);
        if (certified_candidate_cell(4.0 * one_shot, sc.exact, sc.clip_ws) ||
            certified_candidate_cell(wide * one_shot, sc.exact, sc.clip_ws)) {
            from_clip(sc, c, r);
        } else {
            // Unbounded, huge or degenerate: the exact cell of the same candidates.
            sc.clip_ws.candidates(sc.cand);
            candidate_cell(c, sc.cand, inner, sc.ws, sc.dws, sc.cell);
            from_cell(sc, c, std::sqrt(sc.clip_ws.lo), r);
        }
        finish(sc, c, spos, r);
    }

    /// The rows and the neighbour CSR in input order (scattered reads, prefetched).
    void lay_out(VoronoiPartition& out) {
        const auto n = static_cast<std::size_t>(points.rows());
        std::vector<Index> source(n);  // where agent i's neighbours start (column_place, then joined offsets)
        gather_in_input_order(positions_of(index.grid_order()), by_pos, [&](Index i, std::size_t, const VoronoiRow& r) {
            const auto ii = static_cast<std::size_t>(i);
            source[ii] = r.first;
            out.areas[ii] = r.area;
            out.centroids(i, 0) = r.cx;
            out.centroids(i, 1) = r.cy;
            out.on_hull[ii] = r.hull;
            out.radius_steps[ii] = r.steps;
            out.agents_used[ii] = r.used;
            out.indptr[ii + 1] = out.indptr[ii] + r.count;
        });
        out.indices = runs_in_input_order(columns, source, out.indptr, team);
    }

    /// Loads the clip with the agents strictly within 2 one_shot of the agent at grid position spos.
    /// The near-first radius comes from the previous agent's count, which at the first agent of a
    /// block (`block_start`) would be whatever agent this thread did last: there the agent's own
    /// count is taken, so the clipping order, and the rounding of areas, is the same for any thread
    /// count and schedule (a block's agents run in order on one thread).
    void load_in_range(VoronoiScratch& sc, std::size_t spos, const Vec2& c, bool block_start) const {
        const std::size_t previous = block_start ? static_cast<std::size_t>(index.count_within_at(spos, one_shot)) : sc.clip_ws.m;
        sc.clip_ws.start(c, near_first_sq(one_shot, previous));
        index.for_each_batch_within_at(spos, one_shot, [&](auto... batch) { sc.clip_ws.add_batch(batch...); });
    }

    /// The result of a cell certified by clipping (`exact` over the loaded candidates, which hold
    /// every agent strictly within 2 one_shot): ASR's numbers, neighbours and measures.
    void from_clip(VoronoiScratch& sc, const Vec2& c, VoronoiRow& r) const {
        ClipWorkspace& clip_ws = sc.clip_ws;
        const double d1 = std::sqrt(clip_ws.lo);  // the nearest neighbour is loaded
        const auto [k, certified] = schedule.stop(
            c, d1, farthest_vertex(sc.exact), [&](double radius) { return vertices_inside(sc.exact, clip_ws, radius); });
        r.steps = static_cast<std::int16_t>(k);
        // Agents strictly within 2 R_k: among the loaded ones when R_k <= R.
        const double rk = schedule_radius(d1, k);
        if (certified && rk <= one_shot) {
            r.used = count_within_2r(
                0, clip_ws.m, rk, [&](std::size_t t) { return clip_ws.n2[t]; },
                [&](std::size_t t) { return pred::within_2r(c, Vec2(clip_ws.px[t], clip_ws.py[t]), rk) > 0; });
        } else {
            r.used = schedule.used(c, rk, certified);
        }
        for (std::size_t t = 0; t < sc.exact.side.size(); ++t)
            sc.mine.push_back(clip_ws.id[static_cast<std::size_t>(sc.exact.side[t])]);
        const ClippedCell m = certified_cell_measures(sc.exact, clip_ws, one_shot);
        r.area = m.area;
        r.cx = m.centroid.x();
        r.cy = m.centroid.y();
    }

    /// The same for a cell in sc.cell (from the radius schedule or all candidates; first: the
    /// nearest-neighbour distance).
    void from_cell(VoronoiScratch& sc, const Vec2& c, double first, VoronoiRow& r) const {
        r.hull = sc.cell.on_hull ? 1 : 0;
        if (points.rows() > 1) {  // the schedule's numbers from the exact cell
            const auto [k, certified] = schedule.stop(c, first, sc.cell);
            r.steps = static_cast<std::int16_t>(k);
            r.used = schedule.used(c, schedule_radius(first, k), certified);
        }
        for (const VoronoiEdge& e : sc.cell.edges) sc.mine.push_back(e.neighbor);
        sc.cell.is_clipped = false;
        const ClippedCell m = sc.cell.measures();
        r.area = m.area;
        r.cx = m.centroid.x();
        r.cy = m.centroid.y();
    }

    /// Neighbours ascending into the thread's column, the clipped measures when bounds are given;
    /// the row stored at its grid position.
    void finish(VoronoiScratch& sc, const Vec2& c, std::size_t spos, VoronoiRow& r) {
        auto& column = columns[static_cast<std::size_t>(sc.thread)];
        std::vector<Index>& mine = sc.mine;
        sort_small(mine.data(), mine.data() + mine.size());
        mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
        if (!bounds.empty()) {
            sc.cand.clear();
            for (Index j : mine) sc.cand.push_back({points.row(j).transpose(), j});
            const ClippedCell m = clip_to(c, sc.cand, bounds);
            r.area = m.area;
            r.cx = m.centroid.x();
            r.cy = m.centroid.y();
        }
        r.first = column_place(column.size(), team, sc.thread);
        r.count = static_cast<Index>(mine.size());
        column.insert(column.end(), mine.begin(), mine.end());
        by_pos[spos] = r;
    }

    /// ASR on the agent at grid position spos (centre c, input index i), every radius step with the
    /// inner step `inner` (Scan: Boundary Scan itself, no clipping filter; Auto with n <= 3).
    void by_asr(VoronoiScratch& sc, std::size_t spos, const Vec2& c, Index i, VoronoiRow& r) const {
        const Index n = points.rows();
        const auto query = [&](double radius, std::vector<Candidate>& cs) { index.within_at(spos, radius, cs); };
        // The nearest neighbour starts the schedule: widen a query until it finds someone.
        double first = 0.0;
        if (n > 1) {
            double rr = one_shot;
            for (index.within_at(spos, rr, sc.cand); sc.cand.empty(); index.within_at(spos, rr, sc.cand)) rr *= 2.0;
            double best = std::numeric_limits<double>::infinity();
            for (const Candidate& q : sc.cand) best = std::min(best, (q.p - c).squaredNorm());
            first = std::sqrt(best);
        }
        asr(c, query, n - 1, first, inner, sc.ws, sc.dws, sc.cand, sc.limited, sc.cell, i, cert,
            inner == AsrInner::Auto ? &sc.clip_ws : nullptr);
        from_cell(sc, c, first, r);
    }
};

/// The mean spacing of the points over their bounding box (1 when it is degenerate).
inline double mean_spacing(const Points& pts) {
    double x0, y0, x1, y1;
    bounding_box(pts, x0, y0, x1, y1);
    const double w = x1 - x0, h = y1 - y0;
    const double spacing = std::sqrt(std::max(w * h, std::max(w, h) * std::max(w, h) * 1e-12) / static_cast<double>(pts.rows()));
    return spacing > 0.0 && std::isfinite(spacing) ? spacing : 1.0;
}

}  // namespace detail

/// Every agent's exact Voronoi neighbours and hull flag. Scan and Evt run ASR with that inner step
/// (Boundary Scan, ASR+BS, or the exact tessellation, ASR+EVT) on every agent: each agent starts
/// from its nearest-neighbour distance and doubles its sensing radius until its cell certifies
/// itself (cells/asr.hpp); hull agents end with every agent. Auto (default) is our fast path, not a
/// published algorithm (see the note). All three give the same neighbours and hull flags.
/// `radius_steps` and `agents_used` are ASR's schedule numbers for each agent, however the cell was
/// found; `computed_by` says which route found how many cells.
///
/// \param threads number of OpenMP threads; 0 = all cores. Results do not depend on it.
/// \param bounds  a convex region (box or polygon) to clip every cell to: `areas` and `centroids`
///                then measure the clipped cells, and `cell(i)` carries the clipped polygon.
/// \throws InputError for non-finite coordinates; CoincidentError for coinciding agents; RangeError
///         when an exact test over- or underflows (coordinates far outside the exact range of
///         core/expansion.hpp), naming the agent whose cell needed it ("points[17]: ...") or
///         "points" for the steps over all agents.
/// \note With Auto, each agent first tries one certified clipping at a
///       radius R of 1.5 mean spacings (cells/certified_exact_cell.hpp), from one grid query (about
///       28 agents within 2R in a uniform swarm); that certifies ~97% of a uniform swarm's cells. The
///       others (a vertex beyond R, near the swarm's edge, on its hull, ties) are finished together:
///       their neighbours beyond 2R are their neighbours in a Delaunay triangulation of just them
///       (the comment at that step says why), so the loaded agents and those give the exact cell.
///       With inner = Scan or Evt every agent runs the radius schedule of cells/asr.hpp; from step
///       EmptyCircleCertificate::kFromStep on, a cell that the radius does not certify is certified
///       by empty vertex circles and the global convex hull (partition/empty_circle_certificate.hpp),
///       so agents near the hull do not sweep most agents. Uniform agents cost O(1) each in
///       expectation; inputs where k agents are (nearly) cocircular around a shared vertex cost O(k)
///       exact tests per agent there. Thread-safe.
inline VoronoiPartition voronoi_cells(PointsRef points, AsrInner inner = AsrInner::Auto,
                                      int threads = 0, const ProgressFn& progress = nullptr,
                                      const ConvexRegion& bounds = ConvexRegion()) {
    detail::require_finite_points(points, "points");
    const Index n = points.rows();
    VoronoiPartition out;
    out.points = points;
    out.bounds = bounds;
    const auto un = static_cast<std::size_t>(n);
    out.areas.assign(un, 0.0);
    out.centroids.resize(n, 2);
    out.on_hull.assign(un, 0);
    out.radius_steps.assign(un, 0);
    out.agents_used.assign(un, 0);
    out.indptr.assign(un + 1, 0);
    if (n == 0) return out;

    // The one-shot radius R: 1.5 mean spacings certifies ~97% of a uniform swarm's cells; the grid's
    // cells are 2R. The index, the hull and the certificates every step needs.
    const double one_shot = 1.5 * detail::mean_spacing(out.points);
    const int team = detail::thread_team(threads, detail::block_count(n));
    const GridIndex index(out.points, 2.0 * one_shot, team);
    detail::require_distinct(index, out.points);
    const ConvexHull hull = detail::naming_range_error("points", [&] { return ConvexHull(out.points); });
    const detail::EmptyCircleCertificate cert(out.points, index, hull);
    const detail::AsrSchedule schedule(out.points, index, hull);
    detail::VoronoiSteps steps{out.points, index, schedule, cert, inner, one_shot, bounds, team};
    steps.size_for(n);
    const auto make = [](int thread) { return detail::VoronoiScratch(thread); };
    const auto agent_at = [&](Index pos) { return index.grid_order()[static_cast<std::size_t>(pos)]; };

    // Every agent: with Auto one certified clipping at R, deferring the cells it does not certify;
    // with Scan or Evt, ASR.
    const bool deferring = inner == AsrInner::Auto && n > 3;
    std::vector<Index> deferred;  // grid positions
    detail::ProgressTracker tracker(progress, n);
    detail::for_each_block(
        n, team, tracker, make, [&](detail::VoronoiScratch& sc, Index pos) { return steps.first_pass(sc, pos, deferring); },
        agent_at, [&](detail::VoronoiScratch& sc) { deferred.insert(deferred.end(), sc.deferred.begin(), sc.deferred.end()); });

    // The deferred agents, from a Delaunay triangulation of themselves.
    if (!deferred.empty()) {
        std::sort(deferred.begin(), deferred.end());
        std::vector<Vec2> dpts(deferred.size());
        for (std::size_t t = 0; t < deferred.size(); ++t) dpts[t] = index.point_at(static_cast<std::size_t>(deferred[t]));
        const detail::DeferredTriangulation dt(dpts);
        const auto nd = static_cast<Index>(deferred.size());
        detail::for_each_block(
            nd, detail::thread_team(threads, detail::block_count(nd)), tracker, make,
            [&](detail::VoronoiScratch& sc, Index t) { steps.deferred_cell(sc, t, deferred, dt); },
            [&](Index t) { return agent_at(deferred[static_cast<std::size_t>(t)]); });
    }

    steps.lay_out(out);
    const auto nd = static_cast<Index>(deferred.size());
    out.computed_by.one_shot = deferring ? n - nd : 0;
    out.computed_by.deferred = nd;
    out.computed_by.asr = deferring ? 0 : n;
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
