// dvoronoi's heterogeneous cells (limited_cells with one radius per agent, power_limited_cell) against
// the exact CGAL oracle of power_oracle.hpp (Regular_triangulation_2 with weights R_i^2).
//
// Checked on every case and for every method (auto: the certified fast path and the exact clipping;
// scan and chords: Boundary Scan and RCVC generalised to radical axes, cells/power_boundary_scan.hpp
// and cells/power_rcvc.hpp): limited-neighbour sets and empty flags equal the exact ones, areas agree
// to 1e-9 relative (floor 1e-12 R_i^2), and exactly transformed copies (permuted, translated by a
// power of two, rotated by 90°, scaled by 2^5 and 2^-7) give the same sets. Families: random
// teams, equal radii (the oracle against the Delaunay oracle), nested disks, a tiny disk inside a
// big one (strictly inside, internally tangent, straddling), externally tangent disks, four radical
// axes through one point (inside the disks and on the circles), integer lattices with two radii,
// crescents, and agents at one place with different radii.
#include "cgal_oracle.hpp"
#include "families.hpp"
#include "power_oracle.hpp"

#include <dvoronoi/cells/power_cell.hpp>
#include <dvoronoi/partition/power_partition.hpp>

#include <doctest/doctest.h>

#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

using dvoronoi_oracle::XY;

struct Team {
    std::string name;
    std::vector<XY> points;
    std::vector<double> radii;
};

dvoronoi::Points to_points(const std::vector<XY>& pts) {
    dvoronoi::Points m(static_cast<Eigen::Index>(pts.size()), 2);
    for (std::size_t i = 0; i < pts.size(); ++i) m(static_cast<Eigen::Index>(i), 0) = pts[i][0], m(static_cast<Eigen::Index>(i), 1) = pts[i][1];
    return m;
}

std::vector<std::set<std::size_t>> sets_of(const dvoronoi::LimitedPartition& p) {
    std::vector<std::set<std::size_t>> out(static_cast<std::size_t>(p.size()));
    for (dvoronoi::Index i = 0; i < p.size(); ++i) {
        const auto [b, e] = p.neighbors(i);
        for (const auto* j = b; j != e; ++j) out[static_cast<std::size_t>(i)].insert(static_cast<std::size_t>(*j));
    }
    return out;
}

std::string show(const std::set<std::size_t>& s) {
    std::string out = "{";
    for (std::size_t j : s) out += std::to_string(j) + " ";
    return out + "}";
}

constexpr dvoronoi::Method kMethods[] = {dvoronoi::Method::Auto, dvoronoi::Method::Scan, dvoronoi::Method::Chords};

/// Compares dvoronoi (each method) with the oracle on one team; returns dvoronoi's neighbour sets.
std::vector<std::set<std::size_t>> check_team(const Team& t) {
    const auto oracle = dvoronoi_oracle::compute_power_oracle(t.points, t.radii);
    std::vector<std::set<std::size_t>> first;
    for (const dvoronoi::Method method : kMethods) {
        INFO("case ", t.name, " method ", dvoronoi::method_name(method));
        const dvoronoi::LimitedPartition part = dvoronoi::limited_cells(to_points(t.points), t.radii, method, 2);
        const auto got = sets_of(part);
        int reports = 0;
        for (std::size_t i = 0; i < t.points.size(); ++i) {
            const bool ok_sets = got[i] == oracle.limited_neighbors[i];
            const bool ok_empty = part.is_empty(static_cast<dvoronoi::Index>(i)) == oracle.empty[i];
            const double r = t.radii[i];
            const bool ok_area = std::fabs(part.areas[i] - oracle.areas[i]) <= 1e-9 * oracle.areas[i] + 1e-12 * r * r;
            if ((!ok_sets || !ok_empty || !ok_area) && reports++ < 8) {
                INFO("agent ", i, " at (", t.points[i][0], ", ", t.points[i][1], ") R=", r, " area ", part.areas[i], " oracle ",
                     oracle.areas[i], " empty ", part.is_empty(static_cast<dvoronoi::Index>(i)), " oracle ", oracle.empty[i],
                     " neighbours ", show(got[i]), " oracle ", show(oracle.limited_neighbors[i]));
                CHECK(ok_sets);
                CHECK(ok_empty);
                CHECK(ok_area);
            }
            // The oracle's own consistency: limited neighbours are power neighbours.
            for (std::size_t j : oracle.limited_neighbors[i]) CHECK(oracle.power_neighbors[i].count(j) == 1);
        }
        CHECK(reports == 0);
        if (first.empty()) first = got;
    }
    return first;
}

/// The same sets on exactly transformed copies (coordinates and radii transformed together).
void check_transforms(const Team& t, const std::vector<std::set<std::size_t>>& base) {
    const std::size_t n = t.points.size();
    std::vector<std::size_t> perm(n);
    std::iota(perm.begin(), perm.end(), std::size_t{0});
    std::mt19937_64 rng(n);
    std::shuffle(perm.begin(), perm.end(), rng);
    // Copy k: point perm[k] of the original.
    const auto run = [&](const std::string& what, const std::function<XY(const XY&)>& f, double scale) {
        Team c;
        c.name = t.name + "/" + what;
        for (std::size_t k = 0; k < n; ++k) {
            c.points.push_back(f(t.points[perm[k]]));
            c.radii.push_back(t.radii[perm[k]] * scale);
        }
        for (const dvoronoi::Method method : kMethods) {
            const auto part = dvoronoi::limited_cells(to_points(c.points), c.radii, method, 1);
            const auto got = sets_of(part);
            bool same = true;
            for (std::size_t k = 0; k < n; ++k) {
                std::set<std::size_t> mapped;
                for (std::size_t j : got[k]) mapped.insert(perm[j]);
                same = same && mapped == base[perm[k]];
            }
            INFO("transformed copy ", c.name, " method ", dvoronoi::method_name(method));
            CHECK(same);
        }
    };
    run("permuted", [](const XY& p) { return p; }, 1.0);
    run("rotated90", [](const XY& p) { return XY{-p[1], p[0]}; }, 1.0);
    run("scaled2^5", [](const XY& p) { return XY{p[0] * 32.0, p[1] * 32.0}; }, 32.0);
    run("scaled2^-7", [](const XY& p) { return XY{p[0] * 0x1p-7, p[1] * 0x1p-7}; }, 0x1p-7);
    double tx, ty;
    if (dvoronoi_oracle::families::exact_translation(t.points, tx, ty))
        run("translated", [=](const XY& p) { return XY{p[0] + tx, p[1] + ty}; }, 1.0);
}

void check_all(const Team& t) { check_transforms(t, check_team(t)); }

double u40(std::mt19937_64& rng) { return dvoronoi_oracle::families::uniform40(rng); }

}  // namespace

TEST_CASE("random teams") {
    for (std::uint64_t seed = 0; seed < 6; ++seed) {
        std::mt19937_64 rng(seed);
        Team t;
        t.name = "random/seed=" + std::to_string(seed);
        const std::size_t n = 150;
        const double R = seed < 3 ? 0.06 : 0.15;
        for (std::size_t i = 0; i < n; ++i) {
            t.points.push_back({u40(rng), u40(rng)});
            t.radii.push_back(R * (0.5 + u40(rng)));  // uniform in [0.5R, 1.5R]
        }
        check_all(t);
    }
    // Widely spread radii: many empty cells and crescents.
    for (std::uint64_t seed = 10; seed < 13; ++seed) {
        std::mt19937_64 rng(seed);
        Team t;
        t.name = "spread/seed=" + std::to_string(seed);
        for (std::size_t i = 0; i < 120; ++i) {
            t.points.push_back({u40(rng), u40(rng)});
            t.radii.push_back(0.01 * std::ldexp(1.0, static_cast<int>(rng() % 5)) * (0.5 + u40(rng)));
        }
        check_all(t);
    }
}

TEST_CASE("equal radii: the power oracle is the Delaunay oracle, dvoronoi the scalar call") {
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
        const auto c = dvoronoi_oracle::families::uniform(200, 12.0, seed);
        const auto delaunay = dvoronoi_oracle::compute_oracle(c.points, c.radius);
        const auto power = dvoronoi_oracle::compute_power_oracle(c.points, std::vector<double>(c.points.size(), c.radius));
        for (std::size_t i = 0; i < c.points.size(); ++i) {
            const std::set<std::size_t> d(delaunay.limited_neighbors[i].begin(), delaunay.limited_neighbors[i].end());
            CHECK(d == power.limited_neighbors[i]);
            CHECK(std::fabs(delaunay.limited_areas[i] - power.areas[i]) <= 1e-9 * power.areas[i]);
        }
        Team t{c.name, c.points, std::vector<double>(c.points.size(), c.radius)};
        check_team(t);
    }
}

TEST_CASE("nested disks, tiny disks in big ones, same places") {
    Team nested{"nested", {}, {}};
    for (int k = 0; k < 8; ++k) {  // disks around (k/8, 0) with growing radii: each contains the last
        nested.points.push_back({0.125 * k, 0.0});
        nested.radii.push_back(0.25 + 0.25 * k);
    }
    nested.points.push_back({0.5, 0.75});  // and one that straddles several
    nested.radii.push_back(0.5);
    check_all(nested);

    Team tiny{"tiny", {{0, 0}}, {1.0}};
    const double r = 0x1p-10;
    for (int k = 1; k < 8; ++k) {
        const double a = 0.25 * k;
        tiny.points.push_back({(1.0 - r) * std::cos(a), (1.0 - r) * std::sin(a)});  // about internally tangent
        tiny.radii.push_back(r);
    }
    tiny.points.push_back({1.0 - r, 0.0});  // exactly internally tangent
    tiny.radii.push_back(r);
    tiny.points.push_back({0.5, 0.0});  // strictly inside
    tiny.radii.push_back(r);
    tiny.points.push_back({0.0, 1.0});  // straddling the big circle
    tiny.radii.push_back(r);
    tiny.points.push_back({0.0, -1.0 - r});  // externally tangent
    tiny.radii.push_back(r);
    check_all(tiny);

    Team same{"same-place", {{0, 0}, {0, 0}, {0.5, 0}, {0.5, 0}, {0.5, 0}}, {1.0, 0.5, 0.25, 0.75, 0.5}};
    check_all(same);
}

TEST_CASE("tangent disks, crescents") {
    check_all({"tangent", {{0, 0}, {3, 0}, {0, 4}, {6, 4}}, {1.0, 2.0, 3.0, 3.0}});
    check_all({"crescent", {{0, 0}, {9.5, 0}, {0, 10.5}, {-10.25, 0}}, {10.0, 1.0, 1.0, 1.0}});
}

TEST_CASE("four radical axes through one point") {
    // All circles through the origin (power 0 there for every agent): a power vertex of degree > 3
    // exactly on the circles.
    check_all({"through-origin", {{3, 4}, {-3, 4}, {1, 0}, {0, -2}, {-4, -3}}, {5, 5, 1, 2, 5}});
    // Power -144 at the origin for every agent: a degree-4 vertex inside all disks.
    check_all({"radical-centre", {{5, 0}, {0, 9}, {-16, 0}, {0, -5}}, {13, 15, 20, 13}});
}

TEST_CASE("integer lattices with two radii") {
    const double pairs[][2] = {{0.5, 1.0}, {0.75, 1.25}, {1.0, 2.0}, {1.0, 1.5}};
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
        std::mt19937_64 rng(seed);
        Team t;
        t.name = "lattice/" + std::to_string(pairs[seed][0]) + "," + std::to_string(pairs[seed][1]);
        for (int x = 0; x < 9; ++x)
            for (int y = 0; y < 9; ++y) {
                t.points.push_back({double(x), double(y)});
                t.radii.push_back(pairs[seed][rng() % 2]);
            }
        check_all(t);
    }
}

TEST_CASE("far from the origin and tiny spacings (the documented range)") {
    // Integer lattices near 1e7 with two radii (exact ties far from the origin), and a random team
    // scaled to spacings near 1e-9: the fast path's bounds must hand the close calls to the exact
    // predicates.
    std::mt19937_64 rng(9);
    Team far{"lattice+1e7", {}, {}};
    for (int x = 0; x < 7; ++x)
        for (int y = 0; y < 7; ++y) {
            far.points.push_back({1e7 + x, -1e7 + y});
            far.radii.push_back(rng() % 2 ? 0.75 : 1.25);
        }
    check_all(far);
    Team tiny{"spacing-1e-9", {}, {}};
    for (int i = 0; i < 100; ++i) {
        tiny.points.push_back({1.0 + 1e-8 * u40(rng), 2.0 + 1e-8 * u40(rng)});
        tiny.radii.push_back(1e-9 * (0.5 + u40(rng)));
    }
    check_team(tiny);
}

TEST_CASE("one agent's cell equals the partition's") {
    std::mt19937_64 rng(5);
    std::vector<XY> pts;
    std::vector<double> radii;
    for (int i = 0; i < 120; ++i) pts.push_back({u40(rng), u40(rng)}), radii.push_back(0.05 + 0.1 * u40(rng));
    const auto part = dvoronoi::limited_cells(to_points(pts), radii, dvoronoi::Method::Auto, 1);
    for (std::size_t i = 0; i < pts.size(); i += 7) {
        dvoronoi::Points others(static_cast<Eigen::Index>(pts.size() - 1), 2);
        std::vector<double> ro;
        std::vector<std::size_t> ids;
        for (std::size_t j = 0, k = 0; j < pts.size(); ++j)
            if (j != i) others(static_cast<Eigen::Index>(k), 0) = pts[j][0], others(static_cast<Eigen::Index>(k), 1) = pts[j][1], ++k,
                        ro.push_back(radii[j]), ids.push_back(j);
        for (const dvoronoi::Method method : kMethods) {
            INFO("agent ", i, " method ", dvoronoi::method_name(method));
            const auto cell = dvoronoi::power_limited_cell(dvoronoi::Vec2(pts[i][0], pts[i][1]), others, radii[i], ro, method);
            std::set<std::size_t> got;
            for (auto j : cell.neighbors()) got.insert(ids[static_cast<std::size_t>(j)]);
            const auto [b, e] = part.neighbors(static_cast<dvoronoi::Index>(i));
            CHECK(got == std::set<std::size_t>(b, e));
            // The same cell; its pieces may start elsewhere and its vertices come from another
            // construction (the fast path's own, within 2^-44 R_i), so the sums may round differently.
            CHECK(cell.measures().area == doctest::Approx(part.areas[i]).epsilon(1e-12));
        }
    }
}
