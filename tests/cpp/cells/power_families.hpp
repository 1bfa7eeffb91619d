// Named heterogeneous teams for the power-cell tests (tests/cpp/cells/test_power_*.cpp), and a check
// that compares one route's cell of every agent with the exact clipping's (cells/power_cell.hpp) as
// sets: the same neighbours, the same empty flag, the same pieces in the same cyclic order (edges by
// neighbour, arcs), areas within 1e-12 R_i^2.
#pragma once

#include "dvoronoi/cells/power_cell.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace power_families {

using namespace dvoronoi;

struct Team {
    std::string name;
    std::vector<Vec2> p;
    std::vector<double> r;
};

/// The families of the issue: equal radii, nested disks, a tiny disk in a big one, tangent disks,
/// three (and four) radical axes through one point, integer lattices with two radii, crescents,
/// agents at one place with different radii, and random teams with spread radii.
inline std::vector<Team> teams() {
    std::vector<Team> out;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Team eq{"equal radii", {}, {}};
    for (int i = 0; i < 60; ++i) eq.p.emplace_back(u(rng), u(rng)), eq.r.push_back(0.15);
    out.push_back(eq);
    Team nested{"nested", {}, {}};
    for (int k = 0; k < 8; ++k) nested.p.emplace_back(0.125 * k, 0.0), nested.r.push_back(0.25 + 0.25 * k);
    nested.p.emplace_back(0.5, 0.75), nested.r.push_back(0.5);
    out.push_back(nested);
    Team tiny{"tiny in big", {{0, 0}, {0.5, 0}, {1.0 - 0x1p-10, 0}, {0, 1}, {0, -1 - 0x1p-10}}, {1.0, 0x1p-10, 0x1p-10, 0x1p-10, 0x1p-10}};
    out.push_back(tiny);
    out.push_back({"tangent", {{0, 0}, {3, 0}, {0, 4}, {6, 4}}, {1.0, 2.0, 3.0, 3.0}});
    // Power -144 at the origin for all four (three and more axes through one point, inside the
    // disks), and power 0 at the origin for five (axes meeting on the circles).
    out.push_back({"radical centre", {{5, 0}, {0, 9}, {-16, 0}, {0, -5}, {30, 30}}, {13, 15, 20, 13, 1}});
    out.push_back({"three axes on the circles", {{3, 4}, {-3, 4}, {1, 0}, {0, -2}, {-4, -3}}, {5, 5, 1, 2, 5}});
    out.push_back({"crescent", {{0, 0}, {9.5, 0}, {0, 10.5}, {-10.25, 0}, {7, 7.5}}, {10.0, 1.0, 1.0, 1.0, 1.5}});
    out.push_back({"same place", {{0, 0}, {0, 0}, {0.5, 0}, {0.5, 0}, {0.5, 0}}, {1.0, 0.5, 0.25, 0.75, 0.5}});
    for (double r2 : {1.25, 1.5, 2.0}) {
        Team lat{"lattice 1/" + std::to_string(r2), {}, {}};
        for (int x = 0; x < 7; ++x)
            for (int y = 0; y < 7; ++y) lat.p.emplace_back(x, y), lat.r.push_back(rng() % 2 ? r2 : 1.0);
        out.push_back(lat);
    }
    for (int seed = 0; seed < 6; ++seed) {
        Team t{"spread " + std::to_string(seed), {}, {}};
        std::mt19937_64 g(static_cast<unsigned>(seed));
        for (int i = 0; i < 80; ++i) t.p.emplace_back(10 * u(g), 10 * u(g)), t.r.push_back(0.5 * std::ldexp(1.0, static_cast<int>(g() % 4)) * (0.5 + u(g)));
        out.push_back(t);
    }
    return out;
}

/// Agent i's candidates: every other agent, with its radius.
inline void others_of(const Team& t, std::size_t i, std::vector<detail::Candidate>& cand, std::vector<double>& rs) {
    cand.clear();
    rs.clear();
    for (std::size_t j = 0; j < t.p.size(); ++j)
        if (j != i) cand.push_back({t.p[j], static_cast<Index>(j)}), rs.push_back(t.r[j]);
}

/// The pieces as (neighbour or kArc) from the first edge on, so two cells compare as cyclic lists.
inline std::vector<Index> labels(const LimitedCell& c) {
    std::vector<Index> l;
    for (const Piece& p : c.pieces) l.push_back(p.is_arc() ? kArc : p.neighbor);
    std::size_t first = 0;
    while (first < l.size() && l[first] == kArc) ++first;
    if (first < l.size()) std::rotate(l.begin(), l.begin() + static_cast<std::ptrdiff_t>(first), l.end());
    // Rotate to the smallest neighbour's edge, so that any starting edge compares equal.
    std::size_t best = l.size();
    for (std::size_t k = 0; k < l.size(); ++k)
        if (l[k] != kArc && (best == l.size() || l[k] < l[best])) best = k;
    if (best < l.size()) std::rotate(l.begin(), l.begin() + static_cast<std::ptrdiff_t>(best), l.end());
    return l;
}

/// `route(c, r, cand, rs, out)` against the exact clipping on every agent of t; returns how many
/// agents lay outside their nonempty cell (so a test can require that case to be exercised).
inline int check_against_clipping(
    const Team& t, const std::function<void(const Vec2&, double, const std::vector<detail::Candidate>&,
                                            const std::vector<double>&, LimitedCell&)>& route) {
    std::vector<detail::Candidate> cand;
    std::vector<double> rs;
    detail::PowerWorkspace ws;
    int outside = 0;
    for (std::size_t i = 0; i < t.p.size(); ++i) {
        INFO("team ", t.name, " agent ", i);
        others_of(t, i, cand, rs);
        LimitedCell exact, got;
        detail::power_cell(t.p[i], t.r[i], cand, rs, exact, ws, static_cast<Index>(i));
        route(t.p[i], t.r[i], cand, rs, got);
        CHECK(labels(got) == labels(exact));
        CHECK(got.neighbors() == exact.neighbors());
        CHECK(std::fabs(got.measures().area - exact.measures().area) <= 1e-12 * t.r[i] * t.r[i]);
        if (exact.measures().area > 0) {
            bool in = true;
            for (std::size_t j = 0; j < t.p.size(); ++j)
                if (j != i && (t.p[j] - t.p[i]).squaredNorm() + t.r[i] * t.r[i] - t.r[j] * t.r[j] <= 0) in = false;
            outside += !in;
        }
    }
    return outside;
}

}  // namespace power_families
