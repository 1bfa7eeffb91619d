#include "dvoronoi/gvd/medial_brute_force.hpp"
#include "occupancy_scenes.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace dvoronoi::gvd;

namespace {

void require_same_features(const OccupancyGrid& g, const FeatureMap& f, const FeatureMap& b) {
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = g.at(r, c);
            INFO("pixel (" << r << ", " << c << ")");
            REQUIRE(f.fx[i] == b.fx[i]);
            REQUIRE(f.fy[i] == b.fy[i]);
        }
}

}  // namespace

TEST_CASE("nearest points equal the brute force, with the tie rule, for any worker count") {
    std::vector<OccupancyGrid> maps = {scenes::rooms(), scenes::corridors(), scenes::staircase(3), scenes::staircase(1)};
    for (unsigned s = 0; s < 150; ++s) maps.push_back(scenes::clutter(s));
    OccupancyGrid empty(7, 5);
    maps.push_back(empty);
    for (const auto& g : maps) {
        const FeatureMap b = brute_force_features(g);
        for (int workers : {1, 2, 3}) require_same_features(g, feature_transform(g, workers), b);
    }
}

TEST_CASE("maps of many bands: the column offsets and nearest points do not depend on where bands start") {
    // Bands of BandEdges::kRows rows each start pass 1 from their edges: columns with no occupied pixel
    // at all, occupied only just above or below a band's edge, or occupied in every row.
    const std::int32_t B = detail::BandEdges::kRows;
    std::mt19937 rng(7);
    for (int m = 0; m < 40; ++m) {
        const std::int32_t H = B + 1 + static_cast<std::int32_t>(rng() % static_cast<unsigned>(4 * B));
        const std::int32_t W = 1 + static_cast<std::int32_t>(rng() % 37);
        OccupancyGrid g(H, W);
        for (std::int32_t c = 0; c < W; ++c) {
            switch (rng() % 5) {
                case 0: break;  // a free column
                case 1: for (std::int32_t r = 0; r < H; ++r) g.occupied[g.at(r, c)] = 1; break;
                case 2:  // pixels at band edges
                    for (std::int32_t r = B - 1; r < H; r += B) g.occupied[g.at(r, c)] = rng() % 2;
                    for (std::int32_t r = B; r < H; r += B) g.occupied[g.at(r, c)] = rng() % 2;
                    break;
                default:  // sparse pixels anywhere
                    for (std::int32_t r = 0; r < H; ++r) g.occupied[g.at(r, c)] = rng() % 23 == 0;
            }
        }
        const FeatureMap b = brute_force_features(g);
        for (int workers : {1, 2, 3}) {
            const FeatureMap f = feature_transform(g, workers);
            require_same_features(g, f, b);
            for (std::int32_t c = 0; c < W; ++c)
                for (std::int32_t r = 0; r < H; ++r) {
                    // the signed offset to the nearest occupied pixel of the column (the frame rows
                    // -1 and H are occupied; ties: below)
                    std::int32_t up = r + 1, down = H - r;
                    for (std::int32_t q = r; q >= 0; --q)
                        if (g.occ(q, c)) { up = r - q; break; }
                    for (std::int32_t q = r; q < H; ++q)
                        if (g.occ(q, c)) { down = q - r; break; }
                    INFO("map " << m << " pixel (" << r << ", " << c << ") workers " << workers);
                    REQUIRE(f.vgap[f.at(r, c)] == (down <= up ? down : -up));
                }
        }
    }
}

TEST_CASE("the nearest point's x never decreases along a row (the updates' binary search relies on it)") {
    for (unsigned s = 0; s < 100; ++s) {
        const OccupancyGrid g = scenes::clutter(s, 64);
        const FeatureMap f = feature_transform(g);
        for (int r = 0; r < g.rows; ++r)
            for (int c = 1; c < g.cols; ++c) REQUIRE(f.fx[f.at(r, c - 1)] <= f.fx[f.at(r, c)]);
    }
}

TEST_CASE("clearance: a free pixel next to a wall is half a pixel away; the map's edge is a wall") {
    OccupancyGrid g(5, 9);
    scenes::fill(g, 0, 5, 4, 5);  // a wall splitting the map
    const FeatureMap f = feature_transform(g);
    CHECK(f.sq(2, 3) == 1);           // (2*0.5)^2 in doubled units
    CHECK(f.sq(2, 0) == 1);           // the map's left edge
    CHECK(f.sq(2, 1) == 9);           // 1.5 pixels from the left edge
    CHECK(f.sq(2, 4) == 0);           // occupied
    CHECK(f.fx[f.at(2, 2)] == 8);     // the wall's face at x = 4 (1.5 away; the edge is 2.5 away)
    OccupancyGrid corridor(4, 5);
    scenes::fill(corridor, 0, 4, 0, 1);
    scenes::fill(corridor, 0, 4, 4, 5);
    const FeatureMap t = feature_transform(corridor);
    CHECK(t.sq(1, 2) == 9);                // 1.5 from both walls: a tie
    CHECK(t.fx[t.at(1, 2)] == 2);          // ties go to the smaller x: the left wall's face
}

TEST_CASE("bad grids are rejected with the reason") {
    OccupancyGrid g(0, 4);
    CHECK_THROWS_WITH_AS(feature_transform(g), doctest::Contains("at least one row"), dvoronoi::InputError);
    OccupancyGrid big(kMaxMapSide + 1, 1);
    CHECK_THROWS_WITH_AS(feature_transform(big), doctest::Contains("at most"), dvoronoi::InputError);
    OccupancyGrid short_data(3, 3);
    short_data.occupied.pop_back();
    CHECK_THROWS_WITH_AS(feature_transform(short_data), doctest::Contains("8 values for 3 x 3"), dvoronoi::InputError);
}
