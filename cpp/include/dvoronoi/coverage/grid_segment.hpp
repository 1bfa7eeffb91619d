// Does a segment stay in the free space of an occupancy grid? Exact test by walking the pixels it crosses.
// Free space = the map's rectangle minus the occupied pixels (closed unit squares) minus the pinch points
// where two occupied pixels touch only diagonally. Pixel units: pixel (r, c) is [c, c+1] x [r, r+1].
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dvoronoi::coverage {

//! A point in image pixel units (u right, w down).
struct PixelPoint {
    double u = 0.0, w = 0.0;
};

//! Is pixel (r, c) occupied, the outside of the map counting as occupied.
struct OccupancyView {
    const std::uint8_t* occ;
    std::int32_t rows, cols;
    bool blocked(std::int64_t r, std::int64_t c) const {
        return r < 0 || c < 0 || r >= rows || c >= cols || occ[r * cols + c] != 0;
    }
};

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

/*! Chessboard distance from each pixel to the nearest occupied pixel or the outside of the map (1 for a
    pixel next to a wall), capped at `cap` (at most 255). Two raster passes. */
inline std::vector<std::uint8_t> chessboard_clearance(const OccupancyView& g, int cap) {
    const std::int64_t rows = g.rows, cols = g.cols;
    std::vector<std::uint8_t> d(static_cast<std::size_t>(rows * cols));
    for (std::int64_t r = 0; r < rows; ++r)
        for (std::int64_t c = 0; c < cols; ++c) {
            if (g.blocked(r, c)) {
                d[r * cols + c] = 0;
                continue;
            }
            const std::int64_t edge = std::min(std::min(r, c), std::min(rows - 1 - r, cols - 1 - c)) + 1;
            int v = static_cast<int>(std::min<std::int64_t>(edge, cap));
            if (r > 0) {
                v = std::min(v, d[(r - 1) * cols + c] + 1);
                if (c > 0) v = std::min(v, d[(r - 1) * cols + c - 1] + 1);
                if (c + 1 < cols) v = std::min(v, d[(r - 1) * cols + c + 1] + 1);
            }
            if (c > 0) v = std::min(v, d[r * cols + c - 1] + 1);
            d[r * cols + c] = static_cast<std::uint8_t>(v);
        }
    for (std::int64_t r = rows - 1; r >= 0; --r)
        for (std::int64_t c = cols - 1; c >= 0; --c) {
            int v = d[r * cols + c];
            if (r + 1 < rows) {
                v = std::min(v, d[(r + 1) * cols + c] + 1);
                if (c > 0) v = std::min(v, d[(r + 1) * cols + c - 1] + 1);
                if (c + 1 < cols) v = std::min(v, d[(r + 1) * cols + c + 1] + 1);
            }
            if (c + 1 < cols) v = std::min(v, d[r * cols + c + 1] + 1);
            d[r * cols + c] = static_cast<std::uint8_t>(v);
        }
    return d;
}

/*! segment_free, walked with long strides where the map is open: from a point in a pixel whose
    chessboard clearance is k, the next k - 1 pixels in every direction are free, so the walk jumps that
    far; next to a wall (k <= 1) it tests the next two pixels' worth exactly with segment_free. Same
    answer as segment_free (up to the rounding of the stride points); `clear` from chessboard_clearance. */
inline bool segment_free_traced(const OccupancyView& g, const std::vector<std::uint8_t>& clear, PixelPoint a, PixelPoint b) {
    const double du = b.u - a.u, dw = b.w - a.w;
    const double cheb = std::max(std::fabs(du), std::fabs(dw));
    if (cheb <= 2.0) return segment_free(g, a, b);
    double t = 0.0;
    while (t < 1.0) {
        const PixelPoint p{a.u + t * du, a.w + t * dw};
        const double c = std::floor(p.u), r = std::floor(p.w);
        const int k = (c >= 0 && r >= 0 && c < g.cols && r < g.rows)
                          ? clear[static_cast<std::size_t>(std::int64_t(r) * g.cols + std::int64_t(c))] : 0;
        if (k >= 2) {
            t += (k - 1) / cheb;
            continue;
        }
        const double t1 = std::min(1.0, t + 2.0 / cheb);
        const PixelPoint q = t1 >= 1.0 ? b : PixelPoint{a.u + t1 * du, a.w + t1 * dw};
        if (!segment_free(g, p, q)) return false;
        t = t1;
    }
    return true;
}

}  // namespace dvoronoi::coverage
