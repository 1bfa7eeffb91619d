// Accurate constructions: every point and measure a cell reports is within 2^-40 D of the exact value
// for the input doubles (D = the cell's diameter; areas within 2^-40 D^2), see docs/guarantees.md.
//
// How: each construction is first evaluated in double together with a forward error bound derived
// for the formula used (stated at each function). Where the bound is too large — nearly parallel
// bisectors, a chord near tangency, a thin cell whose centroid magnifies the roundings — it is redone
// from exact expansions of the input differences (core/expansion.hpp), carried in double-double,
// and rounded once. The bounds are cheap, so the common case costs what the plain formulas cost.
//
// Range: the bounds and the exact stage assume no product underflows or overflows, i.e. agents within
// 2R of each other differ (where they differ) by more than about 1e-90 R in each coordinate, with R
// in [kMinRadius, kMaxRadius]; beyond that results are still computed but the guarantee is not given.
#pragma once

#include "dvoronoi/core/expansion.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dvoronoi::detail {

/// The accuracy every construction is held to, as a fraction of the cell's diameter D (areas: of D^2).
inline constexpr double kConstructionAccuracy = 0x1p-40;

// ---- double-double (about 104 bits; the slow path only) ----

struct DD {
    double hi = 0.0, lo = 0.0;
    double value() const { return hi + lo; }
};

inline DD dd(double a) { return {a, 0.0}; }

inline DD operator+(const DD& a, const DD& b) {
    double s, e, t, f;
    two_sum(a.hi, b.hi, s, e);
    two_sum(a.lo, b.lo, t, f);
    e += t;
    fast_two_sum(s, e, s, e);
    e += f;
    DD r;
    fast_two_sum(s, e, r.hi, r.lo);
    return r;
}
inline DD operator-(const DD& a) { return {-a.hi, -a.lo}; }
inline DD operator-(const DD& a, const DD& b) { return a + (-b); }
inline DD operator*(const DD& a, const DD& b) {
    double p, e;
    two_product(a.hi, b.hi, p, e);
    e += a.hi * b.lo + a.lo * b.hi;
    DD r;
    fast_two_sum(p, e, r.hi, r.lo);
    return r;
}
inline DD operator*(const DD& a, double b) { return a * dd(b); }
inline DD operator/(const DD& a, const DD& b) {
    // Long division: three double quotients, each correcting the remainder of the last.
    const double q1 = a.hi / b.hi;
    DD r = a - b * q1;
    const double q2 = r.hi / b.hi;
    r = r - b * q2;
    const double q3 = r.hi / b.hi;
    DD q;
    fast_two_sum(q1, q2, q.hi, q.lo);
    return q + dd(q3);
}
/// sqrt(a) for a >= 0: one Newton step from the double root.
inline DD sqrt(const DD& a) {
    if (!(a.hi > 0.0)) return {0.0, 0.0};
    const double x = std::sqrt(a.hi);
    double p, e;
    two_product(x, x, p, e);
    const DD rest = a - DD{p, e};
    DD r;
    fast_two_sum(x, rest.hi / (2.0 * x), r.hi, r.lo);
    return r;
}
/// The exact value of an expansion, to double-double (summed from the smallest component).
inline DD to_dd(const Expansion& x) {
    DD s;
    for (double v : x.components()) s = s + dd(v);
    return s;
}

struct DDPoint {
    DD x, y;
    Vec2 value() const { return Vec2(x.value(), y.value()); }
};

inline double l1(double x, double y) { return std::fabs(x) + std::fabs(y); }

// ---- constructions in double with a forward error bound ----

/// A point relative to the agent with a bound on its distance to the exact point (of the exact
/// differences p - c); e is infinite where the bound is meaningless.
struct BoundedPoint {
    double x, y, e;
};

inline constexpr double kUnitRoundoff = 1.1102230246251565e-16;

/// v_jk, the vertex of the bisectors of the agent and p_j, p_k (a = p - c rounded once, n2 = |a|^2
/// rounded), by Cramer's rule: x = (h_j a_k.y - h_k a_j.y) / D, y = (a_j.x h_k - a_k.x h_j) / D,
/// D = cross(a_j, a_k), h = n2 / 2. Error bound: a carries u, n2 4u, each product of two rounded
/// factors 6u of the sum of the magnitudes |h a| (pnx, pny) and 3u of |l| + |r| (pd) for D; a
/// quotient n/d is off by (|x| E_d + E_n) / |d| plus the rounding of 1/d and of the product (3u |x|).
/// That is the first-order bound, doubled: where it is accepted (far below |v|) the second-order
/// terms are smaller than the doubling by a factor 2^30.
inline BoundedPoint line_vertex(double ajx, double ajy, double n2j, double akx, double aky, double n2k) {
    constexpr double kU = kUnitRoundoff;
    const double l = ajx * aky, r = ajy * akx;
    const double d = l - r, pd = std::fabs(l) + std::fabs(r);
    const double hj = 0.5 * n2j, hk = 0.5 * n2k;
    const double nx = hj * aky - hk * ajy, pnx = std::fabs(hj * aky) + std::fabs(hk * ajy);
    const double ny = ajx * hk - akx * hj, pny = std::fabs(ajx * hk) + std::fabs(akx * hj);
    // One division (a reciprocal) instead of four. x and y then take two roundings (of 1/d and of
    // the product) instead of one: 3u |x| below, where the quotient needed u.
    const double inv = 1.0 / d;
    const double x = nx * inv, y = ny * inv;
    if (!(std::fabs(d) > 16.0 * kU * pd)) return {x, y, std::numeric_limits<double>::infinity()};
    const double ainv = std::fabs(inv);
    const double ex = (10.0 * kU * pnx + 6.0 * kU * pd * std::fabs(x)) * ainv + 3.0 * kU * std::fabs(x);
    const double ey = (10.0 * kU * pny + 6.0 * kU * pd * std::fabs(y)) * ainv + 3.0 * kU * std::fabs(y);
    return {x, y, 2.0 * (ex + ey)};
}

/// Half-length of the chord of the bisector of a (relative to c) in the disk of radius r:
/// sqrt(r^2 - |a|^2/4), as sqrt((r - h)(r + h)), h = |a| / 2.
inline double half_chord(double ax, double ay, double r) {
    const double h = 0.5 * std::sqrt(ax * ax + ay * ay);
    return std::sqrt(std::max(0.0, (r - h) * (r + h)));
}

/// The end of the chord of the bisector of a in the disk of radius r (sigma = -1 the
/// counter-clockwise-first, +1 the last): a/2 + sigma w perp(a) / |a|, w the half chord. Error
/// bound: h = |a|/2 carries 3u h, which moves w by 3u h (r + h) / (2 w) (the conditioning near
/// tangency, w -> 0); the roundings of w, of w / |a| and of the sum add 10u w and 4u of |a|; doubled as
/// for line_vertex. Infinite near tangency, where the half chord loses its digits.
inline BoundedPoint chord_vertex(double ax, double ay, double r, int sigma) {
    constexpr double kU = kUnitRoundoff;
    const double na = std::sqrt(ax * ax + ay * ay);
    const double h = 0.5 * na, hc = half_chord(ax, ay, r);
    const double w = hc / na;
    const double x = 0.5 * ax - sigma * w * ay, y = 0.5 * ay + sigma * w * ax;
    if (!(hc > 0.0) || !(r - h > 0.0)) return {x, y, std::numeric_limits<double>::infinity()};
    const double e = 1.5 * kU * h * (r + h) / hc + 10.0 * kU * hc + 4.0 * kU * 2.0 * h;
    return {x, y, 2.0 * e};
}

// ---- the same from exact expansions, in double-double ----

/// (p - c) * s exactly (s a power of two; no underflow in range).
inline Expansion scaled_diff(double p, double c, double s) { return Expansion::diff(p, c).times(s); }

/// v_jk relative to c, times `unit`, from exact expansions of p - c (rescaled to about 1 so that no
/// product under- or overflows): numerators and denominator exact, one double-double division.
/// Within about 2^-100 |v| however nearly parallel the bisectors.
inline DDPoint exact_vertex(const Vec2& c, const Vec2& pj, const Vec2& pk, double unit) {
    const double m = std::max({std::fabs(pj.x() - c.x()), std::fabs(pj.y() - c.y()), std::fabs(pk.x() - c.x()),
                               std::fabs(pk.y() - c.y())}) * unit;
    const int e = m > 0.0 ? std::ilogb(m) : 0;
    const double s = std::ldexp(unit, -e);
    const Expansion jx = scaled_diff(pj.x(), c.x(), s), jy = scaled_diff(pj.y(), c.y(), s);
    const Expansion kx = scaled_diff(pk.x(), c.x(), s), ky = scaled_diff(pk.y(), c.y(), s);
    const Expansion nj = jx * jx + jy * jy, nk = kx * kx + ky * ky;
    const DD d2 = to_dd(jx * ky - jy * kx) * 2.0;
    const double back = std::ldexp(1.0, e);
    return {to_dd(nj * ky - nk * jy) / d2 * back, to_dd(jx * nk - kx * nj) / d2 * back};
}

/// The chord end of p's bisector (sigma as chord_vertex) relative to c, times `unit`, with r =
/// radius * unit: a/2 + sigma t perp(a), t = sqrt((4 r^2 - |a|^2) / |a|^2) / 2, the two squares exact
/// (so tangency costs no digits), the rest in double-double.
inline DDPoint exact_chord_end(const Vec2& c, const Vec2& p, double r, double unit, int sigma) {
    const Expansion ax = scaled_diff(p.x(), c.x(), unit), ay = scaled_diff(p.y(), c.y(), unit);
    const Expansion n2 = ax * ax + ay * ay;
    const Expansion q = Expansion(4.0 * r) * Expansion(r) - n2;  // 4r is exact (a power of two times r)
    const DD t = sqrt(to_dd(q) / to_dd(n2)) * 0.5;
    const DD x = to_dd(ax), y = to_dd(ay);
    const double sg = sigma;
    return {x * 0.5 - t * y * sg, y * 0.5 + t * x * sg};
}

// ---- measures of a cell boundary, with a bound, else in double-double ----

/// A cell boundary relative to its agent, in a frame where the radius is about 1 (or the cell about
/// 1, for polygons): vertex k starts piece k, an edge or (arc[k]) an arc of the circle of radius r
/// sweeping span[k] counter-clockwise. e[k] bounds the error of vertex k.
struct Boundary {
    std::vector<Vec2> v;
    std::vector<double> e;
    std::vector<char> arc;
    std::vector<double> span;  ///< arcs: in, the approximate span (picks the branch); out, the span
    std::vector<DDPoint> dd;

    void clear() {
        v.clear();
        e.clear();
        arc.clear();
        span.clear();
    }
    void push(const BoundedPoint& p, bool is_arc, double approx_span) {
        v.emplace_back(p.x, p.y);
        e.push_back(p.e);
        arc.push_back(is_arc ? 1 : 0);
        span.push_back(approx_span);
    }
    std::size_t size() const { return v.size(); }
};

/// Area, centroid (relative to the agent) and perimeter.
struct LocalMeasures {
    double area = 0.0, cx = 0.0, cy = 0.0, perimeter = 0.0;
};

/// The counter-clockwise angle from u to w in [0, 2 pi], on the branch nearest `approx`.
inline double arc_angle(double cross, double dot, double approx) {
    constexpr double kTwoPi = 6.283185307179586476925286766559;
    double direct = std::atan2(cross, dot);
    if (direct < 0.0) direct += kTwoPi;
    if (direct - approx > kTwoPi / 2) direct -= kTwoPi;
    if (approx - direct > kTwoPi / 2) direct += kTwoPi;
    return std::clamp(direct, 0.0, kTwoPi);
}

/// Spans of the arcs from their (double) endpoints.
inline void arc_spans(Boundary& b) {
    const std::size_t n = b.size();
    for (std::size_t k = 0; k < n; ++k) {
        if (!b.arc[k]) continue;
        const Vec2 &u = b.v[k], &w = b.v[(k + 1) % n];
        b.span[k] = n == 1 ? b.span[k] : arc_angle(u.x() * w.y() - u.y() * w.x(), u.dot(w), b.span[k]);
    }
}

/// The measures in double with their error bounds; false when a bound exceeds kConstructionAccuracy
/// / 2 of `dlo` (a lower bound on the diameter; its square for the area). Per term, from the vertex
/// errors e and the roundings (u per operation, magnitudes bounded by 1-norms):
///  - edge (u, w): cross(u, w) is off by |u| e_w + |w| e_u + e_u e_w + 3u (|u_x w_y| + |u_y w_x|) (dc);
///    area term half that; first moment cross (u + w) / 6 off by (dc |u + w| + 2 |cross| (e_u + e_w)) / 6
///    plus 3u of its size; length off by e_u + e_w + 4u |w - u|.
///  - arc: the angle is off by (e_u + e_w) / (r (1 - 2^-20)) (an endpoint moved by e turns by at most
///    e / (r - e)) plus 8u + 4u span (cross, dot, atan2 and a 2 pi shift, rounded); area r^2 / 2 and
///    length r times that; first moment r^2/3 (w_y - u_y, u_x - w_x) off by 2 r^2/3 (e_u + e_w) and 4u.
///  - each sum of n terms: (n + 2) u of the sum of the terms' magnitudes.
/// The centroid M / A is then off by (E_M + |g| E_A) / (A - E_A) plus 2u |g|.
inline bool measure_bounded(const Boundary& b, double r, double dlo, LocalMeasures& out) {
    constexpr double kU = kUnitRoundoff;
    const std::size_t n = b.size();
    const double tol = 0.5 * kConstructionAccuracy * dlo;
    double A = 0.0, mx = 0.0, my = 0.0, P = 0.0;
    double EA = 0.0, SA = 0.0, EM = 0.0, SM = 0.0, EP = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t k1 = k + 1 == n ? 0 : k + 1;
        const Vec2 &u = b.v[k], &w = b.v[k1];
        const double eu = b.e[k], ew = b.e[k1];
        if (b.arc[k]) {
            const double phi = b.span[k], r2 = r * r;
            const double dphi = (eu + ew) / (r * (1.0 - 0x1p-20)) + kU * (8.0 + 4.0 * phi);
            if (!(r * dphi <= tol)) return false;
            const double t = 0.5 * r2 * phi;
            A += t;
            SA += t;
            EA += 0.5 * r2 * dphi;
            const double k3 = r2 / 3.0;
            const double fx = k3 * (w.y() - u.y()), fy = k3 * (u.x() - w.x());
            mx += fx;
            my += fy;
            SM += l1(fx, fy);
            EM += 2.0 * k3 * (eu + ew) + 4.0 * kU * k3 * (l1(u.x(), u.y()) + l1(w.x(), w.y()));
            P += r * phi;
            EP += r * dphi + kU * r * phi;
        } else {
            const double lp = u.x() * w.y(), rp = u.y() * w.x();
            const double cr = lp - rp, pc = std::fabs(lp) + std::fabs(rp);
            const double nu = l1(u.x(), u.y()), nw = l1(w.x(), w.y());
            const double dc = nu * ew + nw * eu + eu * ew + 3.0 * kU * pc;
            A += 0.5 * cr;
            SA += 0.5 * pc;
            EA += 0.5 * dc;
            const double sx = u.x() + w.x(), sy = u.y() + w.y(), ns = l1(sx, sy);
            mx += cr * sx / 6.0;
            my += cr * sy / 6.0;
            SM += std::fabs(cr) * ns / 6.0;
            EM += (dc * ns + 2.0 * std::fabs(cr) * (eu + ew)) / 6.0 + 3.0 * kU * (std::fabs(cr) + dc) * ns / 6.0;
            const double len = std::sqrt((w.x() - u.x()) * (w.x() - u.x()) + (w.y() - u.y()) * (w.y() - u.y()));
            P += len;
            EP += eu + ew + 4.0 * kU * len;
        }
    }
    const double sum_err = static_cast<double>(n + 2) * kU;
    EA += sum_err * SA;
    EM += sum_err * SM;
    EP += sum_err * P;
    if (!(EA <= tol * dlo && EP <= tol && A > 2.0 * EA)) return false;
    const double gx = mx / A, gy = my / A;
    const double EG = (EM + l1(gx, gy) * EA) / (A - EA) + 2.0 * kU * l1(gx, gy);
    if (!(EG <= tol)) return false;
    out = {A, gx, gy, P};
    return true;
}

/// The measures from the double-double vertices b.dd (arc spans from them, rounded to double, on the
/// branch of b.span): vertices within about 2^-100 of the cell, every sum and product in
/// double-double, the spans within 6u of themselves, so area, centroid and perimeter are within a
/// few u of the cell's size whatever the cancellation.
inline LocalMeasures measure_dd(Boundary& b, double r) {
    const std::size_t n = b.size();
    DD A, mx, my, P;
    const DD r2 = dd(r) * dd(r);
    const DD k3 = r2 / dd(3.0);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t k1 = k + 1 == n ? 0 : k + 1;
        const DDPoint &u = b.dd[k], &w = b.dd[k1];
        if (b.arc[k]) {
            if (n > 1)
                b.span[k] = arc_angle((u.x * w.y - u.y * w.x).value(), (u.x * w.x + u.y * w.y).value(), b.span[k]);
            const double phi = b.span[k];
            A = A + r2 * (0.5 * phi);
            mx = mx + k3 * (w.y - u.y);
            my = my + k3 * (u.x - w.x);
            P = P + dd(r) * phi;
        } else {
            const DD cr = u.x * w.y - u.y * w.x;
            A = A + cr * 0.5;
            mx = mx + cr * (u.x + w.x) / dd(6.0);
            my = my + cr * (u.y + w.y) / dd(6.0);
            const DD dx = w.x - u.x, dy = w.y - u.y;
            P = P + sqrt(dx * dx + dy * dy);
        }
    }
    LocalMeasures out;
    out.area = A.value();
    out.cx = (mx / A).value();
    out.cy = (my / A).value();
    out.perimeter = P.value();
    return out;
}

/// A lower bound on the diameter of the cell whose boundary is b: the agent lies in its cell, so
/// the cell reaches at least as far as any vertex (at least r when it has an arc).
inline double diameter_below(const Boundary& b, double r) {
    double d = 0.0;
    bool has_arc = false;
    for (std::size_t k = 0; k < b.size(); ++k) {
        d = std::max(d, 0.7071 * l1(b.v[k].x(), b.v[k].y()) * (1.0 - 8.0 * kUnitRoundoff) - b.e[k]);
        has_arc = has_arc || b.arc[k];
    }
    return has_arc ? std::max(d, r * (1.0 - 8.0 * kUnitRoundoff)) : d;
}

/// Makes b's vertices, arc spans and measures meet kConstructionAccuracy. exact(k) gives vertex k in
/// double-double (from exact expansions). A vertex whose bound is above 2^-44 of the diameter is
/// recomputed that way (rounded: within u of itself); then the measures are taken in double with
/// their bounds, and when those do not meet the target, everything again in double-double.
template <class Exact>
LocalMeasures accurate_measures(Boundary& b, double r, Exact&& exact) {
    const std::size_t n = b.size();
    double dlo = diameter_below(b, r);
    bool refined = false;
    for (std::size_t k = 0; k < n; ++k)
        if (!(b.e[k] <= 0x1p-44 * dlo)) {
            b.v[k] = exact(k).value();
            b.e[k] = 2.0 * kUnitRoundoff * l1(b.v[k].x(), b.v[k].y());
            refined = true;
        }
    if (refined) dlo = diameter_below(b, r);
    arc_spans(b);
    LocalMeasures m;
    if (measure_bounded(b, r, dlo, m)) return m;
    b.dd.resize(n);
    for (std::size_t k = 0; k < n; ++k) b.dd[k] = exact(k);
    m = measure_dd(b, r);
    for (std::size_t k = 0; k < n; ++k) b.v[k] = b.dd[k].value();
    return m;
}

}  // namespace dvoronoi::detail
