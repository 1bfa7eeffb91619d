// The certified clipping filter against Boundary Scan itself: whenever the filter decides, its cell is
// Boundary Scan's bit for bit (pieces, order, coordinates, spans, measures); when it cannot, it says so
// and the filtered call still returns Boundary Scan's cell. Inputs are chosen to put the filter's
// error bounds under stress: exact lattices (it must give up, never guess), lattices jittered by a few
// units in the last place, nearly collinear and nearly cocircular sets, tangent chords, far offsets
// and tiny spacings.
#include "dvoronoi/cells/certified_clip.hpp"
#include "dvoronoi/core/grid_index.hpp"
#include "dvoronoi/partition/limited_partition.hpp"

#include "cells/cell_reference.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

using namespace dvoronoi;

namespace {

struct Tally {
    long decided = 0, total = 0;
};

bool same_cell(const LimitedCell& a, const LimitedCell& b) {
    if (a.pieces.size() != b.pieces.size() || a.candidates != b.candidates) return false;
    for (std::size_t t = 0; t < a.pieces.size(); ++t) {
        const Piece &x = a.pieces[t], &y = b.pieces[t];
        if (x.neighbor != y.neighbor || x.start != y.start || x.arc_span != y.arc_span) return false;
    }
    const CellMeasures ma = a.measures(), mb = b.measures();
    return ma.area == mb.area && ma.perimeter == mb.perimeter && ma.centroid == mb.centroid;
}

/// Every agent of P: the filter, when it decides, equals Boundary Scan; the filtered call always does.
Tally check_all(const Points& P, double R, const std::string& name) {
    Tally tally;
    const GridIndex index(P, 2.0 * R);
    std::vector<detail::Candidate> cand;
    LimitedCell bs, clipped, filtered;
    detail::CellWorkspace ws;
    detail::ClipWorkspace cw;
    for (std::size_t pos = 0; pos < static_cast<std::size_t>(P.rows()); ++pos) {
        index.within_at(pos, R, cand);
        const Vec2 c = index.point_at(pos);
        detail::boundary_scan(c, cand, R, bs, ws);
        const bool decided = detail::certified_clip_cell(c, cand, R, clipped, cw);
        INFO(name, " R=", R, " agent=", index.grid_order()[pos]);
        if (decided) CHECK(same_cell(clipped, bs));
        detail::filtered_boundary_scan(c, cand, R, filtered, ws, cw);
        CHECK(same_cell(filtered, bs));
        tally.decided += decided;
        ++tally.total;
    }
    return tally;
}

Points uniform(unsigned seed, int n, double side, Vec2 offset = Vec2::Zero()) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, side);
    Points P(n, 2);
    for (int i = 0; i < n; ++i) P.row(i) << offset.x() + u(rng), offset.y() + u(rng);
    return P;
}

}  // namespace

TEST_CASE("uniform swarms: the filter decides almost every cell and equals Boundary Scan") {
    for (unsigned seed = 0; seed < 6; ++seed) {
        const int n = 3000;
        const Points P = uniform(seed, n, 1.0);
        for (double k : {3.0, 8.0, 30.0, 120.0}) {  // agents within 2R
            const double R = std::sqrt(k / (4.0 * 3.14159265358979 * n));
            const Tally t = check_all(P, R, "uniform seed " + std::to_string(seed));
            // The point of the filter: in a swarm it, not the fallback, computes the cells.
            if (k >= 8.0) CHECK(t.decided >= t.total * 9 / 10);
        }
    }
}

TEST_CASE("exact lattices and cocircular sets: the filter gives up rather than guess") {
    for (const auto& f : testref::degenerate_families()) check_all(f.pts, f.radius, f.name);
    // Square lattice, R = 1.5: every agent has four cocircular neighbours at each of its vertices.
    const Tally t = check_all(testref::grid(12, 1.0), 1.5, "square lattice");
    CHECK(t.decided == 0);
}

TEST_CASE("lattices jittered by a few ulps or by 1e-14 .. 1e-10, far offsets, tiny spacings") {
    std::mt19937_64 rng(42);
    std::uniform_int_distribution<int> ulps(-4, 4);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const std::pair<double, Vec2> cases[] = {{1.0, Vec2(0.0, 0.0)},  {1.0, Vec2(1e7, -1e7)},    {1e-9, Vec2(0.0, 0.0)},
                                             {1e-9, Vec2(0.3, 0.7)}, {3.0e6, Vec2(1e7, -1e7)}, {0.1, Vec2(0.3, 0.7)}};
    Tally all;
    for (const auto& [scale, offset] : cases)
        for (double jitter : {0.0, 1e-14, 1e-12, 1e-10}) {  // 0: a few ulps
            Points P = testref::grid(14, scale, offset);
            for (Index i = 0; i < P.rows(); ++i)
                for (int d = 0; d < 2; ++d) {
                    double& x = P(i, d);
                    if (jitter > 0.0) {
                        x += jitter * scale * unit(rng);
                        continue;
                    }
                    const int k = ulps(rng);
                    // 0 stays 0: a few ulps of 0 are subnormals (1e-323) beside spacings of 1e-9, a
                    // span no test in doubles holds (a RangeError now, test_predicates.cpp; before,
                    // a sign of 0 where the exact one was not).
                    if (x == 0.0) continue;
                    for (int s = 0; s < std::abs(k); ++s) x = std::nextafter(x, k > 0 ? 1e300 : -1e300);
                }
            for (double R : {0.5, 0.71, 1.0, 1.5, 2.3}) {
                const Tally t = check_all(P, R * scale, "jittered lattice");
                all.decided += t.decided;
                all.total += t.total;
            }
        }
    // Both outcomes occur: the bounds are exercised, not just the fallback.
    CHECK(all.decided > 0);
    CHECK(all.decided < all.total);
}

TEST_CASE("nearly collinear and nearly cocircular sets, tangent chords") {
    // Agents on a circle of radius 1 around the origin, rounded: nearly cocircular, with the center.
    for (int m : {5, 12, 40}) {
        Points P(m + 1, 2);
        for (int t = 0; t < m; ++t) P.row(t) << std::cos(2 * 3.14159265358979 * t / m), std::sin(2 * 3.14159265358979 * t / m);
        P.row(m) << 0.0, 0.0;
        for (double R : {0.5, 0.5000000000000001, 0.9, 1.0, 3.0}) check_all(P, R, "rounded circle " + std::to_string(m));
    }
    // Two rows at distance 1e-12 .. 1e-3 apart (very elongated cells, nearly parallel bisectors).
    for (double gap : {1e-12, 1e-7, 1e-3}) {
        Points P(60, 2);
        for (int a = 0; a < 30; ++a) {
            P.row(a) << a * 0.1, 0.0;
            P.row(30 + a) << a * 0.1 + 0.05, gap;
        }
        for (double R : {0.05, 0.2, 1.0}) check_all(P, R, "two rows");
    }
    // Neighbours at exactly 2R minus an ulp (chords nearly tangent to the circle).
    Points P(5, 2);
    const double d = std::nextafter(1.0, 0.0);
    P << 0, 0, d, 0, -d, 0, 0, d, 0, -d;
    check_all(P, 0.5, "tangent chords");
}

TEST_CASE("limited_cells through the filter equals the per-agent Boundary Scan") {
    const Points P = uniform(9, 2000, 10.0, Vec2(-5.0, 3.0));
    for (double R : {0.08, 0.2, 0.6}) {
        const LimitedPartition part = limited_cells(P, R, Method::Auto, 2);  // the filter's route
        CHECK(part.computed_by.clip > 0);
        for (Index i = 0; i < P.rows(); i += 7) {
            Points others(P.rows() - 1, 2);
            for (Index j = 0, k = 0; j < P.rows(); ++j)
                if (j != i) others.row(k++) = P.row(j);
            LimitedCell one = limited_cell(P.row(i).transpose(), others, R, Method::Scan);
            for (Piece& p : one.pieces)
                if (!p.is_arc() && p.neighbor >= i) ++p.neighbor;  // rows of `others` -> rows of P
            CHECK(same_cell(part.cell(i), one));
        }
    }
}

TEST_CASE("a ring of agents near 2R: an arc after every edge (the filter's buffers hold 2 m vertices)") {
    for (int k : {9, 16, 24}) {
        std::vector<detail::Candidate> cand;
        for (int t = 0; t < k; ++t) {
            const double a = 2 * 3.14159265358979 * t / k + 0.1, d = 1.99 + 0.0001 * t;
            cand.push_back({Vec2(d * std::cos(a), d * std::sin(a)), t});
        }
        LimitedCell clipped, scanned;
        detail::ClipWorkspace cw;
        detail::CellWorkspace ws;
        REQUIRE(detail::certified_clip_cell(Vec2(0, 0), cand, 1.0, clipped, cw));
        detail::boundary_scan(Vec2(0, 0), cand, 1.0, scanned, ws);
        CHECK(clipped.pieces.size() == static_cast<std::size_t>(2 * k));
        CHECK(same_cell(clipped, scanned));
    }
}
