// Both published algorithms against the exact brute-force definition, on random and degenerate
// inputs, and against closed-form cells.
#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/partition/limited_partition.hpp"

#include "cells/cell_reference.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace dvoronoi;

namespace {

constexpr double kPi = 3.14159265358979323846;

void check_against_reference(const Points& P, double R, const std::string& name) {
    for (Method m : {Method::Scan, Method::Chords}) {
        const LimitedPartition part = limited_cells(P, R, m, 1);
        for (Index i = 0; i < P.rows(); ++i) {
            const auto [b, e] = part.neighbors(i);
            const std::set<Index> got(b, e);
            const std::set<Index> expected = testref::brute_limited_neighbors(P, i, R);
            INFO(name, " R=", R, " method=", method_name(m), " agent=", i);
            CHECK(got == expected);
            // Symmetry of the limited-neighbour relation.
            for (Index j : got) {
                const auto [bj, ej] = part.neighbors(j);
                CHECK(std::find(bj, ej, i) != ej);
            }
            CHECK(part.areas[static_cast<std::size_t>(i)] > 0.0);
            CHECK(part.areas[static_cast<std::size_t>(i)] <= kPi * R * R * (1 + 1e-12));
        }
    }
}

}  // namespace

TEST_CASE("random inputs: both methods equal the exact definition") {
    for (int seed = 0; seed < 60; ++seed) {
        std::mt19937 rng(static_cast<unsigned>(seed));
        const int n = 10 + seed * 3;
        const double side = 1.0 + seed % 9;
        std::uniform_real_distribution<double> u(0.0, side);
        Points P(n, 2);
        for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng);
        check_against_reference(P, 0.4 + 0.15 * (seed % 6), "random seed " + std::to_string(seed));
    }
}

TEST_CASE("integer-grid subsets (many exact cocircularities): both methods equal the definition") {
    for (int seed = 0; seed < 30; ++seed) {
        std::mt19937 rng(static_cast<unsigned>(100 + seed));
        std::uniform_int_distribution<int> u(0, 7);
        std::set<std::pair<int, int>> s;
        while (s.size() < 30) s.insert({u(rng), u(rng)});
        Points P(static_cast<Index>(s.size()), 2);
        Index i = 0;
        for (auto [x, y] : s) P.row(i++) << x, y;
        for (double R : {0.5, 1.0, 1.25, 2.5, 5.0}) check_against_reference(P, R, "grid subset " + std::to_string(seed));
    }
}

TEST_CASE("degenerate families: both methods equal the definition") {
    for (const auto& f : testref::degenerate_families()) check_against_reference(f.pts, f.radius, f.name);
}

TEST_CASE("closed forms: lattice cells, tangency, lone agent") {
    const Points P = testref::grid(5, 1.0);
    Points others(24, 2);
    for (Index i = 0, k = 0; i < 25; ++i)
        if (i != 12) others.row(k++) = P.row(i);
    const Vec2 center = P.row(12).transpose();
    for (Method m : {Method::Scan, Method::Chords}) {
        // R = 0.5: the four nearest are at exactly 2R, their bisectors only touch the disk.
        LimitedCell c = limited_cell(center, others, 0.5, m);
        CHECK(c.neighbors().empty());
        CHECK(c.measures().area == doctest::Approx(kPi * 0.25).epsilon(1e-14));
        CHECK(c.measures().perimeter == doctest::Approx(kPi).epsilon(1e-14));
        CHECK(c.vertices().empty());
        // R = 1: the unit square (its corners at sqrt(2)/2 < 1).
        c = limited_cell(center, others, 1.0, m);
        CHECK(c.neighbors().size() == 4);
        CHECK(c.size() == 4);
        CHECK(c.measures().area == doctest::Approx(1.0).epsilon(1e-14));
        CHECK(c.measures().perimeter == doctest::Approx(4.0).epsilon(1e-14));
        CHECK((c.measures().centroid - center).norm() < 1e-14);
        // R = 0.6: the disk minus four circular segments at distance 0.5.
        const double R = 0.6, d = 0.5;
        const double segment = R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d);
        c = limited_cell(center, others, R, m);
        CHECK(c.size() == 8);
        CHECK(c.measures().area == doctest::Approx(kPi * R * R - 4 * segment).epsilon(1e-13));
        // Pieces alternate edge / arc counter-clockwise, each ending where the next starts.
        for (std::size_t k = 0; k < c.size(); ++k) {
            CHECK(c.pieces[k].is_arc() == (k % 2 == 1));
            CHECK(std::fabs((c.pieces[k].start - center).norm() - R) < 1e-14);
        }
    }
    // A lone agent: one full-circle arc.
    const LimitedCell lone = limited_cell(Vec2(3, 4), Points(0, 2), 2.0);
    REQUIRE(lone.size() == 1);
    CHECK(lone.pieces[0].is_arc());
    CHECK(lone.measures().area == doctest::Approx(4 * kPi).epsilon(1e-15));
    CHECK((lone.measures().centroid - Vec2(3, 4)).norm() < 1e-14);
}

TEST_CASE("bad input: clear errors naming the argument") {
    const Points P = testref::grid(3, 1.0);
    CHECK_THROWS_WITH_AS(limited_cell(Vec2(0.5, 0.5), P, 0.0), doctest::Contains("radius"), InputError);
    CHECK_THROWS_WITH_AS(limited_cell(Vec2(0.5, 0.5), P, -1.0), doctest::Contains("radius"), InputError);
    CHECK_THROWS_WITH_AS(limited_cell(Vec2(0.5, 0.5), P, std::nan("")), doctest::Contains("radius"), InputError);
    CHECK_THROWS_WITH_AS(limited_cell(Vec2(std::nan(""), 0.5), P, 1.0), doctest::Contains("center"), InputError);
    Points bad = P;
    bad(4, 1) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH_AS(limited_cell(Vec2(0.5, 0.5), bad, 1.0), doctest::Contains("others[4, 1]"), InputError);
    CHECK_THROWS_WITH_AS(limited_cells(bad, 1.0), doctest::Contains("points[4, 1]"), InputError);
    // The center coincides with others[4].
    CHECK_THROWS_AS(limited_cell(Vec2(1, 1), P, 1.0), CoincidentError);
    Points dup = P;
    dup.row(7) = dup.row(2);
    try {
        limited_cells(dup, 1.0);
        FAIL("coinciding agents must throw");
    } catch (const CoincidentError& e) {
        CHECK(e.first() == 2);
        CHECK(e.second() == 7);
        CHECK(std::string(e.what()).find("points[2] and points[7]") != std::string::npos);
    }
    // One crowded grid cell (radius much larger than the spread): the lowest pair is named.
    Points crowd(100, 2);
    for (Index i = 0; i < 100; ++i) crowd.row(i) << static_cast<double>(i) * 1e-3, 0.0;
    crowd.row(9) = crowd.row(5);
    crowd.row(40) = crowd.row(3);
    try {
        limited_cells(crowd, 10.0);
        FAIL("coinciding agents must throw");
    } catch (const CoincidentError& e) {
        CHECK(e.first() == 3);
        CHECK(e.second() == 40);
    }
    // Empty input and one agent work.
    CHECK(limited_cells(Points(0, 2), 1.0).size() == 0);
    const LimitedPartition one = limited_cells(Points::Constant(1, 2, 5.0), 1.0);
    CHECK(one.areas[0] == doctest::Approx(kPi).epsilon(1e-15));
    CHECK(one.indptr == std::vector<Index>{0, 0});
}
