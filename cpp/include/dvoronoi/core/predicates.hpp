// Exact geometric predicates for limited Voronoi cells around a center c.
//
// Every decision the cell algorithms make goes through one of these: each is the sign of a polynomial
// in the input doubles (coordinates and radius), evaluated with a floating-point filter and, when the
// filter cannot decide, exactly with expansions. Constructed points (Voronoi vertices, chord
// endpoints) are never compared: a test on a vertex is rewritten as a polynomial in the agents that
// define it. Notation: a_j = p_j - c, h_j = |a_j|^2 / 2, the bisector line L_j = {x : x.a_j = h_j}
// (relative to c), the half-plane H_j = {x.a_j <= h_j} contains c, D_jk = cross(a_j, a_k), and
// v_jk = L_j ∩ L_k is the circumcenter of (c, p_j, p_k). Positions along L_j are measured in the
// counter-clockwise direction perp(a_j) = (-a_j.y, a_j.x) from the foot a_j / 2.
// Inputs enter through T::diff and T::from, numeric constants through T::constant: every predicate is
// a homogeneous polynomial in its inputs, which the exact stage may rescale (core/expansion.hpp).
// Do not compile with -ffast-math: the filter and the expansions rely on IEEE rounding.
#pragma once

#include "dvoronoi/core/expansion.hpp"
#include "dvoronoi/core/types.hpp"

namespace dvoronoi::pred {

using detail::filtered_sign;

namespace detail_ {
template <class T>
struct Rel {
    T x, y;
};
template <class T>
Rel<T> rel(const Vec2& p, const Vec2& c) {
    return {T::diff(p.x(), c.x()), T::diff(p.y(), c.y())};
}
template <class T>
T cross(const Rel<T>& a, const Rel<T>& b) {
    return a.x * b.y - a.y * b.x;
}
template <class T>
T dot(const Rel<T>& a, const Rel<T>& b) {
    return a.x * b.x + a.y * b.y;
}
template <class T>
T norm2(const Rel<T>& a) {
    return a.x * a.x + a.y * a.y;
}
}  // namespace detail_

/// sign(4 R^2 - |p - c|^2): +1 when p is strictly closer than 2R, so its bisector cuts the open disk.
inline int within_2r(const Vec2& c, const Vec2& p, double radius) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        const auto a = detail_::rel<T>(p, c);
        const T r = T::from(radius);
        return T::constant(4.0) * r * r - detail_::norm2(a);
    });
}

/// sign(cross(p_j - c, p_k - c)): +1 when p_k is counter-clockwise from p_j as seen from c.
inline int orient(const Vec2& c, const Vec2& pj, const Vec2& pk) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        return detail_::cross(detail_::rel<T>(pj, c), detail_::rel<T>(pk, c));
    });
}

/// sign((p_j - c) . (p_k - c)).
inline int dot_sign(const Vec2& c, const Vec2& pj, const Vec2& pk) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        return detail_::dot(detail_::rel<T>(pj, c), detail_::rel<T>(pk, c));
    });
}

/// sign(|p_j - c|^2 - |p_k - c|^2): -1 when p_j is strictly closer to c.
inline int compare_distance(const Vec2& c, const Vec2& pj, const Vec2& pk) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        return detail_::norm2(detail_::rel<T>(pj, c)) - detail_::norm2(detail_::rel<T>(pk, c));
    });
}

/// Side of the vertex v_jk (requires D_jk != 0) with respect to the bisector L_l:
/// sign(v_jk . a_l - h_l): -1 strictly inside H_l (closer to c than to p_l), 0 on L_l, +1 outside.
/// v . a_l - h_l = -InC / (2 D_jk) with InC = det[[a_j, |a_j|^2], [a_k, |a_k|^2], [a_l, |a_l|^2]].
inline int vertex_side(const Vec2& c, const Vec2& pj, const Vec2& pk, const Vec2& pl) {
    const int d = orient(c, pj, pk);
    const int inc = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using namespace detail_;
        const auto aj = rel<T>(pj, c), ak = rel<T>(pk, c), al = rel<T>(pl, c);
        return norm2(aj) * cross(ak, al) - norm2(ak) * cross(aj, al) + norm2(al) * cross(aj, ak);
    });
    return -inc * d;
}

/// sign(|v_jk - c|^2 - R^2) (requires D_jk != 0): -1 when the vertex lies strictly inside the disk.
/// |v|^2 = |a_j|^2 |a_k|^2 |p_j - p_k|^2 / (4 D^2).
inline int vertex_in_disk(const Vec2& c, const Vec2& pj, const Vec2& pk, double radius) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using namespace detail_;
        const auto aj = rel<T>(pj, c), ak = rel<T>(pk, c);
        const Rel<T> jk{T::diff(pj.x(), pk.x()), T::diff(pj.y(), pk.y())};
        const T d = cross(aj, ak);
        const T r = T::from(radius);
        return norm2(aj) * norm2(ak) * norm2(jk) - T::constant(4.0) * r * r * d * d;
    });
}

/// Position of v_jk along L_j relative to the foot a_j / 2 (requires D_jk != 0): sign(t_jk), +1 when
/// the vertex lies counter-clockwise of the foot. t_jk has the sign of (|a_k|^2 - a_j . a_k) D_jk.
inline int vertex_position(const Vec2& c, const Vec2& pj, const Vec2& pk) {
    const int d = orient(c, pj, pk);
    const int s = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using namespace detail_;
        const auto aj = rel<T>(pj, c), ak = rel<T>(pk, c);
        return norm2(ak) - dot(aj, ak);
    });
    return s * d;
}

/// Side of an endpoint of the chord L_m ∩ disk (sigma = -1: the counter-clockwise-first endpoint,
/// +1: the last; requires |a_m| < 2R) with respect to the bisector L_j: -1 strictly inside H_j.
/// The endpoint is a_m/2 + sigma w perp(a_m)/|a_m|, w = sqrt(R^2 - |a_m|^2/4), so the side is the sign
/// of X sqrt(P) + Y sqrt(Q) with X = a_m.a_j - |a_j|^2, P = |a_m|^2, Y = sigma cross(a_m, a_j),
/// Q = 4R^2 - |a_m|^2 > 0; decided by the signs of X, Y and of X^2 P - Y^2 Q.
inline int endpoint_side(const Vec2& c, const Vec2& pm, int sigma, const Vec2& pj, double radius) {
    const int sx = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using namespace detail_;
        const auto am = rel<T>(pm, c), aj = rel<T>(pj, c);
        return dot(am, aj) - norm2(aj);
    });
    const int sy = sigma * orient(c, pm, pj);
    if (sx == 0) return sy;
    if (sy == 0 || sx == sy) return sx;
    const int cmp = filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using namespace detail_;
        const auto am = rel<T>(pm, c), aj = rel<T>(pj, c);
        const T x = dot(am, aj) - norm2(aj);
        const T y = cross(am, aj);
        const T p = norm2(am);
        const T r = T::from(radius);
        const T q = T::constant(4.0) * r * r - p;
        return x * x * p - y * y * q;
    });
    return sx * cmp;
}

/// Standard in-circle test on input points: sign of
/// det[[a - d, |a - d|^2], [b - d, |b - d|^2], [c - d, |c - d|^2]]. With (a, b, c) counter-clockwise
/// (orient(a, b, c) > 0): +1 when d lies strictly inside their circumcircle, 0 on it, -1 outside (the
/// sign flips for a clockwise triangle). Degree 4 in the coordinate differences; exact like every
/// predicate here (floating-point filter, then expansions).
inline int incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    return filtered_sign([&](auto tag) {
        using T = typename decltype(tag)::type;
        using namespace detail_;
        const auto ad = rel<T>(a, d), bd = rel<T>(b, d), cd = rel<T>(c, d);
        return norm2(ad) * cross(bd, cd) - norm2(bd) * cross(ad, cd) + norm2(cd) * cross(ad, bd);
    });
}

}  // namespace dvoronoi::pred
