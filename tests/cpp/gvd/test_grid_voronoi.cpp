// Grid Voronoi diagram of obstacles against the brute-force oracle (every corner labelled by scanning
// every obstacle): traced cells are oracle cells, every oracle cell is traced on connected diagrams,
// and every worker count and slice approach gives the single worker's cells.
#include "dvoronoi/gvd/brute_force.hpp"
#include "dvoronoi/gvd/grid_voronoi.hpp"
#include "dvoronoi/gvd/path.hpp"
#include "gvd/gvd_scenes.hpp"

#include <doctest/doctest.h>

#include <queue>

using namespace dvoronoi;
using namespace dvoronoi::gvd;
using namespace gvd_test;

namespace {

// Oracle cells reachable from the area-corner cells across label-changing edges (what tracing from
// the corners can find) and all oracle cells.
struct OracleSets {
    std::vector<std::uint8_t> mixed, reachable;
};

OracleSets oracle_sets(const Scene& scene, std::int64_t res) {
    const BruteForceLabels o = brute_force_labels(scene, res, true);
    const GridSpec& g = o.grid;
    const std::size_t w = static_cast<std::size_t>(g.nx) + 1;
    auto lab = [&](std::int32_t i, std::int32_t j) { return o.corner_label[static_cast<std::size_t>(j) * w + static_cast<std::size_t>(i)]; };
    auto idx = [&](std::int32_t i, std::int32_t j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(g.nx) + static_cast<std::size_t>(i); };
    OracleSets s;
    s.mixed = o.mixed;
    s.reachable.assign(o.mixed.size(), 0);
    std::queue<std::pair<std::int32_t, std::int32_t>> q;
    for (const Vec2& v : scene.area)
        for (std::int32_t j = 0; j < g.ny; ++j)
            for (std::int32_t i = 0; i < g.nx; ++i) {
                const Vec2 lo = g.corner(i, j), hi = g.corner(i + 1, j + 1);
                if (lo.x() <= v.x() && v.x() <= hi.x() && lo.y() <= v.y() && v.y() <= hi.y() && o.mixed[idx(i, j)] && !s.reachable[idx(i, j)]) {
                    s.reachable[idx(i, j)] = 1;
                    q.emplace(i, j);
                }
            }
    while (!q.empty()) {
        auto [i, j] = q.front();
        q.pop();
        auto go = [&](bool change, std::int32_t a, std::int32_t b) {
            if (!change || a < 0 || b < 0 || a >= g.nx || b >= g.ny) return;
            if (!o.mixed[idx(a, b)] || s.reachable[idx(a, b)]) return;
            s.reachable[idx(a, b)] = 1;
            q.emplace(a, b);
        };
        go(lab(i, j) != lab(i + 1, j), i, j - 1);
        go(lab(i + 1, j) != lab(i + 1, j + 1), i + 1, j);
        go(lab(i, j + 1) != lab(i + 1, j + 1), i, j + 1);
        go(lab(i, j) != lab(i, j + 1), i - 1, j);
    }
    return s;
}

std::vector<std::uint8_t> mask_of(const GridVoronoi& r) {
    std::vector<std::uint8_t> m(static_cast<std::size_t>(r.grid.nx) * static_cast<std::size_t>(r.grid.ny), 0);
    for (std::size_t k = 0; k < r.size(); ++k)
        m[static_cast<std::size_t>(r.row[k]) * static_cast<std::size_t>(r.grid.nx) + static_cast<std::size_t>(r.col[k])] = 1;
    return m;
}

void check_against_oracle(const Scene& scene, std::int64_t res, const char* name) {
    CAPTURE(name);
    CAPTURE(res);
    const OracleSets o = oracle_sets(scene, res);
    GvdOptions opt;
    opt.resolution = res;
    const GridVoronoi one = grid_voronoi(scene, opt);
    const auto m = mask_of(one);
    std::size_t extra = 0, missed_reachable = 0, oracle = 0, traced = 0;
    for (std::size_t k = 0; k < m.size(); ++k) {
        extra += m[k] && !o.mixed[k];
        missed_reachable += o.reachable[k] && !m[k];
        oracle += o.mixed[k];
        traced += m[k];
    }
    CHECK(extra == 0);             // never a cell the oracle does not mark
    CHECK(missed_reachable == 0);  // everything connected to the area corners is found
    CHECK(traced > 0);
    MESSAGE(std::string(name) << " res " << res << ": recall " << traced << "/" << oracle);
    for (int workers : {2, 3, 4, 7})
        for (SliceMode mode : {SliceMode::Cooperative, SliceMode::Independent}) {
            CAPTURE(workers);
            GvdOptions ok = opt;
            ok.workers = workers;
            ok.mode = mode;
            const GridVoronoi many = grid_voronoi(scene, ok);
            CHECK(many.col == one.col);
            CHECK(many.row == one.row);
            CHECK(many.labels == one.labels);
        }
}

}  // namespace

TEST_CASE("traced diagram equals the oracle's connected cells: random mixed maps") {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const Scene scene = make_scene(random_mixed(seed, 25), box_area(0, 0, 100, 100), true);
        check_against_oracle(scene, 48 + 16 * static_cast<int>(seed % 3), "random");
    }
}

TEST_CASE("paper maps: sea of triangles and mixed shapes") {
    check_against_oracle(make_scene(sea_of_triangles(3), box_area(0, 0, 100, 100), true), 96, "sea");
    check_against_oracle(make_scene(mixed_shapes(), box_area(0, 0, 100, 100), true), 80, "mixed");
}

TEST_CASE("non-square box and convex polygon working areas") {
    check_against_oracle(make_scene(random_mixed(11, 15), box_area(0, 0, 100, 60), true), 70, "box 100x60");
    const std::vector<Vec2> hexagon = {Vec2(50, -5), Vec2(105, 25), Vec2(105, 75), Vec2(50, 105), Vec2(-5, 75), Vec2(-5, 25)};
    check_against_oracle(make_scene(random_mixed(12, 15), hexagon), 64, "hexagon");
}

TEST_CASE("index and visibility test give the brute-force labels") {
    const Scene scene = make_scene(random_mixed(5, 40), box_area(0, 0, 100, 100), true);
    const ObstacleIndex with(scene, true), without(scene, false);
    QueryContext a = with.context(), b = without.context();
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-5.0, 105.0);
    for (int t = 0; t < 5000; ++t) {
        const Vec2 p(u(rng), u(rng));
        const Nearest bf = nearest_brute_force(scene, p, true);
        const Nearest n1 = with.nearest(p, a), n2 = without.nearest(p, b);
        CHECK(n1.label == bf.label);
        CHECK(n1.sq == bf.sq);
        CHECK(n2.label == bf.label);
    }
    CHECK(a.counters.edge_evaluations < b.counters.edge_evaluations);
}

TEST_CASE("blocked cells, vertices and roadmap") {
    const Scene scene = make_scene(mixed_shapes(), box_area(0, 0, 100, 100), true);
    GvdOptions opt;
    opt.resolution = 100;
    opt.robot_radius = 3.0;
    const GridVoronoi r = grid_voronoi(scene, opt);
    std::size_t blocked = 0;
    for (std::size_t k = 0; k < r.size(); ++k) {
        CHECK((r.blocked[k] != 0) == (r.clearance[k] <= 3.0));
        blocked += r.blocked[k];
    }
    CHECK(blocked > 0);
    CHECK(blocked < r.size());
    // the four area corners are Voronoi vertices (two edge labels plus ... ) and every vertex cell has >= 3 labels
    for (std::int64_t v : r.vertices) CHECK(r.distinct_labels(static_cast<std::size_t>(v)) >= 3);
    CHECK(r.vertices.size() >= 4);
    // roadmap: every traced cell is a node or on exactly one chain
    std::vector<int> seen(r.size(), 0);
    for (auto c : r.roadmap.node_cell) seen[static_cast<std::size_t>(c)]++;
    for (auto c : r.roadmap.chain_cells) seen[static_cast<std::size_t>(c)]++;
    for (int s : seen) CHECK(s == 1);
    for (std::size_t e = 0; e < r.roadmap.edge_u.size(); ++e) {
        const auto len = r.roadmap.chain_ptr[e + 1] - r.roadmap.chain_ptr[e];
        CHECK(r.roadmap.edge_length[e] == doctest::Approx(static_cast<double>(len + 1) * r.grid.h));
    }
}

TEST_CASE("paths are collision-free for the robot radius") {
    const Scene scene = make_scene(mixed_shapes(), box_area(0, 0, 100, 100), true);
    GvdOptions opt;
    opt.resolution = 128;
    opt.robot_radius = 1.5;
    const GridVoronoi r = grid_voronoi(scene, opt);
    const ObstacleIndex index(scene);
    const PathResult p = find_path(r, scene, index, Vec2(5, 5), Vec2(95, 95));
    REQUIRE(p.found());
    CHECK(p.points.front() == Vec2(5, 5));
    CHECK(p.points.back() == Vec2(95, 95));
    for (std::size_t t = 0; t + 1 < p.points.size(); ++t)
        for (const ConvexPart& part : scene.parts)
            CHECK(sq_segment_distance(scene, part, p.points[t], p.points[t + 1]) > 1.5 * 1.5);
    CHECK_THROWS_AS(find_path(r, scene, index, Vec2(45, 40.5), Vec2(95, 95)), InputError);  // within 1.5 of a point obstacle
    CHECK_THROWS_AS(find_path(r, scene, index, Vec2(5, 5), Vec2(70, 72)), InputError);       // inside the circle
    CHECK_THROWS_AS(find_path(r, scene, index, Vec2(-5, 5), Vec2(95, 95)), InputError);      // outside the area
}

TEST_CASE("bad input names the obstacle and field") {
    auto msg = [](auto f) {
        try { f(); } catch (const InputError& e) { return std::string(e.what()); }
        return std::string();
    };
    CHECK(msg([] { make_scene({Obstacle(Shape::circle(Vec2(1, 1), -1))}, box_area(0, 0, 10, 10)); }).find("obstacles[0].radius") != std::string::npos);
    CHECK(msg([] { make_scene({Obstacle(Shape::point(Vec2(1, 1))), Obstacle(Shape::polygon({Vec2(0, 0), Vec2(2, 2), Vec2(2, 0), Vec2(0, 2)}))}, box_area(0, 0, 10, 10)); }).find("obstacles[1].vertices: polygon is not simple") != std::string::npos);
    CHECK(msg([] { make_scene({Obstacle(Shape::polygon({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}))}, box_area(0, 0, 10, 10)); }).find("obstacles[0].vertices") != std::string::npos);
    CHECK(msg([] { make_scene({}, {Vec2(0, 0), Vec2(10, 0), Vec2(5, 2), Vec2(10, 10), Vec2(0, 10)}); }).find("area") != std::string::npos);
    CHECK(msg([] { make_scene({Obstacle(Shape::point(Vec2(NAN, 1)))}, box_area(0, 0, 10, 10)); }).find("obstacles[0].position") != std::string::npos);
}

TEST_CASE("non-convex polygons split into convex parts with one label") {
    const Scene scene = make_scene({Obstacle(ell(Vec2(10, 10), 30)), Obstacle(Shape::point(Vec2(80, 80)))}, box_area(0, 0, 100, 100), true);
    int parts0 = 0;
    double area = 0;
    for (const ConvexPart& p : scene.parts)
        if (p.label == 0) {
            ++parts0;
            std::vector<Vec2> v(scene.part_vertices(p), scene.part_vertices(p) + p.count);
            CHECK(gvd::detail::ring_is_convex(v));
            area += gvd::detail::signed_area2(v) / 2;
        }
    CHECK(parts0 == 2);
    CHECK(area == doctest::Approx(30.0 * 30.0 * (1.0 - 4.0 / 9.0)));
}
