// The communication graph of a sensor network (SPEC "Networks of agents"): the unit-disk graph of a
// communication range (a link when |p - q| <= range, decided exactly), minus the links whose segment
// meets an obstacle segment (exact orientation tests, core/predicates.hpp), plus the Gabriel
// planarisation that GPSR's perimeter mode walks on.
#pragma once

#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
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

/// Obstacles bucketed on a uniform grid (cell = range), so a link tests only the obstacles near it.
class ObstacleGrid {
public:
    ObstacleGrid(const std::vector<Segment>& obs, double x0, double y0, double cell)
        : obs_(obs), x0_(x0), y0_(y0), cell_(cell) {
        for (std::size_t k = 0; k < obs.size(); ++k) {
            const auto [ax, ay] = key(obs[k].a);
            const auto [bx, by] = key(obs[k].b);
            for (long long x = std::min(ax, bx); x <= std::max(ax, bx); ++x)
                for (long long y = std::min(ay, by); y <= std::max(ay, by); ++y) cells_[pack(x, y)].push_back(k);
        }
    }
    bool blocks(const Vec2& p, const Vec2& q, std::size_t stamp, std::vector<std::size_t>& mark) const {
        const auto [px, py] = key(p);
        const auto [qx, qy] = key(q);
        for (long long x = std::min(px, qx) - 1; x <= std::max(px, qx) + 1; ++x)
            for (long long y = std::min(py, qy) - 1; y <= std::max(py, qy) + 1; ++y) {
                const auto it = cells_.find(pack(x, y));
                if (it == cells_.end()) continue;
                for (std::size_t k : it->second) {
                    if (mark[k] == stamp) continue;
                    mark[k] = stamp;
                    if (segments_intersect(p, q, obs_[k].a, obs_[k].b)) return true;
                }
            }
        return false;
    }

private:
    std::pair<long long, long long> key(const Vec2& p) const {
        return {static_cast<long long>(std::floor((p.x() - x0_) / cell_)),
                static_cast<long long>(std::floor((p.y() - y0_) / cell_))};
    }
    static long long pack(long long x, long long y) { return x * 2654435761LL ^ (y + (1LL << 31)); }
    const std::vector<Segment>& obs_;
    double x0_, y0_, cell_;
    std::unordered_map<long long, std::vector<std::size_t>> cells_;
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
    // Node grid with cells of side `range` (slightly enlarged against rounding): links only within
    // the 3x3 block; the exact test decides.
    const double cell = range * (1.0 + 1e-9);
    std::unordered_map<long long, std::vector<Index>> grid;
    const auto key = [&](const Vec2& p) {
        return std::pair<long long, long long>{static_cast<long long>(std::floor((p.x() - x0) / cell)),
                                               static_cast<long long>(std::floor((p.y() - y0) / cell))};
    };
    const auto pack = [](long long x, long long y) { return x * 2654435761LL ^ (y + (1LL << 31)); };
    for (Index i = 0; i < n; ++i) {
        const auto [x, y] = key(net.pos(i));
        grid[pack(x, y)].push_back(i);
    }
    const detail::ObstacleGrid og(net.obstacles, x0, y0, cell);
    std::vector<std::size_t> mark(obstacles.size(), 0);
    std::size_t stamp = 0;
    const double half = 0.5 * range;  // |p - q| <= range  <=>  within_2r(p, q, range / 2) >= 0 (halving is exact)
    for (Index i = 0; i < n; ++i) {
        const Vec2 p = net.pos(i);
        const auto [x, y] = key(p);
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy) {
                const auto it = grid.find(pack(x + dx, y + dy));
                if (it == grid.end()) continue;
                for (Index j : it->second) {
                    if (j <= i) continue;
                    const Vec2 q = net.pos(j);
                    if (p == q)
                        throw CoincidentError("points[" + std::to_string(i) + "] and points[" + std::to_string(j) +
                                                  "] coincide; their Voronoi cells are undefined",
                                              i, j);
                    if (pred::within_2r(p, q, half) < 0) continue;
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
