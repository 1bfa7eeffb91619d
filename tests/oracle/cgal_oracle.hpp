// Exact oracle for range-limited Voronoi cells, built on CGAL's exact kernel.
//
// The test suite compares dvoronoi against this file. It shares no code with the library: the
// combinatorics come from CGAL::Delaunay_triangulation_2 over
// CGAL::Exact_predicates_exact_constructions_kernel (every decision exact), the areas from an exact
// half-plane clipping of a box, rounded to double once per vertex, intersected with the disk by the
// standard triangle-sector decomposition.
//
// Definitions (SPEC.md, "Agents, cells, neighbours"):
//  - i, j are Voronoi neighbours when V_i ∩ V_j is a segment of positive length (a Delaunay edge
//    whose two incident faces have distinct circumcentres, a hull edge, or consecutive points of a
//    collinear input);
//  - i, j are limited neighbours when their Voronoi edge passes strictly closer than R to p_i;
//  - i is on the hull when V_i is unbounded (p_i on the boundary of the convex hull, including the
//    relative interior of a hull edge; every point of a collinear input; the single point of n = 1).
#pragma once

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi_oracle {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using Point = K::Point_2;
using Line = K::Line_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>;
using Fb = CGAL::Triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;

using XY = std::array<double, 2>;

/// Everything the oracle knows about n agents and a cell radius R, in input order.
struct OracleResult {
    int dimension = -1;  ///< of the Delaunay triangulation: -1 (n=0), 0 (n=1), 1 (collinear), 2
    std::vector<std::vector<std::size_t>> voronoi_neighbors;  ///< ascending
    std::vector<std::vector<std::size_t>> limited_neighbors;  ///< ascending
    std::vector<bool> on_hull;
    std::vector<double> limited_areas;      ///< area of V_i ∩ B(p_i, R)
    std::vector<XY> limited_centroids;      ///< centroid of V_i ∩ B(p_i, R)
    /// Limited neighbours found a second, independent way (edges of the exactly clipped cell that
    /// enter the open disk); filled only with self_check = true, must equal limited_neighbors.
    std::vector<std::vector<std::size_t>> limited_neighbors_by_clipping;
};

namespace detail {

/// Signed area and first moment of triangle(0, a, b) ∩ disk(0, R), a and b relative to the centre.
struct Moments {
    double area = 0.0, mx = 0.0, my = 0.0;
};

inline double cross(const XY& a, const XY& b) { return a[0] * b[1] - a[1] * b[0]; }
inline double dot(const XY& a, const XY& b) { return a[0] * b[0] + a[1] * b[1]; }

/// Circular sector of the disk between the directions of u and v (signed, |angle| < pi).
inline void add_sector(const XY& u, const XY& v, double R, Moments& m) {
    const double c = cross(u, v), d = dot(u, v);
    if (c == 0.0 && d >= 0.0) return;
    const double phi = std::atan2(c, d);
    const double nu = std::hypot(u[0], u[1]), nv = std::hypot(v[0], v[1]);
    const XY uu{R * u[0] / nu, R * u[1] / nu}, vv{R * v[0] / nv, R * v[1] / nv};
    m.area += 0.5 * R * R * phi;
    m.mx += R * R / 3.0 * (vv[1] - uu[1]);
    m.my += R * R / 3.0 * (uu[0] - vv[0]);
}

inline void add_triangle(const XY& u, const XY& v, Moments& m) {
    const double a = 0.5 * cross(u, v);
    m.area += a;
    m.mx += a * (u[0] + v[0]) / 3.0;
    m.my += a * (u[1] + v[1]) / 3.0;
}

inline void triangle_disk(const XY& a, const XY& b, double R, Moments& m) {
    const XY d{b[0] - a[0], b[1] - a[1]};
    const double A = dot(d, d);
    if (A == 0.0) return;
    const double B = dot(a, d), C = dot(a, a) - R * R;
    const double disc = B * B - A * C;
    if (disc <= 0.0) {  // the line misses the open disk
        add_sector(a, b, R, m);
        return;
    }
    const double sq = std::sqrt(disc);
    double t1 = (-B - sq) / A, t2 = (-B + sq) / A;
    t1 = std::clamp(t1, 0.0, 1.0);
    t2 = std::clamp(t2, 0.0, 1.0);
    if (t1 >= t2) {  // the segment lies outside the disk (before or after the chord)
        add_sector(a, b, R, m);
        return;
    }
    const XY p{a[0] + t1 * d[0], a[1] + t1 * d[1]}, q{a[0] + t2 * d[0], a[1] + t2 * d[1]};
    if (t1 > 0.0) add_sector(a, p, R, m);
    add_triangle(t1 > 0.0 ? p : a, t2 < 1.0 ? q : b, m);
    if (t2 < 1.0) add_sector(q, b, R, m);
}

/// `v - p` rounded to double: from the interval approximation when it is tight, else exactly.
inline double to_double_rel(const FT& v, const FT& p, double scale) {
    const FT d = v - p;
    const auto& ap = d.approx();
    if (ap.sup() - ap.inf() <= 1e-15 * scale) return 0.5 * (ap.inf() + ap.sup());
    return CGAL::to_double(d.exact());
}

inline Point intersect(const Line& a, const Line& b) {
    const auto res = CGAL::intersection(a, b);
    if (res) {
        if (const Point* p = boost::get<Point>(&*res)) return *p;
    }
    throw std::logic_error("cgal_oracle: parallel lines in the clipping (internal error)");
}

/// A convex polygon as a CCW cycle of vertices; edge k runs from verts[k] to verts[k+1] on lines[k]
/// (owner[k]: the neighbour whose bisector it is, or -1 for the box). Every vertex is the
/// intersection of two input lines, computed directly from them (the lazy DAG stays shallow).
struct ClipPolygon {
    std::vector<Point> verts;
    std::vector<Line> lines;
    std::vector<long> owner;

    /// Keep the positive (left) side of L.
    void clip(const Line& L, long who) {
        const std::size_t n = verts.size();
        std::vector<CGAL::Oriented_side> side(n);
        bool any_out = false;
        for (std::size_t k = 0; k < n; ++k) {
            side[k] = L.oriented_side(verts[k]);
            any_out = any_out || side[k] == CGAL::ON_NEGATIVE_SIDE;
        }
        if (!any_out) return;
        // The agent lies strictly inside every half-plane, so some vertex is strictly inside and
        // the vertices outside form one cyclic run s..e.
        std::size_t s = n;
        for (std::size_t k = 0; k < n; ++k)
            if (side[k] == CGAL::ON_NEGATIVE_SIDE && side[(k + n - 1) % n] != CGAL::ON_NEGATIVE_SIDE) {
                s = k;
                break;
            }
        if (s == n) throw std::logic_error("cgal_oracle: half-plane removes the whole cell");
        std::size_t e = s;
        while (side[(e + 1) % n] == CGAL::ON_NEGATIVE_SIDE) e = (e + 1) % n;
        const std::size_t before = (s + n - 1) % n;  // edge lines[before] enters the run
        ClipPolygon out;
        // kept vertices e+1 .. before, each with its outgoing edge.
        for (std::size_t k = (e + 1) % n;; k = (k + 1) % n) {
            out.verts.push_back(verts[k]);
            out.lines.push_back(lines[k]);
            out.owner.push_back(owner[k]);
            if (k == before) break;
        }
        out.verts.push_back(intersect(lines[before], L));
        out.lines.push_back(L);
        out.owner.push_back(who);
        out.verts.push_back(intersect(L, lines[e]));
        out.lines.push_back(lines[e]);
        out.owner.push_back(owner[e]);
        *this = std::move(out);
    }
};

}  // namespace detail

/// Runs the oracle. `self_check` also computes limited_neighbors_by_clipping.
///
/// \throws std::invalid_argument for a non-positive or non-finite radius, non-finite coordinates or
///         coinciding points (the oracle has no cells for them either).
inline OracleResult compute_oracle(const std::vector<XY>& pts, double R, bool self_check = false) {
    if (!(R > 0.0) || !std::isfinite(R)) throw std::invalid_argument("cgal_oracle: bad radius");
    for (const XY& p : pts)
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
            throw std::invalid_argument("cgal_oracle: non-finite coordinate");
    const std::size_t n = pts.size();
    OracleResult res;
    res.voronoi_neighbors.assign(n, {});
    res.limited_neighbors.assign(n, {});
    res.on_hull.assign(n, false);
    res.limited_areas.assign(n, 0.0);
    res.limited_centroids.assign(n, XY{0.0, 0.0});
    if (self_check) res.limited_neighbors_by_clipping.assign(n, {});
    if (n == 0) return res;

    std::vector<std::pair<Point, std::size_t>> input;
    input.reserve(n);
    for (std::size_t i = 0; i < n; ++i) input.emplace_back(Point(pts[i][0], pts[i][1]), i);
    DT dt;
    dt.insert(input.begin(), input.end());
    if (dt.number_of_vertices() != n)
        throw std::invalid_argument("cgal_oracle: coinciding points");
    res.dimension = dt.dimension();

    const FT R_ft(R);
    const FT R2 = R_ft * R_ft;
    const FT four_R2 = FT(4) * R2;
    const auto side_of_circle = K().side_of_oriented_circle_2_object();

    // Voronoi and limited neighbours from the Delaunay edges.
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
        const auto f = e->first;
        const int k = e->second;
        const auto va = f->vertex(DT::cw(k)), vb = f->vertex(DT::ccw(k));
        const std::size_t a = va->info(), b = vb->info();
        bool positive = true;
        if (res.dimension == 2) {
            const auto g = f->neighbor(k);
            if (!dt.is_infinite(f) && !dt.is_infinite(g)) {
                const Point& d = dt.mirror_vertex(f, k)->point();
                positive = side_of_circle(f->vertex(0)->point(), f->vertex(1)->point(),
                                          f->vertex(2)->point(), d) != CGAL::ON_ORIENTED_BOUNDARY;
            }
        }
        if (!positive) continue;
        res.voronoi_neighbors[a].push_back(b);
        res.voronoi_neighbors[b].push_back(a);
        // The Voronoi edge lies on the bisector; it can come within R only if |ab| < 2R.
        if (CGAL::compare_squared_distance(va->point(), vb->point(), four_R2) != CGAL::SMALLER)
            continue;
        const CGAL::Object dual = dt.dual(*e);
        FT d2;
        if (const K::Segment_2* s = CGAL::object_cast<K::Segment_2>(&dual))
            d2 = CGAL::squared_distance(va->point(), *s);
        else if (const K::Ray_2* r = CGAL::object_cast<K::Ray_2>(&dual))
            d2 = CGAL::squared_distance(va->point(), *r);
        else if (const K::Line_2* l = CGAL::object_cast<K::Line_2>(&dual))
            d2 = CGAL::squared_distance(va->point(), *l);
        else
            throw std::logic_error("cgal_oracle: unexpected dual of a Delaunay edge");
        if (CGAL::compare(d2, R2) == CGAL::SMALLER) {
            res.limited_neighbors[a].push_back(b);
            res.limited_neighbors[b].push_back(a);
        }
    }
    for (auto& v : res.voronoi_neighbors) std::sort(v.begin(), v.end());
    for (auto& v : res.limited_neighbors) std::sort(v.begin(), v.end());

    // Hull flags.
    if (res.dimension <= 1) {
        res.on_hull.assign(n, true);
    } else {
        auto c = dt.incident_vertices(dt.infinite_vertex()), done = c;
        do {
            if (!dt.is_infinite(c)) res.on_hull[c->info()] = true;
        } while (++c != done);
    }

    // Limited areas: the box p_i ± 2R (it contains the disk) clipped exactly by the bisectors of
    // the Delaunay neighbours closer than 2R (farther bisectors miss the disk), then ∩ disk.
    const double pi = std::acos(-1.0);
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        const std::size_t i = v->info();
        const Point& p = v->point();
        const double px = pts[i][0], py = pts[i][1];
        detail::ClipPolygon poly;
        const double x0 = px - 2.0 * R, x1 = px + 2.0 * R, y0 = py - 2.0 * R, y1 = py + 2.0 * R;
        const Point c0(x0, y0), c1(x1, y0), c2(x1, y1), c3(x0, y1);
        poly.verts = {c0, c1, c2, c3};
        poly.lines = {Line(c0, c1), Line(c1, c2), Line(c2, c3), Line(c3, c0)};
        poly.owner = {-1, -1, -1, -1};
        bool clipped = false;
        if (res.dimension >= 1) {
            auto c = dt.incident_vertices(v), done = c;
            do {
                if (dt.is_infinite(c)) continue;
                if (CGAL::compare_squared_distance(p, c->point(), four_R2) != CGAL::SMALLER)
                    continue;
                poly.clip(CGAL::bisector(p, c->point()), static_cast<long>(c->info()));
                clipped = true;
            } while (++c != done);
        }
        if (!clipped) {
            res.limited_areas[i] = pi * R * R;
            res.limited_centroids[i] = XY{px, py};
            continue;
        }
        std::vector<XY> rel(poly.verts.size());
        for (std::size_t k = 0; k < poly.verts.size(); ++k)
            rel[k] = XY{detail::to_double_rel(poly.verts[k].x(), p.x(), R),
                        detail::to_double_rel(poly.verts[k].y(), p.y(), R)};
        detail::Moments m;
        for (std::size_t k = 0; k < rel.size(); ++k)
            detail::triangle_disk(rel[k], rel[(k + 1) % rel.size()], R, m);
        res.limited_areas[i] = m.area;
        res.limited_centroids[i] =
            m.area > 0.0 ? XY{px + m.mx / m.area, py + m.my / m.area} : XY{px, py};
        if (self_check) {
            auto& out = res.limited_neighbors_by_clipping[i];
            for (std::size_t k = 0; k < poly.verts.size(); ++k) {
                if (poly.owner[k] < 0) continue;
                const Point& s = poly.verts[k];
                const Point& t = poly.verts[(k + 1) % poly.verts.size()];
                if (s == t) continue;
                if (CGAL::compare(CGAL::squared_distance(p, K::Segment_2(s, t)), R2) ==
                    CGAL::SMALLER)
                    out.push_back(static_cast<std::size_t>(poly.owner[k]));
            }
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        }
    }
    return res;
}

}  // namespace dvoronoi_oracle
