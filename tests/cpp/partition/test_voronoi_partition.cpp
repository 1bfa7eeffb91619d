// voronoi_cells: every agent's radius steps and agents in range are ASR's own (what asr_cell reports
// for that agent alone), whichever certificate found the cell and whichever inner step ran; cells
// and numbers do not depend on the thread count.
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace dvoronoi;

namespace {

Points from(const std::vector<Vec2>& v) {
    Points P(static_cast<Index>(v.size()), 2);
    for (std::size_t i = 0; i < v.size(); ++i) P.row(static_cast<Index>(i)) = v[i].transpose();
    return P;
}

/// Point sets whose schedules end every way: certified at step 1, after many steps (close pairs,
/// far vertices near the hull), or with every agent (hull agents, and a collinear set).
std::vector<std::pair<std::string, Points>> families() {
    std::vector<std::pair<std::string, Points>> out;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec2> v;
    for (int i = 0; i < 600; ++i) v.emplace_back(u(rng), u(rng));
    out.emplace_back("uniform", from(v));
    v.clear();
    for (int i = 0; i < 300; ++i) {  // close pairs: the nearest neighbour is far below the spacing
        const Vec2 p(u(rng), u(rng));
        v.push_back(p);
        if (i % 3 == 0) v.push_back(p + Vec2(1e-4 * u(rng) + 1e-6, 1e-4 * u(rng)));
    }
    out.emplace_back("close pairs", from(v));
    v.clear();
    for (int x = 0; x < 18; ++x)
        for (int y = 0; y < 18; ++y) v.emplace_back(1e7 + x, 1e7 + y);
    out.emplace_back("far lattice", from(v));
    v.clear();
    for (int k = 0; k < 64; ++k) v.emplace_back(std::cos(k * M_PI / 32), std::sin(k * M_PI / 32));
    v.emplace_back(0.0, 0.0);
    out.emplace_back("cocircular", from(v));
    v.clear();
    for (int k = 0; k < 40; ++k) v.emplace_back(k * 0.1, k * 0.1 * 1e-9 * (k % 3));
    out.emplace_back("nearly collinear", from(v));
    v.clear();
    for (int k = 0; k < 30; ++k) v.emplace_back(k * 3.0, k * 2.0);
    out.emplace_back("collinear", from(v));
    // Tiny teams: a pair, three in a line, a triangle, a square (cocircular), a square and its center.
    out.emplace_back("pair", from({Vec2(0, 0), Vec2(1, 2)}));
    out.emplace_back("three in a line", from({Vec2(0, 0), Vec2(1, 1), Vec2(3, 3)}));
    out.emplace_back("triangle", from({Vec2(0, 0), Vec2(4, 0), Vec2(1, 3)}));
    out.emplace_back("square", from({Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}));
    out.emplace_back("square and center", from({Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2), Vec2(1, 1)}));
    return out;
}

const char* io_name(AsrInner inner) {
    return inner == AsrInner::Auto ? "auto" : inner == AsrInner::Scan ? "scan" : "evt";
}

}  // namespace

TEST_CASE("radius steps and agents in range equal the one-agent ASR's, for both inner steps") {
    for (const auto& [name, P] : families()) {
        const Index n = P.rows();
        for (AsrInner inner : {AsrInner::Auto, AsrInner::Scan, AsrInner::Evt}) {
            const VoronoiPartition part = voronoi_cells(P, inner, 1);
            int bad = 0, deep = 0, all = 0;
            for (Index i = 0; i < n; ++i) {
                Points others(n - 1, 2);
                others << P.topRows(i), P.bottomRows(n - 1 - i);
                const VoronoiCell cell = asr_cell(P.row(i).transpose(), others, inner);
                const auto si = static_cast<std::size_t>(i);
                bad += part.radius_steps[si] != cell.radius_steps || part.agents_used[si] != cell.agents_used;
                deep += cell.radius_steps >= 4;
                all += cell.agents_used == n - 1;
            }
            INFO(name, " inner ", io_name(inner));
            CHECK(bad == 0);
            CHECK(all > 0);  // hull agents use every agent
            if (n == 5) CHECK(part.radius_steps[4] == 1);  // the center of the square: certified at once
            if (name == "close pairs") CHECK(deep > 20);
        }
    }
}

TEST_CASE("thread count does not change cells or numbers") {
    const Points P = families()[1].second;
    const VoronoiPartition a = voronoi_cells(P, AsrInner::Scan, 1);
    const VoronoiPartition b = voronoi_cells(P, AsrInner::Scan, 2);
    CHECK(a.indptr == b.indptr);
    CHECK(a.indices == b.indices);
    CHECK(a.on_hull == b.on_hull);
    CHECK(a.radius_steps == b.radius_steps);
    CHECK(a.agents_used == b.agents_used);
}

TEST_CASE("scaled far from 1: the same neighbours, or a RangeError beyond the range, never others or a hang") {
    // Before: from 2^-900 on, an exact test that underflowed called two agents coincident inside the
    // parallel loop, and the exception left the OpenMP region (std::terminate); in between, other
    // neighbour sets. Now exact tests are exact at any common scale (rescaled), and Adjust-Sensing-
    // Radius, whose radii start at the nearest neighbour's distance, refuses a distance outside
    // [1e-150, 1e150] (a squared distance of 0 kept doubling a radius of 0 forever).
    Points P(66, 2);
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(0.0, 5.0);
    for (int k = 0; k < 36; ++k) P.row(k) << k % 6, k / 6;
    for (int k = 36; k < 66; ++k) P.row(k) << u(rng), u(rng);
    for (AsrInner inner : {AsrInner::Auto, AsrInner::Scan, AsrInner::Evt}) {
        const VoronoiPartition ref = voronoi_cells(P, inner, 1);
        for (int k : {-480, -300, 300, 480}) {
            const VoronoiPartition got = voronoi_cells(P * std::ldexp(1.0, k), inner, 2);
            CHECK(got.indptr == ref.indptr);
            CHECK(got.indices == ref.indices);
            CHECK(got.on_hull == ref.on_hull);
        }
        for (int k : {-1060, -1000, -900, -600, 600, 900, 1000})
            CHECK_THROWS_WITH_AS(voronoi_cells(P * std::ldexp(1.0, k), inner, 2),
                                 doctest::Contains("Adjust-Sensing-Radius starts its radii at that distance, and they must "
                                                   "lie between 1e-150 and 1e150"),
                                 RangeError);
    }
}

TEST_CASE("inner steps: auto, scan and evt give the same neighbours and hull flags; each runs its route") {
    std::vector<std::pair<std::string, Points>> inputs = families();
    std::mt19937_64 rng(5);
    std::normal_distribution<double> g(0.0, 0.02);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec2> v;
    for (int k = 0; k < 10; ++k) {  // clustered: Gaussian blobs
        const Vec2 c(u(rng), u(rng));
        for (int t = 0; t < 60; ++t) v.push_back(c + Vec2(g(rng), g(rng)));
    }
    inputs.emplace_back("clustered", from(v));
    v.clear();
    for (int a = 0; a < 20; ++a)
        for (int b = 0; b < 20; ++b) v.emplace_back(b + 0.5 * (a % 2), a * std::sqrt(0.75));
    inputs.emplace_back("hexagonal lattice", from(v));
    for (const auto& [name, P] : inputs) {
        INFO(name);
        const Index n = P.rows();
        const VoronoiPartition a = voronoi_cells(P, AsrInner::Auto, 2);
        const VoronoiPartition s = voronoi_cells(P, AsrInner::Scan, 2);
        const VoronoiPartition e = voronoi_cells(P, AsrInner::Evt, 2);
        for (const VoronoiPartition* o : {&s, &e}) {
            CHECK(o->indptr == a.indptr);
            CHECK(o->indices == a.indices);
            CHECK(o->on_hull == a.on_hull);
            CHECK(o->radius_steps == a.radius_steps);
            CHECK(o->agents_used == a.agents_used);
            CHECK(o->computed_by.asr == n);  // ASR with the inner step on every agent
            CHECK(o->computed_by.one_shot + o->computed_by.deferred == 0);
        }
        if (n > 3) {
            CHECK(a.computed_by.asr == 0);
            CHECK(a.computed_by.one_shot + a.computed_by.deferred == n);
        }
        if (name == "uniform") CHECK(a.computed_by.one_shot > n / 2);
    }
}
