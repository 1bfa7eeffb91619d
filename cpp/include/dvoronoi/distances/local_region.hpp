// A robot's Voronoi region in its own coordinates, from its neighbours in Delaunay-path order and the
// measured distances (Elwin, Freeman & Lynch, Sections I and IV-A): the shape is known up to rotation
// and reflection, so we fix them — the robot at the origin, its first path neighbour on the +x axis,
// the path turning counter-clockwise. Consecutive path neighbours form triangles with the robot; each
// is placed by the law of cosines, O(|V_i|). The region's vertices are the circumcentres of those
// triangles. With exact distances this is the true region up to a rigid motion (and rounding); with
// noisy ones it is the region the measurements imply (it may then be slightly non-convex).
#pragma once

#include "dvoronoi/distances/distance_graph.hpp"

#include <cmath>
#include <vector>

namespace dvoronoi::dist {

/// Robot i's Voronoi region in local coordinates (robot at the origin).
struct LocalRegion {
    std::vector<Index> neighbors;  ///< path order, as given
    std::vector<Vec2> positions;   ///< local coordinates of the neighbours (same order)
    std::vector<Vec2> vertices;    ///< region vertices in boundary order (circumcentres; for a hull
                                   ///< robot the finite ones, from the ray of the first neighbour's edge
                                   ///< to the ray of the last one's)
    bool bounded = false;          ///< interior robot: the vertices close a polygon
    Vec2 ray_in{0.0, 0.0};         ///< hull robot: unit direction from vertices.front() to infinity
                                   ///< along the first neighbour's edge
    Vec2 ray_out{0.0, 0.0};        ///< hull robot: unit direction from vertices.back() to infinity
                                   ///< along the last neighbour's edge
};

namespace detail {
inline Vec2 circumcenter_with_origin(const Vec2& p, const Vec2& q) {
    const double d = 2.0 * (p.x() * q.y() - p.y() * q.x());
    const double pp = p.squaredNorm(), qq = q.squaredNorm();
    return Vec2((q.y() * pp - p.y() * qq) / d, (p.x() * qq - q.x() * pp) / d);
}
}  // namespace detail

/// The region of robot i given its neighbours in path order (`order`) and whether it is on the hull.
/// \throws InputError when two consecutive neighbours (or i and a neighbour) have no measured
///         distance. O(|order| log degree).
inline LocalRegion local_region(const DistanceGraph& g, Index i, const std::vector<Index>& order, bool hull) {
    g.check_index(i);
    LocalRegion r;
    r.neighbors = order;
    r.bounded = !hull;
    const std::size_t m = order.size();
    if (m == 0) return r;
    const auto sq = [&](Index a, Index b) {
        const double v = g.value(a, b);
        if (!std::isfinite(v))
            throw InputError("local_region: robots " + std::to_string(a) + " and " + std::to_string(b) +
                             " have no measured distance (not a path of robot " + std::to_string(i) + ")");
        return g.squared ? v : v * v;
    };
    double theta = 0.0;
    for (std::size_t t = 0; t < m; ++t) {
        const double b = sq(i, order[t]);
        if (t > 0) {
            const double a = sq(i, order[t - 1]), c = sq(order[t - 1], order[t]);
            const double cosang = (a + b - c) / (2.0 * std::sqrt(a * b));
            theta += std::acos(std::max(-1.0, std::min(1.0, cosang)));
        }
        const double d = std::sqrt(b);
        r.positions.emplace_back(d * std::cos(theta), d * std::sin(theta));
    }
    const std::size_t pairs = hull ? m - 1 : m;
    for (std::size_t t = 0; t < pairs && m > 1; ++t)
        r.vertices.push_back(detail::circumcenter_with_origin(r.positions[t], r.positions[(t + 1) % m]));
    if (hull) {
        // Walking the boundary counter-clockwise, the edge shared with neighbour q is travelled along
        // perp(q) = (-q.y, q.x): it comes in from infinity along the first neighbour's edge and leaves
        // along the last one's.
        const Vec2 f = r.positions.front(), l = r.positions.back();
        r.ray_in = Vec2(f.y(), -f.x()).normalized();
        r.ray_out = Vec2(-l.y(), l.x()).normalized();
        if (m == 1) r.vertices.push_back(0.5 * f);  // a half-plane: one point of its boundary line
    }
    return r;
}

}  // namespace dvoronoi::dist
