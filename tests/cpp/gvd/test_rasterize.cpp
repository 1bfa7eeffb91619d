#include "dvoronoi/gvd/medial_brute_force.hpp"
#include "dvoronoi/gvd/rasterize.hpp"
#include "gvd_scenes.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace gvd_test;

namespace {

/// Sandwich the raster between two tests that share nothing with it: a pixel whose centre lies on an
/// obstacle is occupied, and an occupied pixel inside the area has an obstacle within half its
/// diagonal of its centre.
void check_sandwich(const Scene& scene, std::int64_t cells) {
    const OccupancyGrid g = rasterize(scene, cells);
    const double h = g.resolution;
    for (std::int32_t r = 0; r < g.rows; ++r)
        for (std::int32_t c = 0; c < g.cols; ++c) {
            const Vec2 p = g.center(r, c);
            double best = std::numeric_limits<double>::infinity();
            for (const ConvexPart& part : scene.parts)
                if (part.label < scene.n_obstacles) best = std::min(best, sq_distance(scene, part, p, false));
            const bool inside_area = p.x() + h / 2 <= scene.box.x1 && p.y() + h / 2 <= scene.box.y1;
            INFO("pixel (" << r << ", " << c << "), squared distance " << best);
            if (best == 0.0) CHECK(g.occ(r, c));
            if (g.occ(r, c) && inside_area) CHECK(best <= 0.5 * h * h * (1 + 1e-9));
        }
}

}  // namespace

TEST_CASE("a rasterised document: occupied exactly where obstacles meet pixels, area edges as walls") {
    for (unsigned seed = 0; seed < 12; ++seed)
        check_sandwich(make_scene(random_mixed(seed, 12), box_area(0, 0, 100, 100)), 96 + seed * 7);
    check_sandwich(make_scene(mixed_shapes(), box_area(0, 0, 100, 100)), 128);
    // a convex polygon area: pixels not wholly inside are walls
    const Scene tri = make_scene({}, {Vec2(0, 0), Vec2(40, 0), Vec2(0, 30)});
    const OccupancyGrid g = rasterize(tri, 40);
    CHECK(g.occ(0, 39));                // the top-right corner lies outside the triangle
    CHECK_FALSE(g.occ(g.rows - 2, 1));  // near the right angle: inside
}

TEST_CASE("the medial diagram of a document separates the arms of one non-convex obstacle") {
    // a U: two arms joined at the bottom, a corridor between them
    Obstacle u;
    u.shapes.push_back(Shape::polygon({Vec2(20, 10), Vec2(80, 10), Vec2(80, 70), Vec2(60, 70), Vec2(60, 30),
                                       Vec2(40, 30), Vec2(40, 70), Vec2(20, 70)}));
    const Scene scene = make_scene({u}, box_area(0, 0, 100, 100));
    const OccupancyGrid g = rasterize(scene, 100);
    const MedialDiagram m = medial_diagram(g);
    CHECK(m.mask.bytes() == brute_force_medial(g));
    // the corridor 40 < x < 60 between the arms: a centreline at x = 50 from half its width above the
    // closed bottom (y = 30) to its open top (y = 70)
    int on_centreline = 0;
    for (int y = 42; y < 66; ++y) {
        const int r = g.rows - 1 - y;
        on_centreline += m.mask(r, 49) || m.mask(r, 50);
    }
    CHECK(on_centreline == 24);
}
