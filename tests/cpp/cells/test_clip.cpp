// Exact cells clipped to a box: every side of a clipped cell is labelled with what it lies on — a
// side labelled j on the bisector of the agent and j, a side labelled -1 on the box's boundary — also
// when a Voronoi vertex lies exactly on the box's edge (lattices in boxes with half-integer edges).
#include "dvoronoi/cells/clip.hpp"
#include "dvoronoi/coverage/environment.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <map>
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

struct Box {
    double x0, y0, x1, y1;
};

/// Checks the labels of every side of every clipped cell of `P` in `b`; returns the sides checked.
std::size_t check_side_labels(const Points& P, const Box& b, const std::string& name) {
    CAPTURE(name);
    const VoronoiPartition part = voronoi_cells(P, AsrInner::Scan, 1, nullptr, ConvexRegion::box(b.x0, b.y0, b.x1, b.y1));
    const double scale = std::max({P.col(0).maxCoeff() - P.col(0).minCoeff(), P.col(1).maxCoeff() - P.col(1).minCoeff(),
                                   b.x1 - b.x0, b.y1 - b.y0});
    const double tol = 1e-12 * scale;
    std::map<std::pair<Index, Index>, double> shared;  // (i, j) -> length of i's sides labelled j
    std::size_t checked = 0;
    for (Index i = 0; i < part.size(); ++i) {
        const ClippedCell c = part.cell(i).clipped;
        const Vec2 pi = P.row(i).transpose();
        for (std::size_t k = 0; k < c.vertices.size(); ++k) {
            const Vec2& a = c.vertices[k];
            const Vec2& e = c.vertices[(k + 1) % c.vertices.size()];
            const Index j = c.side_neighbor[k];
            CAPTURE(i);
            CAPTURE(k);
            CAPTURE(j);
            if (j >= 0) {
                const Vec2 pj = P.row(j).transpose();
                CHECK(std::fabs((a - pi).norm() - (a - pj).norm()) <= tol);
                CHECK(std::fabs((e - pi).norm() - (e - pj).norm()) <= tol);
                shared[{i, j}] += (e - a).norm();
            } else {
                const auto on = [&](double u, double v, double w) { return std::fabs(u - w) <= tol && std::fabs(v - w) <= tol; };
                CHECK((on(a.x(), e.x(), b.x0) || on(a.x(), e.x(), b.x1) || on(a.y(), e.y(), b.y0) || on(a.y(), e.y(), b.y1)));
            }
            ++checked;
        }
    }
    for (const auto& [ij, length] : shared) {
        if (length <= tol) continue;
        CAPTURE(ij.first);
        CAPTURE(ij.second);
        const auto back = shared.find({ij.second, ij.first});
        REQUIRE(back != shared.end());
        CHECK(back->second == doctest::Approx(length).epsilon(1e-9));
    }
    return checked;
}

}  // namespace

TEST_CASE("issue 20: a Voronoi vertex on the box's edge") {
    // The vertex (70, 0) of the three agents lies on the bottom edge of the box.
    const Points P = from({Vec2(55, 5), Vec2(85, 5), Vec2(65, 15)});
    const ConvexRegion box = ConvexRegion::box(0, 0, 110, 50);
    const VoronoiPartition part = voronoi_cells(P, AsrInner::Scan, 1, nullptr, box);
    const auto label_from = [](const ClippedCell& c, const Vec2& v) {
        for (std::size_t k = 0; k < c.vertices.size(); ++k)  // vertices are constructions: near, not equal
            if ((c.vertices[k] - v).norm() <= 1e-12 * 110.0) return c.side_neighbor[k];
        return Index{-100};
    };
    CHECK(label_from(part.cell(0).clipped, Vec2(70, 0)) == 2);   // up the bisector with 2
    CHECK(label_from(part.cell(2).clipped, Vec2(70, 0)) == 1);   // up the bisector with 1
    CHECK(label_from(part.cell(1).clipped, Vec2(70, 0)) == -1);  // along the bottom edge
    check_side_labels(P, {0, 0, 110, 50}, "three agents");
    // clip_cell itself, with ids of the caller's choosing, in either order of the half-planes.
    const ClippedCell c0 = clip_cell(Vec2(55, 5), {Vec2(85, 5), Vec2(65, 15)}, {7, 9}, box);
    CHECK(label_from(c0, Vec2(70, 0)) == 9);
    const ClippedCell c2 = clip_cell(Vec2(65, 15), {Vec2(55, 5), Vec2(85, 5)}, {4, 7}, box);
    CHECK(label_from(c2, Vec2(70, 0)) == 7);
    const ClippedCell c2r = clip_cell(Vec2(65, 15), {Vec2(85, 5), Vec2(55, 5)}, {7, 4}, box);
    CHECK(label_from(c2r, Vec2(70, 0)) == 7);
}

TEST_CASE("clipped side labels on lattices and random points in boxes") {
    std::mt19937_64 rng(20);
    std::uniform_int_distribution<int> lo_half(-2, 4), len_half(2, 16);
    std::size_t checked = 0;
    for (int k = 5; k <= 8; ++k) {
        std::vector<Vec2> square, hexagonal, triangular;
        for (int x = 0; x < k; ++x)
            for (int y = 0; y < k; ++y) {
                square.emplace_back(x, y);
                hexagonal.emplace_back(x + 0.5 * (y % 2), y);
                triangular.emplace_back(2 * x + (y % 2), y);  // vertices at quarter-integers
            }
        for (const auto& [name, pts] : {std::pair<std::string, std::vector<Vec2>>{"square", square},
                                        {"hexagonal", hexagonal}, {"triangular", triangular}}) {
            for (int t = 0; t < 16; ++t) {
                // Edges on half-integers: through Voronoi vertices, agents and the gaps between.
                const double x0 = 0.5 * lo_half(rng), y0 = 0.5 * lo_half(rng);
                const Box b{x0, y0, x0 + 0.5 * len_half(rng), y0 + 0.5 * len_half(rng)};
                checked += check_side_labels(from(pts), b, name + " " + std::to_string(k) + " box " +
                                                               std::to_string(b.x0) + " " + std::to_string(b.y0) + " " +
                                                               std::to_string(b.x1) + " " + std::to_string(b.y1));
            }
        }
    }
    std::uniform_real_distribution<double> u(0.0, 10.0);
    std::uniform_int_distribution<int> cell(0, 19);
    for (int t = 0; t < 12; ++t) {
        std::vector<Vec2> ints, reals;
        std::map<std::pair<int, int>, int> seen;
        while (ints.size() < 40) {
            const int x = cell(rng), y = cell(rng);
            if (seen[{x, y}]++ == 0) ints.emplace_back(x, y);
        }
        for (int i = 0; i < 60; ++i) reals.emplace_back(u(rng), u(rng));
        const double x0 = 0.5 * lo_half(rng), y0 = 0.5 * lo_half(rng);
        checked += check_side_labels(from(ints), {x0, y0, x0 + 12.5 + 0.5 * len_half(rng), y0 + 12.5 + 0.5 * len_half(rng)},
                                     "integer points " + std::to_string(t));
        checked += check_side_labels(from(reals), {u(rng) - 2.0, u(rng) - 2.0, u(rng) + 8.0, u(rng) + 8.0},
                                     "random points " + std::to_string(t));
    }
    CHECK(checked > 3000);
}

TEST_CASE("a closed ring (the first vertex repeated at the end) is the same polygon") {
    // Before: ConvexRegion::polygon refused it ("vertices 4 and 0 coincide"), ConvexPolygon (lloyd)
    // accepted it: now both drop the repeated vertex.
    Points open(4, 2), closed(5, 2), closed_cw(5, 2);
    open << 0, 0, 2, 0, 2, 1, 0, 1;
    closed << 0, 0, 2, 0, 2, 1, 0, 1, 0, 0;
    closed_cw = closed.colwise().reverse();
    const ConvexRegion a = ConvexRegion::polygon(open), b = ConvexRegion::polygon(closed),
                       c = ConvexRegion::polygon(closed_cw);
    CHECK(b.vertices() == a.vertices());
    CHECK(c.vertices().size() == 4);
    CHECK(c.area() == doctest::Approx(2.0));
    // A vertex repeated in place, or repeated closing vertices, are the same polygon too (before:
    // "bounds: vertices 1 and 2 coincide", while obstacle documents dropped them); lloyd's
    // environment reads the list the same way (one function, detail::convex_ring).
    Points twice(7, 2);
    twice << 0, 0, 2, 0, 2, 0, 2, 1, 0, 1, 0, 0, 0, 0;
    CHECK(ConvexRegion::polygon(twice).vertices() == a.vertices());
    std::vector<Vec2> twice_v;
    for (Index k = 0; k < twice.rows(); ++k) twice_v.push_back(twice.row(k).transpose());
    CHECK(ConvexPolygon(twice_v).vertices() == a.vertices());
}
