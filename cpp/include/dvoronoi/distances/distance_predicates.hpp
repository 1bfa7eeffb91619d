// The distance-only geometry of Elwin, Freeman & Lynch (RA-L 2017, Section III-A): circumradius from
// side lengths (eq. 3), the signed circumradius with the obtuse test, and the opposite-sides test
// S_ijkl of Theorem 3 — as values (for users) and as exact sign predicates (for the algorithm).
//
// Exactness. Every decision is the sign of a polynomial in the input values, evaluated with a
// floating-point filter and, when the filter cannot decide, exactly with expansions
// (core/expansion.hpp). So, GIVEN the double inputs, every sign is exact. The inputs are either
// distances d (the polynomial is then in d, and d^2 is formed exactly inside the expansion) or squared
// distances D = d^2 (`squared = true`, half the degree):
//   * with squared distances that are exact (integer or dyadic coordinates whose squared differences
//     fit in 53 bits, e.g. lattices up to 2^26 wide), every decision equals the one exact arithmetic
//     gives on the true positions, degenerate configurations included;
//   * with distances that are rounded square roots, d = fl(sqrt(D)), each input has a relative error
//     below 2^-53, so a decision whose exact value is not zero is still right whenever its polynomial
//     is farther from zero than that perturbation can move it (always in practice for random
//     positions); exact zeros (three collinear or four cocircular robots) are in general NOT kept:
//     rounding turns them into arbitrary, but deterministic and self-consistent, signs. Pass squared
//     distances where degeneracy matters.
// Do not compile with -ffast-math.
//
// Notation for a pivot edge (i, j) and other robots k, l: a = d_ij^2, b_t = d_it^2, c_t = d_jt^2.
//   16 Area_t^2 = H_t = 4 a b_t - (a + b_t - c_t)^2        (Heron; > 0 iff i, j, t not collinear)
//   r_t^2      = a b_t c_t / H_t                           (eq. 3)
//   signed circumradius: r̂_t = -r_t when the angle at t is obtuse (b_t + c_t < a), else r_t; the
//   circumcenter of (i, j, t) then lies at the signed height h_t = sqrt(a) s_t / (2 sqrt(H_t)) from
//   the line ij, positive on t's side, with s_t = b_t + c_t - a. r̂_t is increasing in h_t
//   (Theorem 2), so MIN-SIGNED-RADIUS minimises s_t / sqrt(H_t); comparisons are exact.
//   S_ijkl = W -/+ U (eq. 7) simplifies to  a (b_k + c_k + b_l + c_l - a - 2 d_kl^2) - (b_l - c_l)(b_k - c_k)
//   which equals 4 cross(p_j - p_i, p_k - p_i) cross(p_j - p_i, p_l - p_i) (Lagrange's identity):
//   S < 0 iff k and l lie strictly on opposite sides of the line through i and j.
#pragma once

#include "dvoronoi/core/expansion.hpp"

#include <cmath>
#include <limits>

namespace dvoronoi::dist {

using ::dvoronoi::detail::filtered_sign;

namespace detail {
/// The squared length of a side from an input value: v itself, or v * v formed exactly.
template <class T>
T sq(double v, bool squared) {
    return squared ? T::from(v) : T::from(v) * T::from(v);
}

/// H = 16 Area^2 = 4 a b - (a + b - c)^2 of a triangle with squared sides a, b, c (Heron).
template <class T>
T heron(const T& a, const T& b, const T& c) {
    const T e = a + b - c;
    return T::constant(4.0) * a * b - e * e;
}

/// The squared sides of two triangles (i, j, k) and (i, j, l) on a common edge: a = d_ij^2,
/// b_t = d_it^2, c_t = d_jt^2, and their Heron values H_k, H_l.
template <class T>
struct EdgePair {
    T a, bk, ck, bl, cl, hk, hl;
    EdgePair(double dij, double dik, double djk, double dil, double djl, bool squared)
        : a(sq<T>(dij, squared)), bk(sq<T>(dik, squared)), ck(sq<T>(djk, squared)), bl(sq<T>(dil, squared)),
          cl(sq<T>(djl, squared)), hk(heron(a, bk, ck)), hl(heron(a, bl, cl)) {}
};
}  // namespace detail

// ------------------------------------------------------------------------------------------ values

/// Circumradius of a triangle with side lengths d1, d2, d3 (eq. 3); +inf for a degenerate triangle
/// (collinear vertices, or lengths that violate the triangle inequality, as noisy ones may).
inline double circumradius(double d1, double d2, double d3) {
    const double a = d1 * d1, b = d2 * d2, c = d3 * d3;
    const double den = 2.0 * a * (b + c) - (b - c) * (b - c) - a * a;
    if (!(den > 0.0)) return std::numeric_limits<double>::infinity();
    return std::sqrt(a * b * c / den);
}

/// obtuse(d1, d2, d3) of the paper: the angle opposite the side d3 is obtuse (d1^2 + d2^2 < d3^2,
/// decided exactly; the paper's d3 > d1, d3 > d2 follow from it for positive lengths).
inline bool obtuse(double d1, double d2, double d3) {
    return filtered_sign([&](auto tag) {
               using T = typename decltype(tag)::type;
               return detail::sq<T>(d1, false) + detail::sq<T>(d2, false) - detail::sq<T>(d3, false);
           }) < 0;
}

/// Signed circumradius r̂(d1, d2, d3): -r when the angle opposite d3 is obtuse, r otherwise.
inline double signed_circumradius(double d1, double d2, double d3) {
    const double r = circumradius(d1, d2, d3);
    return obtuse(d1, d2, d3) ? -r : r;
}

/// S_ijkl of Theorem 3 in double arithmetic (for display; use opposite_sides() for the decision).
inline double opposite_sides_value(double dij, double dik, double djk, double dil, double djl, double dkl) {
    const double a = dij * dij, bk = dik * dik, ck = djk * djk, bl = dil * dil, cl = djl * djl;
    return a * (bk + ck + bl + cl - a - 2.0 * dkl * dkl) - (bl - cl) * (bk - ck);
}

// ------------------------------------------------------------------------------ exact predicates
// Arguments are input values: distances, or squared distances when `squared` is true.

/// sign(H) = sign(16 Area^2) of the triangle (i, j, t) from dij, dit, djt: +1 for a proper triangle,
/// 0 for collinear robots, -1 for lengths that violate the triangle inequality (noise).
inline int triangle_sign(double dij, double dit, double djt, bool squared) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        return detail::heron(detail::sq<T>(dij, squared), detail::sq<T>(dit, squared), detail::sq<T>(djt, squared));
    });
}

/// sign(d_it^2 + d_jt^2 - d_ij^2): -1 when the angle at t of (i, j, t) is obtuse, 0 when right.
inline int angle_sign(double dij, double dit, double djt, bool squared) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        return detail::sq<T>(dit, squared) + detail::sq<T>(djt, squared) - detail::sq<T>(dij, squared);
    });
}

/// sign(S_ijkl) (Theorem 3): -1 when k and l are strictly on opposite sides of the line through i
/// and j, 0 when one of them is on it, +1 on the same side.
inline int opposite_sides(double dij, double dik, double djk, double dil, double djl, double dkl, bool squared) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using detail::sq;
        const T a = sq<T>(dij, squared), bk = sq<T>(dik, squared), ck = sq<T>(djk, squared);
        const T bl = sq<T>(dil, squared), cl = sq<T>(djl, squared), e = sq<T>(dkl, squared);
        return a * (bk + ck + bl + cl - a - T::constant(2.0) * e) - (bl - cl) * (bk - ck);
    });
}

/// sign(r(i, j, k) - r(i, j, l)) for proper triangles (triangle_sign > 0 for both): compares
/// b_k c_k H_l with b_l c_l H_k (the common factor a dropped). MIN-RADIUS.
inline int compare_radius(double dij, double dik, double djk, double dil, double djl, bool squared) {
    return filtered_sign([&](auto tag) {
        const detail::EdgePair<typename decltype(tag)::type> p(dij, dik, djk, dil, djl, squared);
        return p.bk * p.ck * p.hl - p.bl * p.cl * p.hk;
    });
}

/// sign(r̂(i, j, k) - r̂(i, j, l)) of the signed circumradii of two proper triangles on the same edge
/// (i, j) (triangle_sign > 0 for both), each signed towards its own apex. MIN-SIGNED-RADIUS.
/// Compares s_k / sqrt(H_k) with s_l / sqrt(H_l), s_t = b_t + c_t - a.
inline int compare_signed_radius(double dij, double dik, double djk, double dil, double djl, bool squared) {
    const int sk = angle_sign(dij, dik, djk, squared), sl = angle_sign(dij, dil, djl, squared);
    if (sk != sl) return sk < sl ? -1 : 1;
    if (sk == 0) return 0;  // both right angles: both circumcenters on the line, radius d_ij / 2
    const int mag = filtered_sign([&](auto tag) {  // sign(s_k^2 H_l - s_l^2 H_k)
        const detail::EdgePair<typename decltype(tag)::type> p(dij, dik, djk, dil, djl, squared);
        const auto s_k = p.bk + p.ck - p.a, s_l = p.bl + p.cl - p.a;
        return s_k * s_k * p.hl - s_l * s_l * p.hk;
    });
    return sk > 0 ? mag : -mag;
}

}  // namespace dvoronoi::dist
