// GridIndex::for_each_in_disk visits every agent inside any disk (a superset is allowed), for small,
// huge and far-away disks, on dense and sparse grids, and stops when asked.
#include "dvoronoi/core/grid_index.hpp"
#include "dvoronoi/core/predicates.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

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

namespace {

/// Agents j != i strictly within 2R of agent i, by the exact predicate over all agents.
std::set<Index> brute_within(const Points& p, Index i, double radius) {
    std::set<Index> out;
    for (Index j = 0; j < p.rows(); ++j)
        if (j != i && pred::within_2r(p.row(i).transpose(), p.row(j).transpose(), radius) > 0) out.insert(j);
    return out;
}

}  // namespace

TEST_CASE("within / within_at equal the exact brute force for radii below, at and above the index range") {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const auto& [offset, scale] : {std::pair{0.0, 1.0}, std::pair{1e7, 1e-3}, std::pair{-3e5, 40.0}}) {
        // Random agents plus an integer lattice (many agents at exactly 2R: the exact test decides).
        Points p(500, 2);
        for (Index i = 0; i < 300; ++i) p.row(i) << offset + scale * u(rng), offset + scale * u(rng);
        for (Index i = 300; i < 500; ++i) p.row(i) << offset + scale * ((i - 300) % 20) / 20.0, offset + scale * ((i - 300) / 20) / 20.0;
        const double range = 0.04 * scale;
        const GridIndex index(p, range);
        std::vector<detail::Candidate> got;
        for (double radius : {0.01 * scale, 0.02 * scale, 0.025 * scale, 0.05 * scale, 0.11 * scale, 0.2 * scale, 0.25 * scale, 0.4 * scale, 0.7 * scale, 3.0 * scale}) {
            for (std::size_t pos = 0; pos < 500; pos += 3) {
                const Index i = index.grid_order()[pos];
                index.within_at(pos, radius, got);
                std::set<Index> ids;
                for (const auto& q : got) {
                    CHECK(q.p == Vec2(p.row(q.id).transpose()));
                    ids.insert(q.id);
                }
                INFO("offset ", offset, " radius ", radius, " agent ", i);
                CHECK(ids.size() == got.size());
                CHECK(ids == brute_within(p, i, radius));
                // The batches of for_each_batch_within_at hand over the same agents in the same order.
                std::vector<Index> batched;
                index.for_each_batch_within_at(pos, radius, [&](const double* xs, const double* ys, const Index* js,
                                                                const std::uint32_t* sel, std::size_t count) {
                    CHECK(count > 0);
                    for (std::size_t t = 0; t < count; ++t) {
                        CHECK(Vec2(xs[sel[t]], ys[sel[t]]) == Vec2(p.row(js[sel[t]]).transpose()));
                        batched.push_back(js[sel[t]]);
                    }
                });
                REQUIRE(batched.size() == got.size());
                for (std::size_t t = 0; t < got.size(); ++t) CHECK(batched[t] == got[t].id);
                index.within(i, radius, got);
                std::set<Index> by_index;
                for (const auto& q : got) by_index.insert(q.id);
                CHECK(got.size() == ids.size());
                CHECK(by_index == ids);
                CHECK(index.count_within_at(pos, radius) == static_cast<Index>(ids.size()));
            }
        }
    }
}

TEST_CASE("count_within_at on a sparse grid (two far clusters) and for disks holding every agent") {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Points p(400, 2);
    for (Index i = 0; i < 400; ++i) p.row(i) << (i < 200 ? 0.0 : 1e6) + u(rng), u(rng);
    const GridIndex index(p, 0.05);
    for (double radius : {0.01, 0.1, 0.4, 1.0, 4e5, 6e5, 1e7})
        for (std::size_t pos = 0; pos < 400; pos += 7) {
            const Index i = index.grid_order()[pos];
            INFO("radius ", radius, " agent ", i);
            const std::set<Index> want = brute_within(p, i, radius);
            CHECK(index.count_within_at(pos, radius) == static_cast<Index>(want.size()));
            // The sparse grid's queries (its cells are found by binary search) give the same agents.
            std::vector<detail::Candidate> got;
            for (bool at_pos : {true, false}) {
                if (at_pos) index.within_at(pos, radius, got);
                else index.within(i, radius, got);
                std::set<Index> ids;
                for (const auto& q : got) ids.insert(q.id);
                CHECK(ids.size() == got.size());
                CHECK(ids == want);
            }
        }
}

TEST_CASE("the grid's order and queries do not depend on the threads that build it") {
    // Enough agents for three threads to share the counting sort (2^15 each), with a crowded cell
    // whose agents come from every thread's range: within a cell, input order must survive.
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Index n = 3 * (Index{1} << 15) + 17;
    Points p(n, 2);
    for (Index i = 0; i < n; ++i) {
        if (i % 97 == 0) p.row(i) << 0.5 + 1e-4 * u(rng), 0.5 + 1e-4 * u(rng);  // one cell, all ranges
        else p.row(i) << u(rng), u(rng);
    }
    const double radius = 0.004;
    const GridIndex one(p, 2.0 * radius, 1);
    for (int threads : {2, 3, 8}) {
        const GridIndex many(p, 2.0 * radius, threads);
        REQUIRE(many.grid_order() == one.grid_order());
        std::vector<detail::Candidate> a, b;
        for (std::size_t pos = 0; pos < static_cast<std::size_t>(n); pos += 101) {
            one.within_at(pos, radius, a);
            many.within_at(pos, radius, b);
            REQUIRE(a.size() == b.size());
            for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k].id == b[k].id);
        }
    }
    // Within a cell, agents in input order.
    const std::vector<Index>& order = one.grid_order();
    std::vector<Index> crowded;
    for (Index id : order)
        if (id % 97 == 0 && std::abs(p(id, 0) - 0.5) < 1e-3) crowded.push_back(id);
    CHECK(crowded.size() == static_cast<std::size_t>((n + 96) / 97));
    CHECK(std::is_sorted(crowded.begin(), crowded.end()));
}

TEST_CASE("bounding_box equals the coordinates' extremes, for odd and even counts") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    for (Index n : {1, 2, 3, 4, 5, 8, 9, 1001}) {
        Points p(n, 2);
        for (Index i = 0; i < n; ++i) p.row(i) << u(rng), u(rng);
        double x0, y0, x1, y1;
        detail::bounding_box(p, x0, y0, x1, y1);
        CHECK(x0 == p.col(0).minCoeff());
        CHECK(y0 == p.col(1).minCoeff());
        CHECK(x1 == p.col(0).maxCoeff());
        CHECK(y1 == p.col(1).maxCoeff());
    }
}
