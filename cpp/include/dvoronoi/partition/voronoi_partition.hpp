// All agents' exact Voronoi cells by Adjust-Sensing-Radius (+ Boundary Scan), each from the agents
// within its current sensing radius found with the grid index, in parallel (OpenMP).
#pragma once

#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/core/convex_hull.hpp"
#include "dvoronoi/partition/empty_circle_certificate.hpp"
#include "dvoronoi/partition/limited_partition.hpp"

#include <cmath>
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
    std::vector<int> radius_steps;    ///< limited cells the radius schedule computed per agent
    std::vector<Index> agents_used;   ///< agents within the final sensing radius per agent
    ConvexRegion bounds;              ///< the region cells are clipped to (empty: none given)
    /// Per agent: area and centroid of the clipped cell when `bounds` is given (0 and NaN when the
    /// cell misses it), else of the bounded cell (NaN for hull agents).
    std::vector<double> areas;
    Points centroids;

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


/// Every agent's exact Voronoi neighbours and hull flag by ASR (inner step Boundary Scan or EVT, see
/// AsrInner): each agent starts from its
/// nearest-neighbour distance and doubles its sensing radius until its cell certifies itself
/// (cells/asr.hpp); hull agents end with every agent.
///
/// \param threads number of OpenMP threads; 0 = all cores. Results do not depend on it.
/// \param bounds  a convex region (box or polygon) to clip every cell to: `areas` and `centroids`
///                then measure the clipped cells, and `cell(i)` carries the clipped polygon.
/// \throws InputError for non-finite coordinates; CoincidentError for coinciding agents.
/// \note Each agent runs the radius schedule of cells/asr.hpp; from step
///       EmptyCircleCertificate::kFromStep on, a cell that the radius does not certify is certified
///       by empty vertex circles and the global convex hull (partition/empty_circle_certificate.hpp),
///       so agents near the hull do not sweep most agents. Uniform agents cost O(log n) each
///       (sorting), about 1.3 s for 1e5 on one core; inputs where k agents are (nearly)
///       cocircular around a shared vertex cost O(k) exact tests per agent there. Thread-safe.
inline VoronoiPartition voronoi_cells(PointsRef points, AsrInner inner = AsrInner::Scan,
                                      int threads = 0, const ProgressFn& progress = nullptr,
                                      const ConvexRegion& bounds = ConvexRegion()) {
    detail::require_finite_points(points, "points");
    const Index n = points.rows();
    VoronoiPartition out;
    out.points = points;
    out.bounds = bounds;
    out.areas.assign(static_cast<std::size_t>(n), 0.0);
    out.centroids.resize(n, 2);
    out.on_hull.assign(static_cast<std::size_t>(n), 0);
    out.radius_steps.assign(static_cast<std::size_t>(n), 0);
    out.agents_used.assign(static_cast<std::size_t>(n), 0);
    out.indptr.assign(static_cast<std::size_t>(n) + 1, 0);
    if (n == 0) return out;
    // The grid's cells are sized for a few agents each (the mean spacing over the bounding box).
    const double w = out.points.col(0).maxCoeff() - out.points.col(0).minCoeff();
    const double h = out.points.col(1).maxCoeff() - out.points.col(1).minCoeff();
    double range = 2.0 * std::sqrt(std::max(w * h, std::max(w, h) * std::max(w, h) * 1e-12) / static_cast<double>(n));
    if (!(range > 0.0) || !std::isfinite(range)) range = 1.0;
    const GridIndex index(out.points, range);
    detail::require_distinct(index, out.points);
    const ConvexHull hull(out.points);
    const detail::EmptyCircleCertificate cert(out.points, index, hull);
    const std::vector<Index>& order = index.grid_order();
    const Index block = detail::kBlock;
    const Index nblocks = (n + block - 1) / block;
    const int team = detail::thread_team(threads, nblocks);
    std::vector<std::vector<Index>> nbrs(static_cast<std::size_t>(n));
    detail::ProgressTracker tracker(progress, n);

#pragma omp parallel num_threads(team)
    {
        std::vector<detail::Candidate> cand;
        detail::CellWorkspace ws;
        detail::DelaunayWorkspace dws;
        LimitedCell limited;
        VoronoiCell cell;
        detail::ClipWorkspace clip_ws;  // agents are distinct (checked above): the filter may serve
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            if (tracker.cancelled()) continue;
            const Index lo = b * block, hi = std::min(n, lo + block);
            for (Index pos = lo; pos < hi; ++pos) {
                const auto spos = static_cast<std::size_t>(pos);
                const Index i = order[spos];
                const auto ii = static_cast<std::size_t>(i);
                const Vec2 c = index.point_at(spos);
                const auto query = [&](double radius, std::vector<detail::Candidate>& cs) {
                    index.within_at(spos, radius, cs);
                };
                // The nearest neighbour starts the schedule: widen a query until it finds someone.
                double first = 0.0;
                if (n > 1) {
                    double r = 0.5 * range;
                    for (index.within_at(spos, r, cand); cand.empty(); index.within_at(spos, r, cand)) r *= 2.0;
                    double best = std::numeric_limits<double>::infinity();
                    for (const detail::Candidate& q : cand) best = std::min(best, (q.p - c).squaredNorm());
                    first = std::sqrt(best);
                }
                detail::asr(c, query, n - 1, first, inner, ws, dws, cand, limited, cell, i, cert, &clip_ws);
                out.on_hull[ii] = cell.on_hull ? 1 : 0;
                out.radius_steps[ii] = cell.radius_steps;
                out.agents_used[ii] = cell.agents_used;
                auto& mine = nbrs[ii];
                for (const VoronoiEdge& e : cell.edges) mine.push_back(e.neighbor);
                if (!bounds.empty()) {
                    cand.clear();
                    for (const VoronoiEdge& e : cell.edges) cand.push_back({out.points.row(e.neighbor).transpose(), e.neighbor});
                    cell.clipped = detail::clip_to(c, cand, bounds);
                    cell.is_clipped = true;
                }
                const ClippedCell m = cell.measures();
                out.areas[ii] = m.area;
                out.centroids.row(i) = m.centroid.transpose();
                std::sort(mine.begin(), mine.end());
                mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
            }
            tracker.block_done(hi - lo);
        }
    }
    tracker.rethrow_if_failed();
    for (Index i = 0; i < n; ++i) {
        const auto& mine = nbrs[static_cast<std::size_t>(i)];
        out.indptr[static_cast<std::size_t>(i) + 1] = out.indptr[static_cast<std::size_t>(i)] + static_cast<Index>(mine.size());
        out.indices.insert(out.indices.end(), mine.begin(), mine.end());
    }
    tracker.report_all();
    return out;
}

}  // namespace dvoronoi
