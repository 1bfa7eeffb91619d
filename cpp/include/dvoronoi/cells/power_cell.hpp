// One agent's cell of a heterogeneous team (docs/spec.md, heterogeneous teams):
// W_i = {q in B(p_i, R_i) : |q - p_i|^2 - R_i^2 <= |q - p_j|^2 - R_j^2 for all j}, the power cell with
// weights R^2 clipped to the agent's own disk.
//
// Why not Boundary Scan or RCVC as they stand: both walk the chords sorted by angle around p_i and keep
// "p_i's side" of each, but p_i need not lie in its own cell (a big disk nearby can cover it while
// p_i keeps a crescent of its disk). So the cell is built by clipping, which needs no point of the
// cell known in advance:
//   1. classify each agent j with an exact test on (s_j, C4_j) (core/power_predicates.hpp): its
//      radical axis misses the disk on the far side (irrelevant), cuts it (a chord), or leaves the
//      disk outside the open half-plane (the cell is empty: zero area, at most a tangent point);
//   2. clip the box |x|,|y| <= 2R_i (which holds the disk) by the half-planes of the chords:
//      Sutherland-Hodgman on a cyclic list of lines, every vertex the meeting of two consecutive lines,
//      its side of a new line an exact degree-4 sign; a clip that leaves no vertex strictly inside
//      means zero area (empty cell);
//   3. intersect each edge of the polygon with the open disk by exact comparisons of positions along
//      its line (degree 8); edges of positive length inside the disk are the cell's edges, and the
//      arcs of the circle join them.
// All decisions are exact, so neighbours, empty flags and the order of pieces are the exact ones.
// Cost: O(m k) for m chords and k polygon vertices (k is small: about six in a swarm).
// Constructions: vertices in double-double from the exact differences (from exact expansions where
// a denominator or C4 loses more than 40 bits), then rounded to double: each coordinate within a few
// units in the last place of max(|vertex|, R_i) of the exact vertex; measures are summed in double
// from those vertices (Green's theorem, arcs exact).
#pragma once

#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/core/accurate.hpp"
#include "dvoronoi/core/cell.hpp"
#include "dvoronoi/core/power_predicates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace dvoronoi {

namespace detail {

inline constexpr double kPowerPi = 3.14159265358979323846;

/// Scratch of power_cell, reused across agents.
struct PowerWorkspace {
    std::vector<pred::power::WLine> lines;  ///< 0..3 the box, then the chords
    std::vector<pred::power::FastLine> fast;  ///< the same, rounded (the predicates' fast path)
    std::vector<Index> ids;                 ///< caller's index of each line (-1 for the box)
    std::vector<int> poly, next;            ///< the polygon: cyclic list of lines
    std::vector<int> sides;
    std::vector<pred::power::FastVertex> verts, next_verts;  ///< vertex k: poly[k-1] meets poly[k]
    std::vector<int> origin;                                  ///< during a clip: old edge of next[t], -1 = the new line
    struct Kept {
        std::size_t k;     // polygon edge
        bool from_vertex;  // starts at polygon vertex k (else at the chord's entry end)
        bool to_vertex;    // ends at polygon vertex k + 1 (else at the chord's exit end)
    };
    std::vector<Kept> kept;
    std::vector<Vec2> rel;
    std::vector<char> is_arc;
    std::vector<double> span;
};

/// A line in double-double: a = p - c exactly (two_sum), s rounded once per operation (about 2^-104
/// of its terms' sizes `ps`).
struct DDLine {
    DD ax, ay, s;
    double ps;
};

inline DDLine dd_line(const pred::power::Frame& f, const pred::power::WLine& l) {
    const DD r = dd(f.r);
    if (l.box >= 0) {
        const DD zero = dd(0.0);
        const DD s = r * r * 4.0;
        const double ps = 4.0 * f.r * f.r;
        switch (l.box) {
            case 0: return {r, zero, s, ps};
            case 1: return {zero, r, s, ps};
            case 2: return {-r, zero, s, ps};
            default: return {zero, -r, s, ps};
        }
    }
    DD ax, ay;
    two_sum(l.p.x(), -f.c.x(), ax.hi, ax.lo);
    two_sum(l.p.y(), -f.c.y(), ay.hi, ay.lo);
    const DD n2 = ax * ax + ay * ay, R2 = dd(l.R) * dd(l.R);
    return {ax, ay, n2 + r * r - R2, n2.hi + f.r * f.r + l.R * l.R};
}

/// The point x_jk (relative to c) as double-double. From double-double line data when the
/// denominator D_jk keeps 40 of its bits (then each coordinate is within about 2^-60 R of the exact
/// one: |M| / |D| <= 2^40 R-sized terms carry 2^-100 relative errors), else from exact expansions
/// of M_jk and D_jk rounded once.
inline DDPoint power_vertex(const pred::power::Frame& f, const pred::power::WLine& j, const pred::power::WLine& k) {
    using pred::power::line;
    const DDLine A = dd_line(f, j), B = dd_line(f, k);
    const DD D = A.ax * B.ay - A.ay * B.ax;
    const double pD = std::fabs(A.ax.hi * B.ay.hi) + std::fabs(A.ay.hi * B.ax.hi);
    if (std::fabs(D.hi) >= 0x1p-40 * pD && pD > 1e-250 && pD < 1e250) {
        const DD d2 = D * 2.0;
        return {(A.s * B.ay - B.s * A.ay) / d2, (B.s * A.ax - A.s * B.ax) / d2};
    }
    const auto Ae = line<Expansion>(f, j), Be = line<Expansion>(f, k);
    const Expansion mx = Ae.s * Be.ay - Be.s * Ae.ay, my = Be.s * Ae.ax - Ae.s * Be.ax;
    const Expansion De = Ae.ax * Be.ay - Ae.ay * Be.ax;
    const DD d2 = to_dd(De) * 2.0;
    return {to_dd(mx) / d2, to_dd(my) / d2};
}

/// The chord end e_j^sigma (relative to c): (s a + sigma perp(a) sqrt(C4)) / (2 |a|^2). In
/// double-double when C4 keeps 40 of its bits, else with C4 from exact expansions.
inline DDPoint power_chord_end(const pred::power::Frame& f, const pred::power::WLine& j, int sigma) {
    using pred::power::line;
    const DDLine A = dd_line(f, j);
    const DD n2 = A.ax * A.ax + A.ay * A.ay;
    DD c4 = dd(f.r) * dd(f.r) * n2 * 4.0 - A.s * A.s;
    const double pc4 = 4.0 * f.r * f.r * n2.hi + A.ps * A.ps;
    if (!(c4.hi >= 0x1p-40 * pc4) || !(pc4 > 1e-250 && pc4 < 1e250)) {
        const auto Ae = line<Expansion>(f, j);
        const Expansion r = Expansion(f.r);
        c4 = to_dd(Expansion(4.0) * r * r * (Ae.ax * Ae.ax + Ae.ay * Ae.ay) - Ae.s * Ae.s);
    }
    const DD root = sqrt(c4), den = n2 * 2.0, sg = dd(static_cast<double>(sigma));
    return {(A.s * A.ax - sg * A.ay * root) / den, (A.s * A.ay + sg * A.ax * root) / den};
}

/// Area, centroid (relative to c) and perimeter of a closed cycle of pieces given relative to c, by
/// Green's theorem: segments exactly, arcs of radius r through the closed forms of x^2 dy and y^2 dx.
inline CellMeasures power_measures(const std::vector<Vec2>& v, const std::vector<char>& arc,
                                   const std::vector<double>& span, double r) {
    double a2 = 0.0, mx = 0.0, my = 0.0, per = 0.0;
    const std::size_t n = v.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& u = v[k];
        const Vec2& w = v[(k + 1) % n];
        if (arc[k]) {
            a2 += r * r * span[k];
            mx += (r * r * w.y() - w.y() * w.y() * w.y() / 3.0) - (r * r * u.y() - u.y() * u.y() * u.y() / 3.0);
            my += (-r * r * w.x() + w.x() * w.x() * w.x() / 3.0) - (-r * r * u.x() + u.x() * u.x() * u.x() / 3.0);
            per += r * span[k];
        } else {
            a2 += u.x() * w.y() - u.y() * w.x();
            mx += (w.y() - u.y()) * (u.x() * u.x() + u.x() * w.x() + w.x() * w.x()) / 3.0;
            my -= (w.x() - u.x()) * (u.y() * u.y() + u.y() * w.y() + w.y() * w.y()) / 3.0;
            per += (w - u).norm();
        }
    }
    CellMeasures m;
    m.area = 0.5 * a2;
    m.perimeter = per;
    // The moments above are twice the integrals of x and y.
    if (m.area > 0.0) m.centroid = Vec2(0.5 * mx / m.area, 0.5 * my / m.area);
    return m;
}

/// The cell of c (radius r) among candidate agents cand with radii cand_r (any agents: the exact
/// classification ignores those whose radical axis misses the disk). Writes `out`; an empty cell has
/// no pieces, area 0 and its centroid at c.
/// \throws CoincidentError when a candidate lies at c with the same radius (index `self` names c).
inline void power_cell(const Vec2& c, double r, const std::vector<Candidate>& cand, const std::vector<double>& cand_r,
                       LimitedCell& out, PowerWorkspace& ws, Index self = -1) {
    using namespace pred::power;
    const Frame f{c, r};
    out.center = c;
    out.radius = r;
    out.pieces.clear();
    out.candidates = static_cast<Index>(cand.size());
    out.chords_after_check = -1;
    out.measures_ = CellMeasures{};
    out.measures_.centroid = c;

    ws.lines.clear();
    ws.fast.clear();
    ws.ids.clear();
    for (int b = 0; b < 4; ++b) {
        WLine l;
        l.box = b;
        ws.lines.push_back(l);
        ws.fast.push_back(fast_line(f, l));
        ws.ids.push_back(-1);
    }
    bool empty = false;
    bool center_inside = true;  // c strictly inside every chord's half-plane
    for (std::size_t t = 0; t < cand.size(); ++t) {
        const Vec2& p = cand[t].p;
        const double R = cand_r[t];
        if (p == c) {
            if (R == r) {
                const Index j = cand[t].id;
                char at[64];
                std::snprintf(at, sizeof at, "(%.17g, %.17g)", c.x(), c.y());
                const std::string who = self >= 0 ? "points[" + std::to_string(self) + "]" : std::string("center");
                throw CoincidentError(who + " and points[" + std::to_string(j) + "] coincide at " + at +
                                          " with the same radius; their cells are undefined",
                                      self, j);
            }
            if (R > r) empty = true;  // the larger disk at the same place holds the cell
            continue;
        }
        WLine l;
        l.p = p;
        l.R = R;
        const FastLine fl = fast_line(f, l);
        const int c4 = chord_sign(f, l, fl);
        if (c4 > 0) {
            ws.lines.push_back(l);
            ws.fast.push_back(fl);
            ws.ids.push_back(cand[t].id);
            if (center_inside && s_sign(f, l, fl) <= 0) center_inside = false;
        } else if (s_sign(f, l, fl) <= 0) {
            empty = true;  // the closed disk lies outside the open half-plane: zero area
        }
    }
    if (empty) return;

    // 2. Clip the box by the chords' half-planes.
    auto& poly = ws.poly;
    auto& next = ws.next;
    auto& sides = ws.sides;
    poly.assign({0, 1, 2, 3});
    const auto& L = ws.lines;
    const auto& F = ws.fast;
    auto& verts = ws.verts;
    auto& origin = ws.origin;
    const auto vertex_of = [&](int j, int k) { return fast_vertex(F[static_cast<std::size_t>(j)], F[static_cast<std::size_t>(k)]); };
    verts.clear();
    for (std::size_t k = 0; k < 4; ++k) verts.push_back(vertex_of(poly[(k + 3) % 4], poly[k]));
    for (int l = 4; l < static_cast<int>(L.size()); ++l) {
        const std::size_t n = poly.size();
        const auto ll = static_cast<std::size_t>(l);
        sides.resize(n);
        bool any_in = false, any_out = false;
        for (std::size_t k = 0; k < n; ++k) {  // vertex k starts edge k: poly[k-1] meets poly[k]
            const auto j = static_cast<std::size_t>(poly[(k + n - 1) % n]), q = static_cast<std::size_t>(poly[k]);
            sides[k] = side_of_vertex(f, L[ll], L[j], L[q], F[ll], verts[k]);
            any_in |= sides[k] < 0;
            any_out |= sides[k] > 0;
        }
        if (!any_in) return;  // nothing strictly inside: zero area
        if (!any_out) {
            // Unchanged; an edge with both ends on L_l lies on it (coaxal disks): the farther agent
            // holds the far side, so it is the neighbour across that edge.
            for (std::size_t k = 0; k < n; ++k)
                if (sides[k] == 0 && sides[(k + 1) % n] == 0 && farther(f, L[ll], L[static_cast<std::size_t>(poly[k])]) > 0) {
                    poly[k] = l;
                    verts[k] = vertex_of(poly[(k + n - 1) % n], l);
                    verts[(k + 1) % n] = vertex_of(l, poly[(k + 1) % n]);
                }
            continue;
        }
        next.clear();
        origin.clear();
        for (std::size_t k = 0; k < n; ++k) {
            const int s0 = sides[k], s1 = sides[(k + 1) % n];
            if (std::min(s0, s1) < 0) {
                next.push_back(poly[k]);
                origin.push_back(static_cast<int>(k));
            }
            if (s0 < 0 && s1 >= 0) {  // the exit edge: L_l follows it
                next.push_back(l);
                origin.push_back(-1);
            }
        }
        // A vertex between two old consecutive edges is an old vertex; the two at L_l are new.
        auto& nv = ws.next_verts;
        nv.clear();
        const std::size_t m = next.size();
        for (std::size_t t = 0; t < m; ++t) {
            const int o = origin[t], op = origin[(t + m - 1) % m];
            if (o >= 0 && op >= 0 && static_cast<std::size_t>(op) == (static_cast<std::size_t>(o) + n - 1) % n)
                nv.push_back(verts[static_cast<std::size_t>(o)]);
            else
                nv.push_back(vertex_of(next[(t + m - 1) % m], next[t]));
        }
        poly.swap(next);
        verts.swap(nv);
    }

    // 3. The polygon's edges inside the open disk, and the arcs between them.
    const std::size_t n = poly.size();
    using Kept = PowerWorkspace::Kept;
    auto& kept = ws.kept;
    kept.clear();
    for (std::size_t k = 0; k < n; ++k) {
        const int t = poly[k];
        if (t < 4) continue;  // box sides never meet the disk
        const auto it = static_cast<std::size_t>(t), ip = static_cast<std::size_t>(poly[(k + n - 1) % n]),
                   in = static_cast<std::size_t>(poly[(k + 1) % n]);
        const WLine &Lt = L[it], &Lp = L[ip], &Ln = L[in];
        const FastLine &Ft = F[it], &Fp = F[ip], &Fn = F[in];
        // Positive length inside the open disk: starts before the exit end, ends after the entry end.
        if (position_vs_chord_end(f, Lt, Lp, Lt, +1, Ft, Fp, Ft) >= 0) continue;
        if (position_vs_chord_end(f, Lt, Lt, Ln, -1, Ft, Ft, Fn) <= 0) continue;
        kept.push_back({k, position_vs_chord_end(f, Lt, Lp, Lt, -1, Ft, Fp, Ft) >= 0,
                        position_vs_chord_end(f, Lt, Lt, Ln, +1, Ft, Ft, Fn) <= 0});
    }
    if (kept.empty()) {
        if (!center_inside) return;  // the polygon misses the open disk: zero area
        Piece p;
        p.start = c + Vec2(r, 0.0);
        p.arc_span = 2.0 * kPowerPi;
        out.pieces.push_back(p);
        CellMeasures m;
        m.area = kPowerPi * r * r;
        m.centroid = c;
        m.perimeter = 2.0 * kPowerPi * r;
        out.measures_ = m;
        return;
    }
    auto& rel = ws.rel;
    auto& is_arc = ws.is_arc;
    auto& span = ws.span;
    rel.clear();
    is_arc.clear();
    span.clear();
    const auto start_of = [&](const Kept& e) {
        const int t = poly[e.k];
        return e.from_vertex ? power_vertex(f, L[static_cast<std::size_t>(poly[(e.k + n - 1) % n])], L[static_cast<std::size_t>(t)])
                             : power_chord_end(f, L[static_cast<std::size_t>(t)], -1);
    };
    const auto end_of = [&](const Kept& e) {
        const int t = poly[e.k];
        return e.to_vertex ? power_vertex(f, L[static_cast<std::size_t>(t)], L[static_cast<std::size_t>(poly[(e.k + 1) % n])])
                           : power_chord_end(f, L[static_cast<std::size_t>(t)], +1);
    };
    for (std::size_t q = 0; q < kept.size(); ++q) {
        const Kept& e = kept[q];
        const Kept& g = kept[(q + 1) % kept.size()];
        const Vec2 s = start_of(e).value();
        Piece edge;
        edge.neighbor = ws.ids[static_cast<std::size_t>(poly[e.k])];
        edge.start = c + s;
        out.pieces.push_back(edge);
        rel.push_back(s);
        is_arc.push_back(0);
        span.push_back(0.0);
        // Joined at a polygon vertex (inside the disk or on the circle): no arc between.
        if (kept.size() > 1 && e.to_vertex && g.from_vertex && g.k == (e.k + 1) % n) continue;
        const DDPoint ud = end_of(e), wd = start_of(g);
        const Vec2 u = ud.value();
        // The span from the double-double ends (before rounding), so that only an arc shorter than
        // about 2^-100 radians could be mistaken for a full turn; the exact combinatorics above
        // already know it has positive length, and counter-clockwise means a in (0, 2 pi].
        const DD cr = ud.x * wd.y - ud.y * wd.x, dt = ud.x * wd.x + ud.y * wd.y;
        double a = std::atan2(cr.hi + cr.lo, dt.hi + dt.lo);
        if (a <= 0.0) a += 2.0 * kPowerPi;
        Piece arc;
        arc.start = c + u;
        arc.arc_span = a;
        out.pieces.push_back(arc);
        rel.push_back(u);
        is_arc.push_back(1);
        span.push_back(a);
    }
    CellMeasures m = power_measures(rel, is_arc, span, r);
    m.centroid += c;
    out.measures_ = m;
}

}  // namespace detail

/// The cell W of the agent at `center` with radius `radius` among `others` with radii `other_radii`
/// (docs/spec.md, heterogeneous teams): the power cell (weights R^2) clipped to B(center, radius).
/// Edge pieces name their neighbour by its row in `others`. An empty cell (zero area) has no pieces.
/// With every other radius equal to `radius` this is limited_cell(center, others, radius, method).
///
/// \throws InputError for a bad radius, radii of the wrong length, non-finite coordinates, Scan or
///         Chords with unequal radii;
///         CoincidentError for an agent of `others` at `center` with the same radius.
/// \note Thread-safe (pure function). O(m k): m agents within radius + R_j, k vertices of the cell.
inline LimitedCell power_limited_cell(const Vec2& center, PointsRef others, double radius,
                                      const std::vector<double>& other_radii, Method method = Method::Auto) {
    detail::require_finite_radius(radius);
    detail::require_finite_point(center, "center");
    detail::require_finite_points(others, "others");
    if (static_cast<Index>(other_radii.size()) != others.rows())
        throw InputError("other_radii must have one radius per row of others: " + std::to_string(other_radii.size()) +
                         " radii for " + std::to_string(others.rows()) + " agents");
    bool equal = true;
    for (double R : other_radii) {
        detail::require_finite_radius(R, "other_radii");
        equal &= R == radius;
    }
    if (equal) return limited_cell(center, others, radius, method);
    if (method != Method::Auto)
        throw InputError(std::string("method \"") + method_name(method) +
                         "\" (Boundary Scan or RCVC around the agent) needs equal radii; with other_radii the cell is "
                         "computed by power-cell clipping: use method \"auto\"");
    std::vector<detail::Candidate> cand;
    std::vector<double> rs;
    for (Index j = 0; j < others.rows(); ++j) {
        cand.push_back({others.row(j).transpose(), j});
        rs.push_back(other_radii[static_cast<std::size_t>(j)]);
    }
    LimitedCell cell;
    detail::PowerWorkspace ws;
    detail::power_cell(center, radius, cand, rs, cell, ws);
    return cell;
}

}  // namespace dvoronoi
