// Exact Voronoi cells clipped to a convex region (a box or a convex polygon): hull agents' cells are
// unbounded, and a caller that needs areas, centroids or pictures gives the region to cut them with —
// the library never invents a boundary of its own.
//
// The clipped cell is the region intersected with the half-planes of the agent's Voronoi neighbours
// (the cell is exactly that intersection), by Sutherland-Hodgman in the agent's frame. The
// combinatorics of the cell (its neighbours, bounded or not) come from the exact predicates; which
// region corners a bisector cuts off is decided in floating point by the clipping. Each vertex is then
// constructed again from its two lines (bisectors or region edges) and the polygon measured to
// core/accurate.hpp's accuracy (docs/guarantees.md), so clipped areas over all agents sum to the
// region's area up to about n 2^-40 of it. A cell that meets the region with zero area (along the region's side or at
// a corner) misses it: empty, like a cell outside it. Each side is labelled with what it lies on, the
// neighbour whose bisector cut it or the region's boundary (-1), also where a Voronoi vertex lies
// exactly on the region's boundary.
#pragma once

#include "dvoronoi/core/accurate.hpp"
#include "dvoronoi/core/convex_ring.hpp"
#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace dvoronoi {

/// A convex region, vertices counter-clockwise, no three consecutive collinear.
class ConvexRegion {
public:
    ConvexRegion() = default;

    /// The box [xmin, xmax] x [ymin, ymax]. \throws InputError naming `name` unless finite with
    /// xmin < xmax and ymin < ymax.
    static ConvexRegion box(double xmin, double ymin, double xmax, double ymax, const std::string& name = "bounds") {
        if (!(std::isfinite(xmin) && std::isfinite(ymin) && std::isfinite(xmax) && std::isfinite(ymax)))
            throw InputError(name + ": box coordinates must be finite");
        if (!(xmin < xmax && ymin < ymax))
            throw InputError(name + ": box needs xmin < xmax and ymin < ymax, got (" + std::to_string(xmin) + ", " +
                             std::to_string(ymin) + ", " + std::to_string(xmax) + ", " + std::to_string(ymax) + ")");
        ConvexRegion r;
        r.v_ = {Vec2(xmin, ymin), Vec2(xmax, ymin), Vec2(xmax, ymax), Vec2(xmin, ymax)};
        return r;
    }

    /// A convex polygon given by its vertices in order, read by detail::convex_ring: either
    /// orientation, closed rings, repeated and straight-on vertices are the same polygon.
    /// \throws InputError naming `name` when a coordinate is not finite, fewer than three vertices
    /// that are not collinear remain, or the polygon is not convex or not simple (exact tests).
    static ConvexRegion polygon(PointsRef pts, const std::string& name = "bounds") {
        std::vector<Vec2> v;
        for (Index k = 0; k < pts.rows(); ++k) v.push_back(pts.row(k).transpose());
        ConvexRegion r;
        r.v_ = detail::convex_ring(std::move(v), name);
        return r;
    }

    const std::vector<Vec2>& vertices() const noexcept { return v_; }
    bool empty() const noexcept { return v_.empty(); }

    /// Area (shoelace).
    double area() const {
        double a = 0.0;
        for (std::size_t k = 0; k < v_.size(); ++k) {
            const Vec2& p = v_[k];
            const Vec2& q = v_[(k + 1) % v_.size()];
            a += p.x() * q.y() - p.y() * q.x();
        }
        return 0.5 * a;
    }

private:
    std::vector<Vec2> v_;
};

/// A Voronoi cell clipped to a convex region: a convex polygon, counter-clockwise.
struct ClippedCell {
    std::vector<Vec2> vertices;        ///< counter-clockwise; empty when the cell misses the region (or
                                       ///< meets it with zero area)
    std::vector<Index> side_neighbor;  ///< per side (vertex k -> k+1): the Voronoi neighbour, or -1 for the region's boundary
    double area = 0.0;
    Vec2 centroid = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
};

namespace detail {

/// Line `k` of a clipping relative to c, times s (a power of two), exactly, as n . x = h: the
/// region's edge k from its vertex k to k + 1 (k < region size), else the bisector of c and
/// neighbour k - region size.
struct ExactLine {
    Expansion nx, ny, h;
};

inline ExactLine exact_line(const Vec2& c, const std::vector<Vec2>& corners, const std::vector<Vec2>& neighbors,
                            std::size_t k, double s) {
    ExactLine l;
    const std::size_t m = corners.size();
    if (k >= m) {
        const Vec2& p = neighbors[k - m];
        l.nx = scaled_diff(p.x(), c.x(), s);
        l.ny = scaled_diff(p.y(), c.y(), s);
        l.h = (l.nx * l.nx + l.ny * l.ny).times(0.5);
        return l;
    }
    const Vec2 &r0 = corners[k], &r1 = corners[(k + 1) % m];
    l.nx = -scaled_diff(r1.y(), r0.y(), s);  // the outward normal perp(r1 - r0) of a CCW region
    l.ny = scaled_diff(r1.x(), r0.x(), s);
    l.h = l.nx * scaled_diff(r0.x(), c.x(), s) + l.ny * scaled_diff(r0.y(), c.y(), s);
    return l;
}

/// The meeting point of two exact lines, by Cramer's rule on exact expansions, in double-double.
inline DDPoint meet(const ExactLine& a, const ExactLine& b) {
    const DD d = to_dd(a.nx * b.ny - a.ny * b.nx);
    return {to_dd(a.h * b.ny - b.h * a.ny) / d, to_dd(a.nx * b.h - b.nx * a.h) / d};
}

}  // namespace detail

/// The cell of the agent at `center` whose Voronoi neighbours are at `neighbors` (ids `ids`),
/// clipped to `region`. Every neighbour's half-plane is applied, so any superset of the true
/// neighbours gives the same polygon.
inline ClippedCell clip_cell(const Vec2& center, const std::vector<Vec2>& neighbors, const std::vector<Index>& ids,
                             const ConvexRegion& region) {
    ClippedCell out;
    // Work in the agent's frame: coordinates near 1e7 lose no more precision than near 0. Each side
    // carries the line it lies on (detail::exact_line's numbering), so that the vertices, found by
    // rounded clipping, can be constructed again from their two lines (below).
    const std::vector<Vec2>& corners = region.vertices();
    const int m = static_cast<int>(corners.size());
    std::vector<Vec2> poly, next;
    std::vector<int> side, next_side;
    for (int k = 0; k < m; ++k) {
        poly.push_back(corners[static_cast<std::size_t>(k)] - center);
        side.push_back(k);
    }
    for (std::size_t t = 0; t < neighbors.size() && !poly.empty(); ++t) {
        const Vec2 a = neighbors[t] - center;
        const double h = 0.5 * a.squaredNorm();
        const int line = m + static_cast<int>(t);
        const auto f = [&](const Vec2& q) { return q.dot(a) - h; };  // <= 0: on the agent's side
        next.clear();
        next_side.clear();
        const std::size_t n = poly.size();
        for (std::size_t k = 0; k < n; ++k) {
            const Vec2& p = poly[k];
            const Vec2& q = poly[(k + 1) % n];
            const double fp = f(p), fq = f(q);
            if (fp <= 0.0) {
                next.push_back(p);
                // p on the bisector with q outside: the side from p now runs along the bisector
                // (the old side leaves the half-plane at p itself).
                next_side.push_back(fp == 0.0 && fq > 0.0 ? line : side[k]);
            }
            if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
                const double s = fp / (fp - fq);
                next.push_back(p + s * (q - p));
                // Leaving the half-plane: the new side runs along the bisector; entering: the old side.
                next_side.push_back(fp < 0.0 ? line : side[k]);
            }
        }
        poly.swap(next);
        side.swap(next_side);
    }
    // Drop repeated vertices (a bisector through a corner).
    for (std::size_t k = 0; k < poly.size();) {
        if (poly.size() > 1 && poly[k] == poly[(k + 1) % poly.size()]) {
            poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(k));
            side.erase(side.begin() + static_cast<std::ptrdiff_t>(k));
        } else {
            ++k;
        }
    }
    if (poly.size() < 3) return out;
    // A cell that only touches the region (along a side of the region, or at a corner) leaves a flat
    // polygon whose area is rounding noise (each vertex is off by ~1e-16 of its distance from the
    // agent): it misses the region. Its sides would lie on a bisector and the region's boundary at once.
    double twice_area = 0.0, fan = 0.0, reach = 0.0;
    for (std::size_t k = 0; k < poly.size(); ++k) {
        const Vec2& p = poly[k];
        const Vec2& q = poly[(k + 1) % poly.size()];
        const double w = p.x() * q.y() - p.y() * q.x();
        twice_area += w;
        fan += std::fabs(w);
        reach = std::max(reach, p.cwiseAbs().maxCoeff());
    }
    if (!(twice_area > 1e-12 * fan)) return out;
    // The vertices again from their lines, in units of 2^e ~ the polygon's reach (an exact scaling):
    // two bisectors by line_vertex with its bound, a region corner as given, any other meeting from
    // exact expansions; then measured to core/accurate.hpp's accuracy.
    const int e = reach > 0.0 && reach <= std::numeric_limits<double>::max() ? std::ilogb(reach) : 0;
    const double unit = std::ldexp(1.0, -e), back = std::ldexp(1.0, e);
    const std::size_t n = poly.size();
    using namespace detail;
    thread_local Boundary b;
    b.clear();
    const auto lines = [&](std::size_t k) {
        return std::pair<int, int>(side[(k + n - 1) % n], side[k]);
    };
    const auto exact = [&](std::size_t k) {
        const auto [i, j] = lines(k);
        if (i < m && j == (i + 1) % m) {  // a corner of the region
            const Vec2& r = corners[static_cast<std::size_t>(j)];
            return DDPoint{to_dd(scaled_diff(r.x(), center.x(), unit)), to_dd(scaled_diff(r.y(), center.y(), unit))};
        }
        return meet(exact_line(center, corners, neighbors, static_cast<std::size_t>(i), unit),
                    exact_line(center, corners, neighbors, static_cast<std::size_t>(j), unit));
    };
    for (std::size_t k = 0; k < n; ++k) {
        const auto [i, j] = lines(k);
        if (i >= m && j >= m) {
            const Vec2 ai = (neighbors[static_cast<std::size_t>(i - m)] - center) * unit;
            const Vec2 aj = (neighbors[static_cast<std::size_t>(j - m)] - center) * unit;
            b.push(line_vertex(ai.x(), ai.y(), ai.squaredNorm(), aj.x(), aj.y(), aj.squaredNorm()), false, 0.0);
        } else {
            const Vec2 v = exact(k).value();  // region corners and sides: few, at the region's boundary
            b.push({v.x(), v.y(), 2.0 * kUnitRoundoff * l1(v.x(), v.y())}, false, 0.0);
        }
    }
    b.summarize();
    const LocalMeasures lm = accurate_measures(b, 0.0, exact);
    out.area = lm.area * back * back;
    out.centroid = center + back * Vec2(lm.cx, lm.cy);
    for (const BoundaryPoint& q : b) out.vertices.push_back(center + back * q.v);
    for (int k : side) out.side_neighbor.push_back(k < m ? -1 : ids[static_cast<std::size_t>(k - m)]);
    return out;
}

}  // namespace dvoronoi
