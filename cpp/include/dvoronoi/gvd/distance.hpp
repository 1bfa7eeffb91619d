// Point-to-obstacle and segment-to-obstacle distances for the grid Voronoi diagram.
//
// Distances are to the obstacle's region (0 inside). They are computed in double precision by one
// deterministic formula per shape, and compared as squared distances (circles: (|p-c| - r)^2 clamped
// at 0), so every caller — the tracer, its workers, the brute-force oracle — gets the same label for
// the same corner. Ties (equal squared doubles) go to the lower obstacle label. The value differs
// from the real distance by a few ulps; a corner whose two nearest obstacles are closer than that may
// take either label, which moves the diagram by far less than a cell.
//
// Visibility test (Mendes et al., Section 2): a polygon edge is looked at only when the point lies
// strictly on its outer side (the inner product of the edge's outward normal with the vector from
// the point to the edge is negative); a point on the inner side of every edge is inside (distance 0).
// Without the test every edge's distance is computed and an inside test decides 0.
#pragma once

#include "dvoronoi/gvd/obstacles.hpp"

#include <algorithm>
#include <cmath>

namespace dvoronoi::gvd {

/// Counters of the work a distance query did (optional).
struct DistanceCounters {
    std::uint64_t part_evaluations = 0;  ///< convex parts whose distance was computed
    std::uint64_t edge_evaluations = 0;  ///< polygon edges / segments measured
};

namespace detail {

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Squared distance from p to segment ab. The clamped ends use |p-a|^2 and |p-b|^2 exactly, so the
/// two edges meeting at a vertex agree there.
inline double sq_point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a, ap = p - a;
    const double t = ap.dot(ab);
    if (t <= 0.0) return ap.squaredNorm();
    const double l2 = ab.squaredNorm();
    if (t >= l2) return (p - b).squaredNorm();
    const double c = cross2(ab, ap);
    return c * c / l2;
}

/// Closest point of segment ab to p.
inline Vec2 closest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double l2 = ab.squaredNorm();
    if (l2 == 0.0) return a;
    const double t = std::clamp((p - a).dot(ab) / l2, 0.0, 1.0);
    return a + t * ab;
}

/// Squared distance between segments ab and cd (0 when they intersect).
inline double sq_segment_segment(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    if (segments_touch(a, b, c, d)) return 0.0;
    return std::min({sq_point_segment(a, c, d), sq_point_segment(b, c, d), sq_point_segment(c, a, b),
                     sq_point_segment(d, a, b)});
}

}  // namespace detail

/// Squared distance from p to a convex part (0 inside or on it).
/// \note Thread-safe; O(vertices of the part).
inline double sq_distance(const Scene& s, const ConvexPart& part, const Vec2& p, bool visibility,
                          DistanceCounters* counters = nullptr) {
    if (counters) ++counters->part_evaluations;
    const Vec2* v = s.part_vertices(part);
    switch (part.kind) {
        case ShapeKind::Point: return (p - v[0]).squaredNorm();
        case ShapeKind::Segment:
            if (counters) ++counters->edge_evaluations;
            return detail::sq_point_segment(p, v[0], v[1]);
        case ShapeKind::Circle: {
            const double d = std::max(0.0, (p - part.center).norm() - part.radius);
            return d * d;
        }
        case ShapeKind::Polygon: {
            const std::uint32_t n = part.count;
            double best = std::numeric_limits<double>::infinity();
            bool outside = false;
            for (std::uint32_t i = 0; i < n; ++i) {
                const Vec2& a = v[i];
                const Vec2& b = v[i + 1 == n ? 0 : i + 1];
                // CCW polygon: p is strictly outside edge ab when cross(b - a, p - a) < 0, i.e. the
                // outward normal and p - a point the same way (the paper's visibility test). The cross
                // product is reused below: the value equals sq_point_segment(p, a, b) exactly.
                const Vec2 ab = b - a, ap = p - a;
                const double c = detail::cross2(ab, ap);
                const bool out = c < 0.0;
                outside |= out;
                if (visibility && !out) continue;
                if (counters) ++counters->edge_evaluations;
                const double t = ap.dot(ab);
                double d;
                if (t <= 0.0) {
                    d = ap.squaredNorm();
                } else {
                    const double l2 = ab.squaredNorm();
                    d = t >= l2 ? (p - b).squaredNorm() : c * c / l2;
                }
                best = std::min(best, d);
            }
            return outside ? best : 0.0;
        }
    }
    return std::numeric_limits<double>::infinity();
}

/// Closest point of a convex part to p (p itself when p is inside).
inline Vec2 closest_point(const Scene& s, const ConvexPart& part, const Vec2& p) {
    const Vec2* v = s.part_vertices(part);
    switch (part.kind) {
        case ShapeKind::Point: return v[0];
        case ShapeKind::Segment: return detail::closest_on_segment(p, v[0], v[1]);
        case ShapeKind::Circle: {
            const Vec2 d = p - part.center;
            const double n = d.norm();
            if (n <= part.radius) return p;
            return part.center + d * (part.radius / n);
        }
        case ShapeKind::Polygon: {
            bool outside = false;
            double best = std::numeric_limits<double>::infinity();
            Vec2 q = p;
            for (std::uint32_t i = 0; i < part.count; ++i) {
                const Vec2& a = v[i];
                const Vec2& b = v[i + 1 == part.count ? 0 : i + 1];
                if (detail::cross2(b - a, p - a) < 0.0) outside = true;
                const Vec2 c = detail::closest_on_segment(p, a, b);
                const double d = (p - c).squaredNorm();
                if (d < best) { best = d; q = c; }
            }
            return outside ? q : p;
        }
    }
    return p;
}

/// Squared distance from segment ab to a convex part (0 when they meet).
/// \note Thread-safe; O(vertices of the part).
inline double sq_segment_distance(const Scene& s, const ConvexPart& part, const Vec2& a, const Vec2& b) {
    const Vec2* v = s.part_vertices(part);
    switch (part.kind) {
        case ShapeKind::Point: return detail::sq_point_segment(v[0], a, b);
        case ShapeKind::Segment: return detail::sq_segment_segment(a, b, v[0], v[1]);
        case ShapeKind::Circle: {
            const double d = std::max(0.0, std::sqrt(detail::sq_point_segment(part.center, a, b)) - part.radius);
            return d * d;
        }
        case ShapeKind::Polygon: {
            if (sq_distance(s, part, a, false) == 0.0 || sq_distance(s, part, b, false) == 0.0) return 0.0;
            double best = std::numeric_limits<double>::infinity();
            for (std::uint32_t i = 0; i < part.count; ++i)
                best = std::min(best, detail::sq_segment_segment(a, b, v[i], v[i + 1 == part.count ? 0 : i + 1]));
            return best;
        }
    }
    return std::numeric_limits<double>::infinity();
}

}  // namespace dvoronoi::gvd
