// coverage/lloyd.hpp and partition/swarm.hpp: the moving swarm's cells equal limited_cells, the grid
// survives small moves, Lloyd's cost never increases, agents stay in the environment, results do not
// depend on the thread count or on the order agents are stored in; the cost keeps its digits at any
// radius. Heterogeneous teams (a radius per agent): equal radii are the scalar stepper, the cells are
// limited_cells(points, radii), the cost never increases, and permuted ids (an MPI rank's storage)
// give the same cells.
#include "dvoronoi/cells/clip.hpp"
#include "dvoronoi/coverage/lloyd.hpp"
#include "dvoronoi/partition/power_partition.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <random>

using namespace dvoronoi;

namespace {
Points random_points(int n, unsigned seed, double side) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, side);
    Points P(n, 2);
    for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng);
    return P;
}
}  // namespace

TEST_CASE("unclipped swarm cells equal limited_cells") {
    for (unsigned seed : {1u, 2u, 3u}) {
        const Points P = random_points(3000, seed, 30.0);
        const double R = 0.4 + 0.3 * seed;
        const Swarm swarm(P, R);
        const LimitedPartition a = limited_cells(P, R);
        const LimitedPartition b = coverage_cells(swarm, nullptr);
        CHECK(a.indptr == b.indptr);
        CHECK(a.indices == b.indices);
        for (Index i = 0; i < a.size(); ++i) {
            CHECK(b.areas[static_cast<std::size_t>(i)] ==
                  doctest::Approx(a.areas[static_cast<std::size_t>(i)]).epsilon(1e-12));
            CHECK((b.centroids.row(i) - a.centroids.row(i)).norm() < 1e-12 * R);
        }
        const CoverageMoments m = coverage_moments(swarm, nullptr);
        for (Index i = 0; i < a.size(); ++i)
            CHECK(m.mass[static_cast<std::size_t>(i)] == b.areas[static_cast<std::size_t>(i)]);
    }
}

TEST_CASE("the swarm's grid follows small moves and equals a fresh index") {
    Points P = random_points(5000, 9, 40.0);
    const double R = 0.7;
    Swarm swarm(P, R);
    std::mt19937 rng(4);
    std::normal_distribution<double> step(0.0, 0.05);
    std::vector<detail::Candidate> a, b;
    for (int t = 0; t < 5; ++t) {
        for (Index i = 0; i < P.rows(); ++i) P.row(i) += Eigen::RowVector2d(step(rng), step(rng));
        swarm.move_to(P);
        CHECK(swarm.rebucketed() > 0);
        CHECK(swarm.rebucketed() < P.rows() / 5);  // only the movers
        const Swarm fresh(P, R);
        for (Index i = 0; i < P.rows(); i += 7) {
            swarm.within(i, a);
            fresh.within(i, b);
            REQUIRE(a.size() == b.size());
            for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k].id == b[k].id);
        }
    }
    CHECK(swarm.rebuilds() == 1);
    // A far move widens the grid (one rebuild) and the queries stay right.
    P(0, 0) += 1e4;
    swarm.move_to(P);
    CHECK(swarm.rebuilds() == 2);
    swarm.within(0, a);
    CHECK(a.empty());
}

TEST_CASE("Lloyd in a box: cost never increases, agents stay inside, threads do not matter") {
    const ConvexPolygon box = ConvexPolygon::box(0, 0, 10, 10);
    for (double gain : {1.0, 0.5}) {
        const Points P = random_points(300, 21, 10.0);
        LloydStepper one(P, 0.8, box, gain, 1), two(P, 0.8, box, gain, 2);
        double prev = one.cost();
        CHECK(prev <= 0.64 * 100.0);
        for (int t = 0; t < 40; ++t) {
            const double c1 = one.step(), c2 = two.step();
            CHECK(c1 == c2);
            CHECK(c1 <= prev * (1 + 1e-13));
            prev = c1;
            for (Index i = 0; i < P.rows(); ++i) CHECK(box.contains(one.points().row(i).transpose()));
        }
        CHECK(one.points() == two.points());
        CHECK(one.cost() <= prev * (1 + 1e-13));
    }
}

TEST_CASE("issue 20: the cost at a radius far beyond the environment") {
    // Once the disks hold the box, H = Σ_i ∫_{V_i ∩ Q} |q - p_i|^2: the Voronoi cells cut to the box by
    // cells/clip.hpp (every other agent's bisector, in the agent's frame), their polar moments by the
    // shoelace formula. The old sum R^2 |Q| + Σ (J_i - R^2 M_i) was off by ~1e-16 R^2: 5 at R = 1e6.
    const Points P = random_points(30, 7, 1.0);
    const ConvexRegion region = ConvexRegion::box(0, 0, 1, 1);
    double want = 0.0;
    for (Index i = 0; i < P.rows(); ++i) {
        std::vector<Vec2> others;
        std::vector<Index> ids;
        for (Index j = 0; j < P.rows(); ++j)
            if (j != i) {
                others.push_back(P.row(j).transpose());
                ids.push_back(j);
            }
        const Vec2 c = P.row(i).transpose();
        const ClippedCell cell = clip_cell(c, others, ids, region);
        for (std::size_t k = 0; k < cell.vertices.size(); ++k) {
            const Vec2 u = cell.vertices[k] - c, v = cell.vertices[(k + 1) % cell.vertices.size()] - c;
            want += (u.x() * v.y() - u.y() * v.x()) / 12.0 * (u.squaredNorm() + v.squaredNorm() + u.dot(v));
        }
    }
    const ConvexPolygon box = ConvexPolygon::box(0, 0, 1, 1);
    for (double R : {2.0, 1e3, 1e5, 1e6, 1e9, 1e12}) {
        CAPTURE(R);
        LloydStepper s(P, R, box);
        CHECK(s.cost() == doctest::Approx(want).epsilon(1e-13));
        const CoverageMoments m = coverage_moments(s.swarm(), s.environment());
        CHECK(std::count(m.open.begin(), m.open.end(), char{1}) == 0);
    }
    // Lloyd's cost never increases, also where the rounding of R^2 |Q| exceeded each step's decrease.
    for (double R : {1e5, 1e6}) {
        CAPTURE(R);
        LloydStepper s(P, R, box);
        double prev = s.cost();
        for (int t = 0; t < 30; ++t) {
            const double c = s.step();
            CHECK(c <= prev);
            prev = c;
        }
    }
}

TEST_CASE("coverage_cost: uncovered area only while a cell reaches its circle") {
    const std::vector<double> mass = {0.25, 0.5}, polar = {0.01, 0.02};
    const double total = 1.0;
    CHECK(coverage_cost(mass, polar, {0, 0}, 3.0, &total) == doctest::Approx(0.03));
    CHECK(coverage_cost(mass, polar, {0, 1}, 3.0, &total) == doctest::Approx(0.03 + 9.0 * 0.25));
    CHECK(coverage_cost(mass, polar, {0, 1}, 3.0, nullptr) == doctest::Approx(0.03 - 9.0 * 0.75));
    CHECK(coverage_cost({}, {}, {}, 3.0, &total) == doctest::Approx(9.0));  // no agent: nothing covered
}

TEST_CASE("cells depend on positions only: ids fix the order, a permuted swarm gives the same cells") {
    const Points P = random_points(800, 5, 12.0);
    const ConvexPolygon tri({Vec2(-1, -1), Vec2(14, 0), Vec2(5, 14)});
    std::vector<Index> perm(800);
    std::iota(perm.begin(), perm.end(), Index{0});
    std::shuffle(perm.begin(), perm.end(), std::mt19937(3));
    Points Q(800, 2);
    for (Index k = 0; k < 800; ++k) Q.row(k) = P.row(perm[static_cast<std::size_t>(k)]);
    const CoverageMoments a = coverage_moments(Swarm(P, 0.6), &tri);
    const CoverageMoments b = coverage_moments(Swarm(Q, 0.6, perm), &tri);
    for (Index k = 0; k < 800; ++k) {
        const auto i = static_cast<std::size_t>(perm[static_cast<std::size_t>(k)]);
        CHECK(a.mass[i] == b.mass[static_cast<std::size_t>(k)]);
        CHECK(a.polar[i] == b.polar[static_cast<std::size_t>(k)]);
        CHECK(a.centroid.row(static_cast<Index>(i)) == b.centroid.row(k));
    }
}

namespace {
std::vector<double> random_radii(Index n, unsigned seed, double lo, double hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    std::vector<double> r(static_cast<std::size_t>(n));
    for (double& v : r) v = u(rng);
    return r;
}
}  // namespace

TEST_CASE("heterogeneous team: equal radii are the scalar stepper, bit for bit") {
    const ConvexPolygon box = ConvexPolygon::box(0, 0, 10, 10);
    const Points P = random_points(400, 31, 10.0);
    LloydStepper a(P, 0.7, box, 0.8, 1), b(P, std::vector<double>(400, 0.7), box, 0.8, 2);
    CHECK(b.radii().equal());
    for (int t = 0; t < 10; ++t) CHECK(a.step() == b.step());
    CHECK(a.points() == b.points());
}

TEST_CASE("heterogeneous team: cells are limited_cells(points, radii); cost never increases") {
    for (unsigned seed : {41u, 42u}) {
        const Points P = random_points(1500, seed, 20.0);
        const std::vector<double> radii = random_radii(1500, seed, 0.2, 1.2);
        const Swarm swarm(P, *std::max_element(radii.begin(), radii.end()));
        const AgentRadii team(swarm, radii);
        const LimitedPartition a = limited_cells(P, radii);
        const LimitedPartition b = coverage_cells(swarm, team, nullptr);
        CHECK(a.indptr == b.indptr);
        CHECK(a.indices == b.indices);
        for (Index i = 0; i < a.size(); ++i) {
            CHECK(b.areas[static_cast<std::size_t>(i)] ==
                  doctest::Approx(a.areas[static_cast<std::size_t>(i)]).epsilon(1e-12));
            // Both divide first moments (errors ~ eps |p| R_i^2) by the area: a sliver's centroid is
            // as good as its area is large.
            const double r = radii[static_cast<std::size_t>(i)], area = a.areas[static_cast<std::size_t>(i)];
            if (area > 0)
                CHECK((b.centroids.row(i) - a.centroids.row(i)).norm() < 1e-13 * 20.0 * std::max(1.0, r * r / area));
        }
        const ConvexPolygon box = ConvexPolygon::box(0, 0, 20, 20);
        LloydStepper one(P, radii, box, 1.0, 1), two(P, radii, box, 1.0, 2);
        double prev = one.cost();
        for (int t = 0; t < 25; ++t) {
            const double c1 = one.step(), c2 = two.step();
            CHECK(c1 == c2);
            CHECK(c1 <= prev * (1 + 1e-13));
            prev = c1;
        }
        CHECK(one.points() == two.points());
        for (Index i = 0; i < P.rows(); ++i) CHECK(box.contains(one.points().row(i).transpose()));
    }
}

TEST_CASE("heterogeneous team: stored order and ids do not change the cells") {
    const Points P = random_points(600, 7, 10.0);
    const std::vector<double> radii = random_radii(600, 7, 0.2, 0.9);
    const ConvexPolygon tri({Vec2(-1, -1), Vec2(12, 0), Vec2(4, 12)});
    std::vector<Index> perm(600);
    std::iota(perm.begin(), perm.end(), Index{0});
    std::shuffle(perm.begin(), perm.end(), std::mt19937(4));
    Points Q(600, 2);
    std::vector<double> rq(600);
    for (Index k = 0; k < 600; ++k) {
        Q.row(k) = P.row(perm[static_cast<std::size_t>(k)]);
        rq[static_cast<std::size_t>(k)] = radii[static_cast<std::size_t>(perm[static_cast<std::size_t>(k)])];
    }
    const double rmax = *std::max_element(radii.begin(), radii.end());
    const Swarm sp(P, rmax), sq(Q, rmax, perm);
    const CoverageMoments a = coverage_moments(sp, AgentRadii(sp, radii), &tri);
    const CoverageMoments b = coverage_moments(sq, AgentRadii(sq, rq), &tri);
    for (Index k = 0; k < 600; ++k) {
        const auto i = static_cast<std::size_t>(perm[static_cast<std::size_t>(k)]);
        CHECK(a.mass[i] == b.mass[static_cast<std::size_t>(k)]);
        CHECK(a.polar[i] == b.polar[static_cast<std::size_t>(k)]);
        CHECK(a.centroid.row(static_cast<Index>(i)) == b.centroid.row(k));
    }
    CHECK_THROWS_AS(AgentRadii(sp, std::vector<double>(599, 0.5)), InputError);
    CHECK_THROWS_AS(AgentRadii(sp, std::vector<double>(600, 2.0 * rmax)), InputError);
}

TEST_CASE("bad input") {
    const ConvexPolygon box = ConvexPolygon::box(0, 0, 1, 1);
    Points P(2, 2);
    P << 0.5, 0.5, 2.0, 0.5;
    CHECK_THROWS_WITH_AS(LloydStepper(P, 0.1, box), "points[1] lies outside bounds", InputError);
    P << 0.5, 0.5, 0.5, 0.5;
    LloydStepper s(P, 0.1, box);
    CHECK_THROWS_AS(s.step(), CoincidentError);
    CHECK_THROWS_AS(LloydStepper(P, 0.1, box, 0.0), InputError);
    CHECK_THROWS_AS(LloydStepper(P, 0.1, box, 1.5), InputError);
    CHECK_THROWS_AS(LloydStepper(P, -1.0, box), InputError);
}
