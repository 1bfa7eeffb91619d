// Inputs for the oracle tests: seeded random families, the degenerate corpus reader, and the exact
// transformations (permutation, power-of-two translation and scaling, 90° rotation, mirror) under
// which every combinatorial answer must stay the same.
//
// Random generators use std::mt19937_64 (its output sequence is fixed by the C++ standard) and
// integer arithmetic only, so a (family, seed) pair names the same points on every platform.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi_oracle {

using XY = std::array<double, 2>;

/// A named input: points and a cell radius.
struct NamedCase {
    std::string name;
    double radius = 1.0;
    std::vector<XY> points;
};

namespace families {

/// Uniform double in [0, 1) on the grid 2^-40 (spare low bits keep power-of-two translations
/// exact).
inline double uniform40(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 24) * 0x1p-40;
}

/// n points uniform in the unit square, radius chosen so that on average `density` other agents lie
/// within 2R of an agent (ignoring the border): density = n * pi * (2R)^2.
inline NamedCase uniform(std::size_t n, double density, std::uint64_t seed) {
    std::mt19937_64 rng(seed * 7919u + n);
    NamedCase c;
    c.name = "uniform/n=" + std::to_string(n) + "/density=" + std::to_string(density) +
             "/seed=" + std::to_string(seed);
    c.radius = std::sqrt(density / (4.0 * std::acos(-1.0) * static_cast<double>(n)));
    for (std::size_t i = 0; i < n; ++i) {
        const double x = uniform40(rng);
        const double y = uniform40(rng);
        c.points.push_back({x, y});
    }
    return c;
}

/// A random subset (each site kept with probability keep_permille / 1000) of the integer grid
/// size x size: exact cocircularities, exact distances 2R for the radii used with it.
inline NamedCase grid_subset(int size, int keep_permille, double radius, std::uint64_t seed) {
    std::mt19937_64 rng(seed * 104729u + static_cast<std::uint64_t>(size));
    NamedCase c;
    c.name = "grid_subset/size=" + std::to_string(size) + "/keep=" + std::to_string(keep_permille) +
             "/R=" + std::to_string(radius) + "/seed=" + std::to_string(seed);
    c.radius = radius;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
            if (static_cast<int>(rng() % 1000u) < keep_permille)
                c.points.push_back({static_cast<double>(i), static_cast<double>(j)});
    return c;
}

/// A size x size unit lattice, each coordinate moved by a seeded multiple of `jitter` in
/// [-jitter, jitter] (jitter 0x1p-50: a few units in the last place; the lattice's exact
/// cocircularities and 2R distances become near-ties that only exact predicates decide).
inline NamedCase jittered_lattice(int size, double jitter, double radius, std::uint64_t seed) {
    std::mt19937_64 rng(seed * 15485863u + static_cast<std::uint64_t>(size));
    NamedCase c;
    c.name = "jittered_lattice/size=" + std::to_string(size) + "/jitter=" + std::to_string(jitter) +
             "/R=" + std::to_string(radius) + "/seed=" + std::to_string(seed);
    c.radius = radius;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const auto step = [&] { return static_cast<double>(static_cast<int>(rng() % 5u) - 2) * 0.5; };
            c.points.push_back({i + jitter * step(), j + jitter * step()});
        }
    return c;
}

/// Inputs whose cells reach far beyond their agents (the exact-cell driver's hard cases): `kind`
/// 0 = agents on the boundary of a square (long collinear hull edges) around a uniform interior,
/// 1 = a convex arc y = x^2 / 2^20 (nearly collinear; huge Delaunay circles) with agents just above,
/// 2 = every integer point of the circle x^2 + y^2 = 5^6 (exactly cocircular) plus its centre and
///     agents just inside, 3 = two concentric rings (the inner one's cells reach the outer one's).
inline NamedCase far_vertices(int kind, std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed * 2654435761u + static_cast<std::uint64_t>(kind) * 97u + n);
    NamedCase c;
    c.name = "far_vertices/kind=" + std::to_string(kind) + "/n=" + std::to_string(n) + "/seed=" + std::to_string(seed);
    const auto u = [&] { return uniform40(rng); };
    if (kind == 0) {
        const int side = static_cast<int>(n / 8) + 2;
        for (int t = 0; t < side; ++t) {
            c.points.push_back({static_cast<double>(t), 0.0});
            c.points.push_back({static_cast<double>(side), static_cast<double>(t)});
            c.points.push_back({static_cast<double>(side - t), static_cast<double>(side)});
            c.points.push_back({0.0, static_cast<double>(side - t)});
        }
        for (std::size_t k = 0; k < n / 2; ++k) c.points.push_back({side * (0.001 + 0.998 * u()), side * (0.001 + 0.998 * u())});
    } else if (kind == 1) {
        for (std::size_t k = 0; k < n / 2; ++k) {
            const double x = std::floor(u() * 4096.0) - 2048.0;
            c.points.push_back({x, x * x * 0x1p-20});
            c.points.push_back({x + 0.5, (x + 0.5) * (x + 0.5) * 0x1p-20 + 1.0 + u()});
        }
    } else if (kind == 2) {
        const long r2 = 15625;  // 5^6: many integer points on the circle
        for (long x = -125; x <= 125; ++x) {
            const long y2 = r2 - x * x;
            const long y = std::lround(std::sqrt(static_cast<double>(y2)));
            if (y * y != y2) continue;
            c.points.push_back({static_cast<double>(x), static_cast<double>(y)});
            if (y != 0) c.points.push_back({static_cast<double>(x), static_cast<double>(-y)});
        }
        c.points.push_back({0.0, 0.0});
        for (std::size_t k = 0; k < n; ++k) {
            const double a = 6.283185307179586 * u(), rr = 124.0 * std::sqrt(u());
            c.points.push_back({std::round(rr * std::cos(a) * 64.0) / 64.0 + 0x1p-10, std::round(rr * std::sin(a) * 64.0) / 64.0});
        }
    } else if (kind == 4) {
        // Dense clusters far apart and sparse agents between: neighbours across wide gaps, far
        // beyond a radius chosen from the mean spacing.
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t cl = k % 5;
            if (cl == 4) {
                c.points.push_back({1000.0 * u(), 1000.0 * u()});
                continue;
            }
            const double cx = cl % 2 ? 900.0 : 100.0, cy = cl / 2 ? 900.0 : 100.0;
            c.points.push_back({cx + 3.0 * (u() - 0.5), cy + 3.0 * (u() - 0.5)});
        }
    } else {
        for (std::size_t k = 0; k < n; ++k) {
            const double a = 6.283185307179586 * (static_cast<double>(k) + 0.25 * u()) / static_cast<double>(n);
            const double r = k % 2 ? 100.0 : 99.0;
            c.points.push_back({r * std::cos(a), r * std::sin(a)});
        }
    }
    // Drop exact duplicates (the generators can repeat a point).
    std::sort(c.points.begin(), c.points.end());
    c.points.erase(std::unique(c.points.begin(), c.points.end()), c.points.end());
    const auto perm = [&] {
        std::vector<std::size_t> p(c.points.size());
        std::iota(p.begin(), p.end(), std::size_t{0});
        for (std::size_t i = p.size(); i > 1; --i) std::swap(p[i - 1], p[rng() % i]);
        return p;
    }();
    std::vector<XY> shuffled;
    for (std::size_t k : perm) shuffled.push_back(c.points[k]);
    c.points = shuffled;
    return c;
}

/// A seeded permutation (Fisher-Yates on mt19937_64 output).
inline std::vector<std::size_t> permutation(std::size_t n, std::uint64_t seed) {
    std::vector<std::size_t> p(n);
    std::iota(p.begin(), p.end(), std::size_t{0});
    std::mt19937_64 rng(seed);
    for (std::size_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng() % i]);
    return p;
}

}  // namespace families

/// Reads the degenerate corpus (tools/make_degenerate_corpus.py): `case NAME RADIUS`, `x y` lines,
/// `end`; `#` comment lines.
inline std::vector<NamedCase> read_corpus(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open the degenerate corpus");
    std::vector<NamedCase> out;
    NamedCase cur;
    bool open = false;
    std::string line;
    for (std::size_t lineno = 1; std::getline(in, line); ++lineno) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        std::string head;
        ss >> head;
        const auto fail = [&](const std::string& what) {
            return std::runtime_error(path + ":" + std::to_string(lineno) + ": " + what);
        };
        if (head == "case") {
            if (open) throw fail("`case` inside a case");
            cur = NamedCase{};
            if (!(ss >> cur.name >> cur.radius)) throw fail("expected `case NAME RADIUS`");
            open = true;
        } else if (head == "end") {
            if (!open) throw fail("`end` outside a case");
            out.push_back(std::move(cur));
            open = false;
        } else {
            if (!open) throw fail("point outside a case");
            XY p;
            std::istringstream s2(line);
            if (!(s2 >> p[0] >> p[1])) throw fail("expected `x y`");
            cur.points.push_back(p);
        }
    }
    if (open) throw std::runtime_error(path + ": last case has no `end`");
    return out;
}

/// An exactly transformed copy of an input: point k of `points` is the image of original point
/// perm[k]; areas scale by area_scale.
struct Transformed {
    std::string name;
    std::vector<XY> points;
    double radius = 1.0;
    std::vector<std::size_t> perm;
    double area_scale = 1.0;
    std::function<XY(const XY&)> map;  ///< the transformation of the plane (for centroids)
    bool reverses_orientation = false;  ///< mirror images: counter-clockwise cycles run backwards
};

namespace families {

/// a + b is a double (Knuth's TwoSum error is zero).
inline bool exact_sum(double a, double b) {
    const double s = a + b;
    if (!std::isfinite(s)) return false;
    const double bb = s - a;
    return (a - (s - bb)) + (b - bb) == 0.0;
}

/// The largest translation (2^k, -2^(k+1)), k <= e + 1 (2^e <= max |coordinate|: the points move
/// by about their own extent from the origin), that is exact on every coordinate; false if none
/// down to the last bit.
inline bool exact_translation(const std::vector<XY>& pts, double& tx, double& ty) {
    double m = 0.0;
    for (const XY& p : pts) m = std::max({m, std::fabs(p[0]), std::fabs(p[1])});
    if (m == 0.0) m = 1.0;
    const int e = std::ilogb(m);
    for (int k = e + 1; k >= e - 52; k -= 3) {
        const double t = std::ldexp(1.0, k);
        bool ok = true;
        for (const XY& p : pts)
            if (!exact_sum(p[0], t) || !exact_sum(p[1], -2.0 * t)) {
                ok = false;
                break;
            }
        if (ok) {
            tx = t;
            ty = -2.0 * t;
            return true;
        }
    }
    return false;
}

}  // namespace families

/// The exact transformed copies of an input: permuted, translated (when some power of two is
/// exact), rotated by 90°, mirrored, scaled by 2^5 and 2^-7, and all of these at once.
inline std::vector<Transformed> exact_transforms(const std::vector<XY>& pts, double radius,
                                                 std::uint64_t seed) {
    const std::size_t n = pts.size();
    std::vector<std::size_t> id(n);
    std::iota(id.begin(), id.end(), std::size_t{0});
    std::vector<Transformed> out;
    const auto map = [&](const std::string& name, const std::vector<std::size_t>& perm, double r,
                         double area_scale, auto f) {
        Transformed t;
        t.name = name;
        t.perm = perm;
        t.radius = r;
        t.area_scale = area_scale;
        t.map = f;
        for (std::size_t k = 0; k < n; ++k) t.points.push_back(f(pts[perm[k]]));
        out.push_back(std::move(t));
    };
    const auto perm = families::permutation(n, seed);
    map("permuted", perm, radius, 1.0, [](const XY& p) { return p; });
    double tx = 0.0, ty = 0.0;
    const bool can_translate = families::exact_translation(pts, tx, ty);
    if (can_translate)
        map("translated", id, radius, 1.0, [tx, ty](const XY& p) { return XY{p[0] + tx, p[1] + ty}; });
    map("rotated90", id, radius, 1.0, [](const XY& p) { return XY{-p[1], p[0]}; });
    map("mirrored", id, radius, 1.0, [](const XY& p) { return XY{-p[0], p[1]}; });
    out.back().reverses_orientation = true;
    map("scaled2^5", id, std::ldexp(radius, 5), std::ldexp(1.0, 10),
        [](const XY& p) { return XY{std::ldexp(p[0], 5), std::ldexp(p[1], 5)}; });
    map("scaled2^-7", id, std::ldexp(radius, -7), std::ldexp(1.0, -14),
        [](const XY& p) { return XY{std::ldexp(p[0], -7), std::ldexp(p[1], -7)}; });
    map(can_translate ? "permuted+rotated+mirrored+translated+scaled" : "permuted+rotated+mirrored+scaled",
        perm, std::ldexp(radius, 3), std::ldexp(1.0, 6), [=](const XY& p) {
            const double x = can_translate ? p[0] + tx : p[0];
            const double y = can_translate ? p[1] + ty : p[1];
            return XY{std::ldexp(y, 3), std::ldexp(x, 3)};  // rotate by 90° and mirror = swap
        });
    out.back().reverses_orientation = true;
    return out;
}

}  // namespace dvoronoi_oracle
