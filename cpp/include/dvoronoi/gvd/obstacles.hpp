// Obstacles and the working area of the grid Voronoi diagram (Mendes et al., docs/spec.md, "Grid diagram of
// obstacles"), compiled into a Scene of convex parts.
//
// An Obstacle is one label: a point, a segment, a circle, a simple polygon (convex or not), or a union
// of such shapes (an occupancy-grid region is a union of rectangles). Non-convex polygons are split
// into convex parts (ear clipping, then Hertel-Mehlhorn: drop every diagonal whose removal keeps both
// sides convex, at most 4x the optimal part count) that keep the obstacle's label, as the paper asks.
// The working area is an axis-aligned box or a convex polygon; each of its boundary edges is an
// obstacle of its own, labelled after the user's obstacles (label n + k for edge k, from vertex k to
// vertex k+1 counter-clockwise), so the area's corners are Voronoi vertices.
//
// All decisions about shapes (convexity, simplicity, ears) use the exact orientation predicate.
#pragma once

#include "dvoronoi/core/convex_ring.hpp"
#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace dvoronoi::gvd {

/// Kind of a convex shape.
enum class ShapeKind : std::uint8_t { Point = 0, Segment = 1, Polygon = 2, Circle = 3 };

/// One shape as the user gives it. Polygon: a simple polygon with >= 3 vertices, any orientation,
/// convex or not. Segment: 2 vertices. Point: 1 vertex. Circle: center + radius > 0.
struct Shape {
    ShapeKind kind = ShapeKind::Point;
    std::vector<Vec2> vertices;
    Vec2 center = Vec2::Zero();
    double radius = 0.0;

    static Shape point(const Vec2& p) { return {ShapeKind::Point, {p}, p, 0.0}; }
    static Shape segment(const Vec2& a, const Vec2& b) { return {ShapeKind::Segment, {a, b}, a, 0.0}; }
    static Shape polygon(std::vector<Vec2> v) { return {ShapeKind::Polygon, std::move(v), Vec2::Zero(), 0.0}; }
    static Shape circle(const Vec2& c, double r) { return {ShapeKind::Circle, {}, c, r}; }
};

/// One obstacle = one label: a union of shapes (usually one).
struct Obstacle {
    std::vector<Shape> shapes;
    Obstacle() = default;
    Obstacle(Shape s) : shapes{std::move(s)} {}  // NOLINT: a shape is an obstacle
    explicit Obstacle(std::vector<Shape> s) : shapes(std::move(s)) {}
};

/// Axis-aligned bounding box.
struct Box {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
    double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
    void add(const Vec2& p) {
        x0 = std::min(x0, p.x()); y0 = std::min(y0, p.y());
        x1 = std::max(x1, p.x()); y1 = std::max(y1, p.y());
    }
    /// Squared distance from p to the box (0 inside).
    double sq_distance(const Vec2& p) const {
        const double dx = std::max({x0 - p.x(), 0.0, p.x() - x1});
        const double dy = std::max({y0 - p.y(), 0.0, p.y() - y1});
        return dx * dx + dy * dy;
    }
};

/// A convex part of an obstacle (or an area edge), ready for distance queries. Polygon vertices are
/// counter-clockwise, without repeated or collinear vertices.
struct ConvexPart {
    ShapeKind kind = ShapeKind::Point;
    std::int32_t label = 0;   ///< obstacle index (area edges: n_obstacles + edge index)
    std::uint32_t first = 0;  ///< first vertex in Scene::vertices
    std::uint32_t count = 0;  ///< vertex count (Point 1, Segment 2, Polygon >= 3, Circle 0)
    Vec2 center = Vec2::Zero();
    double radius = 0.0;
    Box box;
};

/// The compiled input: convex parts of every obstacle and of the area boundary.
struct Scene {
    std::vector<ConvexPart> parts;
    std::vector<Vec2> vertices;
    std::vector<Vec2> area;        ///< working area, counter-clockwise convex polygon
    bool area_is_box = false;      ///< area given as an axis-aligned box
    std::int32_t n_obstacles = 0;  ///< user obstacles; labels [n_obstacles, n_labels) are area edges
    std::int32_t n_labels = 0;
    Box box;                       ///< bounding box of the area
    const Vec2* part_vertices(const ConvexPart& p) const { return vertices.data() + p.first; }
};

namespace detail {

inline std::string where(std::size_t obstacle, std::size_t shape, std::size_t n_shapes) {
    std::string s = "obstacles[" + std::to_string(obstacle) + "]";
    if (n_shapes > 1) s += ".parts[" + std::to_string(shape) + "]";
    return s;
}

/// +1 when the ring (core/convex_ring.hpp's clean_ring: no repeats, no straight-on vertices) runs
/// counter-clockwise, -1 clockwise, exactly: the turn at the lowest of the leftmost vertices, a corner of the polygon's
/// hull, has the polygon's orientation (for a simple ring; other rings are refused later anyway).
/// Not the shoelace sum: in doubles it cancels at large coordinates and underflows at tiny ones.
inline int ring_orientation(const std::vector<Vec2>& v) {
    std::size_t m = 0;
    for (std::size_t k = 1; k < v.size(); ++k)
        if (v[k].x() < v[m].x() || (v[k].x() == v[m].x() && v[k].y() < v[m].y())) m = k;
    const std::size_t n = v.size();
    return pred::orient(v[(m + n - 1) % n], v[m], v[(m + 1) % n]) >= 0 ? 1 : -1;
}

/// Is the CCW ring (clean_ring's) convex and simple: a left turn at every vertex, one winding?
inline bool ring_is_convex(const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i)
        if (pred::orient(v[i], v[(i + 1) % n], v[(i + 2) % n]) < 0) return false;
    return ::dvoronoi::detail::windings(v) == 1;
}

/// Do segments ab and cd share a point (exact)?
inline bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    const int o1 = pred::orient(a, b, c), o2 = pred::orient(a, b, d);
    const int o3 = pred::orient(c, d, a), o4 = pred::orient(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    auto on = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on segment pq, given collinear
        return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
               std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
    };
    return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
           (o4 == 0 && on(c, d, b));
}

/// Is the closed ring simple (no two non-adjacent edges touch)? O(n^2), exact. Returns the first
/// offending pair of edge indices in (e1, e2), or (-1, -1).
inline bool ring_is_simple(const std::vector<Vec2>& v, long& e1, long& e2) {
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // adjacent edges share a vertex
            if (segments_touch(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
                e1 = static_cast<long>(i);
                e2 = static_cast<long>(j);
                return false;
            }
        }
    e1 = e2 = -1;
    return true;
}

inline bool cycle_is_convex(const std::vector<Vec2>& pts, const std::vector<std::uint32_t>& c) {
    const std::size_t n = c.size();
    for (std::size_t i = 0; i < n; ++i)
        if (pred::orient(pts[c[i]], pts[c[(i + 1) % n]], pts[c[(i + 2) % n]]) < 0) return false;
    return true;
}

/// Convex decomposition of a simple CCW polygon without collinear vertices: ear clipping into
/// triangles (exact predicates), then Hertel-Mehlhorn merging across diagonals while the union stays
/// convex. Returns vertex-index cycles (CCW).
inline std::vector<std::vector<std::uint32_t>> convex_decomposition(const std::vector<Vec2>& v) {
    const std::uint32_t n = static_cast<std::uint32_t>(v.size());
    std::vector<std::vector<std::uint32_t>> pieces;
    if (ring_is_convex(v)) {
        pieces.emplace_back(n);
        std::iota(pieces[0].begin(), pieces[0].end(), 0u);
        return pieces;
    }
    // Ear clipping, O(n^2).
    std::vector<std::uint32_t> ring(n);
    std::iota(ring.begin(), ring.end(), 0u);
    std::vector<std::array<std::uint32_t, 2>> diagonals;
    auto inside_closed = [&](const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
        return pred::orient(a, b, p) >= 0 && pred::orient(b, c, p) >= 0 && pred::orient(c, a, p) >= 0;
    };
    std::size_t guard = 0;
    while (ring.size() > 3) {
        const std::size_t m = ring.size();
        bool clipped = false;
        for (std::size_t k = 0; k < m && !clipped; ++k) {
            const std::uint32_t ia = ring[(k + m - 1) % m], ib = ring[k], ic = ring[(k + 1) % m];
            const Vec2 &a = v[ia], &b = v[ib], &c = v[ic];
            const int o = pred::orient(a, b, c);
            if (o < 0) continue;  // reflex
            bool ear = true;
            if (o > 0) {
                for (std::size_t t = 0; t < m && ear; ++t) {
                    const std::uint32_t ip = ring[t];
                    if (ip == ia || ip == ib || ip == ic) continue;
                    if (v[ip] == a || v[ip] == b || v[ip] == c) continue;
                    if (inside_closed(a, b, c, v[ip])) ear = false;
                }
            }
            if (!ear) continue;
            if (o > 0) {
                pieces.push_back({ia, ib, ic});
                diagonals.push_back({ia, ic});
            }  // o == 0: a degenerate (collinear) ear has no area; drop the vertex
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
            clipped = true;
        }
        if (!clipped || ++guard > 4 * static_cast<std::size_t>(n)) break;  // cannot happen for simple input
    }
    if (ring.size() == 3 && pred::orient(v[ring[0]], v[ring[1]], v[ring[2]]) > 0)
        pieces.push_back({ring[0], ring[1], ring[2]});
    // The last diagonal added closes the final triangle, so it is shared too; keep every diagonal
    // (those that border one piece only are skipped below).
    // Hertel-Mehlhorn: merge the two pieces on either side of a diagonal while the union is convex.
    std::vector<int> owner_alias(pieces.size());
    std::iota(owner_alias.begin(), owner_alias.end(), 0);
    std::function<int(int)> find = [&](int x) { return owner_alias[x] == x ? x : owner_alias[x] = find(owner_alias[x]); };
    auto has_edge = [](const std::vector<std::uint32_t>& c, std::uint32_t a, std::uint32_t b) -> long {
        for (std::size_t i = 0; i < c.size(); ++i)
            if (c[i] == a && c[(i + 1) % c.size()] == b) return static_cast<long>(i);
        return -1;
    };
    for (const auto& d : diagonals) {
        int pa = -1, pb = -1;
        long ea = -1, eb = -1;
        for (int p = 0; p < static_cast<int>(pieces.size()); ++p) {
            if (find(p) != p) continue;
            long e = has_edge(pieces[static_cast<std::size_t>(p)], d[0], d[1]);
            if (e >= 0) { pa = p; ea = e; }
            e = has_edge(pieces[static_cast<std::size_t>(p)], d[1], d[0]);
            if (e >= 0) { pb = p; eb = e; }
        }
        if (pa < 0 || pb < 0 || pa == pb) continue;
        const auto& A = pieces[static_cast<std::size_t>(pa)];
        const auto& B = pieces[static_cast<std::size_t>(pb)];
        // A has d0 -> d1 at ea; B has d1 -> d0 at eb. Union: A from d1 around to d0, then B from d0
        // (exclusive) around to d1 (exclusive).
        std::vector<std::uint32_t> merged;
        for (std::size_t i = 0; i < A.size(); ++i) merged.push_back(A[(static_cast<std::size_t>(ea) + 1 + i) % A.size()]);
        for (std::size_t i = 2; i < B.size(); ++i) merged.push_back(B[(static_cast<std::size_t>(eb) + i) % B.size()]);
        if (!cycle_is_convex(v, merged)) continue;
        pieces[static_cast<std::size_t>(pa)] = std::move(merged);
        owner_alias[static_cast<std::size_t>(pb)] = pa;
    }
    std::vector<std::vector<std::uint32_t>> out;
    for (std::size_t p = 0; p < pieces.size(); ++p)
        if (find(static_cast<int>(p)) == static_cast<int>(p)) out.push_back(std::move(pieces[p]));
    return out;
}

inline void require_finite(const Vec2& p, const std::string& name) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
        throw InputError(name + " has a non-finite coordinate (NaN or inf)");
}

}  // namespace detail

/// A working area: an axis-aligned box.
inline std::vector<Vec2> box_area(double x0, double y0, double x1, double y1) {
    if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1)))
        throw InputError("area: box coordinates must be finite");
    if (!(x1 > x0 && y1 > y0)) throw InputError("area: box max must exceed min in x and y");
    return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
}

/// Compiles obstacles and a convex working area into a Scene.
///
/// \throws InputError naming `obstacles[i]` (and `.parts[k]`, `.vertices`, `.radius`) for a
/// non-finite coordinate, a non-positive radius, a polygon with fewer than 3 non-collinear vertices, a
/// spike or one that is not simple; naming `area` for an area that is not a convex polygon.
/// \note O(total vertices^2) for the simplicity checks of non-convex polygons; linear otherwise.
inline Scene make_scene(const std::vector<Obstacle>& obstacles, const std::vector<Vec2>& area_in,
                        bool area_is_box = false) {
    Scene s;
    if (obstacles.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2))
        throw InputError("obstacles: too many obstacles");
    s.n_obstacles = static_cast<std::int32_t>(obstacles.size());
    // Area: CCW convex polygon.
    for (std::size_t k = 0; k < area_in.size(); ++k)
        detail::require_finite(area_in[k], "area.vertices[" + std::to_string(k) + "]");
    std::vector<Vec2> area = ::dvoronoi::detail::clean_ring(area_in, "area");
    if (detail::ring_orientation(area) < 0) std::reverse(area.begin(), area.end());
    if (!detail::ring_is_convex(area)) throw InputError("area: the working area must be a convex polygon");
    s.area = area;
    s.area_is_box = area_is_box;
    for (const Vec2& p : area) s.box.add(p);

    auto add_part = [&](ShapeKind kind, std::int32_t label, const std::vector<Vec2>& pts, const Vec2& c,
                        double r) {
        ConvexPart p;
        p.kind = kind;
        p.label = label;
        p.first = static_cast<std::uint32_t>(s.vertices.size());
        p.count = static_cast<std::uint32_t>(pts.size());
        p.center = c;
        p.radius = r;
        for (const Vec2& q : pts) {
            s.vertices.push_back(q);
            p.box.add(q);
        }
        if (kind == ShapeKind::Circle) {
            // Rounded outward a little: the bounding box must contain the whole disk.
            const double rr = r * (1.0 + 1e-12) + 1e-300;
            p.box.add(Vec2(c.x() - rr, c.y() - rr));
            p.box.add(Vec2(c.x() + rr, c.y() + rr));
        }
        s.parts.push_back(p);
    };

    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        const auto label = static_cast<std::int32_t>(i);
        const auto& shapes = obstacles[i].shapes;
        if (shapes.empty()) throw InputError("obstacles[" + std::to_string(i) + "]: has no shape");
        for (std::size_t k = 0; k < shapes.size(); ++k) {
            const Shape& sh = shapes[k];
            const std::string name = detail::where(i, k, shapes.size());
            switch (sh.kind) {
                case ShapeKind::Point:
                    if (sh.vertices.size() != 1) throw InputError(name + ": a point has one position");
                    detail::require_finite(sh.vertices[0], name + ".position");
                    add_part(ShapeKind::Point, label, sh.vertices, sh.vertices[0], 0.0);
                    break;
                case ShapeKind::Segment:
                    if (sh.vertices.size() != 2) throw InputError(name + ": a segment has two endpoints");
                    detail::require_finite(sh.vertices[0], name + ".vertices[0]");
                    detail::require_finite(sh.vertices[1], name + ".vertices[1]");
                    if (sh.vertices[0] == sh.vertices[1])
                        add_part(ShapeKind::Point, label, {sh.vertices[0]}, sh.vertices[0], 0.0);
                    else
                        add_part(ShapeKind::Segment, label, sh.vertices, sh.vertices[0], 0.0);
                    break;
                case ShapeKind::Circle:
                    detail::require_finite(sh.center, name + ".center");
                    if (!std::isfinite(sh.radius) || !(sh.radius > 0.0))
                        throw InputError(name + ".radius: must be a positive finite number");
                    add_part(ShapeKind::Circle, label, {}, sh.center, sh.radius);
                    break;
                case ShapeKind::Polygon: {
                    for (std::size_t t = 0; t < sh.vertices.size(); ++t)
                        detail::require_finite(sh.vertices[t], name + ".vertices[" + std::to_string(t) + "]");
                    std::vector<Vec2> ring = ::dvoronoi::detail::clean_ring(sh.vertices, name + ".vertices");
                    if (detail::ring_orientation(ring) < 0) std::reverse(ring.begin(), ring.end());
                    if (detail::ring_is_convex(ring)) {
                        add_part(ShapeKind::Polygon, label, ring, ring[0], 0.0);
                        break;
                    }
                    long e1, e2;
                    if (!detail::ring_is_simple(ring, e1, e2))
                        throw InputError(name + ".vertices: polygon is not simple (edges " +
                                         std::to_string(e1) + " and " + std::to_string(e2) + " touch)");
                    for (const auto& cyc : detail::convex_decomposition(ring)) {
                        std::vector<Vec2> pts;
                        for (auto id : cyc) pts.push_back(ring[id]);
                        pts = ::dvoronoi::detail::clean_ring(pts, name + ".vertices");  // merged pieces may hold straight-on vertices
                        add_part(ShapeKind::Polygon, label, pts, pts[0], 0.0);
                    }
                    break;
                }
            }
        }
    }
    // Area edges, one label each.
    for (std::size_t k = 0; k < area.size(); ++k) {
        const auto label = static_cast<std::int32_t>(obstacles.size() + k);
        add_part(ShapeKind::Segment, label, {area[k], area[(k + 1) % area.size()]}, area[k], 0.0);
    }
    s.n_labels = static_cast<std::int32_t>(obstacles.size() + area.size());
    return s;
}

}  // namespace dvoronoi::gvd
