// Exact predicates of the weighted (power) configuration around an agent c with radius r
// (docs/spec.md, heterogeneous teams).
//
// Notation, relative to c: a_j = p_j - c; s_j = |a_j|^2 + r^2 - R_j^2; the radical axis of c and j is
// L_j = {x : 2 a_j.x = s_j}, and c's power is not larger than j's on H_j = {2 a_j.x <= s_j}. The
// agent need not lie in H_j (s_j < 0: j's disk covers c). C4_j = 4 r^2 |a_j|^2 - s_j^2 > 0 exactly when
// L_j cuts the open disk B(c, r) (its chord has half-length sqrt(C4_j) / (2 |a_j|)).
// Lines may also be the four sides of the box |x|, |y| <= 2r around the disk (a = (+-r, 0) or
// (0, +-r), s = 4 r^2): they bound the polygon being clipped and never meet the disk.
// Two lines j, k meet at x_jk = M_jk / (2 D_jk), D_jk = cross(a_j, a_k), M_jk = (s_j a_k.y - s_k a_j.y,
// s_k a_j.x - s_j a_k.x). Positions along L_j are measured by cross(a_j, x) (direction perp(a_j),
// the counter-clockwise direction of a cell's boundary on L_j); the chord ends e_j^-+ sit at
// -+ sqrt(C4_j) / 2 on that scale.
//
// Degrees in the inputs (coordinate differences and radii), each the sign of a homogeneous
// polynomial evaluated by core/expansion.hpp's filtered_sign (ErrDouble filter, then exact
// expansions, rescaled where an exact product under- or overflowed):
//   chord_class: s (2) and C4 (4); side_of_vertex: D (2) and a_l.M - s_l D (4);
//   position_vs_chord_end: cross(a_t, M) (4), cross(a_t, M)^2 - D^2 C4_t (8); farther: |a_l|^2 - |a_j|^2 (2);
//   the scan's and the walk's (cells/power_chords.hpp): dot_sign (2), foot_side (4), axis_distance_cmp
//   (6), chord_end_side (4, then 8), cap_middle_side (3, then 6).
#pragma once

#include "dvoronoi/core/expansion.hpp"
#include "dvoronoi/core/types.hpp"

#include <cmath>

namespace dvoronoi::pred::power {

using detail::filtered_sign;

/// A line of the weighted configuration around c: an agent's radical axis (box < 0) or a box side
/// (box = 0..3: outward normal +x, +y, -x, -y).
struct WLine {
    Vec2 p = Vec2::Zero();  ///< the agent (agent lines)
    double R = 0.0;         ///< its radius (agent lines)
    int box = -1;
};

/// The geometry every predicate reads: the agent and its radius.
struct Frame {
    Vec2 c;
    double r;
};

template <class T>
struct LineT {
    T ax, ay, s;
};

template <class T>
LineT<T> line(const Frame& f, const WLine& l) {
    const T r = T::from(f.r);
    if (l.box >= 0) {
        const T zero = T::constant(0.0);
        const T s = T::constant(4.0) * r * r;
        switch (l.box) {
            case 0: return {r, zero, s};
            case 1: return {zero, r, s};
            case 2: return {-r, zero, s};
            default: return {zero, -r, s};
        }
    }
    const T ax = T::diff(l.p.x(), f.c.x()), ay = T::diff(l.p.y(), f.c.y());
    const T Rj = T::from(l.R);
    return {ax, ay, ax * ax + ay * ay + r * r - Rj * Rj};
}

/// sign(s_j): +1 when c lies strictly on its own side of L_j.
inline int s_sign(const Frame& f, const WLine& j) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        return line<T>(f, j).s;
    });
}

/// sign(C4_j) = sign(4 r^2 |a_j|^2 - s_j^2): +1 when L_j cuts the open disk B(c, r).
inline int chord_sign(const Frame& f, const WLine& j) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> L = line<T>(f, j);
        const T r = T::from(f.r);
        return T::constant(4.0) * r * r * (L.ax * L.ax + L.ay * L.ay) - L.s * L.s;
    });
}

/// sign(D_jk) = sign(cross(a_j, a_k)).
inline int cross_sign(const Frame& f, const WLine& j, const WLine& k) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, k);
        return A.ax * B.ay - A.ay * B.ax;
    });
}

/// sign(2 a_l.x_jk - s_l): -1 when the vertex x_jk lies strictly inside H_l, 0 on L_l, +1 outside.
/// Requires D_jk != 0.
inline int side_of_vertex(const Frame& f, const WLine& l, const WLine& j, const WLine& k) {
    const int d = cross_sign(f, j, k);
    const int n = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, k), Lh = line<T>(f, l);
        const T mx = A.s * B.ay - B.s * A.ay, my = B.s * A.ax - A.s * B.ax;
        const T D = A.ax * B.ay - A.ay * B.ax;
        return Lh.ax * mx + Lh.ay * my - Lh.s * D;
    });
    return n * d;
}

/// Where the vertex x_jk lies on L_t (t is j or k) relative to the chord end e_t^sigma (sigma = -1:
/// the end where the boundary enters the disk, +1: where it leaves): sign(pos(x_jk) - pos(e_t^sigma)).
/// Requires D_jk != 0 and C4_t > 0.
inline int position_vs_chord_end(const Frame& f, const WLine& t, const WLine& j, const WLine& k, int sigma) {
    const int d = cross_sign(f, j, k);
    const auto X = [&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, k), Lt = line<T>(f, t);
        const T mx = A.s * B.ay - B.s * A.ay, my = B.s * A.ax - A.s * B.ax;
        return Lt.ax * my - Lt.ay * mx;
    };
    const int q = filtered_sign(X) * d;  // sign of the position X / D (positions scaled by 2)
    if (sigma > 0 && q <= 0) return -1;
    if (sigma < 0 && q >= 0) return 1;
    // Same signs: compare squares, X^2 vs D^2 C4_t.
    const int sq = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const T x = X(tag);
        const LineT<T> A = line<T>(f, j), B = line<T>(f, k), Lt = line<T>(f, t);
        const T D = A.ax * B.ay - A.ay * B.ax;
        const T r = T::from(f.r);
        const T c4 = T::constant(4.0) * r * r * (Lt.ax * Lt.ax + Lt.ay * Lt.ay) - Lt.s * Lt.s;
        return x * x - D * D * c4;
    });
    return sigma > 0 ? sq : -sq;
}

/// sign(|a_l|^2 - |a_j|^2) for agent lines: of two agents with the same radical axis (coaxal disks),
/// the farther one holds the far side of it.
inline int farther(const Frame& f, const WLine& l, const WLine& j) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, l), B = line<T>(f, j);
        return A.ax * A.ax + A.ay * A.ay - (B.ax * B.ax + B.ay * B.ay);
    });
}

/// sign(a_j . a_k): with cross_sign, the exact direction order of the normals (Boundary Scan's sort).
inline int dot_sign(const Frame& f, const WLine& j, const WLine& k) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, k);
        return A.ax * B.ax + A.ay * B.ay;
    });
}

/// Side of the foot of L_j (the point of L_j nearest c, s_j a_j / (2 |a_j|^2)) w.r.t. L_l: sign of
/// s_j (a_l.a_j) - s_l |a_j|^2 (degree 4; -1 strictly inside H_l). For parallel lines it is the side
/// of all of L_j.
inline int foot_side(const Frame& f, const WLine& j, const WLine& l) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, l);
        return A.s * (B.ax * A.ax + B.ay * A.ay) - B.s * (A.ax * A.ax + A.ay * A.ay);
    });
}

/// sign(d_j - d_k) for the signed distances d = s / (2 |a|) of the radical axes from c (negative: c
/// outside the half-plane): sign(s_j |a_k| - s_k |a_j|), by signs and then squares (degree 6).
inline int axis_distance_cmp(const Frame& f, const WLine& j, const WLine& k) {
    const int sj = s_sign(f, j), sk = s_sign(f, k);
    if (sj != sk) return sj > sk ? 1 : -1;
    if (sj == 0) return 0;
    const int sq = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, k);
        return A.s * A.s * (B.ax * B.ax + B.ay * B.ay) - B.s * B.s * (A.ax * A.ax + A.ay * A.ay);
    });
    return sj > 0 ? sq : -sq;
}

/// Side of the chord end e_m^sigma w.r.t. L_l (-1 strictly inside H_l): 2 a_l.e - s_l has the sign
/// of X + sigma Y sqrt(C4_m), X = s_m (a_l.a_m) - s_l |a_m|^2 (degree 4), Y = cross(a_m, a_l) (2);
/// compared by squares where the signs differ (degree 8). Requires C4_m > 0.
inline int chord_end_side(const Frame& f, const WLine& m, int sigma, const WLine& l) {
    const int sx = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, m), B = line<T>(f, l);
        return A.s * (B.ax * A.ax + B.ay * A.ay) - B.s * (A.ax * A.ax + A.ay * A.ay);
    });
    const int sy = sigma * cross_sign(f, m, l);
    if (sy == 0 || sx == sy) return sx;
    if (sx == 0) return sy;
    const int sq = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, m), B = line<T>(f, l);
        const T r = T::from(f.r);
        const T x = A.s * (B.ax * A.ax + B.ay * A.ay) - B.s * (A.ax * A.ax + A.ay * A.ay);
        const T y = A.ax * B.ay - A.ay * B.ax;
        const T n2 = A.ax * A.ax + A.ay * A.ay;
        return x * x - y * y * (T::constant(4.0) * r * r * n2 - A.s * A.s);
    });
    return sq > 0 ? sx : sq < 0 ? sy : 0;  // the larger magnitude decides (0: the end lies on L_l)
}

/// Side of q_j = r a_j / |a_j| (the circle's point in the middle of the cap that H_j cuts off)
/// w.r.t. L_l: sign(2 r (a_l.a_j) - s_l |a_j|), by signs and then squares (degree 6).
inline int cap_middle_side(const Frame& f, const WLine& j, const WLine& l) {
    const int su = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, l);
        return B.ax * A.ax + B.ay * A.ay;
    });
    const int sv = s_sign(f, l);
    if (su != sv) return su > sv ? 1 : -1;
    if (su == 0) return 0;
    const int sq = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const LineT<T> A = line<T>(f, j), B = line<T>(f, l);
        const T r = T::from(f.r);
        const T u = B.ax * A.ax + B.ay * A.ay;
        return T::constant(4.0) * r * r * u * u - B.s * B.s * (A.ax * A.ax + A.ay * A.ay);
    });
    return su > 0 ? sq : -sq;
}

// ---- the fast path: the same signs in double from values rounded once per line ----
//
// Each predicate is evaluated in double from the rounded line data (a = fl(p - c), s computed from
// it) and certified by the a-priori bound c * u * perm (perm: the polynomial with every term made
// positive, c at least twice the rounding depth, input roundings included): core/expansion.hpp's
// error analysis, the filter of cells/bisectors.hpp (fast_sign). Undecided (2) -> the exact
// predicates above. Measured: the exact path runs for well under one test in a thousand in a
// uniform swarm.

/// A line's data rounded to double, for the fast path; `ps` bounds |s| term by term.
struct FastLine {
    double ax = 0.0, ay = 0.0, s = 0.0, ps = 0.0;
};

inline FastLine fast_line(const Frame& f, const WLine& l) {
    FastLine o;
    const double r2 = f.r * f.r;
    if (l.box >= 0) {
        o.ax = l.box == 0 ? f.r : l.box == 2 ? -f.r : 0.0;
        o.ay = l.box == 1 ? f.r : l.box == 3 ? -f.r : 0.0;
        o.s = 4.0 * r2;
        o.ps = o.s;
        return o;
    }
    o.ax = l.p.x() - f.c.x();
    o.ay = l.p.y() - f.c.y();
    const double n2 = o.ax * o.ax + o.ay * o.ay, R2 = l.R * l.R;
    o.s = n2 + r2 - R2;
    o.ps = n2 + r2 + R2;
    return o;
}

/// sign(v) if |v| > c u perm (certainly), else 2; 2 also where over- or underflow could void it.
inline int certain_sign(double v, double perm, double c) {
    if (!(perm < 1e290) || perm < 1e-270) return 2;
    const double b = c * 1.1102230246251565e-16 * perm;
    if (v > b) return 1;
    if (v < -b) return -1;
    return 2;
}

inline int fast_cross_sign(const FastLine& A, const FastLine& B) {
    const double d = A.ax * B.ay - A.ay * B.ax;
    return certain_sign(d, std::fabs(A.ax * B.ay) + std::fabs(A.ay * B.ax), 8.0);
}

/// side_of_vertex with the fast path first.
inline int side_of_vertex(const Frame& f, const WLine& l, const WLine& j, const WLine& k, const FastLine& L,
                          const FastLine& A, const FastLine& B) {
    const int d = fast_cross_sign(A, B);
    if (d != 2) {
        const double mx = A.s * B.ay - B.s * A.ay, my = B.s * A.ax - A.s * B.ax;
        const double pmx = A.ps * std::fabs(B.ay) + B.ps * std::fabs(A.ay), pmy = B.ps * std::fabs(A.ax) + A.ps * std::fabs(B.ax);
        const double D = A.ax * B.ay - A.ay * B.ax, pD = std::fabs(A.ax * B.ay) + std::fabs(A.ay * B.ax);
        const double v = L.ax * mx + L.ay * my - L.s * D;
        const double pv = std::fabs(L.ax) * pmx + std::fabs(L.ay) * pmy + L.ps * pD;
        const int n = certain_sign(v, pv, 32.0);
        if (n != 2) return n * d;
    }
    return side_of_vertex(f, l, j, k);
}

/// A vertex x_jk for the fast path: M_jk, D_jk in double with their term bounds, and sign(D_jk) if
/// certain (else 2). Computed once per polygon vertex, read by every side test against it.
struct FastVertex {
    double mx = 0.0, my = 0.0, D = 0.0, pmx = 0.0, pmy = 0.0, pD = 0.0;
    int d = 2;
};

inline FastVertex fast_vertex(const FastLine& A, const FastLine& B) {
    FastVertex v;
    v.d = fast_cross_sign(A, B);
    v.mx = A.s * B.ay - B.s * A.ay;
    v.my = B.s * A.ax - A.s * B.ax;
    v.pmx = A.ps * std::fabs(B.ay) + B.ps * std::fabs(A.ay);
    v.pmy = B.ps * std::fabs(A.ax) + A.ps * std::fabs(B.ax);
    v.D = A.ax * B.ay - A.ay * B.ax;
    v.pD = std::fabs(A.ax * B.ay) + std::fabs(A.ay * B.ax);
    return v;
}

/// side_of_vertex with the fast path first, from the vertex's cached data.
inline int side_of_vertex(const Frame& f, const WLine& l, const WLine& j, const WLine& k, const FastLine& L,
                          const FastVertex& V) {
    if (V.d != 2) {
        const double v = L.ax * V.mx + L.ay * V.my - L.s * V.D;
        const double pv = std::fabs(L.ax) * V.pmx + std::fabs(L.ay) * V.pmy + L.ps * V.pD;
        const int n = certain_sign(v, pv, 32.0);
        if (n != 2) return n * V.d;
    }
    return side_of_vertex(f, l, j, k);
}

/// chord_sign with the fast path first.
inline int chord_sign(const Frame& f, const WLine& j, const FastLine& A) {
    const double r2 = f.r * f.r, n2 = A.ax * A.ax + A.ay * A.ay;
    const int c = certain_sign(4.0 * r2 * n2 - A.s * A.s, 4.0 * r2 * n2 + A.ps * A.ps, 32.0);
    return c != 2 ? c : chord_sign(f, j);
}

/// s_sign with the fast path first.
inline int s_sign(const Frame& f, const WLine& j, const FastLine& A) {
    const int c = certain_sign(A.s, A.ps, 12.0);
    return c != 2 ? c : s_sign(f, j);
}

/// position_vs_chord_end with the fast path first.
inline int position_vs_chord_end(const Frame& f, const WLine& t, const WLine& j, const WLine& k, int sigma,
                                 const FastLine& T, const FastLine& A, const FastLine& B) {
    const int d = fast_cross_sign(A, B);
    if (d != 2) {
        const double mx = A.s * B.ay - B.s * A.ay, my = B.s * A.ax - A.s * B.ax;
        const double pmx = A.ps * std::fabs(B.ay) + B.ps * std::fabs(A.ay), pmy = B.ps * std::fabs(A.ax) + A.ps * std::fabs(B.ax);
        const double X = T.ax * my - T.ay * mx, pX = std::fabs(T.ax) * pmy + std::fabs(T.ay) * pmx;
        const int xs = certain_sign(X, pX, 32.0);
        if (xs != 2) {
            const int q = xs * d;
            if (sigma > 0 && q <= 0) return -1;
            if (sigma < 0 && q >= 0) return 1;
            const double D = A.ax * B.ay - A.ay * B.ax, pD = std::fabs(A.ax * B.ay) + std::fabs(A.ay * B.ax);
            const double r2 = f.r * f.r, n2 = T.ax * T.ax + T.ay * T.ay;
            const double c4 = 4.0 * r2 * n2 - T.s * T.s, pc4 = 4.0 * r2 * n2 + T.ps * T.ps;
            const int sq = certain_sign(X * X - D * D * c4, pX * pX + pD * pD * pc4, 64.0);
            if (sq != 2) return sigma > 0 ? sq : -sq;
        }
    }
    return position_vs_chord_end(f, t, j, k, sigma);
}

}  // namespace dvoronoi::pred::power
