// Grid Voronoi diagram of obstacles against the brute-force oracle (every corner labelled by scanning
// every obstacle): the traced cells are exactly the oracle's diagram cells — isolated pieces
// included — for every worker count and both slice approaches, on random scenes, the paper's maps,
// scenes with slivers thinner than a cell, an island inside a ring, and occupancy-grid maps whose
// area corners lie inside walls.
#include "dvoronoi/gvd/brute_force.hpp"
#include "dvoronoi/gvd/grid_voronoi.hpp"
#include "dvoronoi/gvd/path.hpp"
#include "gvd/gvd_scenes.hpp"
#include "gvd/occupancy_scenes.hpp"

#include <doctest/doctest.h>

#include <queue>

using namespace dvoronoi;
using namespace dvoronoi::gvd;
using namespace gvd_test;

namespace {

// The oracle's diagram cells, and its pieces: cells joined across label-changing edges (what the
// paper's tracing follows from a cell).
struct OracleSets {
    std::vector<std::uint8_t> mixed;
    std::vector<std::int32_t> piece;  // per cell, -1 off the diagram
    std::int32_t pieces = 0;
    std::vector<std::int32_t> piece_size;
    std::vector<std::uint8_t> at_area_corner;  // per piece: holds a cell at one of the area's corners
};

OracleSets oracle_sets(const Scene& scene, std::int64_t res) {
    const BruteForceLabels o = brute_force_labels(scene, res, true);
    const GridSpec& g = o.grid;
    const std::size_t w = static_cast<std::size_t>(g.nx) + 1;
    auto lab = [&](std::int32_t i, std::int32_t j) { return o.corner_label[static_cast<std::size_t>(j) * w + static_cast<std::size_t>(i)]; };
    auto idx = [&](std::int32_t i, std::int32_t j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(g.nx) + static_cast<std::size_t>(i); };
    OracleSets s;
    s.mixed = o.mixed;
    s.piece.assign(o.mixed.size(), -1);
    for (std::int32_t j0 = 0; j0 < g.ny; ++j0)
        for (std::int32_t i0 = 0; i0 < g.nx; ++i0) {
            if (!o.mixed[idx(i0, j0)] || s.piece[idx(i0, j0)] >= 0) continue;
            const std::int32_t p = s.pieces++;
            s.piece_size.push_back(0);
            std::queue<std::pair<std::int32_t, std::int32_t>> q;
            s.piece[idx(i0, j0)] = p;
            q.emplace(i0, j0);
            while (!q.empty()) {
                auto [i, j] = q.front();
                q.pop();
                ++s.piece_size.back();
                auto go = [&](bool change, std::int32_t a, std::int32_t b) {
                    if (!change || a < 0 || b < 0 || a >= g.nx || b >= g.ny) return;
                    if (!o.mixed[idx(a, b)] || s.piece[idx(a, b)] >= 0) return;
                    s.piece[idx(a, b)] = p;
                    q.emplace(a, b);
                };
                go(lab(i, j) != lab(i + 1, j), i, j - 1);
                go(lab(i + 1, j) != lab(i + 1, j + 1), i + 1, j);
                go(lab(i, j + 1) != lab(i + 1, j + 1), i, j + 1);
                go(lab(i, j) != lab(i, j + 1), i - 1, j);
            }
        }
    s.at_area_corner.assign(static_cast<std::size_t>(s.pieces), 0);
    for (const Vec2& v : scene.area) {
        std::int32_t ci, cj;
        g.locate(v, ci, cj);
        for (std::int32_t j = cj - 1; j <= cj + 1; ++j)
            for (std::int32_t i = ci - 1; i <= ci + 1; ++i) {
                if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) continue;
                const Vec2 lo = g.corner(i, j), hi = g.corner(i + 1, j + 1);
                if (lo.x() <= v.x() && v.x() <= hi.x() && lo.y() <= v.y() && v.y() <= hi.y() && s.piece[idx(i, j)] >= 0)
                    s.at_area_corner[static_cast<std::size_t>(s.piece[idx(i, j)])] = 1;
            }
    }
    return s;
}

std::vector<std::uint8_t> mask_of(const GridVoronoi& r) {
    std::vector<std::uint8_t> m(static_cast<std::size_t>(r.grid.nx) * static_cast<std::size_t>(r.grid.ny), 0);
    for (std::size_t k = 0; k < r.size(); ++k)
        m[static_cast<std::size_t>(r.row[k]) * static_cast<std::size_t>(r.grid.nx) + static_cast<std::size_t>(r.col[k])] = 1;
    return m;
}

/// The traced cells are exactly the oracle's, for 1, 2, 3, 4 and 7 workers and both approaches.
/// Returns the oracle's sets.
OracleSets check_against_oracle(const Scene& scene, std::int64_t res, const char* name) {
    CAPTURE(name);
    CAPTURE(res);
    const OracleSets o = oracle_sets(scene, res);
    GvdOptions opt;
    opt.resolution = res;
    opt.graph = false;
    const GridVoronoi one = grid_voronoi(scene, opt);
    for (int workers : {1, 2, 3, 4, 7})
        for (SliceMode mode : {SliceMode::Cooperative, SliceMode::Independent}) {
            CAPTURE(workers);
            CAPTURE(static_cast<int>(mode));
            GvdOptions ok = opt;
            ok.workers = workers;
            ok.mode = mode;
            const GridVoronoi r = grid_voronoi(scene, ok);
            const auto m = mask_of(r);
            std::size_t extra = 0, missed = 0;
            for (std::size_t k = 0; k < m.size(); ++k) {
                extra += m[k] && !o.mixed[k];
                missed += o.mixed[k] && !m[k];
            }
            CHECK(extra == 0);   // never a cell the oracle does not mark
            CHECK(missed == 0);  // every cell it marks, isolated pieces included
            CHECK(r.stats.traced_cells == r.size());
            CHECK(r.stats.discarded_cells == 0);
            CHECK(r.col == one.col);
            CHECK(r.row == one.row);
            CHECK(r.labels == one.labels);
            CHECK(r.clearance == one.clearance);
        }
    return o;
}

/// Obstacles as dv.obstacles_from_occupancy_grid builds them: each 8-connected occupied region one
/// obstacle (a union of its row runs), the map's extent the (box) working area.
Scene occupancy_scene(const OccupancyGrid& g, double res, Vec2 origin) {
    const std::int32_t H = g.rows, W = g.cols;
    std::vector<std::int32_t> region(g.size(), -1);
    std::int32_t n = 0;
    for (std::int32_t r0 = 0; r0 < H; ++r0)
        for (std::int32_t c0 = 0; c0 < W; ++c0) {
            if (!g.occupied[g.at(r0, c0)] || region[g.at(r0, c0)] >= 0) continue;
            std::queue<std::pair<std::int32_t, std::int32_t>> q;
            region[g.at(r0, c0)] = n;
            q.emplace(r0, c0);
            while (!q.empty()) {
                auto [r, c] = q.front();
                q.pop();
                for (int dr = -1; dr <= 1; ++dr)
                    for (int dc = -1; dc <= 1; ++dc) {
                        const std::int32_t rr = r + dr, cc = c + dc;
                        if (rr < 0 || cc < 0 || rr >= H || cc >= W || !g.occupied[g.at(rr, cc)] || region[g.at(rr, cc)] >= 0) continue;
                        region[g.at(rr, cc)] = n;
                        q.emplace(rr, cc);
                    }
            }
            ++n;
        }
    std::vector<std::vector<Shape>> parts(static_cast<std::size_t>(n));
    for (std::int32_t r = 0; r < H; ++r)
        for (std::int32_t c = 0; c < W;) {
            const std::int32_t k = region[g.at(r, c)];
            if (k < 0) { ++c; continue; }
            std::int32_t e = c;
            while (e < W && region[g.at(r, e)] == k) ++e;
            const double ya = origin.y() + (H - 1 - r) * res, yb = origin.y() + (H - r) * res;
            const double xa = origin.x() + c * res, xb = origin.x() + e * res;
            parts[static_cast<std::size_t>(k)].push_back(Shape::polygon({Vec2(xa, ya), Vec2(xb, ya), Vec2(xb, yb), Vec2(xa, yb)}));
            c = e;
        }
    std::vector<Obstacle> obstacles;
    for (auto& p : parts) obstacles.emplace_back(std::move(p));
    return make_scene(obstacles, box_area(origin.x(), origin.y(), origin.x() + W * res, origin.y() + H * res), true);
}

}  // namespace

TEST_CASE("traced diagram equals the oracle: random mixed maps") {
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

TEST_CASE("every piece is found: overlapping clutter, obstacles across or outside the area, rings") {
    std::mt19937 rng(19);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int disconnected = 0;
    for (int trial = 0; trial < 24; ++trial) {
        std::vector<Vec2> area;
        bool box = false;
        if (trial % 3 == 0) {
            const int m = 3 + trial % 6;
            const double ph = 6.28 * u(rng);
            for (int t = 0; t < m; ++t) area.emplace_back(50 + 55 * std::cos(ph + 2 * M_PI * t / m), 50 + 55 * std::sin(ph + 2 * M_PI * t / m));
        } else {
            area = box_area(0, 0, 100, trial % 3 == 1 ? 100 : 30 + 70 * u(rng));
            box = true;
        }
        const Scene scene = make_scene(random_clutter(rng, 1 + trial % 29), area, box);
        const int res[] = {8, 13, 24, 50, 77, 128};
        const OracleSets o = check_against_oracle(scene, res[trial % 6], "clutter");
        disconnected += o.pieces > 1;
    }
    CHECK(disconnected >= 5);  // the scenes exercise disconnected diagrams
}

TEST_CASE("slivers thinner than a cell: a grid corner inside one is joined to nothing") {
    int tiny = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const Scene scene = make_scene(needles(seed, 6), box_area(0, 0, 100, 100), true);
        const OracleSets o = check_against_oracle(scene, 100 + 17 * seed, "needles");
        for (std::int32_t size : o.piece_size) tiny += size <= 8;
    }
    CHECK(tiny >= 5);  // tiny pieces exist (and were found)
}

TEST_CASE("an island inside a ring: its loop is found though no area corner reaches it") {
    const std::vector<Obstacle> obstacles = {ring(20, 25, 80, 75, 3.0), Obstacle(Shape::circle(Vec2(47, 52), 6)),
                                             Obstacle(Shape::point(Vec2(10, 90))), ring(35, 35, 65, 68, 1.5)};
    const Scene scene = make_scene(obstacles, box_area(0, 0, 100, 100), true);
    const OracleSets o = check_against_oracle(scene, 97, "island in rings");
    int unreached = 0;
    for (std::uint8_t a : o.at_area_corner) unreached += a == 0;
    CHECK(unreached >= 2);  // the loops between the rings and around the island
    GvdOptions opt;
    opt.resolution = 97;
    opt.workers = 3;
    const GridVoronoi r = grid_voronoi(scene, opt);
    std::size_t loop = 0;
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (std::size_t k = 0; k < r.size(); ++k) {
        bool island = false, inner = false, other = false;
        for (int t = 0; t < 4; ++t) {
            const std::int32_t l = r.labels[4 * k + static_cast<std::size_t>(t)];
            island |= l == 1;
            inner |= l == 3;
            other |= l != 1 && l != 3;
        }
        if (!(island && inner && !other)) continue;
        ++loop;
        const Vec2 c = r.grid.center(r.col[k], r.row[k]);
        x0 = std::min(x0, c.x()); x1 = std::max(x1, c.x()); y0 = std::min(y0, c.y()); y1 = std::max(y1, c.y());
    }
    CHECK(loop > 40);
    CHECK((x0 < 47 && 47 < x1 && y0 < 52 && 52 < y1));  // all the way round the island
}

TEST_CASE("occupancy-grid maps: walls on the map's edge, islands, staircases, clutter") {
    struct Map { const char* name; OccupancyGrid g; };
    std::vector<Map> maps = {{"rooms", scenes::rooms()}, {"corridors", scenes::corridors()}, {"staircase 3", scenes::staircase(3)},
                             {"staircase 1", scenes::staircase(1)}};
    for (unsigned seed = 1; seed <= 10; ++seed) maps.push_back({"clutter", scenes::clutter(seed, 40)});
    std::size_t total = 0;
    for (const auto& m : maps) {
        CAPTURE(m.name);
        for (double res : {1.0, 0.05}) {
            const Scene scene = occupancy_scene(m.g, res, Vec2(res == 1.0 ? 0.0 : -3.0, res == 1.0 ? 0.0 : 1.5));
            const std::int64_t side = std::max(m.g.rows, m.g.cols);
            const OracleSets o = check_against_oracle(scene, side, m.name);  // the pixel grid
            for (std::uint8_t v : o.mixed) total += v;
            check_against_oracle(scene, std::max<std::int64_t>(1, side * 7 / 10), m.name);
        }
    }
    CHECK(total > 0);
    // rooms: the map's edge is a wall, so the area's corners reach nothing; the loops around the
    // pillars and the wall pieces between doors are found (above)
    const OracleSets o = oracle_sets(occupancy_scene(scenes::rooms(), 1.0, Vec2(0, 0)), 60);
    CHECK(o.pieces >= 1);
    for (std::uint8_t a : o.at_area_corner) CHECK(a == 0);
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

TEST_CASE("polygon rings are read exactly: far from the origin, tiny, spikes and second windings") {
    auto msg = [](const std::vector<Obstacle>& obs, const std::vector<Vec2>& area) {
        try { make_scene(obs, area); } catch (const InputError& e) { return std::string(e.what()); }
        return std::string();
    };
    // The parts of a polygon, relative to a shift: the shoelace sum in doubles cancelled at large
    // coordinates and turned rings the wrong way (a triangle vanished, a notch became the polygon).
    const std::vector<Vec2> notched = {Vec2(-5, 2), Vec2(-3, 2), Vec2(-3, 4), Vec2(-4, 3), Vec2(-5, 4)};
    const std::vector<Vec2> triangle = {Vec2(3, 2), Vec2(7, 2), Vec2(3, 6)};
    auto parts_at = [](const std::vector<Vec2>& ring, double shift, double scale) {
        std::vector<Vec2> v;
        for (const Vec2& p : ring) v.push_back(Vec2(shift + scale * p.x(), shift + scale * p.y()));
        const Scene sc = make_scene({Obstacle(Shape::polygon(v))}, box_area(shift - 16 * scale, shift - 16 * scale, shift + 16 * scale, shift + 16 * scale));
        std::vector<std::vector<std::pair<double, double>>> out;
        for (const ConvexPart& p : sc.parts) {
            if (p.label != 0) continue;
            std::vector<std::pair<double, double>> q;
            for (std::uint32_t k = 0; k < p.count; ++k)
                q.push_back({(sc.part_vertices(p)[k].x() - shift) / scale, (sc.part_vertices(p)[k].y() - shift) / scale});
            out.push_back(q);
        }
        return out;
    };
    for (const auto* ring : {&notched, &triangle}) {
        const auto want = parts_at(*ring, 0.0, 1.0);
        CHECK(want.size() == (ring == &notched ? 2u : 1u));
        for (double shift : {5000000264.0, 10395970331.0, 1.0e15}) {  // exact shifts of small integers
            CAPTURE(shift);
            CHECK(parts_at(*ring, shift, 1.0) == want);
        }
        for (double scale : {0x1p-560, 0x1p-300, 0x1p400}) {  // and exact scales, tiny to huge
            CAPTURE(scale);
            CHECK(parts_at(*ring, 0.0, scale) == want);
        }
    }
    CHECK(msg({}, box_area(12345678901, 12345678901, 12345678917, 12345678917)).empty());
    // a second winding is not simple, and a spike changes the shape: both are errors
    const std::vector<Vec2> star = {Vec2(50, 90), Vec2(73, 20), Vec2(13, 63), Vec2(87, 63), Vec2(27, 20)};
    CHECK(msg({Obstacle(Shape::polygon(star))}, box_area(0, 0, 100, 100)).find("obstacles[0].vertices: polygon is not simple") == 0);
    CHECK(msg({}, star).find("area: the working area must be a convex polygon") == 0);
    const std::vector<Vec2> spike = {Vec2(2, 2), Vec2(6, 2), Vec2(6, 6), Vec2(12, 6), Vec2(6, 6), Vec2(2, 6)};
    CHECK(msg({Obstacle(Shape::polygon(spike))}, box_area(0, 0, 16, 16)) ==
          "obstacles[0].vertices: the polygon turns back on itself at vertex 3 (its edges overlap)");
    CHECK(msg({}, spike).find("area: the polygon turns back on itself at vertex 3") == 0);
    // closed rings, repeated and straight-on vertices are spellings of one polygon
    const std::vector<Vec2> spelled = {Vec2(3, 2), Vec2(5, 2), Vec2(7, 2), Vec2(7, 2), Vec2(3, 6), Vec2(3, 2)};
    CHECK(parts_at(spelled, 0.0, 1.0) == parts_at(triangle, 0.0, 1.0));
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
            for (std::size_t k = 0; k < v.size(); ++k)  // the shoelace sum: small integer coordinates, exact
                area += (v[k].x() * v[(k + 1) % v.size()].y() - v[k].y() * v[(k + 1) % v.size()].x()) / 2;
        }
    CHECK(parts0 == 2);
    CHECK(area == doctest::Approx(30.0 * 30.0 * (1.0 - 4.0 / 9.0)));
}
