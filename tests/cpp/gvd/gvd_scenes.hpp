// Scenes shared by the grid Voronoi tests: random mixes and the paper's two maps.
#pragma once

#include "dvoronoi/gvd/obstacles.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace gvd_test {

using dvoronoi::Vec2;
using namespace dvoronoi::gvd;

/// Regular n-gon of radius r around c, rotated by phase.
inline Shape ngon(Vec2 c, double r, int n, double phase) {
    std::vector<Vec2> v;
    for (int k = 0; k < n; ++k) {
        const double a = phase + 2.0 * M_PI * k / n;
        v.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
    }
    return Shape::polygon(v);
}

/// A non-convex "L" (6 vertices) at c of size s.
inline Shape ell(Vec2 c, double s) {
    return Shape::polygon({c, c + Vec2(s, 0), c + Vec2(s, s / 3), c + Vec2(s / 3, s / 3), c + Vec2(s / 3, s), c + Vec2(0, s)});
}

/// Random mixed obstacles (triangles, n-gons, circles, points, L shapes, stars) in [0, 100]^2,
/// kept apart by rejection so the diagram is well defined and connected.
inline std::vector<Obstacle> random_mixed(unsigned seed, int count, double size = 4.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Obstacle> out;
    std::vector<std::pair<Vec2, double>> placed;
    int attempts = 0;
    while (static_cast<int>(out.size()) < count && attempts++ < 100 * count) {
        const double r = size * (0.4 + 0.6 * u(rng));
        const Vec2 c(r + 2 + (96 - 2 * r) * u(rng), r + 2 + (96 - 2 * r) * u(rng));
        bool ok = true;
        for (const auto& [q, rq] : placed) ok = ok && (q - c).norm() > r + rq + 1.0;
        if (!ok) continue;
        placed.emplace_back(c, r);
        switch (static_cast<int>(u(rng) * 6)) {
            case 0: out.emplace_back(ngon(c, r, 3, u(rng) * 6.28)); break;
            case 1: out.emplace_back(ngon(c, r, 4 + static_cast<int>(u(rng) * 5), u(rng) * 6.28)); break;
            case 2: out.emplace_back(Shape::circle(c, r)); break;
            case 3: out.emplace_back(Shape::point(c)); break;
            case 4: out.emplace_back(ell(c - Vec2(r / 1.5, r / 1.5), r * 1.3)); break;
            default: {  // star: non-convex, 10 vertices
                std::vector<Vec2> v;
                for (int k = 0; k < 10; ++k) {
                    const double a = 2.0 * M_PI * k / 10, rr = (k % 2) ? r * 0.45 : r;
                    v.emplace_back(c.x() + rr * std::cos(a), c.y() + rr * std::sin(a));
                }
                out.emplace_back(Shape::polygon(v));
            }
        }
    }
    return out;
}

/// The paper's "sea of triangles": a jittered lattice of small triangles.
inline std::vector<Obstacle> sea_of_triangles(unsigned seed, int per_side = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Obstacle> out;
    const double step = 100.0 / per_side;
    for (int a = 0; a < per_side; ++a)
        for (int b = 0; b < per_side; ++b) {
            const Vec2 c((a + 0.5) * step + 0.15 * step * u(rng), (b + 0.5) * step + 0.15 * step * u(rng));
            out.emplace_back(ngon(c, step * 0.22, 3, 3.0 * u(rng)));
        }
    return out;
}

/// The paper's "mixed shapes": fewer obstacles of different kinds (circles, dots, non-convex polygons).
inline std::vector<Obstacle> mixed_shapes() {
    return {
        Obstacle(ell(Vec2(12, 60), 24)),
        Obstacle(Shape::circle(Vec2(70, 72), 11)),
        Obstacle(Shape::point(Vec2(45, 40))),
        Obstacle(Shape::point(Vec2(85, 25))),
        Obstacle(ngon(Vec2(25, 20), 9, 5, 0.3)),
        Obstacle(Shape::polygon({Vec2(50, 80), Vec2(60, 95), Vec2(40, 95)})),
        Obstacle(Shape::polygon({Vec2(55, 10), Vec2(75, 10), Vec2(75, 40), Vec2(68, 40), Vec2(68, 17), Vec2(55, 17)})),
        Obstacle(Shape::circle(Vec2(40, 62), 4)),
        Obstacle(Shape::segment(Vec2(85, 45), Vec2(92, 60))),
    };
}

/// A closed square ring of wall thickness t: one obstacle (a union of four rectangles).
inline Obstacle ring(double x0, double y0, double x1, double y1, double t) {
    auto rect = [](double a, double b, double c, double d) {
        return Shape::polygon({Vec2(a, b), Vec2(c, b), Vec2(c, d), Vec2(a, d)});
    };
    return Obstacle(std::vector<Shape>{rect(x0, y0, x1, y0 + t), rect(x0, y1 - t, x1, y1), rect(x0, y0, x0 + t, y1),
                                       rect(x1 - t, y0, x1, y1)});
}

/// Random obstacles of every kind with no separation: overlapping, crossing or outside the area's
/// boundary, C-shaped rings (non-convex), unions; `count` of them.
inline std::vector<Obstacle> random_clutter(std::mt19937& rng, int count) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Obstacle> out;
    for (int k = 0; k < count; ++k) {
        const Vec2 c(-5 + 110 * u(rng), -5 + 110 * u(rng));
        switch (static_cast<int>(u(rng) * 6)) {
            case 0: out.emplace_back(Shape::point(c)); break;
            case 1: out.emplace_back(Shape::circle(c, 0.5 + 11.5 * u(rng))); break;
            case 2: out.emplace_back(Shape::segment(c, c + Vec2(-15 + 30 * u(rng), -15 + 30 * u(rng)))); break;
            case 3: out.emplace_back(ngon(c, 1 + 11 * u(rng), 3 + static_cast<int>(u(rng) * 5), u(rng) * 6.28)); break;
            case 4: {  // nearly closed C-shaped ring
                const double r = 5 + 15 * u(rng), w = 0.5 + 2.5 * u(rng), gap = 0.02 + 0.78 * u(rng), a0 = 6.28 * u(rng);
                std::vector<Vec2> v;
                for (int t = 0; t <= 24; ++t) {
                    const double a = a0 + gap + (2 * M_PI - 2 * gap) * t / 24;
                    v.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
                }
                for (int t = 24; t >= 0; --t) {
                    const double a = a0 + gap + (2 * M_PI - 2 * gap) * t / 24;
                    v.emplace_back(c.x() + (r - w) * std::cos(a), c.y() + (r - w) * std::sin(a));
                }
                out.emplace_back(Shape::polygon(v));
                break;
            }
            default:
                out.emplace_back(std::vector<Shape>{Shape::circle(c, 0.5 + 4.5 * u(rng)),
                                                    Shape::point(c + Vec2(-3 + 6 * u(rng), -3 + 6 * u(rng)))});
        }
    }
    return out;
}

/// Points just off discs (1e-6 .. 1e-2 away): behind each point a needle of its region thinner than
/// a cell, whose grid corners are surrounded by the disc's label.
inline std::vector<Obstacle> needles(unsigned seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Obstacle> out;
    for (int k = 0; k < count; ++k) {
        const Vec2 c(20 + 60 * u(rng), 20 + 60 * u(rng));
        const double r = 3 + 7 * u(rng), a = 2 * M_PI * u(rng), eps = std::pow(10.0, -6 + 4 * u(rng));
        out.emplace_back(Shape::circle(c, r));
        out.emplace_back(Shape::point(c + (r + eps) * Vec2(std::cos(a), std::sin(a))));
    }
    return out;
}

}  // namespace gvd_test
