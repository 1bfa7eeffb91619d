// GridIndex::for_each_in_disk visits every agent inside any disk (a superset is allowed), for small,
// huge and far-away disks, on dense and sparse grids, and stops when asked.
#include "dvoronoi/core/grid_index.hpp"

#include <doctest/doctest.h>

#include <random>
#include <set>

using namespace dvoronoi;

TEST_CASE("for_each_in_disk covers the disk on dense and sparse grids") {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int sparse = 0; sparse < 2; ++sparse) {
        Points p(400, 2);
        for (Index i = 0; i < 400; ++i) p.row(i) << u(rng) + (sparse && i % 2 ? 1e6 : 0.0), u(rng);
        const GridIndex index(p, 0.05);
        int missed = 0;
        for (int q = 0; q < 300; ++q) {
            const Vec2 c(3.0 * u(rng) - 1.0 + (sparse && q % 2 ? 1e6 : 0.0), 3.0 * u(rng) - 1.0);
            const double r = q % 10 == 0 ? 1e3 * u(rng) : 0.3 * u(rng);
            std::set<Index> seen;
            index.for_each_in_disk(c, r, [&](const Vec2& pos, Index id) {
                CHECK(pos == Vec2(p.row(id).transpose()));
                seen.insert(id);
                return true;
            });
            for (Index i = 0; i < 400; ++i)
                if ((Vec2(p.row(i).transpose()) - c).norm() < r && !seen.count(i)) ++missed;
        }
        CHECK(missed == 0);
    }
}

TEST_CASE("for_each_in_disk stops when the visitor returns false") {
    Points p(50, 2);
    for (Index i = 0; i < 50; ++i) p.row(i) << static_cast<double>(i % 7), static_cast<double>(i / 7);
    const GridIndex index(p, 1.0);
    int visits = 0;
    const bool complete = index.for_each_in_disk(Vec2(3, 3), 100.0, [&](const Vec2&, Index) { return ++visits < 5; });
    CHECK_FALSE(complete);
    CHECK(visits == 5);
}
