// Exact orient2d and incircle on coordinate differences that are themselves exact doubles, with
// Shewchuk's expansion routines on fixed-size stack buffers: the allocation-free exact stage for
// inputs where the filter fails often (collinear and cocircular lattice points). Same exact sign as
// the general expansions of core/expansion.hpp, which handle any polynomial but allocate.
#pragma once

#include "dvoronoi/core/expansion.hpp"

#include <cmath>

namespace dvoronoi::detail {

/// Exact second stage of orient2d and incircle when the coordinate differences are exact doubles:
/// Shewchuk's expansion routines (Two_Two_Diff, scale_expansion_zeroelim,
/// fast_expansion_sum_zeroelim) on fixed-size stack buffers. The filter in front of it fails mostly
/// on exact ties (collinear and cocircular lattice points), where the general expansions of
/// core/expansion.hpp would allocate; the result is the same exact sign.
namespace xp {

/// (a1 + a0) - (b1 + b0) as a 4-component expansion x[0..3] (increasing magnitude, zeros kept).
inline void two_two_diff(double a1, double a0, double b1, double b0, double* x) {
    double i, j, z;
    two_sum(a0, -b0, i, x[0]);
    two_sum(a1, i, j, z);
    double k;
    two_sum(z, -b1, k, x[1]);
    two_sum(j, k, x[3], x[2]);
}

/// h = e * b; returns the length of h (>= 1; at most 2 * elen).
inline int scale(int elen, const double* e, double b, double* h) {
    double q, hh;
    two_product(e[0], b, q, hh);
    int n = 0;
    if (hh != 0.0) h[n++] = hh;
    for (int i = 1; i < elen; ++i) {
        double p1, p0, sum;
        two_product(e[i], b, p1, p0);
        two_sum(q, p0, sum, hh);
        if (hh != 0.0) h[n++] = hh;
        fast_two_sum(p1, sum, q, hh);
        if (hh != 0.0) h[n++] = hh;
    }
    if (q != 0.0 || n == 0) h[n++] = q;
    return n;
}

/// h = e + f (both nonempty, nonoverlapping, increasing magnitude); returns the length of h (>= 1).
inline int sum(int elen, const double* e, int flen, const double* f, double* h) {
    int ei = 0, fi = 0, n = 0;
    const auto take = [&]() {  // the next component of smaller magnitude
        if (fi >= flen || (ei < elen && std::fabs(e[ei]) < std::fabs(f[fi]))) return e[ei++];
        return f[fi++];
    };
    double q = take();
    while (ei < elen || fi < flen) {
        double qn, hh;
        two_sum(q, take(), qn, hh);
        q = qn;
        if (hh != 0.0) h[n++] = hh;
    }
    if (q != 0.0 || n == 0) h[n++] = q;
    return n;
}

inline int sign_of(int n, const double* h) {
    for (int i = n - 1; i >= 0; --i)
        if (h[i] != 0.0) return h[i] > 0.0 ? 1 : -1;
    return 0;
}

/// True when every value is 0 or has a magnitude in [2^-Bound, 2^Bound]. Each such value is a
/// multiple of 2^-(Bound + 52), so a product of `degree` of them, and every component of its
/// expansion, is a multiple of 2^-degree (Bound + 52): with degree (Bound + 52) <= 1074 nothing is
/// lost to underflow (subnormals hold it exactly), and nothing overflows while 2^(degree Bound) and
/// the sums stay below the largest double. orient_exact: degree 2, bound 480; incircle_exact: degree
/// 4, bound 200. Otherwise the general, checked exact stage decides (pred::orient, pred::incircle).
template <int Bound>
bool exact_range(const double* v, int n) {
    static_assert(Bound == 480 || Bound == 200, "the bounds used below");
    constexpr double lo = Bound == 480 ? 0x1p-480 : 0x1p-200, hi = Bound == 480 ? 0x1p480 : 0x1p200;
    bool ok = true;
    for (int i = 0; i < n; ++i) {
        const double a = std::fabs(v[i]);
        ok &= a == 0.0 || (a >= lo && a <= hi);
    }
    return ok;
}

/// sign(ax * by - ay * bx), exactly.
inline int orient_exact(double ax, double ay, double bx, double by) {
    double l1, l0, r1, r0, x[4];
    two_product(ax, by, l1, l0);
    two_product(ay, bx, r1, r0);
    two_two_diff(l1, l0, r1, r0, x);
    return sign_of(4, x);
}

/// sign(|a|^2 cross(b, c) - |b|^2 cross(a, c) + |c|^2 cross(a, b)) for a = (ax, ay), ..., exactly.
inline int incircle_exact(double ax, double ay, double bx, double by, double cx, double cy) {
    const auto minor = [](double px, double py, double qx, double qy, double* x) {  // cross(p, q)
        double l1, l0, r1, r0;
        two_product(px, qy, l1, l0);
        two_product(py, qx, r1, r0);
        two_two_diff(l1, l0, r1, r0, x);
    };
    // |p|^2 * m as an expansion of at most 32 components.
    const auto lifted = [](const double* m, double px, double py, double* out) {
        double t8[8], t16a[16], t16b[16];
        int n = scale(4, m, px, t8);
        const int na = scale(n, t8, px, t16a);
        n = scale(4, m, py, t8);
        const int nb = scale(n, t8, py, t16b);
        return sum(na, t16a, nb, t16b, out);
    };
    double bc[4], ca[4], ab[4];
    minor(bx, by, cx, cy, bc);
    minor(cx, cy, ax, ay, ca);
    minor(ax, ay, bx, by, ab);
    double A[32], B[32], C[32], AB[64], D[96];
    const int na = lifted(bc, ax, ay, A), nb = lifted(ca, bx, by, B), nc = lifted(ab, cx, cy, C);
    const int nab = sum(na, A, nb, B, AB);
    return sign_of(sum(nab, AB, nc, C, D), D);
}

}  // namespace xp

}  // namespace dvoronoi::detail
