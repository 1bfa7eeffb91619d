// Exact oracle for range-limited Voronoi cells, built on CGAL's exact kernel.
//
// The test suite compares dvoronoi against this file. It shares no code with the library: the
// combinatorics come from CGAL::Delaunay_triangulation_2 over
// CGAL::Exact_predicates_exact_constructions_kernel (every decision exact), the areas from an exact
// half-plane clipping of a box, rounded to double once per vertex, intersected with the disk by the
// standard triangle-sector decomposition.
//
// Definitions (docs/spec.md, "Agents, cells, neighbours"):
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
#include <limits>
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

/// Marker for an arc in OracleResult::limited_pieces.
inline constexpr long kArcPiece = -1;

/// Everything the oracle knows about n agents and a cell radius R, in input order.
struct OracleResult {
    int dimension = -1;  ///< of the Delaunay triangulation: -1 (n=0), 0 (n=1), 1 (collinear), 2
    std::vector<std::vector<std::size_t>> voronoi_neighbors;  ///< ascending
    std::vector<std::vector<std::size_t>> limited_neighbors;  ///< ascending
    std::vector<bool> on_hull;
    std::vector<double> limited_areas;      ///< area of V_i ∩ B(p_i, R)
    std::vector<XY> limited_centroids;      ///< centroid of V_i ∩ B(p_i, R)
    /// The boundary of V_i ∩ B(p_i, R) as a counter-clockwise cycle of pieces: a limited neighbour's
    /// index for an edge, kArcPiece for an arc, starting at the smallest neighbour ([kArcPiece]
    /// for a full disk). Two consecutive edges meet (no arc between) when their common Voronoi
    /// vertex lies in the closed disk; a vertex exactly on the circle gives no zero-length arc.
    std::vector<std::vector<long>> limited_pieces;
    /// Limited neighbours found a second, independent way (edges of the exactly clipped cell that
    /// enter the open disk); filled only with self_check = true, must equal limited_neighbors.
    std::vector<std::vector<std::size_t>> limited_neighbors_by_clipping;
    /// With self_check: a side of the box p_i ± 2R survives the clipping. For R beyond every
    /// Voronoi vertex this is "V_i is unbounded", found independently of on_hull.
    std::vector<bool> box_side_survives;
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

/// `v` rounded to double: from the interval approximation when it is narrower than 1e-14 * scale
/// (the area tolerance of the tests is 1e-9 relative and 1e-12 R^2 absolute), else exactly.
inline double to_double_tight(const FT& v, double scale) {
    const auto& ap = v.approx();
    if (ap.sup() - ap.inf() <= 1e-14 * scale) return 0.5 * (ap.inf() + ap.sup());
    return CGAL::to_double(v.exact());
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

/// Runs the oracle. `self_check` also fills limited_neighbors_by_clipping and box_side_survives.
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
    res.limited_pieces.assign(n, std::vector<long>{kArcPiece});
    if (self_check) {
        res.limited_neighbors_by_clipping.assign(n, {});
        res.box_side_survives.assign(n, true);
    }
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

    // Voronoi and limited neighbours from the Delaunay edges. The Voronoi edge of a, b lies on
    // their bisector between the circumcentres of the incident faces (a ray for a hull edge, the
    // whole line for a collinear input). Along the bisector, the circumcentre of (a, b, c) lies on
    // c's side of ab when the angle at c is acute, on ab when it is right, beyond when obtuse. So
    // the edge meets the midpoint of ab (distance |ab|/2 from p_a) unless one incident angle is
    // obtuse; then its point nearest p_a is that face's circumcentre, at distance its circumradius.
    // Every test is an exact predicate or an exact comparison of lazily computed numbers.
    const auto side_of_circle = K().side_of_oriented_circle_2_object();
    const auto angle = K().angle_2_object();
    const auto squared_radius = K().compute_squared_radius_2_object();
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
        const auto f = e->first;
        const int k = e->second;
        const auto va = f->vertex(DT::cw(k)), vb = f->vertex(DT::ccw(k));
        const std::size_t a = va->info(), b = vb->info();
        const Point& pa = va->point();
        const Point& pb = vb->point();
        // Third vertices of the finite incident faces (none in dimension 1, one on the hull).
        const Point* third[2] = {nullptr, nullptr};
        if (res.dimension == 2) {
            const auto g = f->neighbor(k);
            if (!dt.is_infinite(f)) third[0] = &f->vertex(k)->point();
            if (!dt.is_infinite(g)) third[1] = &dt.mirror_vertex(f, k)->point();
            if (third[0] && third[1] &&
                side_of_circle(pa, pb, *third[0], *third[1]) == CGAL::ON_ORIENTED_BOUNDARY)
                continue;  // both circumcentres coincide: the cells touch in a point
        }
        res.voronoi_neighbors[a].push_back(b);
        res.voronoi_neighbors[b].push_back(a);
        if (CGAL::compare_squared_distance(pa, pb, four_R2) != CGAL::SMALLER) continue;
        bool limited = true;  // the edge passes through the midpoint, at |ab|/2 < R
        for (const Point* c : third)
            if (c && angle(pa, *c, pb) == CGAL::OBTUSE)
                limited = CGAL::compare(squared_radius(pa, pb, *c), R2) == CGAL::SMALLER;
        if (limited) {
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

    // Limited areas, in the frame of p_i (q - p_i exact, as a lazy vector): the box ±2R (it
    // contains the disk) clipped exactly by the bisectors of the Delaunay neighbours closer than 2R
    // (farther bisectors miss the disk), its vertices rounded to double, then ∩ disk. In the local
    // frame the interval approximations are tight at the scale of R, so exact evaluation is rare.
    const double pi = std::acos(-1.0);
    const Point origin(0, 0);
    const double two_R = 2.0 * R;
    const Point c0(-two_R, -two_R), c1(two_R, -two_R), c2(two_R, two_R), c3(-two_R, two_R);
    const Line box[4] = {Line(c0, c1), Line(c1, c2), Line(c2, c3), Line(c3, c0)};
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        const std::size_t i = v->info();
        const Point& p = v->point();
        const double px = pts[i][0], py = pts[i][1];
        detail::ClipPolygon poly;
        poly.verts = {c0, c1, c2, c3};
        poly.lines = {box[0], box[1], box[2], box[3]};
        poly.owner = {-1, -1, -1, -1};
        bool clipped = false;
        if (res.dimension >= 1) {
            auto c = dt.incident_vertices(v), done = c;
            do {
                if (dt.is_infinite(c)) continue;
                if (CGAL::compare_squared_distance(p, c->point(), four_R2) != CGAL::SMALLER)
                    continue;
                // |x|^2 <= |x - d|^2  <=>  -2 d.x + |d|^2 >= 0: the positive side of this line.
                const K::Vector_2 d = c->point() - p;
                poly.clip(Line(FT(-2) * d.x(), FT(-2) * d.y(), d.squared_length()),
                          static_cast<long>(c->info()));
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
            rel[k] = XY{detail::to_double_tight(poly.verts[k].x(), R),
                        detail::to_double_tight(poly.verts[k].y(), R)};
        detail::Moments m;
        for (std::size_t k = 0; k < rel.size(); ++k)
            detail::triangle_disk(rel[k], rel[(k + 1) % rel.size()], R, m);
        res.limited_areas[i] = m.area;
        res.limited_centroids[i] =
            m.area > 0.0 ? XY{px + m.mx / m.area, py + m.my / m.area} : XY{px, py};
        // Edges of the clipped cell that enter the open disk, in counter-clockwise order.
        const std::size_t nv = poly.verts.size();
        std::vector<std::size_t> inside;
        for (std::size_t k = 0; k < nv; ++k) {
            if (poly.owner[k] < 0) continue;
            const Point& s = poly.verts[k];
            const Point& t = poly.verts[(k + 1) % nv];
            if (s == t) continue;
            if (CGAL::compare(CGAL::squared_distance(origin, K::Segment_2(s, t)), R2) ==
                CGAL::SMALLER)
                inside.push_back(k);
        }
        if (self_check) {
            res.box_side_survives[i] =
                std::find(poly.owner.begin(), poly.owner.end(), -1L) != poly.owner.end();
            auto& out = res.limited_neighbors_by_clipping[i];
            for (const std::size_t k : inside) out.push_back(static_cast<std::size_t>(poly.owner[k]));
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        }
        if (!inside.empty()) {
            std::vector<long> pieces;
            for (std::size_t t = 0; t < inside.size(); ++t) {
                const std::size_t k1 = inside[t], k2 = inside[(t + 1) % inside.size()];
                pieces.push_back(poly.owner[k1]);
                // They meet when nothing but zero-length edges lies between them and their common
                // vertex is in the closed disk.
                const Point& end1 = poly.verts[(k1 + 1) % nv];
                const bool meet = inside.size() > 1 && end1 == poly.verts[k2] &&
                                  CGAL::compare(CGAL::squared_distance(origin, end1), R2) !=
                                      CGAL::LARGER;
                if (!meet) pieces.push_back(kArcPiece);
            }
            const auto first = std::min_element(pieces.begin(), pieces.end(), [](long a, long b) {
                return (a < 0 ? std::numeric_limits<long>::max() : a) <
                       (b < 0 ? std::numeric_limits<long>::max() : b);
            });
            std::rotate(pieces.begin(), first, pieces.end());
            res.limited_pieces[i] = std::move(pieces);
        }
    }
    return res;
}

/// Areas of the exact Voronoi cells clipped to the box [x0, x1] x [y0, y1]: the box clipped exactly
/// (CGAL's exact kernel, in the agent's frame) by the bisectors of all Delaunay neighbours, its
/// area summed exactly and rounded once. 0 for a cell that misses the box.
inline std::vector<double> clipped_areas(const std::vector<XY>& pts, double x0, double y0, double x1, double y1) {
    const std::size_t n = pts.size();
    std::vector<double> areas(n, 0.0);
    DT dt;
    std::vector<std::pair<Point, std::size_t>> input;
    for (std::size_t i = 0; i < n; ++i) input.emplace_back(Point(pts[i][0], pts[i][1]), i);
    dt.insert(input.begin(), input.end());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        const std::size_t i = v->info();
        const Point& p = v->point();
        const Point c0(FT(x0) - p.x(), FT(y0) - p.y()), c1(FT(x1) - p.x(), FT(y0) - p.y());
        const Point c2(FT(x1) - p.x(), FT(y1) - p.y()), c3(FT(x0) - p.x(), FT(y1) - p.y());
        std::vector<Point> poly{c0, c1, c2, c3};
        if (dt.dimension() >= 1) {
            auto c = dt.incident_vertices(v), done = c;
            do {
                if (dt.is_infinite(c)) continue;
                const K::Vector_2 d = c->point() - p;
                const Line L(FT(-2) * d.x(), FT(-2) * d.y(), d.squared_length());  // keep the positive side
                std::vector<Point> out;
                for (std::size_t k = 0; k < poly.size(); ++k) {
                    const Point& a = poly[k];
                    const Point& b = poly[(k + 1) % poly.size()];
                    const auto sa = L.oriented_side(a), sb = L.oriented_side(b);
                    if (sa != CGAL::ON_NEGATIVE_SIDE) out.push_back(a);
                    if ((sa == CGAL::ON_POSITIVE_SIDE && sb == CGAL::ON_NEGATIVE_SIDE) ||
                        (sa == CGAL::ON_NEGATIVE_SIDE && sb == CGAL::ON_POSITIVE_SIDE))
                        out.push_back(detail::intersect(K::Line_2(a, b), L));
                }
                poly.swap(out);
            } while (++c != done && !poly.empty());
        }
        if (poly.size() < 3) continue;
        FT a2 = 0;
        for (std::size_t k = 0; k < poly.size(); ++k) {
            const Point& a = poly[k];
            const Point& b = poly[(k + 1) % poly.size()];
            a2 += a.x() * b.y() - a.y() * b.x();
        }
        areas[i] = CGAL::to_double((a2 / 2).exact());
    }
    return areas;
}

}  // namespace dvoronoi_oracle
