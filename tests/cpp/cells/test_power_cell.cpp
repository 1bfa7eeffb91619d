// Heterogeneous cells (cells/power_cell.hpp, partition/power_partition.hpp) against closed forms,
// the equal-radius path, and properties every exact answer has (symmetry, partition of the union).
#include "dvoronoi/cells/power_cell.hpp"
#include "dvoronoi/partition/power_partition.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace dvoronoi;

namespace {

constexpr double kPi = 3.14159265358979323846;

Points pts(std::initializer_list<std::pair<double, double>> xy) {
    Points p(static_cast<Index>(xy.size()), 2);
    Index i = 0;
    for (auto [x, y] : xy) {
        p(i, 0) = x;
        p(i, 1) = y;
        ++i;
    }
    return p;
}

/// Area of the lens-complement: disk (0, r) minus disk (d, R) (|r - R| < d < r + R).
double disk_minus_disk(double r, double R, double d) {
    const double a = std::acos((d * d + r * r - R * R) / (2 * d * r));
    const double b = std::acos((d * d + R * R - r * r) / (2 * d * R));
    const double lens = r * r * (a - std::sin(2 * a) / 2) + R * R * (b - std::sin(2 * b) / 2);
    return kPi * r * r - lens;
}

}  // namespace

TEST_CASE("crescent: the agent outside its own cell (the issue's example)") {
    // R = 10 at the origin, R = 1 at (9.5, 0): agent 1 keeps the part of its disk outside the big one.
    const Points P = pts({{0, 0}, {9.5, 0}});
    const LimitedPartition part = limited_cells(P, std::vector<double>{10.0, 1.0}, Method::Auto, 1);
    CHECK(part.computed_by.clip + part.computed_by.power == 2);
    CHECK(!part.is_empty(1));
    // W_1 is the cap of B_1 beyond the radical axis, at h = (d^2 + R_0^2 - R_1^2) / 2d - d from p_1.
    const double h = (9.5 * 9.5 + 100.0 - 1.0) / 19.0 - 9.5;
    CHECK(part.areas[1] == doctest::Approx(std::acos(h) - h * std::sqrt(1 - h * h)).epsilon(1e-12));
    CHECK(part.areas[0] + part.areas[1] == doctest::Approx(kPi * 100 + disk_minus_disk(1.0, 10.0, 9.5)).epsilon(1e-12));
    // The agent is not in its cell: the centroid lies beyond the big circle.
    CHECK(part.centroids(1, 0) > 10.0);
    const auto [b, e] = part.neighbors(1);
    REQUIRE(e - b == 1);
    CHECK(*b == 0);
}

TEST_CASE("nested and coinciding disks: the larger holds the cell, the smaller is empty") {
    const Points P = pts({{0, 0}, {0.5, 0}, {3, 0}, {3, 0}});
    const LimitedPartition part = limited_cells(P, std::vector<double>{2.0, 1.0, 1.0, 0.5}, Method::Auto, 1);
    CHECK(part.is_empty(1));  // inside disk 0
    CHECK(part.is_empty(3));  // same place as 2, smaller
    CHECK(!part.is_empty(0));
    CHECK(!part.is_empty(2));
    CHECK(part.areas[1] == 0.0);
    CHECK(part.indptr[2] - part.indptr[1] == 0);
    CHECK(part.areas[0] == doctest::Approx(kPi * 4).epsilon(1e-14));
    CHECK(part.areas[2] == doctest::Approx(kPi).epsilon(1e-14));
    CHECK_THROWS_AS(limited_cells(pts({{0, 0}, {1, 1}, {1, 1}}), std::vector<double>{1.0, 2.0, 2.0}), CoincidentError);
    try {
        limited_cells(pts({{0, 0}, {1, 1}, {1, 1}}), std::vector<double>{1.0, 2.0, 2.0});
    } catch (const CoincidentError& e) {
        CHECK(e.first() == 1);
        CHECK(e.second() == 2);
    }
}

TEST_CASE("tangent disks: no neighbours, full disks") {
    const Points P = pts({{0, 0}, {3, 0}, {3, 5}});
    const LimitedPartition part = limited_cells(P, std::vector<double>{1.0, 2.0, 3.0}, Method::Auto, 1);
    for (Index i = 0; i < 3; ++i) CHECK(part.indptr[i + 1] == part.indptr[i]);
    CHECK(part.areas[0] == doctest::Approx(kPi).epsilon(1e-15));
    CHECK(part.areas[1] == doctest::Approx(4 * kPi).epsilon(1e-15));
}

TEST_CASE("equal radii: bit for bit the scalar call") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Points P(300, 2);
    for (Index i = 0; i < P.rows(); ++i) P(i, 0) = u(rng), P(i, 1) = u(rng);
    const LimitedPartition a = limited_cells(P, 0.07);
    const LimitedPartition b = limited_cells(P, std::vector<double>(300, 0.07));
    CHECK(a.piece_x == b.piece_x);
    CHECK(a.piece_y == b.piece_y);
    CHECK(a.piece_span == b.piece_span);
    CHECK(a.indices == b.indices);
    CHECK(a.areas == b.areas);
    CHECK(b.radii.empty());
    const LimitedCell c1 = limited_cell(P.row(0).transpose(), P.bottomRows(299), 0.07);
    const LimitedCell c2 = power_limited_cell(P.row(0).transpose(), P.bottomRows(299), 0.07, std::vector<double>(299, 0.07));
    CHECK(c1.measures().area == c2.measures().area);
}

TEST_CASE("random teams: symmetric neighbours, cells partition the disks' union") {
    for (int seed = 0; seed < 5; ++seed) {
        std::mt19937_64 rng(static_cast<unsigned>(seed));
        std::uniform_real_distribution<double> u(0.0, 1.0), ur(0.03, 0.12);
        const Index n = 400;
        Points P(n, 2);
        std::vector<double> R(static_cast<std::size_t>(n));
        for (Index i = 0; i < n; ++i) P(i, 0) = u(rng), P(i, 1) = u(rng), R[static_cast<std::size_t>(i)] = ur(rng);
        const LimitedPartition part = limited_cells(P, R, Method::Auto, 2);
        for (Index i = 0; i < n; ++i) {
            const auto [b, e] = part.neighbors(i);
            for (const Index* j = b; j != e; ++j) {
                const auto [bj, ej] = part.neighbors(*j);
                CHECK(std::find(bj, ej, i) != ej);
            }
            CHECK(part.areas[static_cast<std::size_t>(i)] <= kPi * R[static_cast<std::size_t>(i)] * R[static_cast<std::size_t>(i)] * (1 + 1e-12));
            // The centroid lies in the own disk (the cell does).
            const double dx = part.centroids(i, 0) - P(i, 0), dy = part.centroids(i, 1) - P(i, 1);
            CHECK(std::hypot(dx, dy) <= R[static_cast<std::size_t>(i)] * (1 + 1e-12));
        }
        // One agent's cell alone equals the partition's.
        const Index i = 17;
        Points others(n - 1, 2);
        std::vector<double> ro;
        for (Index j = 0, t = 0; j < n; ++j)
            if (j != i) others.row(t++) = P.row(j), ro.push_back(R[static_cast<std::size_t>(j)]);
        const LimitedCell c = power_limited_cell(P.row(i).transpose(), others, R[static_cast<std::size_t>(i)], ro);
        CHECK(c.measures().area == doctest::Approx(part.areas[static_cast<std::size_t>(i)]).epsilon(1e-14));
    }
}

TEST_CASE("bad radii name the argument") {
    const Points P = pts({{0, 0}, {1, 0}});
    CHECK_THROWS_WITH_AS(limited_cells(P, std::vector<double>{1.0}), doctest::Contains("radius"), InputError);
    CHECK_THROWS_WITH_AS(limited_cells(P, std::vector<double>{1.0, -1.0}), doctest::Contains("radius"), InputError);
    CHECK_THROWS_WITH_AS(limited_cells(P, std::vector<double>{1.0, NAN}), doctest::Contains("radius"), InputError);
    // an entry out of the documented range names its index, as a bad one does
    CHECK_THROWS_WITH_AS(limited_cells(P, std::vector<double>{1.0, 1e151}), doctest::Contains("radius[1] must lie between 1e-150 and 1e150"),
                         RangeError);
}

TEST_CASE("nearly tangent disks: a tiny cap and a disk minus a tiny cap") {
    // Cap of the unit disk beyond the line at distance h from its centre, in long double.
    const auto cap = [](long double h) { return std::acos(h) - h * std::sqrt(1.0L - h * h); };
    for (int e : {10, 20, 30}) {
        const double d = 2.0 - std::ldexp(1.0, -e);  // two unit disks overlapping by 2^-e
        const LimitedPartition p = limited_cells(pts({{0, 0}, {d, 0}}), std::vector<double>{1.0, 1.0 + 0x1p-40}, Method::Auto, 1);
        // Disk 0 minus the cap beyond its radical axis with disk 1: one edge, one arc of nearly 2 pi.
        const long double h = ((long double)d * d + 1.0L - (1.0L + 0x1p-40L) * (1.0L + 0x1p-40L)) / (2.0L * d);
        CHECK(p.areas[0] == doctest::Approx(static_cast<double>(3.14159265358979323846L - cap(h))).epsilon(1e-13));
        const LimitedCell c = p.cell(0);
        REQUIRE(c.pieces.size() == 2);
        CHECK(c.pieces[1].arc_span > 6.0);
        CHECK(c.pieces[1].arc_span < 2 * kPi);
    }
    for (int e : {10, 20, 30}) {
        // R = 10 at the origin, r = 1 at 9 + 2^-e: a cap of height about 2^-e survives.
        const double d = 9.0 + std::ldexp(1.0, -e);
        const LimitedPartition p = limited_cells(pts({{0, 0}, {d, 0}}), std::vector<double>{10.0, 1.0}, Method::Auto, 1);
        const long double h = ((long double)d * d + 100.0L - 1.0L) / (2.0L * d) - d;
        REQUIRE(!p.is_empty(1));
        CHECK(p.areas[1] == doctest::Approx(static_cast<double>(cap(h))).epsilon(1e-6));
        const LimitedCell c = p.cell(1);
        REQUIRE(c.pieces.size() == 2);
        CHECK(c.pieces[1].arc_span < 0.1);
        CHECK(c.pieces[1].arc_span > 0.0);
    }
}

TEST_CASE("every method with unequal radii, and computed_by says which ran") {
    const Points others = pts({{1, 0}});
    for (Method m : {Method::Auto, Method::Scan, Method::Chords}) {
        CHECK(power_limited_cell(Vec2(0, 0), others, 1.0, {1.5}, m).neighbors() == std::vector<Index>{0});
        CHECK(power_limited_cell(Vec2(0, 0), others, 1.0, {2.0}, m).pieces.empty());  // inside, tangent
        CHECK(power_limited_cell(Vec2(0, 0), others, 1.0, {1.0}, m).neighbors() == std::vector<Index>{0});
    }
    const Points P = pts({{0, 0}, {9.5, 0}, {0, 10.5}, {3, 3}});
    const std::vector<double> R{10.0, 1.0, 1.0, 0.5};
    const LimitedPartition a = limited_cells(P, R, Method::Auto, 1), s = limited_cells(P, R, Method::Scan, 1),
                           c = limited_cells(P, R, Method::Chords, 1);
    CHECK(a.computed_by.clip + a.computed_by.power == 4);
    CHECK(s.computed_by.scan == 4);
    CHECK(c.computed_by.chords == 4);
    CHECK(s.computed_by.clip + s.computed_by.power + c.computed_by.power == 0);
    CHECK(a.indices == s.indices);
    CHECK(a.indices == c.indices);
    CHECK(a.is_empty(3));
    CHECK_THROWS_WITH_AS(power_limited_cell(Vec2(0, 0), others, 1.0, {1.0, 2.0}), doctest::Contains("other_radii"), InputError);
}

TEST_CASE("dyadic scales: heterogeneous cells scale exactly, across the documented radius range") {
    // The half chord has terms of degree 4 in the radii: beyond radii of 2^+-256 they overflowed or
    // underflowed (arc ends at the chord's midpoint, full disks, NaN areas).
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 6.0), ur(0.5, 1.5);
    const Index n = 60;
    Points P(n, 2);
    std::vector<double> R(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) P(i, 0) = u(rng), P(i, 1) = u(rng), R[static_cast<std::size_t>(i)] = ur(rng);
    for (Method m : {Method::Auto, Method::Scan, Method::Chords}) {
        const LimitedPartition one = limited_cells(P, R, m, 1);
        for (int e : {-490, -300, -268, -210, 210, 256, 300, 465, 490}) {  // 2^+-490: radii within [1e-150, 1e150]
            CAPTURE(e);
            std::vector<double> Rs;
            for (double r : R) Rs.push_back(std::ldexp(r, e));
            const LimitedPartition s = limited_cells(Points(std::ldexp(1.0, e) * P), Rs, m, 1);
            REQUIRE(s.indices == one.indices);
            for (Index i = 0; i < n; ++i) {
                const auto k = static_cast<std::size_t>(i);
                CHECK(std::ldexp(s.areas[k], -2 * e) == doctest::Approx(one.areas[k]).epsilon(1e-12));
                CHECK(std::ldexp(s.centroids(i, 0), -e) == doctest::Approx(one.centroids(i, 0)).epsilon(1e-12));
                CHECK(std::ldexp(s.centroids(i, 1), -e) == doctest::Approx(one.centroids(i, 1)).epsilon(1e-12));
                const LimitedCell a = one.cell(i), b = s.cell(i);
                REQUIRE(a.pieces.size() == b.pieces.size());
                if (a.pieces.empty()) continue;
                // the same cycle of pieces, maybe from another first piece
                std::size_t shift = 0;
                auto gap = [&](std::size_t q, std::size_t t) {
                    return std::hypot(std::ldexp(b.pieces[t].start.x(), -e) - a.pieces[q].start.x(),
                                      std::ldexp(b.pieces[t].start.y(), -e) - a.pieces[q].start.y());
                };
                for (std::size_t t = 1; t < b.pieces.size(); ++t)
                    if (gap(0, t) < gap(0, shift)) shift = t;
                for (std::size_t q = 0; q < a.pieces.size(); ++q) {
                    const std::size_t t = (q + shift) % b.pieces.size();
                    CHECK(b.pieces[t].neighbor == a.pieces[q].neighbor);
                    CHECK(b.pieces[t].arc_span == doctest::Approx(a.pieces[q].arc_span).epsilon(1e-12));
                    CHECK(gap(q, t) <= 1e-12 * R[k]);
                }
            }
        }
    }
}
