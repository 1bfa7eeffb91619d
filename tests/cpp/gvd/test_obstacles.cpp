// Compiling obstacles into a scene: repeated vertices collapse to one (a closed ring, as GeoJSON
// writes it, keeps every corner), for obstacles and for the working area alike.
#include "dvoronoi/gvd/brute_force.hpp"
#include "dvoronoi/gvd/grid_voronoi.hpp"
#include "dvoronoi/gvd/obstacles.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace dvoronoi;
using namespace dvoronoi::gvd;

namespace {

const std::vector<Vec2> kSquare = {Vec2(40, 40), Vec2(60, 40), Vec2(60, 60), Vec2(40, 60)};

std::vector<Vec2> closed(std::vector<Vec2> v) {
    v.push_back(v.front());
    return v;
}

std::vector<Vec2> part_vertices(const Scene& s, const ConvexPart& p) {
    return {s.part_vertices(p), s.part_vertices(p) + p.count};
}

/// The convex parts (kind, label, vertices) of two scenes are the same.
void check_same_parts(const Scene& a, const Scene& b) {
    REQUIRE(a.parts.size() == b.parts.size());
    CHECK(a.n_labels == b.n_labels);
    CHECK(a.area == b.area);
    for (std::size_t k = 0; k < a.parts.size(); ++k) {
        CAPTURE(k);
        CHECK(a.parts[k].kind == b.parts[k].kind);
        CHECK(a.parts[k].label == b.parts[k].label);
        CHECK(part_vertices(a, a.parts[k]) == part_vertices(b, b.parts[k]));
    }
}

/// Same traced cells and corner labels.
void check_same_diagram(const Scene& a, const Scene& b) {
    GvdOptions opt;
    opt.resolution = 64;
    const GridVoronoi ra = grid_voronoi(a, opt), rb = grid_voronoi(b, opt);
    CHECK(ra.col == rb.col);
    CHECK(ra.row == rb.row);
    CHECK(ra.labels == rb.labels);
}

}  // namespace

TEST_CASE("a closed polygon ring keeps all its corners") {
    const Scene open = make_scene({Obstacle(Shape::polygon(kSquare))}, box_area(0, 0, 100, 100), true);
    const Scene ring = make_scene({Obstacle(Shape::polygon(closed(kSquare)))}, box_area(0, 0, 100, 100), true);
    REQUIRE(ring.parts.size() == 5);  // the square and the area's four edges
    CHECK(ring.parts[0].kind == ShapeKind::Polygon);
    CHECK(ring.parts[0].count == 4);
    check_same_parts(open, ring);
    // Just outside each corner the square is sqrt(2) away (a triangle would be much farther at one).
    for (const Vec2& c : kSquare) {
        const Vec2 q = c + (c - Vec2(50, 50)) / 10.0;
        const Nearest n = nearest_brute_force(ring, q, true);
        CAPTURE(q.transpose());
        CHECK(n.label == 0);
        CHECK(n.sq == doctest::Approx(2.0));
    }
    check_same_diagram(open, ring);
    // Either orientation, and a non-convex ring (split into convex parts) too.
    std::vector<Vec2> cw(kSquare.rbegin(), kSquare.rend());
    check_same_parts(open, make_scene({Obstacle(Shape::polygon(closed(cw)))}, box_area(0, 0, 100, 100), true));
    const std::vector<Vec2> ell = {Vec2(10, 10), Vec2(40, 10), Vec2(40, 20), Vec2(20, 20), Vec2(20, 40), Vec2(10, 40)};
    check_same_parts(make_scene({Obstacle(Shape::polygon(ell))}, box_area(0, 0, 100, 100), true),
                     make_scene({Obstacle(Shape::polygon(closed(ell)))}, box_area(0, 0, 100, 100), true));
}

TEST_CASE("repeated vertices anywhere in the ring collapse to one") {
    const Vec2 A(40, 40), B(60, 40), C(60, 60), D(40, 60);
    const Scene open = make_scene({Obstacle(Shape::polygon({A, B, C, D}))}, box_area(0, 0, 100, 100), true);
    for (const auto& v : std::vector<std::vector<Vec2>>{{A, A, B, C, C, D},
                                                         {A, B, B, B, C, D},
                                                         {A, B, C, D, D, A, A},
                                                         {A, A, B, C, D, A}}) {
        CAPTURE(v.size());
        check_same_parts(open, make_scene({Obstacle(Shape::polygon(v))}, box_area(0, 0, 100, 100), true));
    }
    // Collinear vertices still go, repeated or not; too few distinct vertices is still an error.
    check_same_parts(open, make_scene({Obstacle(Shape::polygon({A, B, B, Vec2(60, 50), C, D, A}))},
                                      box_area(0, 0, 100, 100), true));
    CHECK_THROWS_AS(make_scene({Obstacle(Shape::polygon({A, A, B, B, A}))}, box_area(0, 0, 100, 100)), InputError);
    CHECK_THROWS_AS(make_scene({Obstacle(Shape::polygon({A, B, B, Vec2(80, 40), A}))}, box_area(0, 0, 100, 100)),
                    InputError);
}

TEST_CASE("a closed working-area ring keeps all its edges") {
    const std::vector<Vec2> box = {Vec2(0, 0), Vec2(100, 0), Vec2(100, 100), Vec2(0, 100)};
    const std::vector<Obstacle> obstacles = {Obstacle(Shape::polygon(kSquare)), Obstacle(Shape::point(Vec2(80, 20)))};
    const Scene open = make_scene(obstacles, box);
    const Scene ring = make_scene(obstacles, closed(box));
    CHECK(ring.area.size() == 4);
    CHECK(ring.n_labels == 2 + 4);
    check_same_parts(open, ring);
    check_same_diagram(open, ring);
    // The area's corner that the closing vertex repeats is still a corner: its edges are labels of
    // their own, nearest at points beside it.
    CHECK(nearest_brute_force(ring, Vec2(1, 3), true).label == 2 + 3);
    CHECK(nearest_brute_force(ring, Vec2(3, 1), true).label == 2 + 0);
    check_same_parts(open, make_scene(obstacles, {box[0], box[0], box[1], box[2], box[2], box[3], box[0]}));
}
