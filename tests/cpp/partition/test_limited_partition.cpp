// limited_cells: results independent of the thread count, equal to the per-agent call, progress
// reported and a throwing progress callback carried out of the parallel region.
#include "dvoronoi/partition/limited_partition.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>
#include <string>
#include <utility>
#include <stdexcept>

using namespace dvoronoi;

namespace {
Points random_points(int n, unsigned seed, double side) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, side);
    Points P(n, 2);
    for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng);
    return P;
}

// Every array of two partitions of the same input is equal.
void check_same(const LimitedPartition& a, const LimitedPartition& b) {
    using P = LimitedPartition;
    for (auto column : {&P::indptr, &P::indices, &P::piece_ptr, &P::piece_neighbor, &P::candidates})
        CHECK(a.*column == b.*column);
    for (auto column : {&P::piece_x, &P::piece_y, &P::piece_span, &P::areas, &P::perimeters})
        CHECK(a.*column == b.*column);
    CHECK(a.centroids == b.centroids);
    CHECK(a.method == b.method);
}
}  // namespace

TEST_CASE("thread count does not change the result") {
    const Points P = random_points(20000, 3, 100.0);
    for (Method m : {Method::Scan, Method::Chords}) {
        const LimitedPartition a = limited_cells(P, 0.6, m, 1);
        const LimitedPartition b = limited_cells(P, 0.6, m, 2);
        check_same(a, b);
        CHECK(a.method == m);
    }
}

TEST_CASE("more pieces than the columns reserve: a lattice whose cells are four edges and four arcs") {
    // Unit square lattice, R = 0.6: every inner cell is the unit square around the agent with its
    // corners cut off by the circle, 8 pieces, above the 7 per agent the per-thread columns reserve,
    // so they regrow; every thread count must still give the same arrays and the exact cells.
    const int side = 160;
    Points P(side * side, 2);
    for (int a = 0; a < side; ++a)
        for (int b = 0; b < side; ++b) P.row(a * side + b) << a, b;
    const double R = 0.6;
    const double segment = R * R * std::acos(0.5 / R) - 0.5 * std::sqrt(R * R - 0.25);
    const double inner_area = M_PI * R * R - 4.0 * segment;
    const LimitedPartition one = limited_cells(P, R, Method::Scan, 1);
    check_same(one, limited_cells(P, R, Method::Scan, 2));
    Index inner = 0;
    for (int a = 1; a + 1 < side; ++a)
        for (int b = 1; b + 1 < side; ++b) {
            const Index i = a * side + b;
            REQUIRE(one.piece_ptr[static_cast<std::size_t>(i) + 1] - one.piece_ptr[static_cast<std::size_t>(i)] == 8);
            const auto [nb, ne] = one.neighbors(i);
            const std::vector<Index> want{i - side, i - 1, i + 1, i + side};
            CHECK(std::vector<Index>(nb, ne) == want);
            CHECK(one.areas[static_cast<std::size_t>(i)] == doctest::Approx(inner_area).epsilon(1e-12));
            ++inner;
        }
    CHECK(one.piece_ptr.back() > 7 * static_cast<Index>(P.rows()));  // the reserve was exceeded
    CHECK(inner == (side - 2) * (side - 2));
}

TEST_CASE("sort_small sorts every order of up to eight values, ties, and longer runs") {
    for (int n = 0; n <= 8; ++n) {
        std::vector<Index> perm(static_cast<std::size_t>(n));
        std::iota(perm.begin(), perm.end(), Index{-3});
        do {
            std::vector<Index> v = perm;
            detail::sort_small(v.data(), v.data() + v.size());
            REQUIRE(std::is_sorted(v.begin(), v.end()));
            REQUIRE(std::is_permutation(v.begin(), v.end(), perm.begin()));
        } while (std::next_permutation(perm.begin(), perm.end()));
    }
    std::mt19937 rng(4);
    for (int trial = 0; trial < 2000; ++trial) {
        std::vector<Index> v(static_cast<std::size_t>(rng() % 20));
        for (Index& x : v) x = static_cast<Index>(rng() % 5);  // many ties
        std::vector<Index> want = v;
        std::sort(want.begin(), want.end());
        detail::sort_small(v.data(), v.data() + v.size());
        REQUIRE(v == want);
    }
}

TEST_CASE("sorted_edge_neighbors keeps the edges' neighbours, ascending, and writes nothing past them") {
    std::mt19937 rng(9);
    const Index big = std::numeric_limits<Index>::max() - 1;  // the largest index below the padding
    for (int trial = 0; trial < 20000; ++trial) {
        const std::size_t len = rng() % 13;  // up to 8 take the network, more std::sort
        std::vector<Index> run(len);
        for (Index& x : run) {
            const unsigned kind = rng() % 8;
            x = kind == 0 ? kArc : kind == 1 ? big - static_cast<Index>(rng() % 3) : static_cast<Index>(rng() % 50);
        }
        std::vector<Index> want;
        for (Index x : run)
            if (x >= 0) want.push_back(x);
        std::sort(want.begin(), want.end());
        std::vector<Index> out(len + 8, -7);  // -7: never written
        const std::size_t count = detail::sorted_edge_neighbors(run.data(), len, out.data());
        REQUIRE(count == want.size());
        REQUIRE(std::equal(want.begin(), want.end(), out.begin()));
        REQUIRE(std::all_of(out.begin() + static_cast<std::ptrdiff_t>(count), out.end(), [](Index x) { return x == -7; }));
    }
}

TEST_CASE("the partition's cells equal the per-agent call") {
    const Points P = random_points(600, 5, 10.0);
    const double R = 0.45;
    const LimitedPartition part = limited_cells(P, R);
    Index arcs = 0;  // spans travel apart from the other piece columns: they must land on their arcs
    for (Index i = 0; i < P.rows(); i += 7) {
        Points others(P.rows() - 1, 2);
        for (Index j = 0, k = 0; j < P.rows(); ++j)
            if (j != i) others.row(k++) = P.row(j);
        const LimitedCell one = limited_cell(P.row(i).transpose(), others, R);
        const LimitedCell mine = part.cell(i);
        REQUIRE(one.size() == mine.size());
        for (std::size_t k = 0; k < one.size(); ++k) {
            const Index nb = one.pieces[k].neighbor;
            CHECK(mine.pieces[k].neighbor == (nb < 0 ? nb : (nb < i ? nb : nb + 1)));
            CHECK((mine.pieces[k].start - one.pieces[k].start).norm() <= 1e-12);
            CHECK(mine.pieces[k].arc_span == doctest::Approx(one.pieces[k].arc_span).epsilon(1e-12));
            arcs += one.pieces[k].is_arc() ? 1 : 0;
        }
        CHECK(mine.measures().area == doctest::Approx(one.measures().area).epsilon(1e-13));
        CHECK(part.candidates[static_cast<std::size_t>(i)] == one.candidates);
    }
    CHECK(arcs > 20);
}

TEST_CASE("progress is reported to the end, and a throwing callback stops the run") {
    const Points P = random_points(50000, 9, 200.0);
    Index last = -1, calls = 0;
    limited_cells(P, 0.5, Method::Scan, 2, [&](Index done, Index total) {
        CHECK(total == 50000);
        CHECK(done >= last);
        last = done;
        ++calls;
    });
    CHECK(last == 50000);
    CHECK(calls >= 2);
    CHECK_THROWS_WITH_AS(limited_cells(P, 0.5, Method::Scan, 2,
                                       [](Index, Index) { throw std::runtime_error("stop"); }),
                         "stop", std::runtime_error);
}

namespace {
// A 6 x 6 lattice (cocircular quadruples: the exact stage runs) and 30 random agents in [0, 5]^2.
Points lattice_and_random() {
    Points P(66, 2);
    for (int k = 0; k < 36; ++k) P.row(k) << k % 6, k / 6;
    P.bottomRows(30) = random_points(30, 4, 5.0);
    return P;
}
}  // namespace

TEST_CASE("scaled far from 1 (a lattice and random agents, and the radius, by 2^k): the same cells") {
    // Before: scaled by 2^-480 and beyond, exact tests underflowed and gave other neighbour sets. Now
    // an exact test that loses bits is evaluated again on rescaled inputs (core/expansion.hpp), so
    // any common scale whose radius lies in [kMinRadius, kMaxRadius] gives the unscaled answer.
    const Points P = lattice_and_random();
    for (Method method : {Method::Scan, Method::Chords}) {
        const LimitedPartition ref = limited_cells(P, 1.0, method, 1);
        for (int k : {-498, -490, -480, -470, -460, -400, 400, 460, 480, 490, 498}) {
            const double s = std::ldexp(1.0, k);  // exact scaling: the same exact answer
            const LimitedPartition got = limited_cells(P * s, s, method, 2);
            CHECK(got.indptr == ref.indptr);
            CHECK(got.indices == ref.indices);
            CHECK(got.piece_neighbor == ref.piece_neighbor);
            for (Index i = 0; i < P.rows(); ++i)
                CHECK(got.areas[static_cast<std::size_t>(i)] == ref.areas[static_cast<std::size_t>(i)] * s * s);
        }
    }
}

TEST_CASE("agents whose differences span more than doubles hold: a RangeError naming an agent") {
    // Agent 0 a few subnormal steps beside the line x = 0 on which its neighbours lie 2^-30 apart:
    // the decisions need products below the smallest subnormal next to terms of 2^-60.
    Points P(4, 2);
    P << std::ldexp(3.0, -1074), 0.0, 0.0, std::ldexp(1.0, -30), 0.0, -std::ldexp(1.0, -30),
        -std::ldexp(1.0, -1074), std::ldexp(1.0, -31);
    for (Method method : {Method::Scan, Method::Chords}) {
        std::string message;
        try {
            limited_cells(P, std::ldexp(1.0, -30), method, 1);
        } catch (const RangeError& e) {
            message = e.what();
        }
        CHECK(message.rfind("points[", 0) == 0);
        CHECK(message.find("]: out of the exact range: an exact test underflowed") != std::string::npos);
    }
}

TEST_CASE("the radius must lie in [kMinRadius, kMaxRadius]; measures stay finite up to it") {
    const Points P = random_points(20, 3, 1.0);
    CHECK_THROWS_AS(limited_cells(P, 1.01 * kMaxRadius), RangeError);
    CHECK_THROWS_AS(limited_cells(P, 0.99 * kMinRadius), RangeError);
    CHECK_THROWS_WITH_AS(limited_cells(P, 1e200), doctest::Contains("radius must lie between 1e-150 and 1e150"),
                         RangeError);
    // Two agents 1 apart, R >> 1: each cell is half a disk, to rounding. Its first moment (~R^3)
    // overflowed from R ~ 1e103 on (centroids came out -inf); the measures are now summed in units
    // of R.
    Points two(2, 2);
    two << 0.0, 0.0, 1.0, 0.0;
    for (double R : {1e100, 1e120, kMaxRadius}) {
        const LimitedPartition part = limited_cells(two, R, Method::Scan, 1);
        for (Index i = 0; i < 2; ++i) {
            CHECK(part.areas[static_cast<std::size_t>(i)] == doctest::Approx(M_PI * R * R / 2).epsilon(1e-12));
            CHECK(std::isfinite(part.centroids(i, 0)));
            CHECK(std::isfinite(part.perimeters[static_cast<std::size_t>(i)]));
        }
        // The half disk's centroid lies 4R / (3 pi) from the bisector.
        CHECK(part.centroids(0, 0) == doctest::Approx(0.5 - 4.0 * R / (3.0 * M_PI)).epsilon(1e-12));
    }
}

TEST_CASE("Chords refuses more than kMaxChordsCandidates agents within 2R, naming the agent; Scan does not") {
    const Points P = random_points(static_cast<int>(kMaxChordsCandidates) + 100, 5, 1.0);
    CHECK_THROWS_WITH_AS(limited_cells(P, 1.0, Method::Chords, 2),
                         doctest::Contains("method \"chords\" (RCVC, quadratic in the agents within 2R) accepts at most 1024"),
                         RangeError);
    try {
        limited_cells(P, 1.0, Method::Chords, 2);
    } catch (const RangeError& e) {
        CHECK(std::string(e.what()).rfind("points[", 0) == 0);
    }
    CHECK(limited_cells(P, 1.0, Method::Scan, 2).size() == P.rows());
    // One cell: exactly kMaxChordsCandidates others within 2R is accepted, one more is not.
    const Points others = P.topRows(static_cast<Index>(kMaxChordsCandidates));
    CHECK(limited_cell(Vec2(0.5, 0.5), others, 1.0, Method::Chords).candidates ==
          static_cast<Index>(kMaxChordsCandidates));
    CHECK_THROWS_AS(limited_cell(Vec2(0.5, 0.5), P.topRows(static_cast<Index>(kMaxChordsCandidates) + 1), 1.0,
                                 Method::Chords),
                    RangeError);
}

TEST_CASE("vertices of nearly parallel bisectors are constructed accurately, not as NaN") {
    // Seen from agent 1, 1e50 away, agents 7 and 9 lie 1.9 apart: their bisectors meet inside the disk
    // (exact), but D_jk = cross(a_7, a_9) rounded to nothing. Before: NaN areas and centroids,
    // silently (one Lloyd step without bounds at R = 1e50 produced these positions). Now such a
    // vertex is computed from exact expansions: it is equidistant from the three agents.
    Points P(10, 2);
    P << 0.5618757474128028, 0.26368998318376696, -4.803950461899142e+49, -2.7899023060781243e+49,
        4.24907879479111e+49, 4.471688395115378e+49, 0.5663229472811333, 0.6850047083522466,
        -2.987541129546544e+49, 5.550769095044644e+49, 1.99997520387985e+49, -6.234697987495406e+49,
        5.730835909397884e+49, -2.9238759514447616e+49, 0.7170522508352185, 0.15326515342910968,
        6.648390047658606e+49, 4.068813620489327e+48, -0.849147302260679, 1.0782537037477684;
    for (Method method : {Method::Scan, Method::Chords}) {
        const LimitedPartition part = limited_cells(P, 1e50, method, 2);
        for (Index i = 0; i < P.rows(); ++i) {
            CHECK(std::isfinite(part.areas[static_cast<std::size_t>(i)]));
            CHECK(std::isfinite(part.centroids(i, 0)));
            CHECK(std::isfinite(part.centroids(i, 1)));
        }
        const LimitedCell cell = part.cell(1);
        const Vec2 c = P.row(1).transpose();
        for (std::size_t t = 0; t < cell.pieces.size(); ++t) {
            const Piece& in = cell.pieces[(t + cell.pieces.size() - 1) % cell.pieces.size()];
            const Piece& out = cell.pieces[t];
            if (in.is_arc() || out.is_arc()) continue;
            const Vec2 v = out.start;  // the vertex of the bisectors of `in` and `out`
            const double d = (v - c).norm();
            CHECK((v - Vec2(P.row(in.neighbor).transpose())).norm() == doctest::Approx(d).epsilon(1e-12));
            CHECK((v - Vec2(P.row(out.neighbor).transpose())).norm() == doctest::Approx(d).epsilon(1e-12));
        }
    }
}

namespace {
/// Inputs for the method comparison: uniform, clustered (Gaussian blobs: dense cores, sparse
/// gaps), and degenerate lattices (square: four cocircular agents per vertex; hexagonal: three).
std::vector<std::pair<const char*, Points>> method_inputs() {
    std::vector<std::pair<const char*, Points>> out;
    out.emplace_back("uniform", random_points(3000, 21, 30.0));
    std::mt19937 rng(22);
    std::uniform_real_distribution<double> u(0.0, 30.0);
    std::normal_distribution<double> g(0.0, 0.4);
    Points C(2000, 2);
    for (int k = 0; k < 20; ++k) {
        const double cx = u(rng), cy = u(rng);
        for (int t = 0; t < 100; ++t) C.row(100 * k + t) << cx + g(rng), cy + g(rng);
    }
    out.emplace_back("clustered", C);
    Points S(40 * 40, 2);
    for (int a = 0; a < 40; ++a)
        for (int b = 0; b < 40; ++b) S.row(a * 40 + b) << a, b;
    out.emplace_back("square lattice", S);
    Points H(30 * 30, 2);
    for (int a = 0; a < 30; ++a)
        for (int b = 0; b < 30; ++b) H.row(a * 30 + b) << b + 0.5 * (a % 2), a * std::sqrt(0.75);
    out.emplace_back("hexagonal lattice", H);
    return out;
}
}  // namespace

TEST_CASE("methods: auto, scan and chords give the same cells, and each runs the algorithm it names") {
    for (const auto& [name, P] : method_inputs()) {
        for (double R : {0.75, 1.6}) {
            INFO(name, " R = ", R);
            const LimitedPartition a = limited_cells(P, R, Method::Auto, 2);
            const LimitedPartition s = limited_cells(P, R, Method::Scan, 2);
            const LimitedPartition c = limited_cells(P, R, Method::Chords, 2);
            const Index n = P.rows();
            // Which algorithm computed the cells.
            CHECK(s.computed_by.scan == n);
            CHECK(s.computed_by.clip == 0);
            CHECK(s.computed_by.chords == 0);
            CHECK(c.computed_by.chords == n);
            CHECK(c.computed_by.clip + c.computed_by.scan == 0);
            CHECK(a.computed_by.clip + a.computed_by.scan == n);
            CHECK(a.computed_by.chords == 0);
            if (std::string(name) == "uniform" || std::string(name) == "clustered") CHECK(a.computed_by.clip > n / 2);
            // Auto's filter gives Boundary Scan's cells bit for bit.
            using LP = LimitedPartition;
            for (auto column : {&LP::indptr, &LP::indices, &LP::piece_ptr, &LP::piece_neighbor, &LP::candidates})
                CHECK(a.*column == s.*column);
            for (auto column : {&LP::piece_x, &LP::piece_y, &LP::piece_span, &LP::areas, &LP::perimeters})
                CHECK(a.*column == s.*column);
            // RCVC: the same neighbours and pieces, vertices and measures to rounding.
            CHECK(c.indptr == s.indptr);
            CHECK(c.indices == s.indices);
            CHECK(c.piece_ptr == s.piece_ptr);
            CHECK(c.piece_neighbor == s.piece_neighbor);
            double worst = 0.0;
            for (std::size_t k = 0; k < s.piece_x.size(); ++k)
                worst = std::max({worst, std::fabs(c.piece_x[k] - s.piece_x[k]), std::fabs(c.piece_y[k] - s.piece_y[k])});
            for (std::size_t i = 0; i < s.areas.size(); ++i)
                worst = std::max(worst, std::fabs(c.areas[i] - s.areas[i]) / (R * R));
            CHECK(worst < 1e-12 * 40.0);
        }
    }
    // On the square lattice with R = 0.75 every inner vertex is where four bisectors meet: the
    // filter cannot certify that, so Auto hands those cells to Boundary Scan.
    const LimitedPartition lattice = limited_cells(method_inputs()[2].second, 0.75, Method::Auto, 1);
    CHECK(lattice.computed_by.scan > lattice.size() / 2);
}

TEST_CASE("method names: auto is the default and parses; limited_cell's auto is Boundary Scan") {
    CHECK(parse_method("auto") == Method::Auto);
    CHECK(parse_method("scan") == Method::Scan);
    CHECK(parse_method("chords") == Method::Chords);
    CHECK(std::string(method_name(Method::Auto)) == "auto");
    CHECK_THROWS_AS(parse_method("fast"), InputError);
    const Points P = random_points(200, 5, 5.0);
    CHECK(limited_cells(P, 0.5).method == Method::Auto);
    Points others = P.bottomRows(199);
    const LimitedCell one = limited_cell(P.row(0).transpose(), others, 0.5);
    const LimitedCell bs = boundary_scan_cell(P.row(0).transpose(), others, 0.5);
    CHECK(one.neighbors() == bs.neighbors());
    CHECK(one.measures().area == bs.measures().area);
}
