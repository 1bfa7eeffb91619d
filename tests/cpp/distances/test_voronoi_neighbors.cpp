// VORONOI-NEIGHBORS from distances: equal to the exact Voronoi neighbours and hull flags of
// dvoronoi::voronoi_cells (itself CGAL-checked) on random and integer-lattice positions, Delaunay-path
// order, the limited-detection guarantee, the consistency step, thread independence, errors.
#include "dvoronoi/distances/neighbors_from_distances.hpp"
#include "dvoronoi/distances/local_region.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>

using namespace dvoronoi;
using namespace dvoronoi::dist;

namespace {
Points random_points(int n, unsigned seed, double side) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, side);
    Points P(n, 2);
    for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng);
    return P;
}

Points lattice_points(int n, unsigned seed, int side) {
    std::mt19937 rng(seed);
    std::vector<int> cells(static_cast<std::size_t>(side * side));
    for (int k = 0; k < side * side; ++k) cells[static_cast<std::size_t>(k)] = k;
    std::shuffle(cells.begin(), cells.end(), rng);
    Points P(n, 2);
    for (int i = 0; i < n; ++i) P.row(i) << cells[static_cast<std::size_t>(i)] % side, cells[static_cast<std::size_t>(i)] / side;
    return P;
}

std::set<Index> as_set(const std::pair<const Index*, const Index*>& r) { return {r.first, r.second}; }

bool contains(const VoronoiPartition& v, Index a, Index b) {
    const auto r = v.neighbors(a);
    return std::find(r.first, r.second, b) != r.second;
}

/// Checks every robot against the exact partition; returns the number of robots checked.
void check_equal(const Points& P, const DistanceGraph& g, const std::string& label) {
    const VoronoiPartition exact = voronoi_cells(P);
    const DistanceNeighbors got = neighbors_from_distances(g, false, 2);
    for (Index i = 0; i < exact.size(); ++i) {
        INFO(label << " robot " << i);
        REQUIRE(as_set(got.neighbors(i)) == as_set(exact.neighbors(i)));
        REQUIRE(bool(got.on_hull[static_cast<std::size_t>(i)]) == bool(exact.on_hull[static_cast<std::size_t>(i)]));
        REQUIRE(got.path_length[static_cast<std::size_t>(i)] == static_cast<Index>(as_set(got.neighbors(i)).size()));
    }
}
}  // namespace

TEST_CASE("predicates: values of the paper's formulas and exact signs") {
    // 3-4-5 right triangle: circumradius 2.5; the hypotenuse is opposite the right angle.
    CHECK(circumradius(3, 4, 5) == doctest::Approx(2.5));
    CHECK_FALSE(obtuse(3, 4, 5));
    CHECK(obtuse(3, 4, 5.0000001));
    CHECK(signed_circumradius(3, 4, 6) < 0);
    CHECK(std::isinf(circumradius(1, 2, 3)));  // collinear
    // S_ijkl: i = (0,0), j = (1,0), k = (0,1), l = (0,-1): opposite sides; squared inputs are exact.
    CHECK(opposite_sides(1, 1, 2, 1, 2, 4, true) < 0);
    CHECK(opposite_sides(1, 1, 2, 4, 5, 1, true) > 0);  // l = (0, 2): same side
    CHECK(opposite_sides(1, 1, 2, 4, 1, 5, true) == 0);  // l = (2, 0): on the line
    CHECK(opposite_sides_value(1, 1, std::sqrt(2.0), 1, std::sqrt(2.0), 2) == doctest::Approx(-4.0));
    // Exact ties: k = (0,1), l = (1,1) lie on one circle with i, j: equal (signed) radii.
    CHECK(compare_radius(1, 1, 2, 2, 1, true) == 0);
    CHECK(compare_signed_radius(1, 1, 2, 2, 1, true) == 0);
    CHECK(triangle_sign(1, 4, 1, true) == 0);  // (0,0), (1,0), (2,0)
}

TEST_CASE("random positions: equal to the exact Voronoi neighbours with full detection") {
    for (unsigned seed = 0; seed < 6; ++seed) {
        const Points P = random_points(120, seed, 10.0);
        check_equal(P, distances_from_points(P, 1e9), "random distances seed " + std::to_string(seed));
        check_equal(P, distances_from_points(P, 1e9, true), "random squared seed " + std::to_string(seed));
    }
}

TEST_CASE("integer lattices (collinear, cocircular): exact with squared distances") {
    for (unsigned seed = 0; seed < 8; ++seed) {
        const Points P = lattice_points(seed < 2 ? 100 : 70, seed, 10);
        check_equal(P, distances_from_points(P, 1e9, true), "lattice seed " + std::to_string(seed));
    }
    // A full square lattice and a regular hexagon-ish cocircular set.
    Points full(49, 2);
    for (int k = 0; k < 49; ++k) full.row(k) << k % 7, k / 7;
    check_equal(full, distances_from_points(full, 1e9, true), "full 7x7 lattice");
    Points circle(8, 2);
    const int xy[8][2] = {{5, 0}, {3, 4}, {0, 5}, {-4, 3}, {-5, 0}, {-3, -4}, {0, -5}, {4, -3}};
    for (int k = 0; k < 8; ++k) circle.row(k) << xy[k][0], xy[k][1];
    check_equal(circle, distances_from_points(circle, 1e9, true), "8 cocircular");
}

TEST_CASE("Delaunay-path order: consecutive neighbours are mutual Voronoi neighbours") {
    const Points P = random_points(300, 11, 10.0);
    const VoronoiPartition exact = voronoi_cells(P);
    const DistanceNeighbors got = neighbors_from_distances(distances_from_points(P, 1e9), false, 1);
    for (Index i = 0; i < got.size(); ++i) {
        const auto [b, e] = got.neighbors(i);
        const Index m = e - b;
        const bool hull = got.on_hull[static_cast<std::size_t>(i)];
        for (Index t = 0; t + 1 < m + (hull ? 0 : 1); ++t) {
            const Index a = b[t], c = b[(t + 1) % m];
            INFO("robot " << i << " pair " << a << " " << c);
            CHECK(contains(exact, a, c));
        }
    }
}

TEST_CASE("limited detection: exact for robots whose Delaunay star is shorter than R / 2") {
    const Points P = random_points(400, 21, 10.0);
    const VoronoiPartition exact = voronoi_cells(P);
    const double R = 1.8;
    const DistanceNeighbors got = neighbors_from_distances(distances_from_points(P, R), true, 2);
    int covered = 0;
    for (Index i = 0; i < exact.size(); ++i) {
        double longest = 0.0;  // longest edge of i's Delaunay star: i-j and j-k with j, k neighbours of i
        const auto [b, e] = exact.neighbors(i);
        for (const Index* j = b; j != e; ++j) {
            longest = std::max(longest, (P.row(i) - P.row(*j)).norm());
            for (const Index* k = b; k != e; ++k)
                if (*k != *j && contains(exact, *j, *k)) longest = std::max(longest, (P.row(*j) - P.row(*k)).norm());
        }
        // Every answer is made of detected robots.
        for (auto [gb, ge] = got.neighbors(i); gb != ge; ++gb) CHECK((P.row(i) - P.row(*gb)).norm() < R);
        if (2.0 * longest > R) continue;
        ++covered;
        INFO("robot " << i);
        const auto row = got.neighbors(i);
        const Index own = got.path_length[static_cast<std::size_t>(i)];
        CHECK(std::set<Index>(row.first, row.first + own) == as_set(exact.neighbors(i)));
        CHECK(bool(got.on_hull[static_cast<std::size_t>(i)]) == bool(exact.on_hull[static_cast<std::size_t>(i)]));
    }
    CHECK(covered > 150);
}

TEST_CASE("thread count and consistency") {
    const Points P = random_points(5000, 4, 50.0);
    const DistanceGraph g = distances_from_points(P, 2.5);
    const DistanceNeighbors a = neighbors_from_distances(g, true, 1), b = neighbors_from_distances(g, true, 2);
    CHECK(a.indptr == b.indptr);
    CHECK(a.indices == b.indices);
    CHECK(a.on_hull == b.on_hull);
    // The consistency step makes the relation symmetric.
    std::set<std::pair<Index, Index>> rel;
    for (Index i = 0; i < a.size(); ++i)
        for (auto [s, e] = a.neighbors(i); s != e; ++s) rel.insert({i, *s});
    for (const auto& [x, y] : rel) CHECK(rel.count({y, x}) == 1);
}

TEST_CASE("consistency step on a hand-made relation") {
    std::vector<Index> indptr{0, 2, 3, 3}, indices{1, 2, 0}, added;  // 0:{1,2}, 1:{0}, 2:{}
    make_consistent(indptr, indices, added);
    CHECK(indptr == std::vector<Index>{0, 2, 3, 4});
    CHECK(indices == std::vector<Index>{1, 2, 0, 0});
    CHECK(added == std::vector<Index>{0, 0, 1});
}

TEST_CASE("local region: the exact cell up to a rigid motion") {
    const Points P = random_points(200, 8, 10.0);
    const DistanceGraph g = distances_from_points(P, 1e9);
    int checked = 0;
    for (Index i = 0; i < 200; i += 7) {
        const RobotNeighbors nb = voronoi_neighbors(g, i);
        const LocalRegion r = local_region(g, i, nb.order, nb.hull);
        for (std::size_t t = 0; t < nb.order.size(); ++t)
            CHECK(r.positions[t].norm() == doctest::Approx((P.row(nb.order[t]) - P.row(i)).norm()));
        // Every vertex is equidistant from the robot and the two neighbours that define it.
        for (std::size_t t = 0; t < r.vertices.size(); ++t) {
            const Vec2 v = r.vertices[t];
            const Vec2 q = r.positions[t], s = r.positions[(t + 1) % nb.order.size()];
            CHECK((v - q).norm() == doctest::Approx(v.norm()).epsilon(1e-9));
            CHECK((v - s).norm() == doctest::Approx(v.norm()).epsilon(1e-9));
            // and no neighbour is closer to it than the robot (it is a Voronoi vertex).
            for (const Vec2& o : r.positions) CHECK((v - o).norm() >= v.norm() * (1.0 - 1e-9));
        }
        if (!nb.hull) {
            // Distances between neighbours in local coordinates equal the true ones.
            for (std::size_t a = 0; a < nb.order.size(); ++a)
                for (std::size_t c = a + 1; c < nb.order.size(); ++c)
                    CHECK((r.positions[a] - r.positions[c]).norm() ==
                          doctest::Approx((P.row(nb.order[a]) - P.row(nb.order[c])).norm()).epsilon(1e-9));
            ++checked;
        }
    }
    CHECK(checked > 10);
}

TEST_CASE("bad input names the entry") {
    CHECK_THROWS_WITH_AS(make_distance_graph(3, {0}, {1}, {-1.0}), doctest::Contains("entry 0"), InputError);
    CHECK_THROWS_WITH_AS(make_distance_graph(3, {0}, {3}, {1.0}), doctest::Contains("out of range"), InputError);
    CHECK_THROWS_WITH_AS(make_distance_graph(3, {0, 1}, {1, 0}, {1.0, 2.0}), doctest::Contains("differ"), InputError);
    CHECK_THROWS_WITH_AS(make_distance_graph(3, {0, 0}, {1, 1}, {1.0, 1.0}), doctest::Contains("twice"), InputError);
    CHECK_THROWS_WITH_AS(make_distance_graph(3, {2}, {2}, {1.0}), doctest::Contains("itself"), InputError);
    CHECK_THROWS_AS(make_distance_graph(3, {0}, {1}, {std::nan("")}), InputError);
    CHECK_THROWS_AS(make_distance_graph(3, {0}, {1}, {0.0}), InputError);
    const DistanceGraph avg = make_distance_graph(3, {0, 1}, {1, 0}, {1.0, 2.0}, false, Symmetry::Average);
    CHECK(avg.value(0, 1) == 1.5);
    CHECK(avg.value(1, 0) == 1.5);
    CHECK(std::isinf(avg.value(0, 2)));
}

TEST_CASE("small inputs") {
    const DistanceGraph none = make_distance_graph(0, {}, {}, {});
    CHECK(neighbors_from_distances(none).size() == 0);
    const DistanceGraph one = make_distance_graph(1, {}, {}, {});
    const DistanceNeighbors r1 = neighbors_from_distances(one);
    CHECK(r1.indptr == std::vector<Index>{0, 0});
    CHECK(r1.on_hull[0]);
    // Three collinear robots 0 - 1 - 2 (squared distances 1, 1, 4): 1 sees both, the ends one each.
    const DistanceGraph line = make_distance_graph(3, {0, 1, 0}, {1, 2, 2}, {1.0, 1.0, 4.0}, true);
    const DistanceNeighbors r = neighbors_from_distances(line);
    CHECK(as_set(r.neighbors(0)) == std::set<Index>{1});
    CHECK(as_set(r.neighbors(1)) == std::set<Index>{0, 2});
    CHECK(as_set(r.neighbors(2)) == std::set<Index>{1});
}
