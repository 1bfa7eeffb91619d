// The hull boundary (collinear agents on hull edges included) against a brute-force definition: an
// agent is on the boundary exactly when some line through it and another agent has every agent on
// one closed side; next(i) is the nearest agent along i's counter-clockwise supporting line.
#include "dvoronoi/core/convex_hull.hpp"

#include <doctest/doctest.h>

#include <random>
#include <set>

using namespace dvoronoi;

namespace {

Vec2 at(const Points& p, Index i) { return p.row(i).transpose(); }

bool supports(const Points& p, Index i, Index q, int side) {
    for (Index r = 0; r < p.rows(); ++r)
        if (side * pred::orient(at(p, i), at(p, q), at(p, r)) < 0) return false;
    return true;
}

void check_against_brute_force(const Points& p) {
    const ConvexHull hull(p);
    const Index n = p.rows();
    // The farthest agent from any agent is a corner.
    for (Index i = 0; i < n; ++i) {
        double all = 0.0, corners = 0.0;
        for (Index q = 0; q < n; ++q) all = std::max(all, (at(p, q) - at(p, i)).squaredNorm());
        for (Index q : hull.corners()) corners = std::max(corners, (at(p, q) - at(p, i)).squaredNorm());
        CHECK(corners == all);
    }
    for (Index i = 0; i < n; ++i) {
        bool on = n == 1;
        for (Index q = 0; q < n && !on; ++q)
            if (q != i) on = supports(p, i, q, +1) || supports(p, i, q, -1);
        CHECK(hull.on_boundary(i) == on);
        if (!on || n == 1 || hull.collinear()) continue;
        // Every agent lies left of (or on) i -> next(i), and none strictly between them.
        const Index nx = hull.next(i);
        CHECK(supports(p, i, nx, +1));
        CHECK(hull.prev(nx) == i);
        for (Index r = 0; r < n; ++r)
            if (r != i && r != nx && pred::orient(at(p, i), at(p, nx), at(p, r)) == 0)
                CHECK(pred::dot_sign(at(p, r), at(p, i), at(p, nx)) >= 0);  // r not strictly inside the segment
    }
}

}  // namespace

TEST_CASE("hull boundary of random points, lattices with long collinear edges, and a line") {
    std::mt19937_64 rng(3);
    for (int rep = 0; rep < 40; ++rep) {
        const Index n = 3 + rep * 2;
        Points p(n, 2);
        std::uniform_int_distribution<int> cell(0, rep % 2 ? 5 : 1000);
        std::set<std::pair<int, int>> seen;
        for (Index i = 0; i < n;) {
            const int x = cell(rng), y = cell(rng);
            if (!seen.insert({x, y}).second) {
                if (seen.size() >= 36 && rep % 2) break;
                continue;
            }
            p.row(i++) << x, y;
        }
        check_against_brute_force(p.topRows(static_cast<Index>(seen.size()) < n ? static_cast<Index>(seen.size()) : n));
    }
    // Larger sets, where the extreme-agent prefilter drops most agents: ties in every direction
    // (a lattice), and agents on a circle around an interior cloud.
    Points lattice(289, 2);
    for (Index i = 0; i < 289; ++i) lattice.row(i) << static_cast<double>(i % 17), static_cast<double>(i / 17);
    check_against_brute_force(lattice);
    Points ring(300, 2);
    std::uniform_real_distribution<double> u(-0.7, 0.7);
    for (Index i = 0; i < 200; ++i) ring.row(i) << std::cos(0.0314 * static_cast<double>(i)), std::sin(0.0314 * static_cast<double>(i));
    for (Index i = 200; i < 300; ++i) ring.row(i) << u(rng), u(rng);
    check_against_brute_force(ring);
    Points line(7, 2);
    for (Index i = 0; i < 7; ++i) line.row(i) << 3.0 * static_cast<double>((i * 5) % 7), 1.0 + 2.0 * static_cast<double>((i * 5) % 7);
    const ConvexHull h(line);
    CHECK(h.collinear());
    CHECK(h.boundary().size() == 7);
    CHECK(h.witnesses().empty());
    check_against_brute_force(line);
}

TEST_CASE("extreme corner in a direction") {
    Points sq(5, 2);
    sq << 0, 0, 2, 0, 2, 2, 0, 2, 1, 1;
    const ConvexHull h(sq);
    CHECK(h.extreme(Vec2(1, 0.1), sq) == 2);
    CHECK(h.extreme(Vec2(-1, -0.1), sq) == 0);
    CHECK(h.extreme(Vec2(0.1, -1), sq) == 1);
    CHECK(h.extreme(Vec2(-0.1, 1), sq) == 3);
    CHECK_FALSE(h.on_boundary(4));
}
