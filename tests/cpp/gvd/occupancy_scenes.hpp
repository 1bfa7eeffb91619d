// Small occupancy maps in the shapes real ones have, for the medial diagram's tests: rooms with
// doors, corridors of every width from 1 to 8 pixels, pillars (islands), staircase walls of several
// slopes, walls touching the map's edge, and random clutter.
#pragma once

#include "dvoronoi/gvd/occupancy_grid.hpp"

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace scenes {

using dvoronoi::gvd::OccupancyGrid;

inline void fill(OccupancyGrid& g, int r0, int r1, int c0, int c1, bool v = true) {
    for (int r = std::max(0, r0); r < std::min(g.rows, r1); ++r)
        for (int c = std::max(0, c0); c < std::min(g.cols, c1); ++c) g.occupied[g.at(r, c)] = v ? 1 : 0;
}

/// A map drawn as text: '#' occupied, anything else free; row 0 is the first line.
inline OccupancyGrid from_text(const std::vector<std::string>& lines) {
    OccupancyGrid g(static_cast<int>(lines.size()), static_cast<int>(lines.front().size()));
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) g.occupied[g.at(r, c)] = lines[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] == '#';
    return g;
}

/// Outer walls on the map's edge, a horizontal wall with doors of widths 1..5, two pillars.
inline OccupancyGrid rooms() {
    OccupancyGrid g(40, 60);
    fill(g, 0, 40, 0, 2); fill(g, 0, 40, 58, 60); fill(g, 0, 2, 0, 60); fill(g, 38, 40, 0, 60);
    fill(g, 19, 21, 0, 60);
    int c = 4;
    for (int w = 1; w <= 5; ++w) { fill(g, 19, 21, c, c + w, false); c += w + 8; }
    fill(g, 8, 11, 40, 44);   // pillar in the upper room
    fill(g, 28, 30, 20, 23);  // pillar in the lower room
    return g;
}

/// Vertical corridors of widths 1..8 between 2-pixel walls, open to halls above and below.
inline OccupancyGrid corridors(int length = 20) {
    const int top = 6, H = top + length + 6;
    int W = 2;
    for (int w = 1; w <= 8; ++w) W += w + 2;
    OccupancyGrid g(H, W + 2);
    fill(g, top, top + length, 0, W + 2);
    int c = 2;
    for (int w = 1; w <= 8; ++w) { fill(g, top, top + length, c, c + w, false); c += w + 2; }
    return g;
}

/// A room whose floor is a staircase of steps `run` wide and one pixel high.
inline OccupancyGrid staircase(int run, int H = 30, int W = 48) {
    OccupancyGrid g(H, W);
    for (int c = 0; c < W; ++c) fill(g, std::max(H - 4 - c / run, H / 2), H, c, c + 1);
    return g;
}

/// Random rectangles (walls, blocks) with density and sizes drawn from the seed.
inline OccupancyGrid clutter(unsigned seed, int max_side = 48) {
    std::mt19937 rng(seed);
    const int H = 1 + static_cast<int>(rng() % static_cast<unsigned>(max_side));
    const int W = 1 + static_cast<int>(rng() % static_cast<unsigned>(max_side));
    OccupancyGrid g(H, W);
    const int n = static_cast<int>(rng() % 8);
    for (int b = 0; b < n; ++b) {
        const int r0 = static_cast<int>(rng() % static_cast<unsigned>(H)), c0 = static_cast<int>(rng() % static_cast<unsigned>(W));
        const int h = 1 + static_cast<int>(rng() % 6), w = 1 + static_cast<int>(rng() % 6);
        fill(g, r0, r0 + h, c0, c0 + w);
    }
    if (seed % 5 == 0)  // salt: single pixels
        for (auto& v : g.occupied) v = v || rng() % 17 == 0;
    return g;
}

}  // namespace scenes
