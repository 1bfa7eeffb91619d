// The communication graph of a sensor network (SPEC "Networks of agents"): the unit-disk graph of a
// communication range (a link when |p - q| <= range, decided exactly), minus the links whose segment
// meets an obstacle segment (exact orientation tests, core/predicates.hpp), plus the Gabriel
// planarisation that GPSR's perimeter mode walks on.
#pragma once

#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <unordered_map>
#include <vector>

namespace dvoronoi::network {

/// An obstacle that blocks line of sight: the closed segment a-b (a == b is a point obstacle).
struct Segment {
    Vec2 a = Vec2::Zero(), b = Vec2::Zero();
};

/// Do the closed segments p-q and a-b share a point? Exact (orientation signs only).
inline bool segments_intersect(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
    const int o1 = pred::orient(p, q, a), o2 = pred::orient(p, q, b);
    const int o3 = pred::orient(a, b, p), o4 = pred::orient(a, b, q);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    // Touching or collinear cases: a point of one segment on the other (closed) segment.
    const auto on = [](const Vec2& u, const Vec2& v, const Vec2& w) {  // w on closed u-v, given collinear
        return pred::dot_sign(w, u, v) <= 0;
    };
    if (o1 == 0 && on(p, q, a)) return true;
    if (o2 == 0 && on(p, q, b)) return true;
    if (o3 == 0 && on(a, b, p)) return true;
    if (o4 == 0 && on(a, b, q)) return true;
    return false;
}

/// Nodes, their links (sorted adjacency lists) and what made them.
struct Network {
    Points points;
    double range = 0.0;
    std::vector<Segment> obstacles;
    std::vector<std::vector<Index>> adj;  ///< links, ascending per node
    Index blocked_links = 0;              ///< unit-disk links removed by obstacles

    Index size() const noexcept { return static_cast<Index>(points.rows()); }
    Vec2 pos(Index i) const { return points.row(i).transpose(); }
    Index link_count() const {
        Index m = 0;
        for (const auto& a : adj) m += static_cast<Index>(a.size());
        return m / 2;
    }
    bool linked(Index i, Index j) const {
        const auto& a = adj[static_cast<std::size_t>(i)];
        return std::binary_search(a.begin(), a.end(), j);
    }
};

namespace detail {

/// Obstacles bucketed on a dense uniform grid over the nodes' bounding box (links lie inside it, so
/// only the obstacles' parts inside matter): a link tests the obstacles of the cells its bounding box
/// covers, after a bounding-box pre-test; the exact test decides.
class ObstacleGrid {
public:
    ObstacleGrid(const std::vector<Segment>& obs, double x0, double y0, double x1, double y1, double cell)
        : obs_(obs), x0_(x0), y0_(y0), cell_(cell) {
        nx_ = std::max<long long>(1, static_cast<long long>(std::floor((x1 - x0) / cell)) + 1);
        ny_ = std::max<long long>(1, static_cast<long long>(std::floor((y1 - y0) / cell)) + 1);
        if (static_cast<double>(nx_) * static_cast<double>(ny_) > 4e6) {  // absurd extents: one cell
            nx_ = ny_ = 1;
            cell_ = std::numeric_limits<double>::infinity();
        }
        std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(nx_ * ny_));
        for (std::size_t k = 0; k < obs.size(); ++k) {
            const auto [ax, ay] = key(obs[k].a);
            const auto [bx, by] = key(obs[k].b);
            for (long long x = std::max(0LL, std::min(ax, bx)); x <= std::min(nx_ - 1, std::max(ax, bx)); ++x)
                for (long long y = std::max(0LL, std::min(ay, by)); y <= std::min(ny_ - 1, std::max(ay, by)); ++y)
                    cells[static_cast<std::size_t>(x * ny_ + y)].push_back(k);
        }
        start_.push_back(0);
        for (const auto& c : cells) {
            ids_.insert(ids_.end(), c.begin(), c.end());
            start_.push_back(ids_.size());
        }
    }
    bool blocks(const Vec2& p, const Vec2& q, std::size_t stamp, std::vector<std::size_t>& mark) const {
        const auto [px, py] = key(p);
        const auto [qx, qy] = key(q);
        const double lx = std::min(p.x(), q.x()), hx = std::max(p.x(), q.x());
        const double ly = std::min(p.y(), q.y()), hy = std::max(p.y(), q.y());
        for (long long x = std::max(0LL, std::min(px, qx)); x <= std::min(nx_ - 1, std::max(px, qx)); ++x)
            for (long long y = std::max(0LL, std::min(py, qy)); y <= std::min(ny_ - 1, std::max(py, qy)); ++y) {
                const auto c = static_cast<std::size_t>(x * ny_ + y);
                for (std::size_t t = start_[c]; t < start_[c + 1]; ++t) {
                    const std::size_t k = ids_[t];
                    if (mark[k] == stamp) continue;
                    mark[k] = stamp;
                    const Segment& o = obs_[k];
                    if (std::max(o.a.x(), o.b.x()) < lx || std::min(o.a.x(), o.b.x()) > hx ||
                        std::max(o.a.y(), o.b.y()) < ly || std::min(o.a.y(), o.b.y()) > hy)
                        continue;
                    if (segments_intersect(p, q, o.a, o.b)) return true;
                }
            }
        return false;
    }

private:
    std::pair<long long, long long> key(const Vec2& p) const {
        if (!std::isfinite(cell_)) return {0, 0};
        const double fx = std::floor((p.x() - x0_) / cell_), fy = std::floor((p.y() - y0_) / cell_);
        return {static_cast<long long>(std::clamp(fx, -1.0, static_cast<double>(nx_))),
                static_cast<long long>(std::clamp(fy, -1.0, static_cast<double>(ny_)))};
    }
    const std::vector<Segment>& obs_;
    double x0_, y0_, cell_;
    long long nx_ = 1, ny_ = 1;
    std::vector<std::size_t> start_, ids_;
};

}  // namespace detail

/// Builds the communication graph. Complexity O(n k) for k nodes per range-sized grid cell, plus the
/// obstacles near each link.
///
/// \throws InputError for a bad range, non-finite coordinates, or coinciding nodes (they would need
///         the same cell).
inline Network make_network(PointsRef points, double range, const std::vector<Segment>& obstacles = {}) {
    dvoronoi::detail::require_finite_radius(range, "comm_range");
    dvoronoi::detail::require_finite_points(points, "points");
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
        dvoronoi::detail::require_finite_point(obstacles[k].a, "obstacles[" + std::to_string(k) + "]");
        dvoronoi::detail::require_finite_point(obstacles[k].b, "obstacles[" + std::to_string(k) + "]");
    }
    Network net;
    net.points = points;
    net.range = range;
    net.obstacles = obstacles;
    const Index n = net.size();
    net.adj.assign(static_cast<std::size_t>(n), {});
    if (n == 0) return net;
    const double x0 = net.points.col(0).minCoeff(), y0 = net.points.col(1).minCoeff();
    // Node grid (dense, counting sort) with cells of side `range` (slightly enlarged against
    // rounding): links only within the 3x3 block; the exact test decides.
    const double x1 = net.points.col(0).maxCoeff(), y1 = net.points.col(1).maxCoeff();
    double cell = range * (1.0 + 1e-9);
    cell = std::max({cell, (x1 - x0) / 2048.0, (y1 - y0) / 2048.0});  // at most 2048^2 cells
    const auto nx = static_cast<long long>(std::floor((x1 - x0) / cell)) + 1;
    const auto ny = static_cast<long long>(std::floor((y1 - y0) / cell)) + 1;
    const auto key = [&](const Vec2& p) {
        return std::pair<long long, long long>{std::min(nx - 1, static_cast<long long>(std::floor((p.x() - x0) / cell))),
                                               std::min(ny - 1, static_cast<long long>(std::floor((p.y() - y0) / cell)))};
    };
    std::vector<Index> start(static_cast<std::size_t>(nx * ny + 1), 0), order(static_cast<std::size_t>(n));
    std::vector<long long> cell_of(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        const auto [x, y] = key(net.pos(i));
        cell_of[static_cast<std::size_t>(i)] = x * ny + y;
        ++start[static_cast<std::size_t>(x * ny + y + 1)];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    {
        std::vector<Index> fill(start.begin(), start.end() - 1);
        for (Index i = 0; i < n; ++i) order[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of[static_cast<std::size_t>(i)])]++)] = i;
    }
    const detail::ObstacleGrid og(net.obstacles, x0, y0, x1, y1, 0.5 * cell);
    std::vector<std::size_t> mark(obstacles.size(), 0);
    std::size_t stamp = 0;
    const double half = 0.5 * range;  // |p - q| <= range  <=>  within_2r(p, q, range / 2) >= 0 (halving is exact)
    const double r2 = range * range;
    for (Index i = 0; i < n; ++i) {
        const Vec2 p = net.pos(i);
        const auto [x, y] = key(p);
        for (long long cx = std::max(0LL, x - 1); cx <= std::min(nx - 1, x + 1); ++cx)
            for (long long cy = std::max(0LL, y - 1); cy <= std::min(ny - 1, y + 1); ++cy) {
                const auto c = static_cast<std::size_t>(cx * ny + cy);
                for (Index t = start[c]; t < start[c + 1]; ++t) {
                    const Index j = order[static_cast<std::size_t>(t)];
                    if (j <= i) continue;
                    const Vec2 q = net.pos(j);
                    if (p == q)
                        throw CoincidentError("points[" + std::to_string(i) + "] and points[" + std::to_string(j) +
                                                  "] coincide; their Voronoi cells are undefined",
                                              i, j);
                    // Clear cases in floating point (relative error of d2 far below 1e-12), the
                    // rest exactly.
                    const double d2 = (p - q).squaredNorm();
                    if (d2 > r2 * (1.0 + 1e-12)) continue;
                    if (!(d2 < r2 * (1.0 - 1e-12)) && pred::within_2r(p, q, half) < 0) continue;
                    if (!obstacles.empty() && og.blocks(p, q, ++stamp, mark)) {
                        ++net.blocked_links;
                        continue;
                    }
                    net.adj[static_cast<std::size_t>(i)].push_back(j);
                    net.adj[static_cast<std::size_t>(j)].push_back(i);
                }
            }
    }
    for (auto& a : net.adj) std::sort(a.begin(), a.end());
    return net;
}

/// The Gabriel subgraph GPSR's perimeter mode walks on: link u-v is kept unless a witness w linked to
/// both lies strictly inside the circle with diameter uv (exact: (u - w).(v - w) < 0). Without
/// obstacles this is the Gabriel graph of the unit-disk graph (planar, connected when the unit-disk
/// graph is); requiring the witness to be linked to both keeps it connected with obstacles too, where
/// planarity is no longer guaranteed.
inline std::vector<std::vector<Index>> gabriel_graph(const Network& net) {
    const Index n = net.size();
    std::vector<std::vector<Index>> g(static_cast<std::size_t>(n));
    for (Index u = 0; u < n; ++u) {
        const auto& au = net.adj[static_cast<std::size_t>(u)];
        for (Index v : au) {
            if (v < u) continue;
            const auto& av = net.adj[static_cast<std::size_t>(v)];
            bool keep = true;
            // Common neighbours (both lists sorted).
            auto a = au.begin(), b = av.begin();
            while (keep && a != au.end() && b != av.end()) {
                if (*a < *b) ++a;
                else if (*b < *a) ++b;
                else {
                    if (pred::dot_sign(net.pos(*a), net.pos(u), net.pos(v)) < 0) keep = false;
                    ++a, ++b;
                }
            }
            if (keep) {
                g[static_cast<std::size_t>(u)].push_back(v);
                g[static_cast<std::size_t>(v)].push_back(u);
            }
        }
    }
    for (auto& a : g) std::sort(a.begin(), a.end());
    return g;
}

/// Connected components of a graph given by adjacency lists: component id per node (0, 1, ...).
inline std::vector<Index> components(const std::vector<std::vector<Index>>& adj) {
    std::vector<Index> comp(adj.size(), -1);
    Index next = 0;
    std::vector<Index> stack;
    for (std::size_t s = 0; s < adj.size(); ++s) {
        if (comp[s] >= 0) continue;
        comp[s] = next;
        stack.assign(1, static_cast<Index>(s));
        while (!stack.empty()) {
            const Index u = stack.back();
            stack.pop_back();
            for (Index v : adj[static_cast<std::size_t>(u)])
                if (comp[static_cast<std::size_t>(v)] < 0) {
                    comp[static_cast<std::size_t>(v)] = next;
                    stack.push_back(v);
                }
        }
        ++next;
    }
    return comp;
}

/// Hop-shortest paths from `source` (BFS): parent per node (-1 for the source and unreachable nodes)
/// and hop counts (-1 when unreachable).
inline void bfs(const std::vector<std::vector<Index>>& adj, Index source, std::vector<Index>& parent,
                std::vector<Index>& hops) {
    parent.assign(adj.size(), -1);
    hops.assign(adj.size(), -1);
    std::queue<Index> q;
    hops[static_cast<std::size_t>(source)] = 0;
    q.push(source);
    while (!q.empty()) {
        const Index u = q.front();
        q.pop();
        for (Index v : adj[static_cast<std::size_t>(u)])
            if (hops[static_cast<std::size_t>(v)] < 0) {
                hops[static_cast<std::size_t>(v)] = hops[static_cast<std::size_t>(u)] + 1;
                parent[static_cast<std::size_t>(v)] = u;
                q.push(v);
            }
    }
}

}  // namespace dvoronoi::network
