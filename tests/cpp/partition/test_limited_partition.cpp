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
