// The medial diagram of an occupancy grid (SPEC "Grid diagram on occupancy grids", diagram="medial"):
// the pixels where the nearest occupied point jumps from one side of a passage to the other, so a
// corridor between two parts of the same wall gets its centreline.
//
// Definition (pixel units; a, b, p, q as points, exact integers in doubled units):
//  - F(p): the nearest point of the occupied set (closed occupied squares and the outside of the
//    map) to free pixel p's centre; ties to the smallest x, then the smallest y (feature_transform.hpp).
//  - A pair of 4-adjacent free pixels p, q with a = F(p), b = F(q) *separates* when
//      1. |a - b| > min_separation (default 1.5: unit steps along a wall and 45-degree staircases,
//         whose nearest points move by 1 or sqrt(2), never separate; a 2-pixel corridor does), and
//      2. a and b are not joined by the walls near them: unless |a - b| > prune_length (default 8),
//         the occupied squares that meet the closed box spanned by a and b, grown by one pixel, must
//         not connect a's square to b's square (8-connected, inside the grown box). This drops the
//         spurs of pixel staircases (a step's two corners are joined by the step), of bumps, of room
//         corners (the two walls meet in the corner) and the tips of acute wedges, and keeps every
//         passage: the two sides of an open corridor are not joined across it.
//  - Of a separating pair, the pixel nearer the bisector of a and b is on the diagram (both on a tie):
//    p when |p-b|^2 - |p-a|^2 <= |q-a|^2 - |q-b|^2.
// A pixel is on the diagram when one of its (up to four) pairs puts it there. The rule reads only
// F of the pair and the occupancy inside a box of side <= prune_length, so a pixel's membership is a
// function of its neighbourhood: rows can be split over threads, and an update only needs the pixels
// whose nearest points or nearby walls changed.
#pragma once

#include "dvoronoi/gvd/feature_transform.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dvoronoi::gvd {

struct MedialOptions {
    double min_separation = 1.5;  ///< pixels: nearest points of a pair must be farther apart than this
    double prune_length = 8.0;    ///< pixels: pairs whose nearest points are at most this far apart and joined by walls are dropped
    int workers = 1;
};

inline void check_medial_options(const MedialOptions& o) {
    if (!std::isfinite(o.min_separation) || o.min_separation < 1.0)
        throw InputError("min_separation must be a finite number >= 1 (pixels)");
    if (!std::isfinite(o.prune_length) || o.prune_length < 0.0 || o.prune_length > 256.0)
        throw InputError("prune_length must be a finite number in [0, 256] (pixels)");
    if (o.workers < 1) throw InputError("workers must be at least 1, got " + std::to_string(o.workers));
}

namespace detail {

/// Are the occupied squares containing a and b joined by occupied squares that meet the closed box
/// spanned by a and b grown by one pixel (8-connected)? Squares outside the map count as occupied.
/// a, b in doubled units.
class BoxJoin {
public:
    bool operator()(const OccupancyGrid& g, std::int32_t ax, std::int32_t ay, std::int32_t bx, std::int32_t by) {
        // the box spanned by a and b, grown by one pixel (two doubled units) on every side
        const std::int32_t xlo = std::min(ax, bx) - 2, xhi = std::max(ax, bx) + 2;
        const std::int32_t ylo = std::min(ay, by) - 2, yhi = std::max(ay, by) + 2;
        // square column c covers [2c, 2c+2]; it meets [xlo, xhi] when 2c <= xhi and 2c + 2 >= xlo
        c0_ = std::max<std::int32_t>(-1, ceil_half(xlo - 2));
        const std::int32_t c1 = std::min<std::int32_t>(g.cols, xhi >> 1);
        j0_ = std::max<std::int32_t>(-1, ceil_half(ylo - 2));  // j: square row counted from the bottom
        const std::int32_t j1 = std::min<std::int32_t>(g.rows, yhi >> 1);
        nw_ = c1 - c0_ + 1;
        const std::int32_t nh = j1 - j0_ + 1;
        cell_.assign(static_cast<std::size_t>(nw_ * nh), 0);  // 0 free, 1 occupied, 2 reached
        for (std::int32_t j = j0_; j <= j1; ++j)
            for (std::int32_t c = c0_; c <= c1; ++c)
                cell_[idx(c, j)] = g.blocked(g.rows - 1 - j, c) ? 1 : 0;
        stack_.clear();
        for_squares_at(ax, ay, j1, c1, [&](std::int32_t c, std::int32_t j) {
            auto& v = cell_[idx(c, j)];
            if (v == 1) { v = 2; stack_.push_back({c, j}); }
        });
        while (!stack_.empty()) {
            const auto [c, j] = stack_.back();
            stack_.pop_back();
            for (std::int32_t dj = -1; dj <= 1; ++dj)
                for (std::int32_t dc = -1; dc <= 1; ++dc) {
                    const std::int32_t cc = c + dc, jj = j + dj;
                    if (cc < c0_ || cc > c1 || jj < j0_ || jj > j1) continue;
                    auto& v = cell_[idx(cc, jj)];
                    if (v == 1) { v = 2; stack_.push_back({cc, jj}); }
                }
        }
        bool joined = false;
        for_squares_at(bx, by, j1, c1, [&](std::int32_t c, std::int32_t j) { joined |= cell_[idx(c, j)] == 2; });
        return joined;
    }

private:
    static std::int32_t ceil_half(std::int32_t v) { return v >= 0 ? (v + 1) / 2 : -((-v) / 2); }
    std::size_t idx(std::int32_t c, std::int32_t j) const {
        return static_cast<std::size_t>((j - j0_) * nw_ + (c - c0_));
    }
    /// Squares (in the box) whose closed extent holds the point (x, y).
    template <class Fn>
    void for_squares_at(std::int32_t x, std::int32_t y, std::int32_t j1, std::int32_t c1, Fn&& fn) const {
        const std::int32_t cs[2] = {(x >> 1) - ((x & 1) ? 0 : 1), x >> 1};
        const std::int32_t js[2] = {(y >> 1) - ((y & 1) ? 0 : 1), y >> 1};
        for (std::int32_t a = 0; a < 2; ++a)
            for (std::int32_t b = 0; b < 2; ++b) {
                const std::int32_t c = cs[a], j = js[b];
                if ((a == 1 && cs[1] == cs[0]) || (b == 1 && js[1] == js[0])) continue;
                if (c < c0_ || c > c1 || j < j0_ || j > j1) continue;
                fn(c, j);
            }
    }

    std::int32_t c0_ = 0, j0_ = 0, nw_ = 0;
    std::vector<std::uint8_t> cell_;
    std::vector<std::array<std::int32_t, 2>> stack_;
};

/// Squared thresholds in doubled units.
struct PairRule {
    std::int64_t sep2, prune2;
    explicit PairRule(const MedialOptions& o)
        : sep2(static_cast<std::int64_t>(std::floor(4.0 * o.min_separation * o.min_separation))),
          prune2(static_cast<std::int64_t>(std::floor(4.0 * o.prune_length * o.prune_length))) {}
};

/// Does the pair (p, q) put p on the diagram? p, q: pixel centres; a, b: their nearest points
/// (doubled units). `sep2` is floor(4 s^2): |a-b|^2 > 4 s^2 <=> |a-b|^2 > floor(4 s^2) for integers.
inline bool pair_marks_first(const OccupancyGrid& g, const PairRule& rule, BoxJoin& join, std::int64_t px,
                             std::int64_t py, std::int64_t qx, std::int64_t qy, std::int32_t ax, std::int32_t ay,
                             std::int32_t bx, std::int32_t by) {
    const std::int64_t dx = ax - bx, dy = ay - by, d2 = dx * dx + dy * dy;
    if (d2 <= rule.sep2) return false;
    auto sq = [](std::int64_t x, std::int64_t y, std::int64_t u, std::int64_t v) { return (x - u) * (x - u) + (y - v) * (y - v); };
    const std::int64_t sp = sq(px, py, bx, by) - sq(px, py, ax, ay);
    const std::int64_t sq_ = sq(qx, qy, ax, ay) - sq(qx, qy, bx, by);
    if (sp > sq_) return false;
    if (d2 <= rule.prune2 && join(g, ax, ay, bx, by)) return false;
    return true;
}

/// Is free pixel (r, c) on the diagram, given every pixel's nearest point?
inline bool on_diagram(const OccupancyGrid& g, const FeatureMap& f, const PairRule& rule, BoxJoin& join,
                       std::int32_t r, std::int32_t c) {
    const std::size_t i = f.at(r, c);
    if (g.occupied[i]) return false;
    const std::int32_t ax = f.fx[i], ay = f.fy[i];
    const std::int64_t px = 2 * c + 1, py = 2 * (g.rows - 1 - r) + 1;
    const std::int32_t nr[4] = {r, r, r - 1, r + 1}, nc[4] = {c - 1, c + 1, c, c};
    for (int k = 0; k < 4; ++k) {
        if (g.blocked(nr[k], nc[k])) continue;
        const std::size_t j = f.at(nr[k], nc[k]);
        const std::int32_t bx = f.fx[j], by = f.fy[j];
        if (bx == ax && by == ay) continue;
        if (pair_marks_first(g, rule, join, px, py, 2 * nc[k] + 1, 2 * (g.rows - 1 - nr[k]) + 1, ax, ay, bx, by))
            return true;
    }
    return false;
}

}  // namespace detail

/// The medial diagram of an occupancy grid with its nearest-point transform.
struct MedialDiagram {
    OccupancyGrid grid;
    FeatureMap features;
    std::vector<std::uint8_t> mask;  ///< rows x cols, 1 = on the diagram
    MedialOptions options;
    std::int64_t max_sq = 0;         ///< an upper bound of every pixel's squared clearance (doubled units)

    /// Clearance of pixel (r, c)'s centre in map units (0 for occupied pixels).
    double clearance(std::int32_t r, std::int32_t c) const {
        return 0.5 * std::sqrt(static_cast<double>(features.sq(r, c))) * grid.resolution;
    }
    std::size_t count() const {
        std::size_t n = 0;
        for (std::uint8_t v : mask) n += v;
        return n;
    }
};

namespace detail {

/// The largest squared clearance of rows [r0, r1).
inline std::int64_t largest_sq(const FeatureMap& f, std::int32_t r0, std::int32_t r1) {
    std::int32_t best = 0;
    for (std::int32_t r = r0; r < r1; ++r) {
        const std::int16_t *x = &f.fx[f.at(r, 0)], *y = &f.fy[f.at(r, 0)];
        const std::int32_t Y = 2 * (f.rows - 1 - r) + 1;
        for (std::int32_t c = 0; c < f.cols; ++c) {
            const std::int32_t dx = x[c] - (2 * c + 1), dy = y[c] - Y;
            best = std::max(best, dx * dx + dy * dy);
        }
    }
    return best;
}

/// Marks rows [r0, r1) of `m.mask`. Most pairs fail the separation test: it runs first over whole
/// rows (branch-free, vectorised), and only pixels with a separated pair get the full rule.
inline void mark_rows(MedialDiagram& m, std::int32_t r0, std::int32_t r1) {
    const PairRule rule(m.options);
    BoxJoin join;
    const OccupancyGrid& g = m.grid;
    const FeatureMap& f = m.features;
    const std::int32_t W = g.cols;
    const std::int32_t sep2 = static_cast<std::int32_t>(std::min<std::int64_t>(rule.sep2, INT32_MAX));
    std::vector<std::uint8_t> down(static_cast<std::size_t>(W), 0), up(static_cast<std::size_t>(W), 0),
        flag(static_cast<std::size_t>(W), 0);
    // separated(row a, row b)[c]: the vertical pair (a, c), (b, c)
    auto vertical = [&](std::int32_t a, std::int32_t b, std::uint8_t* out) {
        const std::int16_t *ax = &f.fx[f.at(a, 0)], *ay = &f.fy[f.at(a, 0)];
        const std::int16_t *bx = &f.fx[f.at(b, 0)], *by = &f.fy[f.at(b, 0)];
        for (std::int32_t c = 0; c < W; ++c) {
            const std::int32_t dx = ax[c] - bx[c], dy = ay[c] - by[c];
            out[c] = dx * dx + dy * dy > sep2;
        }
    };
    if (r0 > 0) vertical(r0 - 1, r0, up.data());
    for (std::int32_t r = r0; r < r1; ++r) {
        if (r + 1 < g.rows) vertical(r, r + 1, down.data());
        else std::fill(down.begin(), down.end(), std::uint8_t(0));
        const std::int16_t *x = &f.fx[f.at(r, 0)], *y = &f.fy[f.at(r, 0)];
        flag[0] = 0;
        for (std::int32_t c = 0; c + 1 < W; ++c) {
            const std::int32_t dx = x[c] - x[c + 1], dy = y[c] - y[c + 1];
            flag[static_cast<std::size_t>(c) + 1] = dx * dx + dy * dy > sep2;
        }
        std::uint8_t* out = &m.mask[f.at(r, 0)];
        for (std::int32_t c = 0; c < W; ++c) {
            const std::size_t uc = static_cast<std::size_t>(c);
            const bool right = c + 1 < W && flag[uc + 1];
            const bool any = flag[uc] | right | up[uc] | down[uc];
            out[c] = any && on_diagram(g, f, rule, join, r, c) ? 1 : 0;
        }
        std::swap(up, down);
    }
}

}  // namespace detail

/// The medial diagram of `grid` (copied into the result) with options.workers threads; the same
/// pixels for every worker count.
/// \throws InputError for a bad grid or options.
/// \note O(rows x cols) plus a box search (<= (prune_length + 2)^2) for the few pairs that separate.
inline MedialDiagram medial_diagram(OccupancyGrid grid, const MedialOptions& options = {}) {
    check_medial_options(options);
    MedialDiagram m;
    m.features = feature_transform(grid, options.workers);
    m.grid = std::move(grid);
    m.options = options;
    m.mask.assign(m.grid.size(), 0);
    const int k_rows = std::max(1, std::min(options.workers, m.grid.rows));
    std::vector<std::int64_t> max_sq(static_cast<std::size_t>(k_rows), 0);
    run_team(k_rows, [&](int k) {
        const auto r0 = static_cast<std::int32_t>(static_cast<std::int64_t>(m.grid.rows) * k / k_rows);
        const auto r1 = static_cast<std::int32_t>(static_cast<std::int64_t>(m.grid.rows) * (k + 1) / k_rows);
        detail::mark_rows(m, r0, r1);
        max_sq[static_cast<std::size_t>(k)] = detail::largest_sq(m.features, r0, r1);
    });
    m.max_sq = *std::max_element(max_sq.begin(), max_sq.end());
    return m;
}

}  // namespace dvoronoi::gvd
