// Shortest collision-free path between two free points along the grid Voronoi diagram.
//
// The start (and the goal) is joined to the diagram by retraction: move straight away from its
// nearest obstacle (clearance grows along that ray) to the first free traced cell; if that segment
// is not clear, the nearest free cells are tried in turn. Between the two cells, A* runs over the free
// traced cells (neighbours across label changes, steps of one cell). Every segment of the answer is
// then checked exactly against the obstacles (segment-to-shape distance > robot radius); a step that
// fails is removed and A* runs again (lazy validation), so the returned path is collision-free for a
// disk robot of the diagram's radius, not only at cell corners.
#pragma once

#include "dvoronoi/gvd/obstacle_index.hpp"
#include "dvoronoi/gvd/result.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <queue>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi::gvd {

struct PathResult {
    std::vector<Vec2> points;  ///< start, cell centers along the diagram, goal; empty if no route
    double length = 0.0;
    bool found() const { return !points.empty(); }
};

namespace detail {

inline std::string show_point(const Vec2& p) {  // every digit: a point near another must not read as it
    return "(" + ::dvoronoi::detail::shortest_text(p.x()) + ", " + ::dvoronoi::detail::shortest_text(p.y()) + ")";
}

/// Throws InputError when `p` is outside the area or within the robot radius of an obstacle.
inline void require_free(const Scene& scene, const ObstacleIndex& index, QueryContext& ctx, const Vec2& p,
                         double radius, const char* name) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
        throw InputError(std::string(name) + " has a non-finite coordinate");
    const std::size_t n = scene.area.size();
    for (std::size_t k = 0; k < n; ++k)
        if (pred::orient(scene.area[k], scene.area[(k + 1) % n], p) < 0)
            throw InputError(std::string(name) + " " + show_point(p) + " is outside the working area");
    const Nearest near = index.nearest(p, ctx);
    if (near.sq <= radius * radius)
        throw InputError(std::string(name) + " " + show_point(p) + " is blocked: its clearance " +
                         std::to_string(std::sqrt(near.sq)) + " is not greater than the robot radius " +
                         std::to_string(radius) + " (nearest obstacle label " + std::to_string(near.label) + ")");
}

/// The free traced cell `p` connects to by a clear straight segment, or -1.
inline std::int64_t connect(const GridVoronoi& r, const Scene& scene, const ObstacleIndex& index,
                            QueryContext& ctx, const Vec2& p, const LazyGrid<std::int32_t>& where) {
    const double rad = r.robot_radius;
    const Nearest near = index.nearest(p, ctx);
    const Vec2 q = closest_point(scene, scene.parts[static_cast<std::size_t>(near.part)], p);
    Vec2 dir = p - q;
    const double len = dir.norm();
    const double span = std::hypot(scene.box.x1 - scene.box.x0, scene.box.y1 - scene.box.y0);
    if (len > 0) {
        dir /= len;
        const double step = r.grid.h / 4.0;
        for (double t = 0.0; t <= span; t += step) {
            const Vec2 x = p + t * dir;
            if (x.x() < scene.box.x0 || x.x() > scene.box.x1 || x.y() < scene.box.y0 || x.y() > scene.box.y1) break;
            std::int32_t i, j;
            r.grid.locate(x, i, j);
            const std::int32_t k = where.get(i, j);
            if (k >= 0) {
                if (r.blocked[static_cast<std::size_t>(k)]) continue;
                if (index.segment_clear(p, r.center(static_cast<std::size_t>(k)), rad, ctx)) return k;
                break;
            }
        }
    }
    // Fallback: the nearest free cells, in order of distance.
    std::vector<std::pair<double, std::int64_t>> cand;
    for (std::size_t k = 0; k < r.size(); ++k)
        if (!r.blocked[k]) cand.emplace_back((r.center(k) - p).squaredNorm(), static_cast<std::int64_t>(k));
    const std::size_t tries = std::min<std::size_t>(cand.size(), 256);
    std::partial_sort(cand.begin(), cand.begin() + static_cast<std::ptrdiff_t>(tries), cand.end());
    for (std::size_t t = 0; t < tries; ++t)
        if (index.segment_clear(p, r.center(static_cast<std::size_t>(cand[t].second)), rad, ctx)) return cand[t].second;
    return -1;
}

}  // namespace detail

/// Shortest path from `start` to `goal` along the diagram for a disk robot of radius r.robot_radius.
///
/// Needs r.has_graph (grid_voronoi builds it by default).
/// \throws InputError naming `start` or `goal` when it lies outside the working area or within the
/// robot radius of an obstacle (blocked). Returns an empty path when the two cannot be joined to the
/// diagram or the free part of the diagram does not connect them.
/// \note O(C log C) for C traced cells per A* round.
inline PathResult find_path(const GridVoronoi& r, const Scene& scene, const ObstacleIndex& index,
                            const Vec2& start, const Vec2& goal) {
    if (!r.has_graph) throw Error("find_path: the diagram's graph is not built (call build_graph first)");
    QueryContext ctx = index.context();
    detail::require_free(scene, index, ctx, start, r.robot_radius, "start");
    detail::require_free(scene, index, ctx, goal, r.robot_radius, "goal");
    PathResult out;
    LazyGrid<std::int32_t> where(0, r.grid.nx, r.grid.ny, -1);
    for (std::size_t k = 0; k < r.size(); ++k) where.at(r.col[k], r.row[k]) = static_cast<std::int32_t>(k);
    std::set<std::pair<std::int64_t, std::int64_t>> bad;  // steps that failed the exact check
    const std::int64_t s = detail::connect(r, scene, index, ctx, start, where);
    const std::int64_t g = detail::connect(r, scene, index, ctx, goal, where);
    if (s < 0 || g < 0) return out;
    const std::size_t n = r.size();
    const double h = r.grid.h;
    const Vec2 gc = r.center(static_cast<std::size_t>(g));
    for (int round = 0; round < 10000; ++round) {
        std::vector<double> dist(n, std::numeric_limits<double>::infinity());
        std::vector<std::int64_t> from(n, -1);
        using Item = std::pair<double, std::int64_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
        dist[static_cast<std::size_t>(s)] = 0.0;
        open.emplace((r.center(static_cast<std::size_t>(s)) - gc).norm(), s);
        while (!open.empty()) {
            const auto [f, u] = open.top();
            open.pop();
            const auto uu = static_cast<std::size_t>(u);
            if (u == g) break;
            if (f - (r.center(uu) - gc).norm() > dist[uu] + 1e-9 * h) continue;  // stale entry
            for (std::int32_t v : r.neighbors[uu]) {
                if (v < 0 || r.blocked[static_cast<std::size_t>(v)]) continue;
                if (bad.count({std::min<std::int64_t>(u, v), std::max<std::int64_t>(u, v)})) continue;
                const double d = dist[uu] + h;
                if (d < dist[static_cast<std::size_t>(v)]) {
                    dist[static_cast<std::size_t>(v)] = d;
                    from[static_cast<std::size_t>(v)] = u;
                    open.emplace(d + (r.center(static_cast<std::size_t>(v)) - gc).norm(), v);
                }
            }
        }
        if (!std::isfinite(dist[static_cast<std::size_t>(g)])) return out;
        std::vector<std::int64_t> cells;
        for (std::int64_t c = g; c >= 0; c = from[static_cast<std::size_t>(c)]) cells.push_back(c);
        std::reverse(cells.begin(), cells.end());
        bool ok = true;
        for (std::size_t t = 0; t + 1 < cells.size(); ++t) {
            if (!index.segment_clear(r.center(static_cast<std::size_t>(cells[t])), r.center(static_cast<std::size_t>(cells[t + 1])), r.robot_radius, ctx)) {
                bad.insert({std::min(cells[t], cells[t + 1]), std::max(cells[t], cells[t + 1])});
                ok = false;
            }
        }
        if (!ok) continue;
        out.points.push_back(start);
        for (std::int64_t c : cells) out.points.push_back(r.center(static_cast<std::size_t>(c)));
        out.points.push_back(goal);
        for (std::size_t t = 0; t + 1 < out.points.size(); ++t) out.length += (out.points[t + 1] - out.points[t]).norm();
        return out;
    }
    return out;
}

}  // namespace dvoronoi::gvd
