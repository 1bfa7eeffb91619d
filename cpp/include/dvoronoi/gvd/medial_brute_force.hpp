// The brute-force oracle of the medial diagram (SPEC: computable on small maps): every free pixel's
// nearest point found by scanning every occupied square and the map's four outside half-planes, with
// the same tie rule (smallest squared distance, then x, then y), then the pair rule of
// medial_diagram.hpp with the box rule's join searched square by square. Shares no code with the
// two-pass transform or BoxJoin. O((rows x cols) x occupied).
#pragma once

#include "dvoronoi/gvd/medial_diagram.hpp"

#include <algorithm>
#include <limits>

namespace dvoronoi::gvd {

inline FeatureMap brute_force_features(const OccupancyGrid& g) {
    check_grid(g);
    FeatureMap f;
    f.rows = g.rows;
    f.cols = g.cols;
    f.vgap.assign(g.size(), 0);
    f.fx.assign(g.size(), -1);
    f.fy.assign(g.size(), -1);
    std::vector<std::array<std::int32_t, 2>> squares;  // (c, j): column, row from the bottom
    for (std::int32_t r = 0; r < g.rows; ++r)
        for (std::int32_t c = 0; c < g.cols; ++c)
            if (g.occ(r, c)) squares.push_back({c, g.rows - 1 - r});
    const std::int32_t W2 = 2 * g.cols, H2 = 2 * g.rows;
    for (std::int32_t r = 0; r < g.rows; ++r)
        for (std::int32_t c = 0; c < g.cols; ++c) {
            const std::int32_t X = 2 * c + 1, Y = 2 * (g.rows - 1 - r) + 1;
            if (g.occ(r, c)) {  // its own centre, as the transform stores it
                f.fx[f.at(r, c)] = static_cast<std::int16_t>(X);
                f.fy[f.at(r, c)] = static_cast<std::int16_t>(Y);
                continue;
            }
            detail::Candidate2 best{std::numeric_limits<std::int64_t>::max(), 0, 0};
            auto offer = [&](std::int32_t x, std::int32_t y) {
                const std::int64_t dx = x - X, dy = y - Y;
                const detail::Candidate2 cand{dx * dx + dy * dy, x, y};
                if (cand < best) best = cand;
            };
            offer(0, Y);   // outside, left
            offer(W2, Y);  // right
            offer(X, 0);   // below
            offer(X, H2);  // above
            for (const auto& s : squares)
                offer(std::clamp(X, 2 * s[0], 2 * s[0] + 2), std::clamp(Y, 2 * s[1], 2 * s[1] + 2));
            f.fx[f.at(r, c)] = static_cast<std::int16_t>(best.x);
            f.fy[f.at(r, c)] = static_cast<std::int16_t>(best.y);
        }
    return f;
}

namespace detail {

/// Does the pair (p, q) put p on the diagram? p, q: pixel centres; a, b: their nearest points
/// (doubled units). `sep2` is floor(4 s^2): |a-b|^2 > 4 s^2 <=> |a-b|^2 > floor(4 s^2) for integers.
template <class Join>
bool pair_marks_first(const OccupancyGrid& g, const PairRule& rule, Join& join, std::int64_t px,
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

/// Is free pixel (r, c) on the diagram, given every pixel's nearest point? (The definition, pixel by
/// pixel; RowMarker applies it pair by pair.)
template <class Join>
bool on_diagram(const OccupancyGrid& g, const FeatureMap& f, const PairRule& rule, Join& join, std::int32_t r,
                std::int32_t c) {
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

/// The box rule's join by the definition: a breadth-first search over the occupied squares that meet
/// the grown box (none of BoxJoin's shortcuts or bit tricks).
struct JoinByDefinition {
    bool operator()(const OccupancyGrid& g, std::int32_t ax, std::int32_t ay, std::int32_t bx, std::int32_t by) const {
        const double xlo = std::min(ax, bx) - 2, xhi = std::max(ax, bx) + 2, ylo = std::min(ay, by) - 2, yhi = std::max(ay, by) + 2;
        auto meets = [&](std::int32_t c, std::int32_t j) { return 2.0 * c <= xhi && 2.0 * c + 2 >= xlo && 2.0 * j <= yhi && 2.0 * j + 2 >= ylo; };
        auto holds = [](std::int32_t c, std::int32_t j, std::int32_t x, std::int32_t y) {
            return 2 * c <= x && x <= 2 * c + 2 && 2 * j <= y && y <= 2 * j + 2;
        };
        std::vector<std::array<std::int32_t, 2>> todo, seen;
        for (std::int32_t j = -1; j <= g.rows; ++j)
            for (std::int32_t c = -1; c <= g.cols; ++c)
                if (meets(c, j) && g.blocked(g.rows - 1 - j, c) && holds(c, j, ax, ay)) todo.push_back({c, j});
        seen = todo;
        while (!todo.empty()) {
            const auto s = todo.back();
            todo.pop_back();
            if (holds(s[0], s[1], bx, by)) return true;
            for (std::int32_t dj = -1; dj <= 1; ++dj)
                for (std::int32_t dc = -1; dc <= 1; ++dc) {
                    const std::array<std::int32_t, 2> n{s[0] + dc, s[1] + dj};
                    if (n[0] < -1 || n[0] > g.cols || n[1] < -1 || n[1] > g.rows || !meets(n[0], n[1]) ||
                        !g.blocked(g.rows - 1 - n[1], n[0]) || std::find(seen.begin(), seen.end(), n) != seen.end())
                        continue;
                    seen.push_back(n);
                    todo.push_back(n);
                }
        }
        return false;
    }
};

}  // namespace detail

/// The diagram mask from brute-force nearest points.
inline std::vector<std::uint8_t> brute_force_medial(const OccupancyGrid& g, const MedialOptions& o = {}) {
    check_medial_options(o);
    const FeatureMap f = brute_force_features(g);
    const detail::PairRule rule(o);
    detail::JoinByDefinition join;
    std::vector<std::uint8_t> mask(g.size(), 0);
    for (std::int32_t r = 0; r < g.rows; ++r)
        for (std::int32_t c = 0; c < g.cols; ++c) mask[f.at(r, c)] = detail::on_diagram(g, f, rule, join, r, c);
    return mask;
}

}  // namespace dvoronoi::gvd
