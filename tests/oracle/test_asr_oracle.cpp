// ASR (+ Boundary Scan) exact Voronoi cells against CGAL's exact Delaunay triangulation: Voronoi
// neighbour sets (positive-length edges) and hull flags, on random inputs, integer grids (exact
// cocircularities), jittered lattices and every case of the degenerate corpus, plus exact
// transformed copies.
#include "cgal_oracle.hpp"
#include "families.hpp"

#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <sstream>

using dvoronoi_oracle::XY;
namespace fam = dvoronoi_oracle::families;

namespace {

std::size_t g_compared = 0, g_hull = 0;

// Compares every agent (or every `stride`-th) with the oracle; returns the number of mismatches.
int compare(const std::vector<XY>& pts, const std::string& label, std::size_t stride = 1) {
    const auto exact = dvoronoi_oracle::compute_oracle(pts, 1.0);
    const std::size_t n = pts.size();
    int bad = 0;
    dvoronoi::Points others(static_cast<Eigen::Index>(n > 0 ? n - 1 : 0), 2);
    for (std::size_t i = 0; i < n; i += stride) {
        for (std::size_t j = 0, k = 0; j < n; ++j)
            if (j != i) others.row(static_cast<Eigen::Index>(k++)) << pts[j][0], pts[j][1];
        const dvoronoi::Vec2 center(pts[i][0], pts[i][1]);
        const dvoronoi::VoronoiCell cell = dvoronoi::asr_cell(center, others);
        // ASR+EVT agrees with ASR+BS edge for edge (same order, same vertices up to rounding).
        const dvoronoi::VoronoiCell evt = dvoronoi::asr_cell(center, others, dvoronoi::AsrInner::Evt);
        bool same = evt.on_hull == cell.on_hull && evt.neighbors() == cell.neighbors();
        if (same && !cell.on_hull) {
            std::vector<dvoronoi::Index> a, b;
            for (const auto& e : cell.edges) a.push_back(e.neighbor);
            for (const auto& e : evt.edges) b.push_back(e.neighbor);
            const auto first = std::find(b.begin(), b.end(), a.empty() ? -1 : a.front());
            if (first != b.end()) std::rotate(b.begin(), first, b.end());
            same = a == b;
        }
        if (!same) {
            if (bad < 5) MESSAGE(label << ": agent " << i << " ASR+EVT differs from ASR+BS");
            ++bad;
        }
        ++g_compared;
        g_hull += cell.on_hull ? 1 : 0;
        std::set<std::size_t> got;
        for (dvoronoi::Index nb : cell.neighbors()) {
            const auto j = static_cast<std::size_t>(nb);
            got.insert(j < i ? j : j + 1);
        }
        const std::set<std::size_t> want(exact.voronoi_neighbors[i].begin(), exact.voronoi_neighbors[i].end());
        const bool hull_ok = cell.on_hull == static_cast<bool>(exact.on_hull[i]);
        if (got != want || !hull_ok) {
            if (bad < 5) {
                std::ostringstream os;
                os << label << ": agent " << i << " got {";
                for (auto g : got) os << g << ' ';
                os << "} hull " << cell.on_hull << ", exact {";
                for (auto w : want) os << w << ' ';
                os << "} hull " << exact.on_hull[i];
                MESSAGE(os.str());
            }
            ++bad;
        }
        // Edges are counter-clockwise and consecutive edges of a bounded cell meet.
        if (!cell.on_hull && cell.edges.size() >= 3)
            for (std::size_t t = 0; t < cell.edges.size(); ++t) {
                const auto& e = cell.edges[t];
                const auto& f = cell.edges[(t + 1) % cell.edges.size()];
                if ((e.end - f.start).norm() > 1e-9 * (1.0 + e.end.norm())) ++bad;
            }
    }
    return bad;
}

}  // namespace

TEST_CASE("ASR+BS: exact Voronoi neighbours and hull flags on random inputs") {
    int bad = 0;
    for (std::uint64_t seed = 0; seed < 20; ++seed)
        for (std::size_t n : {std::size_t{2}, std::size_t{3}, std::size_t{7}, std::size_t{40}, std::size_t{150}})
            bad += compare(fam::uniform(n, 10.0, seed).points, "uniform n=" + std::to_string(n));
    CHECK(bad == 0);
}

TEST_CASE("ASR+BS: integer grids and jittered lattices") {
    int bad = 0;
    for (std::uint64_t seed = 0; seed < 30; ++seed) {
        bad += compare(fam::grid_subset(8, 400, 1.0, seed).points, "grid subset");
        bad += compare(fam::jittered_lattice(6, 1e-12, 1.0, seed).points, "jittered lattice");
    }
    CHECK(bad == 0);
}

TEST_CASE("ASR+BS: the degenerate corpus") {
    int bad = 0;
    const auto corpus = dvoronoi_oracle::read_corpus(std::string(DVORONOI_TEST_DATA_DIR) + "/degenerate_corpus.txt");
    REQUIRE(corpus.size() > 200);
    const std::size_t before = g_compared;
    for (const auto& c : corpus) bad += compare(c.points, c.name, c.points.size() > 200 ? 7 : 1);
    CHECK(bad == 0);
    // The corpus exercises both bounded and unbounded cells.
    CHECK(g_compared - before > 5000);
    CHECK(g_hull > 1000);
}

TEST_CASE("ASR+BS: exact transforms keep neighbours and hull flags") {
    int bad = 0;
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
        const auto base = fam::grid_subset(7, 500, 1.0, seed);
        for (const auto& t : dvoronoi_oracle::exact_transforms(base.points, 1.0, seed)) bad += compare(t.points, base.name + " " + t.name);
    }
    CHECK(bad == 0);
}

TEST_CASE("voronoi_cells (all agents, grid index, 2 threads) equals the oracle") {
    int bad = 0;
    std::size_t cases = 0;
    auto check = [&](const std::vector<XY>& pts, const std::string& label) {
        ++cases;
        const auto exact = dvoronoi_oracle::compute_oracle(pts, 1.0);
        dvoronoi::Points P(static_cast<Eigen::Index>(pts.size()), 2);
        for (std::size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Eigen::Index>(i)) << pts[i][0], pts[i][1];
        for (auto inner : {dvoronoi::AsrInner::Auto, dvoronoi::AsrInner::Scan, dvoronoi::AsrInner::Evt}) {
            const dvoronoi::VoronoiPartition part = dvoronoi::voronoi_cells(P, inner, 2);
            for (std::size_t i = 0; i < pts.size(); ++i) {
                const auto [b, e] = part.neighbors(static_cast<dvoronoi::Index>(i));
                const std::vector<std::size_t> got(b, e);
                if (got != exact.voronoi_neighbors[i] || (part.on_hull[i] != 0) != static_cast<bool>(exact.on_hull[i])) {
                    if (bad < 5) MESSAGE(label << " inner " << static_cast<int>(inner) << ": agent " << i);
                    ++bad;
                }
            }
        }
    };
    for (std::uint64_t seed = 0; seed < 10; ++seed) {
        const auto uniform = fam::uniform(3000, 10.0, seed);
        const auto grid = fam::grid_subset(30, 500, 1.0, seed);
        check(uniform.points, "uniform 3000");
        check(grid.points, "grid subset 30x30");
        if (seed < 2)  // transformed copies through the one-shot clip (far offsets, tiny scales, turns)
            for (const auto& base : {uniform, grid})
                for (const auto& t : dvoronoi_oracle::exact_transforms(base.points, 1.0, seed))
                    check(t.points, base.name + " " + t.name);
    }
    for (const auto& c : dvoronoi_oracle::read_corpus(std::string(DVORONOI_TEST_DATA_DIR) + "/degenerate_corpus.txt"))
        check(c.points, c.name);
    CHECK(cases > 200);
    CHECK(bad == 0);
}

TEST_CASE("voronoi_cells: cells that reach far (hull runs, convex arcs, cocircular rings, clusters), transformed") {
    // These need the far neighbours: with Boundary Scan, from the triangulation of the agents the
    // one-shot clip leaves; with EVT, the empty-circle and hull certificates
    // (partition/empty_circle_certificate.hpp).
    int bad = 0;
    std::size_t cases = 0;
    for (std::uint64_t seed = 0; seed < 3; ++seed)
        for (int kind = 0; kind < 5; ++kind) {
            const auto base = fam::far_vertices(kind, kind == 3 ? 200 : 600, seed);
            std::vector<std::pair<std::string, std::vector<XY>>> inputs{{base.name, base.points}};
            if (seed == 0)
                for (const auto& t : dvoronoi_oracle::exact_transforms(base.points, 1.0, seed))
                    inputs.push_back({base.name + " " + t.name, t.points});
            for (const auto& [label, pts] : inputs) {
                ++cases;
                const auto exact = dvoronoi_oracle::compute_oracle(pts, 1.0);
                dvoronoi::Points P(static_cast<Eigen::Index>(pts.size()), 2);
                for (std::size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Eigen::Index>(i)) << pts[i][0], pts[i][1];
                for (auto inner : {dvoronoi::AsrInner::Auto, dvoronoi::AsrInner::Scan, dvoronoi::AsrInner::Evt}) {
                    const auto part = dvoronoi::voronoi_cells(P, inner, 2);
                    for (std::size_t i = 0; i < pts.size(); ++i) {
                        const auto [b, e] = part.neighbors(static_cast<dvoronoi::Index>(i));
                        const std::vector<std::size_t> got(b, e);
                        if (got != exact.voronoi_neighbors[i] ||
                            (part.on_hull[i] != 0) != static_cast<bool>(exact.on_hull[i])) {
                            if (bad < 5) MESSAGE(label << ": agent " << i);
                            ++bad;
                        }
                    }
                }
            }
        }
    CHECK(cases > 30);
    CHECK(bad == 0);
}

TEST_CASE("voronoi_cells: 20000 uniform agents (deep radius schedules) equal the oracle") {
    const auto base = fam::uniform(20000, 10.0, 7);
    const auto exact = dvoronoi_oracle::compute_oracle(base.points, 1.0);
    dvoronoi::Points P(static_cast<Eigen::Index>(base.points.size()), 2);
    for (std::size_t i = 0; i < base.points.size(); ++i) P.row(static_cast<Eigen::Index>(i)) << base.points[i][0], base.points[i][1];
    const auto part = dvoronoi::voronoi_cells(P, dvoronoi::AsrInner::Scan, 2);
    int bad = 0, deep = 0;
    for (std::size_t i = 0; i < base.points.size(); ++i) {
        const auto [b, e] = part.neighbors(static_cast<dvoronoi::Index>(i));
        bad += std::vector<std::size_t>(b, e) != exact.voronoi_neighbors[i] ||
               (part.on_hull[i] != 0) != static_cast<bool>(exact.on_hull[i]);
        deep += part.radius_steps[i] >= 5;
    }
    CHECK(deep > 10);  // the schedule's long tail (agents near the hull) is exercised
    CHECK(bad == 0);
}
