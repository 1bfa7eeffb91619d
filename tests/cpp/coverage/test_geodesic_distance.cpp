// Geodesic distance on occupancy grids (coverage/geodesic_distance.hpp), its segment test
// (grid_segment.hpp) and the geodesic Lloyd (geodesic_lloyd.hpp): exact values on small maps.
// The brute-force comparison with exact visibility-graph paths is tests/python/test_geodesic.py.
#include "dvoronoi/coverage/geodesic_lloyd.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace dvoronoi::coverage;

namespace {

std::vector<std::uint8_t> empty_map(int rows, int cols) { return std::vector<std::uint8_t>(std::size_t(rows) * cols, 0); }

}  // namespace

TEST_CASE("an open map gives the Euclidean distance to the nearest source, ties to the lower index") {
    const int H = 12, W = 17;
    auto occ = empty_map(H, W);
    const std::vector<PixelPoint> src{{3.25, 4.5}, {13.25, 4.5}};
    const GeodesicField f = geodesic_field(occ.data(), H, W, src);
    for (int r = 0; r < H; ++r)
        for (int c = 0; c < W; ++c) {
            const double d0 = std::hypot(c + 0.5 - 3.25, r + 0.5 - 4.5), d1 = std::hypot(c + 0.5 - 13.25, r + 0.5 - 4.5);
            const auto p = std::size_t(r) * W + c;
            CHECK(f.distance[p] == doctest::Approx(std::min(d0, d1)).epsilon(1e-14));
            CHECK(f.label[p] == (d1 < d0 ? 1 : 0));  // column 8 (centre 8.5) is 5.25 from both: agent 0
        }
}

TEST_CASE("around a wall's end, and not through a pinch point") {
    const int H = 10, W = 10;
    auto occ = empty_map(H, W);
    for (int c = 0; c < 8; ++c) occ[5 * W + c] = 1;  // a wall from the left edge, open at the right
    const GeodesicField f = geodesic_field(occ.data(), H, W, {{1.5, 7.5}});
    const double expect = std::hypot(8 - 1.5, 7.5 - 6) + 1 + std::hypot(8 - 1.5, 5 - 3.5);
    CHECK(f.distance[3 * W + 1] == doctest::Approx(expect).epsilon(1e-14));
    auto pinch = empty_map(4, 4);
    pinch[0 * 4 + 1] = pinch[1 * 4 + 0] = 1;  // touch at (1, 1): pixel (0, 0) is closed off
    const GeodesicField g = geodesic_field(pinch.data(), 4, 4, {{2.5, 1.5}});
    CHECK(g.label[0] == -1);
    CHECK(std::isinf(g.distance[0]));
    const OccupancyView view{pinch.data(), 4, 4};
    CHECK_FALSE(segment_free(view, {0.5, 0.5}, {1.5, 1.5}));   // through the pinch point
    CHECK_FALSE(segment_free(view, {0.5, 0.5}, {2.5, 0.5}));   // through an occupied pixel
    CHECK(segment_free(view, {2.0, 0.0}, {2.0, 4.0}));         // along the edge of an occupied pixel
    CHECK(segment_free(view, {1.0, 2.0}, {3.5, 0.5}));         // from a convex corner
}

TEST_CASE("a range leaves far pixels unreached and does not change the near ones") {
    const int H = 20, W = 20;
    auto occ = empty_map(H, W);
    for (int r = 3; r < 17; ++r) occ[r * W + 10] = 1;
    const std::vector<PixelPoint> src{{4.5, 10.5}};
    const GeodesicField all = geodesic_field(occ.data(), H, W, src);
    const GeodesicField some = geodesic_field(occ.data(), H, W, src, 9.0);
    for (std::size_t p = 0; p < all.distance.size(); ++p) {
        if (all.distance[p] <= 9.0) CHECK(some.distance[p] == all.distance[p]);
        else CHECK(some.label[p] == -1);
    }
}

TEST_CASE("geodesic Lloyd: the cost never increases, agents stay in free pixels, workers do not matter") {
    const int H = 30, W = 40;
    auto occ = empty_map(H, W);
    for (int r = 0; r < H; ++r)
        if (r < 12 || r > 15) occ[r * W + 20] = 1;  // two rooms and a door
    std::vector<PixelPoint> agents;
    for (int k = 0; k < 6; ++k) agents.push_back({2.5 + k, 3.5 + 3 * k});
    GeodesicLloyd one(occ, H, W, agents, std::numeric_limits<double>::infinity(), {}, 1.0, 1);
    GeodesicLloyd two(occ, H, W, agents, std::numeric_limits<double>::infinity(), {}, 1.0, 2);
    double last = one.cost();
    for (int t = 0; t < 25; ++t) {
        CHECK(one.step() == two.step());
        CHECK(one.cost() <= last);
        last = one.cost();
        for (std::size_t i = 0; i < agents.size(); ++i) {
            const auto& p = one.points()[i];
            CHECK(occ[std::size_t(std::floor(p.w)) * W + std::size_t(std::floor(p.u))] == 0);
            CHECK(p.u == two.points()[i].u);
            CHECK(p.w == two.points()[i].w);
        }
    }
    int right = 0;
    for (const auto& p : one.points()) right += p.u > 21;
    CHECK(right >= 2);  // through the door
}
