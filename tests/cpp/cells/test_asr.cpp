// The exact Voronoi cell by Adjust-Sensing-Radius: closed forms for bounded cells, rays and strips,
// the radius schedule, and agreement with the limited cell at a radius beyond every vertex.
#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/cells/limited_cell.hpp"

#include "cells/cell_reference.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace dvoronoi;

TEST_CASE("lattice interior agent: the unit square, certified after a few doublings") {
    const Points P = testref::grid(7, 1.0);
    Points others(48, 2);
    for (Index i = 0, k = 0; i < 49; ++i)
        if (i != 24) others.row(k++) = P.row(i);
    const VoronoiCell cell = asr_cell(P.row(24).transpose(), others);
    CHECK_FALSE(cell.on_hull);
    REQUIRE(cell.edges.size() == 4);
    for (const VoronoiEdge& e : cell.edges) {
        CHECK_FALSE(e.from_infinity);
        CHECK_FALSE(e.to_infinity);
        CHECK(std::fabs(std::fabs(e.start.x() - 3.0) - 0.5) < 1e-15);
        CHECK(std::fabs(std::fabs(e.start.y() - 3.0) - 0.5) < 1e-15);
    }
    // Radius 1 (the lattice distance): the corners at sqrt(2)/2 are inside, but agents at exactly
    // 2R = 2 are excluded; the first step already certifies.
    CHECK(cell.radius_steps == 1);
    CHECK(cell.agents_used < 48);
}

TEST_CASE("hull agents: rays, and a strip between parallel bisectors") {
    // Corner of a lattice: two rays and nothing finite between them but one vertex.
    const Points P = testref::grid(3, 1.0);
    const VoronoiCell corner = asr_cell(Vec2(0, 0), P.bottomRows(8));
    CHECK(corner.on_hull);
    REQUIRE(corner.edges.size() == 2);
    CHECK(corner.edges.front().from_infinity);
    CHECK_FALSE(corner.edges.front().to_infinity);
    CHECK(corner.edges.back().to_infinity);
    CHECK((corner.edges.front().end - Vec2(0.5, 0.5)).norm() < 1e-15);
    // The middle of three collinear agents: a strip, two full lines.
    Points two(2, 2);
    two << -1, 0, 1, 0;
    const VoronoiCell strip = asr_cell(Vec2(0, 0), two);
    CHECK(strip.on_hull);
    REQUIRE(strip.edges.size() == 2);
    for (const VoronoiEdge& e : strip.edges) {
        CHECK(e.from_infinity);
        CHECK(e.to_infinity);
    }
    // A lone agent: the whole plane, no edge, unbounded.
    const VoronoiCell lone = asr_cell(Vec2(1, 1), Points(0, 2));
    CHECK(lone.on_hull);
    CHECK(lone.edges.empty());
}

TEST_CASE("bounded cells equal the limited cell at a radius beyond every vertex") {
    for (unsigned seed = 0; seed < 40; ++seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        Points P(60, 2);
        for (int i = 0; i < 60; ++i) P.row(i) << u(rng), u(rng);
        for (Index i = 0; i < 60; i += 5) {
            Points others(59, 2);
            for (Index j = 0, k = 0; j < 60; ++j)
                if (j != i) others.row(k++) = P.row(j);
            const VoronoiCell cell = asr_cell(P.row(i).transpose(), others);
            const LimitedCell big = limited_cell(P.row(i).transpose(), others, 1e3);
            CHECK(cell.neighbors() == big.neighbors());
            if (!cell.on_hull) {
                REQUIRE(cell.edges.size() == big.size());
                for (std::size_t k = 0; k < cell.edges.size(); ++k)
                    CHECK((cell.edges[k].start - big.pieces[k].start).norm() < 1e-12);
            }
        }
    }
}

TEST_CASE("bad input") {
    Points P(2, 2);
    P << 0, 0, 1, std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH_AS(asr_cell(Vec2(5, 5), P), doctest::Contains("others[1, 1]"), InputError);
    P(1, 1) = 0;
    CHECK_THROWS_WITH_AS(asr_cell(Vec2(0, 0), P), doctest::Contains("others[0] coincides with center"),
                         CoincidentError);
}
