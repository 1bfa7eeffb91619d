// The step both published algorithms share: the bisector set of an agent, sorted counter-clockwise by
// the direction of the neighbour starting from the nearest neighbour (Boundary Scan's Step 1, RCVC's
// constructChords), and the final assembly of a cell from its cyclic list of boundary bisectors.
#pragma once

#include "dvoronoi/core/accurate.hpp"
#include "dvoronoi/core/cell.hpp"
#include "dvoronoi/core/predicates.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <cmath>
#include <string>
#include <vector>

namespace dvoronoi::detail {

/// One bisector: the neighbour p, a = p - c (rounded, for constructions only), its caller index.
struct Line {
    Vec2 p;
    Vec2 a;
    double n2;  // |a|^2, rounded (fast-path filters only)
    Index id;
    double key;  // pseudo-angle from the nearest neighbour's direction, in [0, 4); ordering hint only
    int half;    // exact: 0 for directions in [0, pi) from the nearest neighbour, 1 for [pi, 2 pi)
};

/// Scratch buffers reused across the agents a thread processes (no allocation per agent).
/// A bisector on Boundary Scan's stack, with what its predecessor (the entry below, fixed while this
/// one is on the stack) decides about it, so each pair is classified once.
struct ScanEntry {
    int line;
    int o_prev;    // orient(line, predecessor)
    bool ok_prev;  // chord_bound_ok(line, predecessor)
};

struct CellWorkspace {
    std::vector<Line> lines;
    std::vector<ScanEntry> scan;   // Boundary Scan's stack
    std::vector<int> stack;
    std::vector<int> bound;        // RCVC: kept chords
    std::vector<char> removed;     // RCVC: checkChords flags
    std::vector<char> start_is_vertex;
    std::vector<std::size_t> counts;
    std::vector<Line> unsorted;
};

/// The agents of `others` strictly within 2R of `center` (exact), with their row as index.
inline std::vector<Candidate> candidates_within_2r(const Vec2& center, PointsRef others, double radius) {
    std::vector<Candidate> cand;
    for (Eigen::Index j = 0; j < others.rows(); ++j) {
        const Vec2 p = others.row(j).transpose();
        if (pred::within_2r(center, p, radius) > 0) cand.push_back({p, static_cast<Index>(j)});
    }
    return cand;
}

/// The sign of a polynomial evaluated in floating point from the rounded differences a = p - c,
/// certified by the bound c * u * perm (perm: the same polynomial with every term made positive;
/// c at least twice the number of roundings along any path, input roundings included); 2 when not
/// certain, or when over- or underflow could void the bound. The exact predicates decide then.
inline int fast_sign(double v, double perm, double c) {
    if (!(perm < 1e295) || perm < 1e-280) return 2;
    const double b = c * 1.1102230246251565e-16 * perm;
    if (v > b) return 1;
    if (v < -b) return -1;
    return 2;
}

inline double diamond_angle(double x, double y) {
    if (x == 0.0 && y == 0.0) return 0.0;  // underflow; the exact pass orders it
    if (y >= 0.0) return x >= 0.0 ? y / (x + y) : 1.0 - x / (-x + y);
    return x < 0.0 ? 2.0 - y / (-x - y) : 3.0 + x / (x - y);
}

/// Builds ws.lines from the candidates (all strictly within 2R of c): sorted counter-clockwise by
/// the direction of p - c starting at the nearest neighbour; of several neighbours in one direction
/// only the nearest is kept (the farther bisectors are parallel and outside its half-plane).
/// Throws CoincidentError when a candidate lies at c or two candidates coincide.
inline void sorted_bisectors(const Vec2& c, const std::vector<Candidate>& cand, CellWorkspace& ws) {
    auto& L = ws.lines;
    L.clear();
    if (cand.empty()) return;
    // Nearest neighbour (Lemma 1 of Boundary Scan: its bisector is always a boundary edge).
    std::size_t best = 0;
    double best_d2 = (cand[0].p - c).squaredNorm();
    for (std::size_t j = 0; j < cand.size(); ++j) {
        if (cand[j].p == c)  // only the one-agent call gets here (limited_cells checks all pairs)
            throw CoincidentError("others[" + std::to_string(cand[j].id) +
                                      "] coincides with center; its Voronoi cell is undefined",
                                  cand[j].id, cand[j].id);
        if (j == 0) continue;
        const double d2 = (cand[j].p - c).squaredNorm();
        if (d2 > best_d2 * (1.0 + 1e-9)) continue;
        int cmp = d2 < best_d2 * (1.0 - 1e-9) ? -1 : pred::compare_distance(c, cand[j].p, cand[best].p);
        if (cmp < 0 || (cmp == 0 && cand[j].id < cand[best].id)) {
            best = j;
            best_d2 = d2;
        }
    }
    const Vec2 p1 = cand[best].p;
    const Vec2 a1 = p1 - c;
    // Lines with their exact half and pseudo-angle, bucket-sorted by pseudo-angle (about one line per
    // bucket) straight into place, then an insertion pass that only moves within buckets: linear
    // expected time, few mispredicted branches.
    auto& tmp = ws.unsorted;
    tmp.clear();
    bool keys_reliable = true;  // false when products underflow: then every pair is compared exactly
    for (std::size_t j = 0; j < cand.size(); ++j) {
        const Candidate& q = cand[j];
        const Vec2 a = q.p - c;
        const double u = a1.dot(a), v = a1.x() * a.y() - a1.y() * a.x();
        if (!(std::fabs(u) + std::fabs(v) > 1e-280)) keys_reliable = false;
        int o = j == best ? 0 : fast_sign(v, std::fabs(a1.x() * a.y()) + std::fabs(a1.y() * a.x()), 16);
        if (o == 2) o = pred::orient(c, p1, q.p);
        int dsg = 1;
        if (o == 0) {
            dsg = fast_sign(u, std::fabs(a1.x() * a.x()) + std::fabs(a1.y() * a.y()), 16);
            if (dsg == 2) dsg = pred::dot_sign(c, p1, q.p);
        }
        const int half = (o > 0 || (o == 0 && dsg > 0)) ? 0 : 1;
        double key = j == best ? 0.0 : diamond_angle(u, v);
        if (!(key >= 0.0 && key < 4.0)) key = 0.0;
        // A key on the wrong side of the exact half is within rounding of a half boundary: pin it
        // there (0 or pi for half 0; pi or 2 pi for half 1).
        if (half == 0 && key >= 2.0) key = key > 3.0 ? 0.0 : 2.0;
        if (half == 1 && key < 2.0) key = key < 1.0 ? 4.0 : 2.0;
        tmp.push_back({q.p, a, a.squaredNorm(), q.id, key, half});
    }
    const std::size_t m = tmp.size();
    std::size_t nbuckets = 8;
    while (nbuckets < m) nbuckets *= 2;
    const double scale = static_cast<double>(nbuckets) / 4.0;
    const auto bucket = [&](const Line& l) { return std::min(nbuckets - 1, static_cast<std::size_t>(l.key * scale)); };
    auto& counts = ws.counts;
    counts.assign(nbuckets + 1, 0);
    for (const Line& l : tmp) ++counts[bucket(l) + 1];
    for (std::size_t b = 1; b <= nbuckets; ++b) counts[b] += counts[b - 1];
    L.resize(m);
    for (const Line& l : tmp) L[counts[bucket(l)]++] = l;
    for (std::size_t i = 1; i < m; ++i)
        if (L[i].key < L[i - 1].key) {
            const Line x = L[i];
            std::size_t j = i;
            for (; j > 0 && x.key < L[j - 1].key; --j) L[j] = L[j - 1];
            L[j] = x;
        }
    // Repair with the exact order (insertion sort: the floating-point order is already right except
    // among nearly parallel directions, so this pass is linear).
    const auto orient = [&](const Line& x, const Line& y) {
        const double l = x.a.x() * y.a.y(), r = x.a.y() * y.a.x();
        const int s = fast_sign(l - r, std::fabs(l) + std::fabs(r), 16);
        return s != 2 ? s : pred::orient(c, x.p, y.p);
    };
    const auto exact_less = [&](const Line& x, const Line& y) {
        if (x.half != y.half) return x.half < y.half;
        const int o = orient(x, y);
        if (o != 0) return o > 0;
        // Same direction: nearer first; equal distance means the agents coincide.
        const int d = pred::compare_distance(c, x.p, y.p);
        if (d == 0)
            throw CoincidentError("others[" + std::to_string(std::min(x.id, y.id)) + "] and others[" +
                                      std::to_string(std::max(x.id, y.id)) +
                                      "] coincide; their Voronoi cells are undefined",
                                  std::min(x.id, y.id), std::max(x.id, y.id));
        return d < 0;
    };
    // Keys are monotone in the angle and off by at most ~1e-15, so neighbours whose keys differ by
    // more than kKeyGap are certainly in order and in different directions: only closer pairs are
    // compared exactly.
    const double kKeyGap = keys_reliable ? 1e-12 : std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < L.size(); ++i)
        for (std::size_t j = i; j > 0 && L[j].key - L[j - 1].key <= kKeyGap && exact_less(L[j], L[j - 1]); --j)
            std::swap(L[j], L[j - 1]);
    // Drop farther agents in a direction already taken (exact: same half and collinear).
    std::size_t w = 1;
    for (std::size_t i = 1; i < L.size(); ++i) {
        const Line& prev = L[w - 1];
        if (L[i].key - prev.key <= kKeyGap && L[i].half == prev.half && orient(prev, L[i]) == 0) continue;
        L[w++] = L[i];
    }
    L.resize(w);
}

// ---- constructions (never used for decisions; accurate as core/accurate.hpp states) ----

/// v_jk relative to c (the circumcenter of c, p_j, p_k), rounded once per operation: for
/// certificates that need no accuracy (partition/empty_circle_certificate.hpp).
inline Vec2 vertex(const Vec2& aj, const Vec2& ak) {
    const double d = aj.x() * ak.y() - aj.y() * ak.x();
    const double hj = 0.5 * aj.squaredNorm(), hk = 0.5 * ak.squaredNorm();
    return Vec2((hj * ak.y() - hk * aj.y()) / d, (aj.x() * hk - ak.x() * hj) / d);
}

/// v_jk relative to c, within 2^-44 |v_jk| of the exact vertex (the bound of line_vertex, else
/// exact expansions in double-double): for cells whose measures are not taken from it.
inline Vec2 accurate_vertex(const Vec2& c, const Vec2& pj, const Vec2& pk) {
    const Vec2 aj = pj - c, ak = pk - c;
    const BoundedPoint v = line_vertex(aj.x(), aj.y(), aj.squaredNorm(), ak.x(), ak.y(), ak.squaredNorm());
    if (v.e <= 0x1p-44 * 0.7071 * l1(v.x, v.y)) return Vec2(v.x, v.y);
    return exact_vertex(c, pj, pk, 1.0).value();
}

/// The binary exponent of v (ilogb, without a call for a normal v).
inline int binary_exponent(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    return biased == 0 || biased == 0x7ff ? std::ilogb(v) : biased - 1023;
}

/// 2^e, exactly (without a call in the normal range).
inline double power_of_two(int e) {
    if (e < -1022 || e > 1023) return std::ldexp(1.0, e);
    const std::uint64_t bits = static_cast<std::uint64_t>(e + 1023) << 52;
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

/// Half the angle the chord of L_j subtends at c.
inline double chord_half_angle(const Vec2& a, double radius) {
    return std::atan2(half_chord(a.x(), a.y(), radius), 0.5 * a.norm());
}

/// Counter-clockwise angle from direction a_j to a_k, in (0, 2 pi]; `same` lines give 2 pi. The
/// branch (below or above pi) comes from the exact orientation.
inline double ccw_gap(const Vec2& c, const Line& j, const Line& k, double unit = 1.0) {
    constexpr double kTwoPi = 6.283185307179586476925286766559;
    if (&j == &k) return kTwoPi;
    const int o = pred::orient(c, j.p, k.p);
    const Vec2 ja = j.a * unit, ka = k.a * unit;  // `unit`: an exact scaling (no product underflows)
    const double cr = std::fabs(ja.x() * ka.y() - ja.y() * ka.x());
    const double t = std::atan2(cr, ja.dot(ka));  // in [0, pi]
    if (o > 0) return t;
    if (o < 0) return kTwoPi - t;
    return kTwoPi / 2.0;  // opposite directions (same directions were merged)
}

/// What a cell's vertex is, for its exact recomputation: the meeting of two bisectors (lines i, j)
/// or, with sigma != 0, the end of line i's chord.
struct VertexSource {
    int i, j, sigma;
};

/// Per-thread scratch of emit_cell.
struct EmitScratch {
    Boundary boundary;
    std::vector<VertexSource> source;
};

/// Assembles the cell from its boundary bisectors in counter-clockwise order (`cycle`, indices into
/// ws.lines) and, for each t, whether the edge of cycle[t] meets the edge of cycle[t+1] at their
/// vertex (true) or the boundary follows an arc between them (false). Vertices, arc spans and
/// measures meet core/accurate.hpp's guarantee: each is computed in double with an error bound and
/// redone from exact expansions where the bound is too large.
inline void emit_cell(const Vec2& c, double radius, const std::vector<Line>& L,
                      const std::vector<int>& cycle, const std::vector<char>& meets,
                      LimitedCell& out) {
    constexpr double kTwoPi = 6.283185307179586476925286766559;
    out.pieces.clear();
    out.center = c;
    out.radius = radius;
    const std::size_t s = cycle.size();
    // Pieces are assembled relative to c in units of 2^e ~ radius (an exact scaling: the same
    // roundings, but no product of two lengths under- or overflows however small or large the
    // radius), measured there, then moved to the caller's frame.
    const int e = binary_exponent(radius);
    const double unit = power_of_two(-e), back = power_of_two(e), r = radius * unit;
    if (s == 0) {  // the full disk: its start (r, 0) and centroid are exact
        Piece arc;
        arc.start = Vec2(radius, 0.0) + c;
        arc.arc_span = kTwoPi;
        out.pieces.push_back(arc);
        out.measures_.area = 0.5 * kTwoPi * r * r * back * back;
        out.measures_.centroid = c;
        out.measures_.perimeter = kTwoPi * radius;
        return;
    }
    thread_local EmitScratch scratch;
    Boundary& b = scratch.boundary;
    auto& source = scratch.source;
    // At most two pieces per line; written by index with a count in a register (push_back would
    // store the vectors' ends to thread-local memory at every piece).
    BoundaryPoint* bp = b.room(2 * s);
    if (source.size() < 2 * s) source.resize(2 * s);
    VertexSource* src = source.data();
    std::size_t n = 0;
    Boundary::Summary sum;  // in registers through the loop
    // The pieces as they come (moved only where accurate_measures moves a vertex), and the arcs'
    // spans once measured.
    const auto put = [&](const BoundedPoint& q, bool is_arc, double span, VertexSource from, Index id) {
        const BoundaryPoint x{Vec2(q.x, q.y), q.e, span, is_arc};
        sum.add(x);
        bp[n] = x;
        src[n++] = from;
        Piece p;
        p.neighbor = id;
        p.start = c + back * Vec2(q.x, q.y);
        out.pieces.push_back(p);
    };
    const auto line = [&](std::size_t t) -> const Line& { return L[static_cast<std::size_t>(cycle[t])]; };
    const auto chord = [&](const Line& l, int sigma) { return chord_vertex(l.a.x() * unit, l.a.y() * unit, r, sigma); };
    const double u2 = unit * unit;
    for (std::size_t t = 0; t < s; ++t) {
        const Line& j = line(t);
        const std::size_t tp = t == 0 ? s - 1 : t - 1;  // no integer division
        const Line& i = line(tp);
        if (meets[tp])
            put(line_vertex(i.a.x() * unit, i.a.y() * unit, i.n2 * u2, j.a.x() * unit, j.a.y() * unit, j.n2 * u2),
                false, 0.0, {cycle[tp], cycle[t], 0}, j.id);
        else
            put(chord(j, -1), false, 0.0, {cycle[t], 0, -1}, j.id);
        if (!meets[t]) {
            // The span from the combinatorial gap: it picks the branch of the direct angle between
            // the endpoints (tiny arcs never become full turns).
            const Line& k = line(t + 1 == s ? 0 : t + 1);
            const double approx = ccw_gap(c, j, s == 1 ? j : k, unit) - chord_half_angle(j.a * unit, r) -
                                  chord_half_angle(k.a * unit, r);
            put(chord(j, +1), true, approx, {cycle[t], 0, +1}, kArc);
        }
    }
    b.set_size(n);
    sum.to(b);
    const auto exact = [&](std::size_t k) {
        const VertexSource& v = source[k];
        const Line& li = L[static_cast<std::size_t>(v.i)];
        if (v.sigma != 0) return exact_chord_end(c, li.p, r, unit, v.sigma);
        return exact_vertex(c, li.p, L[static_cast<std::size_t>(v.j)].p, unit);
    };
    const auto refine = [&](std::size_t k) {  // most refined vertices: no allocation
        const VertexSource& v = source[k];
        DDPoint x;
        if (v.sigma == 0 && dd_vertex(c, L[static_cast<std::size_t>(v.i)].p, L[static_cast<std::size_t>(v.j)].p, unit, x))
            return x;
        return exact(k);
    };
    const LocalMeasures m = accurate_measures(b, r, refine, exact);
    out.measures_.area = m.area * back * back;
    out.measures_.centroid = c + back * Vec2(m.cx, m.cy);
    out.measures_.perimeter = m.perimeter * back;
    // The combinatorics are exact and the vertices accurate; a cell that still cannot be measured in
    // doubles is refused rather than handed back with a NaN area.
    if (!std::isfinite(out.measures_.area) || !std::isfinite(out.measures_.centroid.x()) ||
        !std::isfinite(out.measures_.centroid.y()))
        throw RangeError(
            "out of the range of doubles: the cell's measures are not finite (its agents within 2R differ in "
            "scale by more than doubles resolve; coordinates are in range for nonzero differences between "
            "about 1e-45 and 1e45)");
    for (std::size_t k = 0; k < b.size(); ++k) {
        Piece& p = out.pieces[k];
        if (b.changed) p.start = c + back * b.p[k].v;
        if (p.is_arc()) p.arc_span = b.p[k].span;
    }
}

/// The predicates on bisectors (indices into ws.lines) around c: a floating-point fast path on the
/// cached differences, certified by fast_sign, and the exact predicates of core/predicates.hpp when it
/// cannot decide.
struct LineGeometry {
    const Vec2& c;
    const std::vector<Line>& L;
    double radius;

    const Line& at(int j) const { return L[static_cast<std::size_t>(j)]; }

    /// sign(D_jk).
    int orient(int j, int k) const {
        const Vec2 &a = at(j).a, &b = at(k).a;
        const double l = a.x() * b.y(), r = a.y() * b.x();
        const int s = fast_sign(l - r, std::fabs(l) + std::fabs(r), 16);
        return s != 2 ? s : pred::orient(c, at(j).p, at(k).p);
    }
    /// sign(t_jk), the position of v_jk along L_j; o = orient(j, k) != 0.
    int position(int j, int k, int o) const {
        const Line &lj = at(j), &lk = at(k);
        const double xx = lj.a.x() * lk.a.x(), yy = lj.a.y() * lk.a.y();
        const int s = fast_sign(lk.n2 - xx - yy, lk.n2 + std::fabs(xx) + std::fabs(yy), 32);
        return s != 2 ? s * o : pred::vertex_position(c, lj.p, lk.p);
    }
    /// sign(|v_jk|^2 - R^2); requires D_jk != 0.
    int in_disk(int j, int k) const {
        const Line &lj = at(j), &lk = at(k);
        const Vec2 jk = lj.p - lk.p;
        const double l = lj.a.x() * lk.a.y(), r = lj.a.y() * lk.a.x();
        const double d = l - r, pd = std::fabs(l) + std::fabs(r);
        const double prod = lj.n2 * lk.n2 * jk.squaredNorm();
        const double r4 = 4.0 * radius * radius;
        const int s = fast_sign(prod - r4 * d * d, prod + r4 * pd * pd, 64);
        return s != 2 ? s : pred::vertex_in_disk(c, lj.p, lk.p, radius);
    }
    /// Side of v_jk with respect to L_l (-1 strictly inside H_l); o = orient(j, k) != 0.
    int side(int j, int k, int l, int o) const {
        const Line &lj = at(j), &lk = at(k), &ll = at(l);
        const auto cr = [](const Vec2& a, const Vec2& b, double& perm) {
            const double x = a.x() * b.y(), y = a.y() * b.x();
            perm = std::fabs(x) + std::fabs(y);
            return x - y;
        };
        double p1, p2, p3;
        const double c1 = cr(lk.a, ll.a, p1), c2 = cr(lj.a, ll.a, p2), c3 = cr(lj.a, lk.a, p3);
        const double inc = lj.n2 * c1 - lk.n2 * c2 + ll.n2 * c3;
        const int s = fast_sign(inc, lj.n2 * p1 + lk.n2 * p2 + ll.n2 * p3, 64);
        return s != 2 ? -s * o : pred::vertex_side(c, lj.p, lk.p, ll.p);
    }

    /// Side of an endpoint of chord m (sigma = -1 first, +1 last) w.r.t. L_j (-1 strictly inside
    /// H_j): the sign of X sqrt(P) + Y sqrt(Q), see pred::endpoint_side.
    int endpoint_side(int m, int sigma, int j) const {
        const Line &lm = at(m), &lj = at(j);
        const double dx = lm.a.x() * lj.a.x(), dy = lm.a.y() * lj.a.y();
        const double cx = lm.a.x() * lj.a.y(), cy = lm.a.y() * lj.a.x();
        const double x = dx + dy - lj.n2, xp = std::fabs(dx) + std::fabs(dy) + lj.n2;
        const double y = sigma * (cx - cy), yp = std::fabs(cx) + std::fabs(cy);
        const int sx = fast_sign(x, xp, 32), sy = fast_sign(y, yp, 32);
        if (sx == 2 || sy == 2) return pred::endpoint_side(c, lm.p, sigma, lj.p, radius);
        if (sx == sy) return sx;
        const double q = 4.0 * radius * radius - lm.n2, qp = 4.0 * radius * radius + lm.n2;
        const int cmp = fast_sign(x * x * lm.n2 - y * y * q, xp * xp * lm.n2 + yp * yp * qp, 64);
        return cmp != 2 ? sx * cmp : pred::endpoint_side(c, lm.p, sigma, lj.p, radius);
    }

    /// Is v_jk inside the closed disk?
    bool vertex_in_closed_disk(int j, int k) const { return in_disk(j, k) <= 0; }
    /// Is v_jk strictly after the chord start s_j along L_j (t_jk > -w)? o = orient(j, k) != 0.
    bool after_chord_start(int j, int k, int o) const { return position(j, k, o) >= 0 || in_disk(j, k) < 0; }
    bool after_chord_start(int j, int k) const { return after_chord_start(j, k, orient(j, k)); }
    /// Is v_jk strictly before the chord end e_j along L_j (t_jk < w)? o = orient(j, k) != 0.
    bool before_chord_end(int j, int k, int o) const { return position(j, k, o) <= 0 || in_disk(j, k) < 0; }
    /// Is v_ji strictly before v_jk along L_j? Requires D_ji < 0 and D_jk > 0.
    bool vertex_before(int j, int i, int k) const { return side(j, i, k, -1) < 0; }
};

}  // namespace dvoronoi::detail
