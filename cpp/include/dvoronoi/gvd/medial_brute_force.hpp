// The brute-force oracle of the medial diagram (SPEC: computable on small maps): every free pixel's
// nearest point found by scanning every occupied square and the map's four outside half-planes, with
// the same tie rule (smallest squared distance, then x, then y), then the pair rule of
// medial_diagram.hpp. Shares no code with the two-pass transform. O((rows x cols) x occupied).
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

/// The diagram mask from brute-force nearest points.
inline std::vector<std::uint8_t> brute_force_medial(const OccupancyGrid& g, const MedialOptions& o = {}) {
    check_medial_options(o);
    const FeatureMap f = brute_force_features(g);
    const detail::PairRule rule(o);
    detail::BoxJoin join;
    std::vector<std::uint8_t> mask(g.size(), 0);
    for (std::int32_t r = 0; r < g.rows; ++r)
        for (std::int32_t c = 0; c < g.cols; ++c) mask[f.at(r, c)] = detail::on_diagram(g, f, rule, join, r, c);
    return mask;
}

}  // namespace dvoronoi::gvd
