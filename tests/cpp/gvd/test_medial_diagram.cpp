#include "dvoronoi/gvd/medial_brute_force.hpp"
#include "dvoronoi/gvd/medial_update.hpp"
#include "occupancy_scenes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <queue>

using namespace dvoronoi::gvd;

namespace {

std::vector<OccupancyGrid> all_scenes() {
    std::vector<OccupancyGrid> maps = {scenes::rooms(), scenes::corridors()};
    for (int run : {1, 2, 3, 4, 5, 7}) maps.push_back(scenes::staircase(run));
    for (unsigned s = 0; s < 120; ++s) maps.push_back(scenes::clutter(s));
    return maps;
}

/// Free pixels 4-connected to (r, c) without crossing diagram pixels.
std::vector<std::uint8_t> reach_without_diagram(const MedialDiagram& m, int r, int c) {
    const OccupancyGrid& g = m.grid;
    std::vector<std::uint8_t> seen(g.size(), 0);
    std::queue<std::pair<int, int>> q;
    q.push({r, c});
    seen[g.at(r, c)] = 1;
    while (!q.empty()) {
        const auto [a, b] = q.front();
        q.pop();
        const int da[4] = {1, -1, 0, 0}, db[4] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
            const int x = a + da[k], y = b + db[k];
            if (g.blocked(x, y) || seen[g.at(x, y)] || m.mask[g.at(x, y)]) continue;
            seen[g.at(x, y)] = 1;
            q.push({x, y});
        }
    }
    return seen;
}

}  // namespace

TEST_CASE("the diagram is exactly the brute-force oracle's, for every worker count and pruning length") {
    for (const auto& g : all_scenes())
        for (double prune : {0.0, 4.0, 8.0, 12.5}) {
            MedialOptions o;
            o.prune_length = prune;
            const auto oracle = brute_force_medial(g, o);
            for (int workers : {1, 2, 3}) {
                o.workers = workers;
                REQUIRE(medial_diagram(g, o).mask.bytes() == oracle);
            }
        }
}

TEST_CASE("any nonzero occupancy byte is occupied (images hold 255), updates included") {
    for (const auto& ones : all_scenes()) {
        OccupancyGrid bytes = ones;
        std::uint8_t v = 2;
        for (auto& b : bytes.occupied)
            if (b) b = v = static_cast<std::uint8_t>(v == 255 ? 2 : v + 1);  // 2 .. 255
        MedialDiagram a = medial_diagram(ones), m = medial_diagram(bytes);
        REQUIRE(m.features.fx == a.features.fx);
        REQUIRE(m.features.fy == a.features.fy);
        REQUIRE(m.mask.bytes() == a.mask.bytes());
        std::vector<std::size_t> some;  // free every other occupied pixel, then take it back
        for (std::size_t i = 0; i < bytes.size(); i += 2)
            if (bytes.occupied[i]) some.push_back(i);
        set_pixels(m, some, false);
        set_pixels(a, some, false);
        REQUIRE(m.mask.bytes() == a.mask.bytes());
        set_pixels(m, some, true);
        REQUIRE(m.mask.bytes() == medial_diagram(ones).mask.bytes());
    }
}

TEST_CASE("long pruning lengths: boxes wider than 64 squares take the square-by-square search") {
    OccupancyGrid g(90, 100);
    scenes::fill(g, 20, 24, 10, 90);  // two long walls joined far away, a hall, a pillar
    scenes::fill(g, 60, 64, 10, 90);
    scenes::fill(g, 20, 64, 86, 90);
    scenes::fill(g, 40, 45, 40, 45);
    for (double prune : {70.0, 256.0}) {
        MedialOptions o;
        o.prune_length = prune;
        REQUIRE(medial_diagram(g, o).mask.bytes() == brute_force_medial(g, o));
    }
}

TEST_CASE("every corridor at least 2 pixels wide has a centreline within one pixel of its middle") {
    const int length = 20, top = 6;
    const OccupancyGrid g = scenes::corridors(length);
    const MedialDiagram m = medial_diagram(g);
    int c = 2;
    for (int w = 1; w <= 8; ++w) {
        const double middle = c + 0.5 * w;  // pixel units
        for (int r = top; r < top + length; ++r) {
            int near = 0;
            for (int x = c; x < c + w; ++x) near += m.mask[g.at(r, x)] && std::abs(x + 0.5 - middle) <= 1.0;
            INFO("corridor of width " << w << ", row " << r);
            if (w >= 2) CHECK(near >= 1);
            else CHECK(near == 0);  // a 1-pixel corridor has no pair of free pixels across it
        }
        c += w + 2;
    }
}

TEST_CASE("a loop of the diagram closes around every pillar; doors of 2 pixels and more are crossed") {
    const OccupancyGrid g = scenes::rooms();
    const MedialDiagram m = medial_diagram(g);
    // from next to each pillar, without crossing the diagram, the room's far corner is out of reach
    for (auto [r, c] : {std::pair<int, int>{7, 41}, std::pair<int, int>{27, 21}}) {
        const auto seen = reach_without_diagram(m, r, c);
        CHECK_FALSE(seen[g.at(2, 2)]);
        CHECK_FALSE(seen[g.at(37, 57)]);
    }
    // each door of width >= 2 holds diagram pixels in both of its wall rows
    int c = 4;
    for (int w = 1; w <= 5; ++w) {
        int in_door = 0;
        for (int r = 19; r < 21; ++r)
            for (int x = c; x < c + w; ++x) in_door += m.mask[g.at(r, x)];
        if (w >= 2) CHECK(in_door >= 2);
        c += w + 8;
    }
}

TEST_CASE("no spurs along staircase walls of slope 1:1 to 1:7") {
    // Away from the acute wedge where the staircase meets the map's left edge: a wedge's bisector is
    // a real branch of the medial axis, and the rule keeps it beyond its tip.
    for (int run : {1, 2, 3, 4, 5, 7}) {
        const OccupancyGrid g = scenes::staircase(run);
        const MedialDiagram m = medial_diagram(g);
        for (int r = 0; r < g.rows; ++r)
            for (int c = 4; c < g.cols; ++c)
                if (m.mask[g.at(r, c)]) {
                    INFO("run " << run << ", pixel (" << r << ", " << c << "), clearance " << m.clearance(r, c));
                    CHECK(m.clearance(r, c) >= 1.5);
                }
        // without pruning the steps' spurs reach the wall
        MedialOptions raw;
        raw.prune_length = 0.0;
        if (run >= 2) {
            const MedialDiagram s = medial_diagram(g, raw);
            bool spur = false;
            for (int r = 0; r < g.rows; ++r)
                for (int c = 0; c < g.cols; ++c) spur |= s.mask[g.at(r, c)] && s.clearance(r, c) < 1.5;
            CHECK(spur);
        }
    }
}

TEST_CASE("maps too narrow for a diagram give none; options are checked") {
    OccupancyGrid one_wide(9, 1);
    CHECK(medial_diagram(one_wide).count() == 0);
    OccupancyGrid full(4, 4);
    for (auto& v : full.occupied) v = 1;
    CHECK(medial_diagram(full).count() == 0);
    MedialOptions bad;
    for (double s : {0.5, 32768.5, 1e300, std::nan("")}) {
        bad.min_separation = s;
        CHECK_THROWS_WITH_AS(medial_diagram(one_wide, bad), doctest::Contains("min_separation must be a number in [1, 32768]"),
                             dvoronoi::InputError);
    }
    bad.min_separation = 32768.0;  // the largest: nothing is that far apart
    OccupancyGrid room(30, 40);
    CHECK(medial_diagram(room, bad).count() == 0);
    bad = MedialOptions{};
    bad.prune_length = std::nan("");
    CHECK_THROWS_WITH_AS(medial_diagram(one_wide, bad), doctest::Contains("prune_length"), dvoronoi::InputError);
    bad = MedialOptions{};
    bad.workers = 0;
    CHECK_THROWS_WITH_AS(medial_diagram(one_wide, bad), doctest::Contains("workers"), dvoronoi::InputError);
}
