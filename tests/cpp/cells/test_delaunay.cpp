// The exact Voronoi neighbours from our Delaunay triangulation (cells/delaunay.hpp): closed-form
// answers on hand-made degenerate inputs (lattices, cocircular sets, collinear and nearly collinear
// points, far offsets, tiny spacings), the new incircle predicate against 128-bit integers, and a
// cross-check against the limited cell with a radius far beyond every Voronoi vertex.
#include "dvoronoi/cells/delaunay.hpp"
#include "dvoronoi/cells/limited_cell.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

using namespace dvoronoi;
__extension__ typedef __int128 I;  // exact reference arithmetic (GCC/Clang)

namespace {

int sgn(I v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

/// The cell of agent i of P among all the others, neighbours as rows of P.
DelaunayCell cell_of(const Points& P, Index i) {
    Points others(P.rows() - 1, 2);
    std::vector<Index> row;
    for (Index j = 0; j < P.rows(); ++j)
        if (j != i) {
            others.row(static_cast<Index>(row.size())) = P.row(j);
            row.push_back(j);
        }
    DelaunayCell c = delaunay_cell(P.row(i).transpose(), others);
    for (Index& k : c.neighbors) k = row[static_cast<std::size_t>(k)];
    return c;
}

Points from(const std::vector<std::array<double, 2>>& xy) {
    Points P(static_cast<Index>(xy.size()), 2);
    for (std::size_t i = 0; i < xy.size(); ++i) P.row(static_cast<Index>(i)) << xy[i][0], xy[i][1];
    return P;
}

Points lattice(int k, double spacing, double ox = 0.0, double oy = 0.0) {  // row a * k + b is (a, b)
    Points P(k * k, 2);
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) P.row(a * k + b) << ox + a * spacing, oy + b * spacing;
    return P;
}

std::set<Index> as_set(const std::vector<Index>& v) { return {v.begin(), v.end()}; }

/// Consecutive neighbours turn strictly counter-clockwise around the agent (cyclically for an
/// interior agent); a hull agent's gap from its last neighbour back to its first is at least pi.
void check_ccw(const Points& P, Index i, const DelaunayCell& c) {
    const Vec2 ctr = P.row(i).transpose();
    const std::size_t s = c.neighbors.size();
    const auto p = [&](std::size_t k) { return Vec2(P.row(c.neighbors[k % s]).transpose()); };
    for (std::size_t k = 0; k + 1 < s + (c.on_hull ? 0 : 1); ++k) CHECK(pred::orient(ctr, p(k), p(k + 1)) > 0);
    if (c.on_hull && s >= 2) CHECK(pred::orient(ctr, p(s - 1), p(0)) <= 0);
    if (!c.on_hull) CHECK(c.neighbors.front() == *std::min_element(c.neighbors.begin(), c.neighbors.end()));
}

/// Square lattice k x k (row a * k + b at (a, b) in lattice units): an agent's Voronoi neighbours
/// are its 4-neighbours in the lattice; the diagonal ones touch in a point only.
void check_square_lattice(const Points& P, int k, const std::string& name) {
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) {
            const Index i = a * k + b;
            INFO(name, " agent (", a, ", ", b, ")");
            std::set<Index> expected;
            if (a > 0) expected.insert(i - k);
            if (a + 1 < k) expected.insert(i + k);
            if (b > 0) expected.insert(i - 1);
            if (b + 1 < k) expected.insert(i + 1);
            const DelaunayCell c = cell_of(P, i);
            CHECK(as_set(c.neighbors) == expected);
            CHECK(c.neighbors.size() == expected.size());
            CHECK(c.on_hull == (a == 0 || b == 0 || a + 1 == k || b + 1 == k));
            check_ccw(P, i, c);
        }
}

}  // namespace

TEST_CASE("pred::incircle and the stack-based exact stage agree with 128-bit integers") {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> coord(-6, 6);
    const double scale = std::ldexp(1.0, -30), shift = std::ldexp(1.0, 20);
    int zeros = 0;
    for (int it = 0; it < 20000; ++it) {
        I x[8];
        for (I& v : x) v = coord(rng);
        const I adx = x[0] - x[6], ady = x[1] - x[7], bdx = x[2] - x[6], bdy = x[3] - x[7];
        const I cdx = x[4] - x[6], cdy = x[5] - x[7];
        const int ref = sgn((adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) -
                            (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
                            (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady));
        zeros += ref == 0;
        for (int variant = 0; variant < 2; ++variant) {
            const auto p = [&](int k) {
                const double u = static_cast<double>(x[2 * k]), v = static_cast<double>(x[2 * k + 1]);
                return variant == 0 ? Vec2(u, v) : Vec2(u * scale + shift, v * scale - shift);
            };
            CHECK(pred::incircle(p(0), p(1), p(2), p(3)) == ref);
            const Vec2 a = p(0) - p(3), b = p(1) - p(3), c = p(2) - p(3);  // exact differences
            CHECK(detail::xp::incircle_exact(a.x(), a.y(), b.x(), b.y(), c.x(), c.y()) == ref);
            CHECK(detail::xp::orient_exact(a.x(), a.y(), b.x(), b.y()) == sgn(adx * bdy - ady * bdx));
        }
    }
    CHECK(zeros > 500);  // ties are frequent: the exact stages are exercised
    // Wide dynamic range: terms of very different magnitude that cancel exactly or almost.
    const double e = std::ldexp(1.0, -52);  // 1 + e and 1 - e / 2 are doubles
    for (double d : {0.0, e, -0.5 * e}) {
        const Vec2 a(1.0, 0.0), b(0.0, 1.0), c(-1.0, 0.0);  // unit circle, counter-clockwise
        const Vec2 q(0.0, -1.0 - d);
        CHECK(pred::incircle(a, b, c, q) == (d == 0.0 ? 0 : (d < 0.0 ? 1 : -1)));
    }
    // The origin against the circle through (2 + t, 0), (1, 1), (1, -1): on it for t = 0, outside for
    // t > 0, inside for t < 0 (the stage takes exact differences to the query point, here the origin).
    for (double t : {0.0, 2 * e, -e}) {
        const int expected = t == 0.0 ? 0 : (t > 0.0 ? -1 : 1);
        CHECK(detail::xp::incircle_exact(2.0 + t, 0.0, 1.0, 1.0, 1.0, -1.0) == expected);
        CHECK(pred::incircle(Vec2(2.0 + t, 0.0), Vec2(1.0, 1.0), Vec2(1.0, -1.0), Vec2(0.0, 0.0)) == expected);
    }
}

TEST_CASE("the stack-based exact stages agree with the general expansions on near-ties") {
    // Full 53-bit coordinates (the products round): points nearly on a line through the origin and
    // nearly on a circle through it. Differences to the origin are exact, as the stage requires.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Vec2 o(0.0, 0.0);
    int zero_o = 0, zero_c = 0;
    for (int it = 0; it < 20000; ++it) {
        const double s = std::ldexp(1.0, static_cast<int>(rng() % 40) - 20);
        const Vec2 a(u(rng) * s, u(rng) * s);
        const double t = u(rng) * 3.0;
        Vec2 b(a.x() * t, a.y() * t);  // rounded: nearly collinear with o and a
        if (it % 3 == 0) b = 2.0 * a;  // exactly collinear
        const int so = pred::orient(o, a, b);
        zero_o += so == 0;
        CHECK(detail::xp::orient_exact(a.x(), a.y(), b.x(), b.y()) == so);
        // Three points near the circle of center m through the origin.
        const Vec2 m(u(rng) * s, u(rng) * s);
        const auto on = [&](double ang) { return Vec2(m.x() + m.norm() * std::cos(ang), m.y() + m.norm() * std::sin(ang)); };
        Vec2 p = on(u(rng) * 3.0), q = on(u(rng) * 3.0), r = on(u(rng) * 3.0);
        if (it % 3 == 0) {  // exactly cocircular: a lattice-like circle through the origin
            p = Vec2(2.0, 0.0) * s;
            q = Vec2(1.0, 1.0) * s;
            r = Vec2(1.0, -1.0) * s;
        }
        const int sc = pred::incircle(p, q, r, o);
        zero_c += sc == 0;
        CHECK(detail::xp::incircle_exact(p.x(), p.y(), q.x(), q.y(), r.x(), r.y()) == sc);
    }
    CHECK(zero_o > 1000);
    CHECK(zero_c > 1000);
}

TEST_CASE("no, one and two others") {
    const Vec2 c(0.25, -3.0);
    DelaunayCell d = delaunay_cell(c, Points(0, 2));
    CHECK(d.neighbors.empty());
    CHECK(d.on_hull);
    d = delaunay_cell(c, from({{{1.0, 1.0}}}));
    CHECK(d.neighbors == std::vector<Index>{0});
    CHECK(d.on_hull);
    d = delaunay_cell(c, from({{{1.0, 1.0}}, {{0.0, 0.0}}}));  // a triangle: both are neighbours
    CHECK(as_set(d.neighbors) == std::set<Index>{0, 1});
    CHECK(d.on_hull);
}

TEST_CASE("square lattices: 4 neighbours inside, corners on the hull with 2") {
    check_square_lattice(lattice(3, 1.0), 3, "3x3");
    check_square_lattice(lattice(5, 1.0), 5, "5x5");
    check_square_lattice(lattice(2, 1.0), 2, "2x2 (four cocircular points)");
    check_square_lattice(lattice(6, 0.5, -1.25, 3.0), 6, "6x6 spacing 0.5");
    // Far from the origin with unit spacing, and tiny spacings (all exactly representable lattices).
    check_square_lattice(lattice(5, 1.0, 1e7, -1e7), 5, "5x5 near 1e7");
    check_square_lattice(lattice(4, 1.0, 123456789.0, 987654321.0), 4, "4x4 near 1e9");
    check_square_lattice(lattice(5, std::ldexp(1.0, -30)), 5, "5x5 spacing 2^-30");
    check_square_lattice(lattice(5, std::ldexp(1.0, -30), 0.5, 0.25), 5, "5x5 spacing 2^-30 at (0.5, 0.25)");
    check_square_lattice(lattice(3, 1e-9), 3, "3x3 spacing 1e-9");  // 0, h, 2h: exact multiples
    // The center of the 5x5 lattice: its four neighbours counter-clockwise from the smallest index.
    const DelaunayCell c = cell_of(lattice(5, 1.0), 12);
    CHECK(c.neighbors == std::vector<Index>{7, 11, 17, 13});  // (1,2) (2,1) (3,2) (2,3): W S E N
    CHECK_FALSE(c.on_hull);
}

TEST_CASE("points on one circle, with and without its center") {
    // The 12 integer points of the circle of radius 5, counter-clockwise from (5, 0).
    const std::vector<std::array<double, 2>> ring = {{{5, 0}},  {{4, 3}},   {{3, 4}},   {{0, 5}},
                                                     {{-3, 4}}, {{-4, 3}},  {{-5, 0}},  {{-4, -3}},
                                                     {{-3, -4}}, {{0, -5}}, {{3, -4}},  {{4, -3}}};
    // (scale, offset) pairs that keep the points exactly on their circle.
    const std::vector<std::pair<double, double>> frames = {
        {1.0, 0.0}, {1.0, 1e7}, {1e6, 1e7}, {std::ldexp(1.0, -32), 0.0}, {std::ldexp(1.0, -32), 0.5}};
    for (const auto& [s, off] : frames) {
        {
            std::vector<std::array<double, 2>> xy;
            for (const auto& p : ring) xy.push_back({{p[0] * s + off, p[1] * s - off}});
            const Points R = from(xy);
            xy.push_back({{off, -off}});
            const Points C = from(xy);
            INFO("scale ", s, " offset ", off);
            // With the center: it sees all 12 (a 12-gon cell), each ring point sees it and its
            // two ring neighbours (two rays and one segment).
            DelaunayCell c = cell_of(C, 12);
            std::vector<Index> all(12);
            for (Index k = 0; k < 12; ++k) all[static_cast<std::size_t>(k)] = k;
            CHECK(c.neighbors == all);
            CHECK_FALSE(c.on_hull);
            for (Index k = 0; k < 12; ++k) {
                c = cell_of(C, k);
                CHECK(c.neighbors == std::vector<Index>{(k + 1) % 12, 12, (k + 11) % 12});
                CHECK(c.on_hull);
                // Without the center every Voronoi vertex is the circle's center: only the two ring
                // neighbours share an edge (a ray each).
                c = cell_of(R, k);
                CHECK(c.neighbors == std::vector<Index>{(k + 1) % 12, (k + 11) % 12});
                CHECK(c.on_hull);
            }
        }
    }
}

TEST_CASE("collinear inputs: predecessor and successor along the line, all on the hull") {
    std::mt19937 rng(5);
    const std::vector<std::array<double, 2>> dirs = {{{1, 0}}, {{0, 1}}, {{1, 1}}, {{3, -7}}, {{-0.125, 0x1p-10}}};
    for (const auto& d : dirs) {
        for (const double off : {0.0, 1e7}) {
            std::vector<int> t(20);
            for (int k = 0; k < 20; ++k) t[static_cast<std::size_t>(k)] = 2 * k - 7;
            std::shuffle(t.begin(), t.end(), rng);  // input order unrelated to the line order
            Points P(20, 2);
            for (Index k = 0; k < 20; ++k)
                P.row(k) << off + t[static_cast<std::size_t>(k)] * d[0], off + t[static_cast<std::size_t>(k)] * d[1];
            for (Index i = 0; i < 20; ++i) {
                INFO("direction (", d[0], ", ", d[1], ") offset ", off, " agent ", i);
                std::set<Index> expected;
                const int ti = t[static_cast<std::size_t>(i)];
                for (Index j = 0; j < 20; ++j)
                    if (std::abs(t[static_cast<std::size_t>(j)] - ti) == 2) expected.insert(j);
                const DelaunayCell c = cell_of(P, i);
                CHECK(as_set(c.neighbors) == expected);
                CHECK(c.neighbors.size() == expected.size());
                CHECK(c.on_hull);
            }
        }
    }
}

TEST_CASE("collinear points plus one agent off the line") {
    // The off-line agent sees every point of the line (each triangle's circle meets the line only at
    // its two points), counter-clockwise; the line points see their line neighbours and the agent.
    const Points P = from({{{-2, 0}}, {{-1, 0}}, {{0, 0}}, {{1, 0}}, {{2, 0}}, {{0.25, 1}}});
    DelaunayCell c = cell_of(P, 5);
    CHECK(c.neighbors == std::vector<Index>{0, 1, 2, 3, 4});
    CHECK(c.on_hull);
    for (Index i = 0; i < 5; ++i) {
        c = cell_of(P, i);
        std::set<Index> expected{5};
        if (i > 0) expected.insert(i - 1);
        if (i < 4) expected.insert(i + 1);
        CHECK(as_set(c.neighbors) == expected);
        CHECK(c.on_hull);
        check_ccw(P, i, c);
    }
}

TEST_CASE("nearly collinear zigzag: the strip of triangles (i, i+1, i+2)") {
    // Point i at (x0 + i, y0 + (-1)^i e): the triangulation is the strip of nearly flat triangles
    // (i, i+1, i+2) (circumcentres about 1/(4e) away), every point is on the hull, and i's
    // neighbours are i-2, i-1, i+1, i+2, counter-clockwise from the hull gap.
    for (const int n : {10, 25})
        for (const double e : {1e-12, std::ldexp(1.0, -50), 1e-6})
            for (const double x0 : {0.0, 1e7, -3.5}) {
                std::vector<std::array<double, 2>> xy;
                for (int i = 0; i < n; ++i) xy.push_back({{x0 + i, 2.0 + (i % 2 ? -e : e)}});
                const Points P = from(xy);
                for (Index i = 0; i < n; ++i) {
                    INFO("n ", n, " e ", e, " x0 ", x0, " agent ", i);
                    const std::vector<Index> cand =
                        i % 2 == 0 ? std::vector<Index>{i - 2, i - 1, i + 1, i + 2} : std::vector<Index>{i + 2, i + 1, i - 1, i - 2};
                    std::vector<Index> expected;
                    for (Index j : cand)
                        if (j >= 0 && j < n) expected.push_back(j);
                    const DelaunayCell c = cell_of(P, i);
                    CHECK(c.neighbors == expected);
                    CHECK(c.on_hull);
                }
            }
}

TEST_CASE("input order does not matter: permuted others give the same cell") {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> u(0, 6);
    for (int rep = 0; rep < 40; ++rep) {
        std::set<std::pair<int, int>> s;
        while (s.size() < 20) s.insert({u(rng), u(rng)});
        std::vector<std::array<double, 2>> xy;
        for (auto [x, y] : s) xy.push_back({{static_cast<double>(x), static_cast<double>(y)}});
        const Points P = from(xy);
        std::vector<Index> perm(20);
        for (Index k = 0; k < 20; ++k) perm[static_cast<std::size_t>(k)] = k;
        std::shuffle(perm.begin(), perm.end(), rng);
        Points Q(20, 2);
        for (Index k = 0; k < 20; ++k) Q.row(k) = P.row(perm[static_cast<std::size_t>(k)]);
        for (Index i = 0; i < 20; ++i) {
            const DelaunayCell a = cell_of(P, perm[static_cast<std::size_t>(i)]);
            DelaunayCell b = cell_of(Q, i);
            for (Index& k : b.neighbors) k = perm[static_cast<std::size_t>(k)];
            if (!b.on_hull && !b.neighbors.empty())
                std::rotate(b.neighbors.begin(), std::min_element(b.neighbors.begin(), b.neighbors.end()), b.neighbors.end());
            CHECK(a.neighbors == b.neighbors);
            CHECK(a.on_hull == b.on_hull);
        }
    }
}

TEST_CASE("cross-check: the limited cell with a radius beyond every Voronoi vertex") {
    // With R far beyond the spread every agent is within 2R and every Voronoi edge of positive
    // length (segment or ray) passes within R, so the limited neighbours are the Voronoi
    // neighbours, and the limited cell has an arc exactly when the Voronoi cell is unbounded.
    // "Far beyond": a Voronoi vertex is a circumcentre, at distance s^2 / delta for a nearly
    // collinear triple of spread s bent by delta; rounded lattices bend by about an ulp of the
    // coordinates, so s / delta reaches 1e17 (spacing 1e-9): R = 1e24 s.
    const auto cross_check = [](const Points& P, const std::string& name) {
        const double spread = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
        const double R = 1e24 * spread;
        for (Index i = 0; i < P.rows(); ++i) {
            INFO(name, " agent ", i);
            Points others(P.rows() - 1, 2);
            for (Index j = 0, r = 0; j < P.rows(); ++j)
                if (j != i) others.row(r++) = P.row(j);
            const LimitedCell lc = limited_cell(P.row(i).transpose(), others, R);
            const DelaunayCell dc = delaunay_cell(P.row(i).transpose(), others);
            const std::vector<Index> lim = lc.neighbors();
            CHECK(as_set(dc.neighbors) == std::set<Index>(lim.begin(), lim.end()));
            CHECK(dc.neighbors.size() == lim.size());
            const bool arc = std::any_of(lc.pieces.begin(), lc.pieces.end(), [](const Piece& p) { return p.is_arc(); });
            CHECK(dc.on_hull == arc);
            check_ccw(P, i, cell_of(P, i));
        }
    };
    std::mt19937 rng(2024);
    for (int seed = 0; seed < 40; ++seed) {
        const int n = 4 + (seed * 7) % 50;
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        Points P(n, 2);
        for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng);
        cross_check(P, "uniform seed " + std::to_string(seed));
        // Near 1e7 with unit spacing, and at spacing 1e-9 (rounded coordinates: near-ties).
        Points F(n, 2), T(n, 2);
        std::uniform_int_distribution<int> g(0, 9);
        std::set<std::pair<int, int>> used;
        for (int i = 0; i < n;) {
            const int x = g(rng), y = g(rng);
            if (!used.insert({x, y}).second) continue;
            F.row(i) << 1e7 + x + 0.25 * u(rng), -1e7 + y + 0.25 * u(rng);
            T.row(i) << x * 1e-9, y * 1e-9;
            ++i;
        }
        cross_check(F, "near 1e7 seed " + std::to_string(seed));
        cross_check(T, "spacing 1e-9 lattice subset seed " + std::to_string(seed));
    }
    // Rounded regular polygons around their center: nearly cocircular, decided exactly.
    for (int k : {3, 4, 5, 6, 8, 16}) {
        Points P(k + 1, 2);
        for (int i = 0; i < k; ++i) P.row(i) << std::cos(2 * 3.14159265358979323846 * i / k), std::sin(2 * 3.14159265358979323846 * i / k);
        P.row(k) << 0.0, 0.0;
        cross_check(P, "regular " + std::to_string(k) + "-gon with center");
        cross_check(Points(P.topRows(k)), "regular " + std::to_string(k) + "-gon");
    }
    // Nearly collinear with rounded products: integer x, y = x / 3 rounded, moved by a few ulps.
    for (int seed = 0; seed < 10; ++seed) {
        std::mt19937_64 g(static_cast<std::uint64_t>(seed));
        std::set<int> xs;
        while (xs.size() < 20) xs.insert(static_cast<int>(g() % 1000));
        Points P(20, 2);
        Index i = 0;
        for (int x : xs) {
            const double y = x / 3.0;
            P.row(i++) << x, y + static_cast<double>(static_cast<int>(g() % 5) - 2) * std::ldexp(y, -52);
        }
        cross_check(P, "nearly collinear, slope 1/3, seed " + std::to_string(seed));
    }
    cross_check(lattice(5, 1e-9, 3e-9, -7e-9), "5x5 lattice, spacing 1e-9 (rounded)");
    cross_check(lattice(5, 0.1), "5x5 lattice, spacing 0.1 (rounded)");
}

TEST_CASE("bad input: coinciding agents and non-finite coordinates") {
    const Points P = from({{{0, 0}}, {{1, 0}}, {{0, 1}}, {{1, 0}}});
    try {
        delaunay_cell(Vec2(5.0, 5.0), P);
        FAIL("expected CoincidentError");
    } catch (const CoincidentError& e) {
        CHECK(e.first() == 1);
        CHECK(e.second() == 3);
    }
    try {
        delaunay_cell(Vec2(0.0, 1.0), from({{{0, 0}}, {{1, 0}}, {{0, 1}}}));
        FAIL("expected CoincidentError");
    } catch (const CoincidentError& e) {
        CHECK(e.first() == 2);
        CHECK(std::string(e.what()).find("center") != std::string::npos);
    }
    CHECK_THROWS_AS(delaunay_cell(Vec2(0.0, 0.0), from({{{1, 1}}, {{2, 2}}, {{1, 1}}})), CoincidentError);  // collinear
    CHECK_THROWS_AS(delaunay_cell(Vec2(std::nan(""), 0.0), P), InputError);
    CHECK_THROWS_AS(delaunay_cell(Vec2(0.5, 0.5), from({{{1, 1}}, {{HUGE_VAL, 2}}})), InputError);
}
