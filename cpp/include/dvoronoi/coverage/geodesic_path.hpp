// Shortest paths out of a geodesic field (geodesic_distance.hpp), and the exact test that a segment stays
// in free space, which every path an agent follows passes before it moves.
#pragma once

#include "dvoronoi/coverage/geodesic_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dvoronoi::coverage {

namespace detail {

// Vertex (i, j) is a pinch point: exactly the two pixels of one diagonal around it are occupied.
inline bool pinch(const OccupancyView& g, std::int64_t i, std::int64_t j) {
    const bool a = g.blocked(j - 1, i - 1), b = g.blocked(j - 1, i), c = g.blocked(j, i - 1), d = g.blocked(j, i);
    return (a && d && !b && !c) || (b && c && !a && !d);
}

inline bool is_integer(double x) { return std::floor(x) == x; }

}  // namespace detail

/*! Does the closed segment a-b lie in free space: meet no occupied pixel's interior, run along a grid
    line only where a free pixel borders it, and pass through no pinch point (two occupied pixels that
    touch diagonally)? Exact for endpoints on pixel corners and centres (their arithmetic is exact);
    O(length) pixels visited. */
inline bool segment_free(const OccupancyView& g, PixelPoint a, PixelPoint b) {
    using detail::is_integer;
    using detail::pinch;
    const double u0 = std::min(a.u, b.u), u1 = std::max(a.u, b.u), w0 = std::min(a.w, b.w), w1 = std::max(a.w, b.w);
    if (u0 < 0 || w0 < 0 || u1 > g.cols || w1 > g.rows) return false;
    const double du = b.u - a.u, dw = b.w - a.w;
    // Axis-parallel segments (a point included): a strip of pixels, or a grid line between two.
    auto along = [&](double fixed, double lo, double hi, bool vertical) {
        auto blocked = [&](std::int64_t along_i, std::int64_t across_i) {
            return vertical ? g.blocked(along_i, across_i) : g.blocked(across_i, along_i);
        };
        const auto k0 = static_cast<std::int64_t>(std::floor(lo));
        auto k1 = static_cast<std::int64_t>(std::ceil(hi));
        if (k1 == k0) k1 = k0 + 1;  // a point, or a segment inside one unit
        if (!is_integer(fixed)) {
            const auto x = static_cast<std::int64_t>(std::floor(fixed));
            for (std::int64_t k = k0; k < k1; ++k)
                if (blocked(k, x)) return false;
            return true;
        }
        const auto x = static_cast<std::int64_t>(fixed);
        for (std::int64_t k = k0; k < k1; ++k)  // on a grid line: one side must be free
            if (blocked(k, x - 1) && blocked(k, x)) return false;
        for (auto k = static_cast<std::int64_t>(std::ceil(lo)); k <= static_cast<std::int64_t>(std::floor(hi)); ++k)
            if (vertical ? pinch(g, x, k) : pinch(g, k, x)) return false;
        return true;
    };
    if (du == 0) return along(a.u, w0, w1, true);
    if (dw == 0) return along(a.w, u0, u1, false);
    auto w_at = [&](double x) { return a.w + ((x - a.u) * dw) / du; };  // product first: exact at lattice hits
    for (auto c = static_cast<std::int64_t>(std::floor(u0)); double(c) < u1; ++c) {
        const double xa = std::max(double(c), u0), xb = std::min(double(c + 1), u1);
        if (!(xa < xb)) continue;
        const double wa = w_at(xa), wb = w_at(xb);
        const double lo = std::min(wa, wb), hi = std::max(wa, wb);
        for (auto r = static_cast<std::int64_t>(std::floor(lo)); double(r) < hi; ++r)
            if (double(r + 1) > lo && g.blocked(r, c)) return false;
    }
    for (auto i = static_cast<std::int64_t>(std::ceil(u0)); double(i) <= u1; ++i) {
        const double w = w_at(double(i));
        if (is_integer(w) && pinch(g, i, static_cast<std::int64_t>(w))) return false;
    }
    return true;
}

/*! The polyline from pixel q's source to point `t` (in pixel q): source, the anchors (bends) in order,
    then `t`; each segment checked with segment_free. When the segment from `t` to q's anchor is not free
    the path goes through q's centre first. Empty when q is unreached or a segment is not free (the local
    line-of-sight test of the wavefront misjudged a shadow boundary; rare). */
inline std::vector<PixelPoint> geodesic_path(const GeodesicField& f, const OccupancyView& g, std::int64_t q,
                                             PixelPoint t) {
    std::vector<PixelPoint> path;
    if (q < 0 || f.anchor[static_cast<std::size_t>(q)] < 0) return path;
    path.push_back(t);
    std::int64_t a = f.anchor[static_cast<std::size_t>(q)];
    const PixelPoint centre{double(q % f.cols) + 0.5, double(q / f.cols) + 0.5};
    if (!segment_free(g, t, f.anchor_point(a))) path.push_back(centre);
    const std::int64_t guard = std::int64_t(f.distance.size()) + f.vertices() + f.sources;
    for (std::int64_t k = 0; a >= 0 && k <= guard; ++k) {
        const PixelPoint A = f.anchor_point(a);
        if (!segment_free(g, path.back(), A)) return {};
        path.push_back(A);
        a = f.anchor_parent(a);
    }
    if (a >= 0) return {};  // a cycle of relays (cannot happen with a settled field; guarded)
    std::reverse(path.begin(), path.end());
    return path;
}

//! The point at arc length `s` along a polyline (its end when s >= its length).
inline PixelPoint point_along(const std::vector<PixelPoint>& path, double s) {
    for (std::size_t k = 1; k < path.size(); ++k) {
        const double len = std::hypot(path[k].u - path[k - 1].u, path[k].w - path[k - 1].w);
        if (s < len) {
            const double t = s / len;
            return {path[k - 1].u + t * (path[k].u - path[k - 1].u), path[k - 1].w + t * (path[k].w - path[k - 1].w)};
        }
        s -= len;
    }
    return path.back();
}

inline double path_length(const std::vector<PixelPoint>& path) {
    double s = 0;
    for (std::size_t k = 1; k < path.size(); ++k) s += std::hypot(path[k].u - path[k - 1].u, path[k].w - path[k - 1].w);
    return s;
}

}  // namespace dvoronoi::coverage
