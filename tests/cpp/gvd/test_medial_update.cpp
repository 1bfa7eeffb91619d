#include "dvoronoi/gvd/medial_update.hpp"
#include "occupancy_scenes.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace dvoronoi::gvd;

namespace {

void require_same_as_full_build(const MedialDiagram& m) {
    const MedialDiagram full = medial_diagram(m.grid, m.options);
    REQUIRE(m.features.vgap == full.features.vgap);
    REQUIRE(m.features.fx == full.features.fx);
    REQUIRE(m.features.fy == full.features.fy);
    REQUIRE(m.mask == full.mask);
    REQUIRE(m.boxed == full.boxed);  // the pixels an update rechecks near a change
    if (!m.block_sq.empty()) {  // the bounds of each block's clearance that updates keep
        const std::vector<std::int32_t> now = detail::block_clearances(full.features);
        REQUIRE(m.block_sq.size() == now.size());
        for (std::size_t b = 0; b < now.size(); ++b) REQUIRE(m.block_sq[b] >= now[b]);
    }
}

/// The free pixels of `count` square blobs at random places, sides min_side .. min_side + sides - 1
/// (a pixel of two blobs comes twice: an update skips pixels already so).
std::vector<std::size_t> free_blob_pixels(const MedialDiagram& m, std::mt19937& rng, int count, int min_side, int sides) {
    std::vector<std::size_t> px;
    for (int b = 0; b < count; ++b) {
        const int side = min_side + static_cast<int>(rng() % static_cast<unsigned>(sides));
        const int r0 = static_cast<int>(rng() % static_cast<unsigned>(m.grid.rows - side));
        const int c0 = static_cast<int>(rng() % static_cast<unsigned>(m.grid.cols - side));
        for (int r = r0; r < r0 + side; ++r)
            for (int c = c0; c < c0 + side; ++c)
                if (!m.grid.occ(r, c)) px.push_back(m.grid.at(r, c));
    }
    return px;
}

/// The pixels whose nearest point differs between two transforms.
std::uint64_t moved(const FeatureMap& a, const FeatureMap& b) {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < a.fx.size(); ++i) n += a.fx[i] != b.fx[i] || a.fy[i] != b.fy[i];
    return n;
}

}  // namespace

TEST_CASE("after any sequence of additions and removals the diagram is the full build's") {
    for (unsigned seed = 0; seed < 400; ++seed) {
        std::mt19937 rng(seed);
        OccupancyGrid g = seed % 7 == 0 ? scenes::rooms() : scenes::clutter(seed, 60);
        MedialOptions o;
        o.prune_length = static_cast<double>(seed % 4) * 3.0;
        MedialDiagram m = medial_diagram(g, o);
        for (int step = 0; step < 10; ++step) {
            const unsigned kind = rng() % 3;
            if (kind < 2) {  // a block becomes occupied or free
                std::vector<std::size_t> px;
                const int r0 = static_cast<int>(rng() % static_cast<unsigned>(g.rows));
                const int c0 = static_cast<int>(rng() % static_cast<unsigned>(g.cols));
                const int h = 1 + static_cast<int>(rng() % 5), w = 1 + static_cast<int>(rng() % 5);
                for (int r = r0; r < std::min(g.rows, r0 + h); ++r)
                    for (int c = c0; c < std::min(g.cols, c0 + w); ++c) px.push_back(g.at(r, c));
                const FeatureMap before = m.features;
                const UpdateStats st = set_pixels(m, px, kind == 0);
                // each pixel whose nearest point changed, once (one direction: a point never moves back)
                CHECK(st.feature_changes == moved(before, m.features));
            } else {  // scattered flips in both directions at once
                std::vector<std::uint8_t> occ(m.grid.occupied.begin(), m.grid.occupied.end());
                const unsigned flips = 1 + rng() % 30;
                for (unsigned k = 0; k < flips; ++k) occ[rng() % occ.size()] ^= 1;
                const FeatureMap before = m.features;
                const UpdateStats st = update_occupancy(m, occ);
                CHECK(st.feature_changes >= moved(before, m.features));  // and a point moved back counts
                CHECK(st.feature_changes >= st.changed_pixels);
            }
            INFO("seed " << seed << ", step " << step);
            require_same_as_full_build(m);
        }
    }
}

TEST_CASE("blobs put into open space and next to walls: the diagram is the full build's") {
    // Large open maps, where an update skips the search for pixels whose nearest point lies near a
    // blob when no unchanged wall is near it, and blobs next to walls and the border, where it cannot.
    for (unsigned seed = 0; seed < 60; ++seed) {
        std::mt19937 rng(seed);
        OccupancyGrid g(128, 128 + static_cast<std::int32_t>(seed % 3) * 17);
        for (int k = 0; k < 3; ++k) {  // a few walls
            const int r0 = static_cast<int>(rng() % 110), c0 = static_cast<int>(rng() % 110);
            const bool across = rng() % 2 == 0;
            for (int t = 0; t < 40; ++t) {
                const int r = across ? r0 : std::min(g.rows - 1, r0 + t), c = across ? std::min(g.cols - 1, c0 + t) : c0;
                g.occupied[g.at(r, c)] = 1;
            }
        }
        MedialOptions o;
        const double prune[4] = {0.0, 3.0, 8.0, 20.0};
        o.prune_length = prune[seed % 4];
        MedialDiagram m = medial_diagram(g, o);
        for (int step = 0; step < 8; ++step) {
            const std::vector<std::size_t> px = free_blob_pixels(m, rng, 3, 2, 5);
            set_pixels(m, px, true);
            INFO("seed " << seed << ", step " << step << ", added");
            require_same_as_full_build(m);
            if (step % 2 == 1) {
                set_pixels(m, px, false);
                INFO("seed " << seed << ", step " << step << ", removed");
                require_same_as_full_build(m);
            }
        }
    }
}

TEST_CASE("blobs side by side, on the map's edge and across corridors: the diagram is the full build's") {
    // Cases the update handles apart: runs of new pixels that meet in a column or a row (one blob's
    // walk reaches the other's), blobs whose walks end at the outside, corridors closed by a blob and
    // opened again (a removal whose pixels take points beyond the reopened gap), and a wall taken
    // away while a blob appears.
    auto block = [](const OccupancyGrid& g, int r0, int c0, int h, int w) {
        std::vector<std::size_t> px;
        for (int r = std::max(0, r0); r < std::min(g.rows, r0 + h); ++r)
            for (int c = std::max(0, c0); c < std::min(g.cols, c0 + w); ++c) px.push_back(g.at(r, c));
        return px;
    };
    for (const double prune : {0.0, 3.0, 8.0, 20.0}) {
        for (int variant = 0; variant < 3; ++variant) {
            OccupancyGrid g = variant == 0 ? scenes::corridors(30) : (variant == 1 ? scenes::rooms() : OccupancyGrid(70, 131));
            MedialOptions o;
            o.prune_length = prune;
            MedialDiagram m = medial_diagram(g, o);
            auto step = [&](const std::vector<std::size_t>& px, bool occupied, const char* what) {
                set_pixels(m, px, occupied);
                INFO("prune " << prune << ", map " << variant << ": " << what);
                require_same_as_full_build(m);
            };
            const int H = g.rows, W = g.cols;
            // side by side, above one another and corner to corner, in one update and then one at a time
            std::vector<std::size_t> pair = block(g, H / 2 - 3, W / 3, 3, 4), other = block(g, H / 2 - 3, W / 3 + 4, 3, 4);
            pair.insert(pair.end(), other.begin(), other.end());
            const std::vector<std::size_t> below = block(g, H / 2, W / 3 + 2, 2, 3), corner = block(g, H / 2 + 2, W / 3 + 5, 2, 2);
            step(pair, true, "two blocks side by side");
            step(below, true, "a block under them");
            step(corner, true, "a block touching a corner");
            step(other, false, "one of the pair removed");
            step(below, false, "the block under them removed");
            step(pair, false, "the rest of the pair removed");
            step(corner, false, "the corner block removed");
            // on the edge and in the corners of the map
            for (const auto& rc : {std::pair<int, int>{0, 0}, {0, W - 3}, {H - 2, 0}, {H - 3, W - 4}, {0, W / 2}, {H / 2, 0}, {H / 2, W - 1}}) {
                const std::vector<std::size_t> px = block(g, rc.first, rc.second, 3, 4);
                step(px, true, "a block on the edge");
                step(px, false, "a block on the edge removed");
            }
            // a blob across the map's full height closes every corridor it crosses; taking it away opens them
            const std::vector<std::size_t> across = block(g, 0, W / 2 - 1, H, 2);
            step(across, true, "a wall across the map");
            step(across, false, "the wall across the map removed");
            // a wall removed and a blob added in one update_occupancy
            std::vector<std::uint8_t> occ(m.grid.occupied.begin(), m.grid.occupied.end());
            for (int c = 0; c < W; ++c) occ[g.at(H / 3, c)] ^= 1;
            for (std::size_t i : block(g, 2 * H / 3, W / 4, 4, 6)) occ[i] = 1;
            update_occupancy(m, occ);
            INFO("prune " << prune << ", map " << variant << ": a row flipped and a blob added at once");
            require_same_as_full_build(m);
        }
    }
}

TEST_CASE("block_clearances: the largest squared clearance of each 32 x 32 block") {
    for (unsigned seed = 0; seed < 40; ++seed) {
        const OccupancyGrid g = seed % 5 == 0 ? scenes::rooms() : scenes::clutter(seed, 100);
        const FeatureMap f = feature_transform(g);
        const std::vector<std::int32_t> got = detail::block_clearances(f);
        const std::int32_t bw = (g.cols + 31) / 32;
        std::vector<std::int32_t> want(static_cast<std::size_t>(bw * ((g.rows + 31) / 32)), 0);
        for (int r = 0; r < g.rows; ++r)
            for (int c = 0; c < g.cols; ++c) {
                std::int32_t& w = want[static_cast<std::size_t>(r / 32 * bw + c / 32)];
                w = std::max(w, static_cast<std::int32_t>(f.sq(r, c)));
            }
        INFO("seed " << seed << ": " << g.rows << " x " << g.cols);
        REQUIRE(got == want);
    }
}

TEST_CASE("OccupancyBits::free_run finds the free columns around one, across words") {
    std::mt19937 rng(7);
    for (int t = 0; t < 200; ++t) {
        OccupancyGrid g(3, 1 + static_cast<int>(rng() % 300));
        for (auto& v : g.occupied) v = rng() % (2 + t % 40) == 0 ? 1 : 0;
        const OccupancyBits bits(g);
        for (int r = 0; r < g.rows; ++r)
            for (int c = 0; c < g.cols; ++c) {
                if (g.occ(r, c)) continue;
                int s = c, e = c;
                while (s > 0 && !g.occ(r, s - 1)) --s;
                while (e + 1 < g.cols && !g.occ(r, e + 1)) ++e;
                const auto run = bits.free_run(g.rows - 1 - r, c);
                REQUIRE(run.first == s);
                REQUIRE(run.second == e);
            }
    }
}

TEST_CASE("an update reports what it touched and rejects bad input") {
    MedialDiagram m = medial_diagram(scenes::rooms());
    const auto before = m.mask;
    const UpdateStats none = set_pixels(m, {m.grid.at(0, 0)}, true);  // already occupied
    CHECK(none.changed_pixels == 0);
    CHECK(m.mask == before);
    const UpdateStats st = set_pixels(m, {m.grid.at(30, 40), m.grid.at(30, 41)}, true);
    CHECK(st.changed_pixels == 2);
    CHECK(st.feature_changes > 0);
    CHECK_THROWS_WITH_AS(set_pixels(m, {m.grid.size()}, true), doctest::Contains("outside"), dvoronoi::InputError);
    CHECK_THROWS_WITH_AS(update_occupancy(m, std::vector<std::uint8_t>(3, 0)), doctest::Contains("3 pixels"),
                         dvoronoi::InputError);
}

TEST_CASE("for_each_difference lists every pixel whose occupancy differs, in order") {
    std::mt19937 rng(7);
    for (std::size_t n : {0, 1, 63, 64, 65, 127, 128, 200, 1000}) {
        for (int density : {0, 1, 50}) {  // differing bytes per 1,000
            std::vector<std::uint8_t> a(n), b(n);
            for (std::size_t i = 0; i < n; ++i) {
                a[i] = static_cast<std::uint8_t>(rng() % 2 == 0 ? 0 : (rng() % 2 == 0 ? 1 : 255));  // nonzero bytes differ in value
                b[i] = static_cast<std::uint8_t>(a[i] == 0 ? 0 : 1 + rng() % 255);
                if (static_cast<int>(rng() % 1000) < density) b[i] = b[i] == 0 ? 1 : 0;
            }
            for (const bool vs_zero : {false, true}) {
                std::vector<std::size_t> want, got;
                for (std::size_t i = 0; i < n; ++i)
                    if ((a[i] != 0) != (!vs_zero && b[i] != 0)) want.push_back(i);
                detail::for_each_difference(a.data(), vs_zero ? nullptr : b.data(), n, [&](std::size_t i) { got.push_back(i); });
                INFO("n " << n << ", density " << density << ", against zero " << vs_zero);
                CHECK(got == want);
            }
        }
    }
}

TEST_CASE("updates on several workers give the full build's diagram") {
    // Updates large enough to be split over the workers (rows in groups of block rows, re-marking in
    // chunks of rows): the same nearest points, diagram and bounds as a build, for 2 and 3 workers.
    for (unsigned seed = 0; seed < 6; ++seed) {
        std::mt19937 rng(seed);
        OccupancyGrid g(300 + static_cast<std::int32_t>(seed) * 13, 260 + static_cast<std::int32_t>(seed % 2) * 31);
        for (int k = 0; k < 6; ++k) {  // walls, some touching the border
            const int r0 = static_cast<int>(rng() % static_cast<unsigned>(g.rows)), c0 = static_cast<int>(rng() % static_cast<unsigned>(g.cols));
            const bool across = rng() % 2 == 0;
            for (int t = 0; t < 120; ++t) {
                const int r = across ? r0 : std::min(g.rows - 1, r0 + t), c = across ? std::min(g.cols - 1, c0 + t) : c0;
                g.occupied[g.at(r, c)] = 1;
            }
        }
        MedialOptions o;
        o.workers = 2 + static_cast<int>(seed % 2);
        MedialDiagram m = medial_diagram(g, o);
        for (int step = 0; step < 4; ++step) {
            const std::vector<std::size_t> px = free_blob_pixels(m, rng, 16, 8, 12);
            const UpdateStats added = set_pixels(m, px, true);
            INFO("seed " << seed << ", step " << step << ", workers " << o.workers);
            CHECK(added.column_cells > 3 * detail::Updater::kCellsPerWorker);  // large enough to split
            require_same_as_full_build(m);
            set_pixels(m, px, false);
            require_same_as_full_build(m);
        }
    }
}
