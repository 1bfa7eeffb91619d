// Exact oracle for heterogeneous teams (docs/spec.md, heterogeneous teams), on CGAL's exact kernel.
// Shares no code with the library:
//  - agents whose power cell has zero area (exact clipping of a box far larger than the team) are
//    left out of the triangulation: they are empty and do not change the other cells;
//  - power neighbours: CGAL::Regular_triangulation_2 of the weighted points (p_i, R_i^2); i, j are
//    power neighbours when the dual of their edge (a segment between the two faces' power centres, a
//    ray or a line) has positive length; hidden points have empty power cells;
//  - limited neighbours: that dual edge comes strictly closer than R_i to p_i (exact squared
//    distance of the segment, ray or line): the radical axis meets B_i and B_j in the same chord, so
//    the shared edge then has positive length inside the disks;
//  - empty cells: hidden, a power cell of zero area (exact area of its exact clipping: agents whose
//    radical axes coincide with opposite sides squeeze it to a segment), or no limited neighbour and
//    p_i not strictly inside its power cell; an empty cell has no neighbours (docs/spec.md), so it is
//    taken out of the other agents' sets;
//  - areas: the box p_i +- 2R_i clipped exactly by every radical half-plane, rounded to double once
//    per vertex, intersected with the disk by the triangle-sector decomposition of cgal_oracle.hpp.
#pragma once

#include "cgal_oracle.hpp"

#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>

#include <set>

namespace dvoronoi_oracle {

using WPoint = K::Weighted_point_2;
using RVbBase = CGAL::Regular_triangulation_vertex_base_2<K>;
using RVb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K, RVbBase>;
using RFb = CGAL::Regular_triangulation_face_base_2<K>;
using RTds = CGAL::Triangulation_data_structure_2<RVb, RFb>;
using RT = CGAL::Regular_triangulation_2<K, RTds>;

struct PowerOracle {
    std::vector<std::set<std::size_t>> power_neighbors;    ///< unclipped power diagram
    std::vector<std::set<std::size_t>> limited_neighbors;  ///< edge of positive length inside the disks
    std::vector<bool> empty;
    std::vector<double> areas;
};

namespace detail {

/// Exact squared distance from p to the dual object (segment, ray or line) < r2.
inline bool comes_closer(const CGAL::Object& dual, const Point& p, const FT& r2) {
    if (const auto* s = CGAL::object_cast<K::Segment_2>(&dual)) return CGAL::squared_distance(p, *s) < r2;
    if (const auto* r = CGAL::object_cast<K::Ray_2>(&dual)) return CGAL::squared_distance(p, *r) < r2;
    if (const auto* l = CGAL::object_cast<K::Line_2>(&dual)) return CGAL::squared_distance(p, *l) < r2;
    throw std::logic_error("power_oracle: unexpected dual object");
}

inline bool positive_length(const CGAL::Object& dual) {
    if (const auto* s = CGAL::object_cast<K::Segment_2>(&dual)) return !s->is_degenerate();
    return CGAL::object_cast<K::Ray_2>(&dual) || CGAL::object_cast<K::Line_2>(&dual);
}

/// The convex polygon `poly` (CCW) cut to the closed positive side of L (empty when nothing is left).
inline std::vector<Point> clip_exact(const std::vector<Point>& poly, const Line& L) {
    std::vector<Point> out;
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Point& a = poly[k];
        const Point& b = poly[(k + 1) % n];
        const auto sa = L.oriented_side(a), sb = L.oriented_side(b);
        if (sa != CGAL::ON_NEGATIVE_SIDE) out.push_back(a);
        if ((sa == CGAL::ON_POSITIVE_SIDE && sb == CGAL::ON_NEGATIVE_SIDE) ||
            (sa == CGAL::ON_NEGATIVE_SIDE && sb == CGAL::ON_POSITIVE_SIDE))
            out.push_back(intersect(Line(a, b), L));
    }
    return out;
}

}  // namespace detail

/// The exact power cell of agent i (among all agents) clipped to the box c +- w, CCW (degenerate or
/// empty when the cell meets the box in zero area).
inline std::vector<Point> clipped_power_cell(const std::vector<XY>& pts, const std::vector<double>& radii, std::size_t i,
                                             const FT& cx, const FT& cy, const FT& w) {
    const FT x = pts[i][0], y = pts[i][1];
    const auto R2 = [&](std::size_t j) { return FT(radii[j]) * FT(radii[j]); };
    std::vector<Point> poly{Point(cx - w, cy - w), Point(cx + w, cy - w), Point(cx + w, cy + w), Point(cx - w, cy + w)};
    for (std::size_t j = 0; j < pts.size() && !poly.empty(); ++j) {
        if (j == i) continue;
        const FT dx = FT(pts[j][0]) - x, dy = FT(pts[j][1]) - y;
        // power_i(q) <= power_j(q): c - 2 (p_j - p_i).q >= 0, c = |p_j|^2 - |p_i|^2 - R_j^2 + R_i^2.
        const FT c = FT(pts[j][0]) * FT(pts[j][0]) + FT(pts[j][1]) * FT(pts[j][1]) - x * x - y * y - R2(j) + R2(i);
        poly = detail::clip_exact(poly, Line(FT(-2) * dx, FT(-2) * dy, c));
    }
    return poly;
}

inline bool zero_area(const std::vector<Point>& poly) {
    FT twice = 0;
    for (std::size_t t = 0; t < poly.size(); ++t) {
        const Point& a = poly[t];
        const Point& b = poly[(t + 1) % poly.size()];
        twice = twice + (a.x() * b.y() - a.y() * b.x());
    }
    return twice == 0;
}

inline PowerOracle compute_power_oracle(const std::vector<XY>& pts, const std::vector<double>& radii) {
    const std::size_t n = pts.size();
    PowerOracle res;
    res.power_neighbors.assign(n, {});
    res.limited_neighbors.assign(n, {});
    res.empty.assign(n, true);
    res.areas.assign(n, 0.0);
    const auto P = [&](std::size_t i) { return Point(pts[i][0], pts[i][1]); };
    const auto R2 = [&](std::size_t i) { return FT(radii[i]) * FT(radii[i]); };
    // Agents whose power cell has zero area (hidden, or squeezed to a segment between two agents
    // with the same radical axis) take no part: the others' cells are the same without them, and
    // a degenerate vertex in the triangulation would hide the neighbour relation across it. Zero
    // area is decided exactly on a box far larger than the team (margin 1e3 times its extent).
    double lo = 0, hi = 0;
    if (n > 0) lo = hi = pts[0][0];
    for (std::size_t i = 0; i < n; ++i) {
        lo = std::min({lo, pts[i][0], pts[i][1]});
        hi = std::max({hi, pts[i][0], pts[i][1], radii[i]});
    }
    const FT mid = FT(0.5 * (lo + hi)), big = FT(1e3 * (hi - lo + 1.0));
    std::vector<std::pair<WPoint, std::size_t>> wp;
    for (std::size_t i = 0; i < n; ++i)
        if (!zero_area(clipped_power_cell(pts, radii, i, mid, mid, big)))
            wp.push_back({WPoint(P(i), R2(i)), i});
    RT rt(wp.begin(), wp.end());
    std::vector<bool> visible(n, false);
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) visible[v->info()] = true;
    if (rt.dimension() >= 1) {
        for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
            const auto f = e->first;
            const int k = e->second;
            const std::size_t a = f->vertex(RT::cw(k))->info(), b = f->vertex(RT::ccw(k))->info();
            const CGAL::Object dual = rt.dual(*e);
            if (!detail::positive_length(dual)) continue;
            res.power_neighbors[a].insert(b);
            res.power_neighbors[b].insert(a);
            if (detail::comes_closer(dual, P(a), R2(a))) {
                res.limited_neighbors[a].insert(b);
                res.limited_neighbors[b].insert(a);
            }
        }
    }
    std::vector<std::vector<Point>> polys(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (!visible[i]) continue;
        std::vector<Point> poly = clipped_power_cell(pts, radii, i, FT(pts[i][0]), FT(pts[i][1]), FT(2.0 * radii[i]));
        if (zero_area(poly)) continue;
        bool inside = true;  // p_i strictly inside its power cell
        for (std::size_t j = 0; j < n && inside; ++j)
            if (j != i && !(CGAL::squared_distance(P(i), P(j)) - R2(j) > -R2(i))) inside = false;
        res.empty[i] = res.limited_neighbors[i].empty() && !inside;
        polys[i] = std::move(poly);
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!res.empty[i]) continue;
        for (std::size_t j : res.limited_neighbors[i]) res.limited_neighbors[j].erase(i);
        res.limited_neighbors[i].clear();
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (res.empty[i]) continue;
        const double r = radii[i];
        const FT x = pts[i][0], y = pts[i][1];
        const std::vector<Point>& poly = polys[i];
        detail::Moments m;
        const std::size_t k = poly.size();
        for (std::size_t t = 0; t < k; ++t) {
            const Point& a = poly[t];
            const Point& b = poly[(t + 1) % k];
            const XY ra{detail::to_double_tight(a.x() - x, r), detail::to_double_tight(a.y() - y, r)};
            const XY rb{detail::to_double_tight(b.x() - x, r), detail::to_double_tight(b.y() - y, r)};
            detail::triangle_disk(ra, rb, r, m);
        }
        res.areas[i] = m.area;
    }
    return res;
}

}  // namespace dvoronoi_oracle
