// Accurate constructions: every point and measure a cell reports is within 2^-40 D of the exact value
// for the input doubles (D = the cell's diameter; areas within 2^-40 D^2), see docs/guarantees.md.
//
// How: each construction is first evaluated in double together with a forward error bound derived
// for the formula used (stated at each function). Where the bound is too large — nearly parallel
// bisectors, a chord near tangency, a thin cell whose centroid magnifies the roundings — it is redone
// from exact expansions of the input differences (core/expansion.hpp), carried in double-double,
// and rounded once. The bounds are a few flops per piece: limited_cells of a uniform swarm takes
// about 3% longer than with the plain formulas (measured), and redoes 1 vertex in 2000 exactly.
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

/// A vertex whose error bound is above this fraction of the cell's diameter is redone from exact
/// differences (measured: 348 of 600000 vertices of a uniform swarm); below it the measures'
/// bounds pass for all but thin cells (none of 100000 cells of that swarm).
inline constexpr double kRefineBelow = 0x1p-44;

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
/// D = cross(a_j, a_k), h = n2 / 2. Error bound against the exact a: each a carries u, n2 4u; a
/// product of two of them 3u (a a) or 6u (h a) of itself, so the numerator nx is off by
/// 6u pnx + u |nx| (pnx = |h_j a_k.y| + |h_k a_j.y|) and D by 3u pd + u |D| (pd = |l| + |r|); the
/// quotient nx / D by (E_n + |x| E_D) / |D|, and 1/D and the product round twice more:
/// ex <= (6u pnx + 3u pd |x|) / |D| + 4u |x|, likewise ey. That is first order; with D above 2^-20 of
/// pd (else the bound is infinite: such vertices are redone exactly) the second-order terms are below
/// 2^-17 of it, and one more u in each constant covers them.
inline BoundedPoint line_vertex(double ajx, double ajy, double n2j, double akx, double aky, double n2k) {
    constexpr double kU = kUnitRoundoff;
    const double l = ajx * aky, r = ajy * akx;
    const double d = l - r, pd = std::fabs(l) + std::fabs(r);
    const double hj = 0.5 * n2j, hk = 0.5 * n2k;
    const double nx = hj * aky - hk * ajy, ny = ajx * hk - akx * hj;
    const double pn = std::fabs(hj * aky) + std::fabs(hk * ajy) + std::fabs(ajx * hk) + std::fabs(akx * hj);
    const double an = std::fabs(nx) + std::fabs(ny);
    // One division (a reciprocal) instead of four.
    const double inv = 1.0 / d;
    const double x = nx * inv, y = ny * inv;
    if (!(std::fabs(d) > 0x1p-20 * pd)) return {x, y, std::numeric_limits<double>::infinity()};
    // ex + ey with |x| + |y| taken as (|nx| + |ny|) / |D| (within u: the spare u covers it), so
    // that few operations wait for 1/D.
    const double ainv = std::fabs(inv);
    return {x, y, ainv * (7.0 * kU * pn + kU * an * (4.0 * pd * ainv + 5.0))};
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
    const double h = 0.5 * na, hc = std::sqrt(std::max(0.0, (r - h) * (r + h)));  // half_chord
    const double w = hc / na;
    const double x = 0.5 * ax - sigma * w * ay, y = 0.5 * ay + sigma * w * ax;
    if (!(hc > 0.0) || !(r - h > 0.0)) return {x, y, std::numeric_limits<double>::infinity()};
    // h (r + h) / hc <= 4 r while hc >= r / 2 (most chords): no division there.
    const double cond = hc >= 0.5 * r ? 4.0 * r : h * (r + h) / hc;
    const double e = 1.5 * kU * cond + 10.0 * kU * hc + 4.0 * kU * 2.0 * h;
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

/// v_jk as exact_vertex, but in double-double arithmetic on the exact differences p - c (which are
/// double-doubles): far cheaper, and within 2^-51 |v| while D_jk is not below 2^-44 of its terms
/// (each double-double operation is off by about 2^-104 of its operands, so D and the numerators are
/// off by at most 2^-100 of their terms; relative to D and |v| >= |a| / 2 that is 2^-56 and 2^-51).
/// False (out unspecified) otherwise.
inline bool dd_vertex(const Vec2& c, const Vec2& pj, const Vec2& pk, double unit, DDPoint& out) {
    const auto diff = [&](double p, double q) {
        DD r;
        two_sum(p, -q, r.hi, r.lo);
        return DD{r.hi * unit, r.lo * unit};
    };
    const DD jx = diff(pj.x(), c.x()), jy = diff(pj.y(), c.y()), kx = diff(pk.x(), c.x()), ky = diff(pk.y(), c.y());
    const DD l = jx * ky, r = jy * kx, d = l - r;
    if (!(std::fabs(d.hi) > 0x1p-44 * (std::fabs(l.hi) + std::fabs(r.hi)))) return false;
    const DD hj = (jx * jx + jy * jy) * 0.5, hk = (kx * kx + ky * ky) * 0.5;
    out = {(hj * ky - hk * jy) / d, (jx * hk - kx * hj) / d};
    return std::isfinite(out.x.hi) && std::isfinite(out.y.hi);
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
/// 1, for polygons): vertex k starts piece k, an edge or (arc) an arc of the circle of radius r
/// sweeping `span` counter-clockwise; e bounds the error of vertex k. One array of structs, with a
/// summary (largest |v|, largest and summed e) that a builder may gather as the vertices come: the
/// fast path then walks the pieces once more only.
struct BoundaryPoint {
    Vec2 v;
    double e;
    double span;  ///< arcs: in, the approximate span (picks the branch); out, the span
    bool arc;
};

struct Boundary {
    std::vector<BoundaryPoint> p;  ///< the first size() are the boundary (the rest: room, kept)
    std::vector<DDPoint> dd;
    double emax = 0.0;   ///< the largest e (NaN if any is)
    double vmax = 0.0;   ///< the largest |v|_1
    double esum = 0.0;   ///< the sum of the e
    bool changed = false;  ///< accurate_measures moved a vertex (refined it, or the double-double path)
    bool has_arc = false;

    void clear() { n_ = 0; }
    /// Room for `count` points, so that put() needs no check (a cell is rebuilt per agent: the room
    /// is allocated once per thread).
    BoundaryPoint* room(std::size_t count) {
        if (p.size() < count) p.resize(count);
        return p.data();
    }
    void set_size(std::size_t count) { n_ = count; }
    void push(const BoundedPoint& q, bool is_arc, double approx_span) {
        room(n_ + 1)[n_] = {Vec2(q.x, q.y), q.e, approx_span, is_arc};
        ++n_;
    }
    std::size_t size() const { return n_; }
    BoundaryPoint* begin() { return p.data(); }
    BoundaryPoint* end() { return p.data() + n_; }
    /// emax, vmax, esum and has_arc from the points, on locals (kept up to date in push, they went
    /// through memory at every point).
    void summarize() {
        Summary sum;
        for (std::size_t k = 0; k < n_; ++k) sum.add(p[k]);
        sum.to(*this);
    }
    /// The running values of summarize(), for a caller that adds points in a loop of its own.
    struct Summary {
        double e = 0.0, v = 0.0, es = 0.0;
        bool arc = false;
        void add(const BoundaryPoint& q) {
            v = std::max(v, l1(q.v.x(), q.v.y()));
            if (!(q.e <= e)) e = q.e;  // NaN stays
            es += q.e;
            arc = arc || q.arc;
        }
        void to(Boundary& b) const {
            b.emax = e;
            b.vmax = v;
            b.esum = es;
            b.has_arc = arc;
        }
    };

private:
    std::size_t n_ = 0;
};

/// A lower bound on the diameter of the cell whose boundary is b: the agent lies in its cell, so
/// the cell reaches at least as far as any vertex (|v| >= |v|_1 / sqrt 2, less its error), and at
/// least r when it has an arc.
inline double diameter_below(const Boundary& b, double r) {
    const double reach = 0.7071 * b.vmax * (1.0 - 8.0 * kUnitRoundoff) - b.emax;
    return b.has_arc ? std::max(reach, r * (1.0 - 8.0 * kUnitRoundoff)) : std::max(reach, 0.0);
}

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

/// The measures in double with their error bounds; false when a bound exceeds
/// kConstructionAccuracy / 2 of `dlo` (a lower bound on the diameter; its square for the area).
/// Per term, from the vertex errors (e_k, at most e = emax, summing to esum) and the roundings (u per
/// operation; magnitudes by 1-norms, at most V = vmax):
///  - edge (u, w): cross(u, w) is off by dc = |u| e_w + |w| e_u + e_u e_w + 3u (|u_x w_y| + |u_y w_x|),
///    and over the edges sum dc <= (2 V + e) esum + 3u sum pc; six times its first moment,
///    cross (u + w), by dc 2V + 4 e |cross| + 6u V (|cross| + dc) (|cross| <= pc); its length by
///    e_u + e_w + 4u of itself.
///  - arc: the angle is off by (e_u + e_w) / (r (1 - 2^-20)) (an endpoint moved by e turns by at most
///    e / (r - e)) plus 8u + 4u span (cross, dot, atan2 and a 2 pi shift, rounded); twice the area r^2
///    and the length r times that; six times the first moment 2 r^2 (w_y - u_y, u_x - w_x) off by
///    4 r^2 (e_u + e_w) and 8u r^2 (|u| + |w|).
///  - each sum of n terms: (n + 2) u of the sum of the terms' magnitudes.
/// The centroid M / A is then off by (E_M + |g| E_A) / (A - E_A) plus 4u |g|. Only the sums of the
/// edges' |products| are gathered per edge (the rest from e and V at the end): the bounds cost a few
/// flops per piece, and pass with a wide margin unless the cell is thin or its vertices are poor.
inline bool measure_bounded(Boundary& b, double r, double dlo, LocalMeasures& out) {
    constexpr double kU = kUnitRoundoff;
    const std::size_t n = b.size();
    const double tol = 0.5 * kConstructionAccuracy * dlo;
    const double r2 = r * r, e = b.emax, V = b.vmax, es = b.esum;
    // Twice the area and six times the first moment (no division per piece), the arcs' bounds (E),
    // the sums of the terms' magnitudes (S; SP for the edges' |products|, which also bounds their
    // |cross|).
    double A2 = 0.0, mx = 0.0, my = 0.0, P = 0.0;
    double EA = 0.0, SA = 0.0, EM = 0.0, SM = 0.0, EP = 0.0, SP = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t k1 = k + 1 == n ? 0 : k + 1;
        BoundaryPoint& q = b.p[k];
        const Vec2 &u = q.v, &w = b.p[k1].v;
        if (q.arc) {
            const double eu = q.e, ew = b.p[k1].e;
            // The span from the endpoints, on the branch of the approximate one.
            if (n > 1) q.span = arc_angle(u.x() * w.y() - u.y() * w.x(), u.dot(w), q.span);
            const double phi = q.span;
            const double dphi = (eu + ew) / (r * (1.0 - 0x1p-20)) + kU * (8.0 + 4.0 * phi);
            if (!(r * dphi <= tol)) return false;
            const double t = r2 * phi;
            A2 += t;
            SA += t;
            EA += r2 * dphi;
            const double fx = 2.0 * r2 * (w.y() - u.y()), fy = 2.0 * r2 * (u.x() - w.x());
            mx += fx;
            my += fy;
            SM += l1(fx, fy);
            EM += 4.0 * r2 * (eu + ew) + 8.0 * kU * r2 * (l1(u.x(), u.y()) + l1(w.x(), w.y()));
            P += r * phi;
            EP += r * dphi + kU * r * phi;
        } else {
            const double lp = u.x() * w.y(), rp = u.y() * w.x();
            const double cr = lp - rp;
            A2 += cr;
            SP += std::fabs(lp) + std::fabs(rp);
            mx += cr * (u.x() + w.x());
            my += cr * (u.y() + w.y());
            const double dx = w.x() - u.x(), dy = w.y() - u.y();
            P += std::sqrt(dx * dx + dy * dy);
        }
    }
    const double sum_err = static_cast<double>(n + 2) * kU;
    const double dc = (2.0 * V + e) * es + 3.0 * kU * SP;  // summed over the edges
    EA += dc + sum_err * (SA + SP);                        // of 2 A
    EM += 2.0 * V * dc + 4.0 * e * SP + 6.0 * kU * V * (SP + dc) + sum_err * (SM + 2.0 * V * SP);  // of 6 M
    EP += 2.0 * es + (4.0 * kU + sum_err) * P;
    if (!(EA <= 2.0 * tol * dlo && EP <= tol && A2 > 2.0 * EA)) return false;
    // g = M / A = 6M / (3 (2A)): off by (E_6M / 3 + |g| E_2A) / (2A - E_2A), and 4u for 3 (2A), its
    // reciprocal and the product; tested without a division (0.34 > 1/3 covers its rounding).
    const double inv = 1.0 / (3.0 * A2);
    const double gx = mx * inv, gy = my * inv, ng = l1(gx, gy);
    if (!(0.34 * EM + ng * EA <= (tol - 4.0 * kU * ng) * (A2 - EA) * (1.0 - 0x1p-40))) return false;
    out = {0.5 * A2, gx, gy, P};
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
        if (b.p[k].arc) {
            if (n > 1)
                b.p[k].span = arc_angle((u.x * w.y - u.y * w.x).value(), (u.x * w.x + u.y * w.y).value(), b.p[k].span);
            const double phi = b.p[k].span;
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

/// Makes b's vertices, arc spans and measures meet kConstructionAccuracy (b summarized first).
/// exact(k) gives vertex k in double-double from exact expansions; refine(k) within 2^-51 of |v|
/// (cheaper, or the same). A vertex whose bound is above 2^-44 of the diameter is recomputed by
/// refine (rounded: within 8u of itself); then the measures are taken in double with their bounds,
/// and when those do not meet the target, everything again in double-double from exact().
template <class Refine, class Exact>
LocalMeasures accurate_measures(Boundary& b, double r, Refine&& refine, Exact&& exact) {
    const std::size_t n = b.size();
    double dlo = diameter_below(b, r);
    b.changed = false;
    LocalMeasures m;
    if (!(b.emax <= kRefineBelow * dlo)) {
        // A poor vertex: the diameter from the others (with their own errors), then the poor ones
        // again, and the measures from scratch.
        dlo = b.has_arc ? r * (1.0 - 8.0 * kUnitRoundoff) : 0.0;
        for (const BoundaryPoint& q : b) dlo = std::max(dlo, 0.7071 * l1(q.v.x(), q.v.y()) * (1.0 - 8.0 * kUnitRoundoff) - q.e);
        b.changed = true;
        for (std::size_t k = 0; k < n; ++k) {
            BoundaryPoint& q = b.p[k];
            if (q.e <= kRefineBelow * dlo) continue;
            q.v = refine(k).value();
            q.e = 8.0 * kUnitRoundoff * l1(q.v.x(), q.v.y());
        }
        b.summarize();
        dlo = diameter_below(b, r);
    }
    if (measure_bounded(b, r, dlo, m)) return m;
    b.changed = true;
    b.dd.resize(n);
    for (std::size_t k = 0; k < n; ++k) b.dd[k] = exact(k);
    m = measure_dd(b, r);
    for (std::size_t k = 0; k < n; ++k) b.p[k].v = b.dd[k].value();
    return m;
}

template <class Exact>
LocalMeasures accurate_measures(Boundary& b, double r, Exact&& exact) {
    return accurate_measures(b, r, exact, exact);
}

}  // namespace dvoronoi::detail
