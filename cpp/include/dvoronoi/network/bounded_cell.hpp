// A Voronoi cell clipped to an axis-aligned box, as a labelled convex polygon: the box cut by the
// bisector half-planes of the agent's Voronoi neighbours (Sutherland-Hodgman, floating point; which
// neighbours there are was decided exactly before, so only the vertex coordinates are rounded).
// CC reports its cells this way when given bounds; BD07 refines cells of this kind.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi::network {

/// The bounded region [xmin, xmax] x [ymin, ymax].
struct Box {
    double xmin = 0.0, ymin = 0.0, xmax = 0.0, ymax = 0.0;
    bool contains(const Vec2& p) const {
        return p.x() >= xmin && p.x() <= xmax && p.y() >= ymin && p.y() <= ymax;
    }
};

inline void require_box(const Box& b) {
    if (!(std::isfinite(b.xmin) && std::isfinite(b.ymin) && std::isfinite(b.xmax) && std::isfinite(b.ymax)) ||
        !(b.xmin < b.xmax && b.ymin < b.ymax))
        throw InputError("bounds must be finite (xmin, ymin, xmax, ymax) with xmin < xmax and ymin < ymax");
}

/// Label of a box side in Polygon::edge_label: the bottom, right, top, left sides.
inline constexpr Index kBoxBottom = -2, kBoxRight = -3, kBoxTop = -4, kBoxLeft = -5;

/// A convex polygon, counter-clockwise. Edge k runs from vertex k to vertex k+1 and lies on the
/// bisector with node edge_label[k] (>= 0) or on a box side (kBox*).
struct Polygon {
    std::vector<Vec2> vertices;
    std::vector<Index> edge_label;

    double area() const {
        double a = 0.0;
        const std::size_t m = vertices.size();
        for (std::size_t k = 0; k < m; ++k) {
            const Vec2& u = vertices[k];
            const Vec2& v = vertices[(k + 1) % m];
            a += u.x() * v.y() - u.y() * v.x();
        }
        return 0.5 * a;
    }
    Vec2 centroid() const {
        double a = 0.0, cx = 0.0, cy = 0.0;
        const std::size_t m = vertices.size();
        if (m == 0) return Vec2(NAN, NAN);
        const Vec2 o = vertices[0];
        for (std::size_t k = 1; k + 1 < m; ++k) {
            const Vec2 u = vertices[k] - o, v = vertices[k + 1] - o;
            const double t = 0.5 * (u.x() * v.y() - u.y() * v.x());
            a += t;
            cx += t * (u.x() + v.x()) / 3.0;
            cy += t * (u.y() + v.y()) / 3.0;
        }
        return a > 0.0 ? Vec2(o.x() + cx / a, o.y() + cy / a) : o;
    }
};

inline Polygon box_polygon(const Box& b) {
    Polygon p;
    p.vertices = {Vec2(b.xmin, b.ymin), Vec2(b.xmax, b.ymin), Vec2(b.xmax, b.ymax), Vec2(b.xmin, b.ymax)};
    p.edge_label = {kBoxBottom, kBoxRight, kBoxTop, kBoxLeft};
    return p;
}

/// Cuts `poly` by the half-plane of points at least as close to c as to q (label `id`), writing to
/// `out` (a separate buffer, reused). Computed in the frame of c, so the rounding does not grow with
/// the distance from the origin.
inline void clip_bisector(const Polygon& poly, const Vec2& c, const Vec2& q, Index id, Polygon& out) {
    out.vertices.clear();
    out.edge_label.clear();
    const Vec2 a = q - c;
    const double h = 0.5 * a.squaredNorm();
    const std::size_t m = poly.vertices.size();
    if (m == 0) return;
    const auto f = [&](const Vec2& v) { return (v - c).dot(a) - h; };  // <= 0 inside
    const auto push = [&](const Vec2& v, Index label) {
        if (!out.vertices.empty() && out.vertices.back() == v) {
            out.edge_label.back() = label;  // a vertex exactly on the bisector: no zero-length edge
            return;
        }
        out.vertices.push_back(v);
        out.edge_label.push_back(label);
    };
    double fu = f(poly.vertices[0]);
    for (std::size_t k = 0; k < m; ++k) {
        const Vec2& u = poly.vertices[k];
        const Vec2& v = poly.vertices[(k + 1) % m];
        const double fv = f(v);
        if (fu <= 0.0) push(u, poly.edge_label[k]);
        if ((fu <= 0.0) != (fv <= 0.0)) {
            const double t = fu / (fu - fv);
            // Leaving the half-plane, the bisector follows the crossing; entering, the old edge does.
            push(u + t * (v - u), fu <= 0.0 ? id : poly.edge_label[k]);
        }
        fu = fv;
    }
    if (out.vertices.size() > 1 && out.vertices.back() == out.vertices.front()) {
        out.vertices.pop_back();
        out.edge_label.pop_back();
    }
    if (out.vertices.size() < 3) {
        out.vertices.clear();
        out.edge_label.clear();
    }
}

/// The cell of c among `neighbours` (their positions and labels), clipped to the box.
inline Polygon clipped_cell(const Vec2& c, const std::vector<Vec2>& nb, const std::vector<Index>& ids,
                            const Box& box) {
    Polygon p = box_polygon(box), tmp;
    for (std::size_t k = 0; k < nb.size(); ++k) {
        clip_bisector(p, c, nb[k], ids[k], tmp);
        std::swap(p, tmp);
    }
    return p;
}

}  // namespace dvoronoi::network
