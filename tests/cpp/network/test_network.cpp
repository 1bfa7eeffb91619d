// Network simulator (cpp/include/dvoronoi/network/): exact link geometry, the engine's guarantees
// (reproducible per seed, every try counted, budget), GPSR's nearest-node delivery (brute force), CC's
// exactness on lattices and cocircular inputs against the library's exact diagram (itself checked
// against CGAL in tests/oracle), BD07's tiling, DV-Hop with every node an anchor.
#include "dvoronoi/network/bd07.hpp"
#include "dvoronoi/network/cc.hpp"
#include "dvoronoi/network/delaunay_check.hpp"
#include "dvoronoi/network/distributed_boundary_scan.hpp"
#include "dvoronoi/network/dv_hop.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace dvoronoi;
namespace nw = dvoronoi::network;

namespace {

Points random_points(std::uint64_t seed, int n, double side) {
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(0.0, side);
    Points p(n, 2);
    for (int i = 0; i < n; ++i) p(i, 0) = u(g), p(i, 1) = u(g);
    return p;
}

Points lattice_points(std::uint64_t seed, int n, int side) {
    std::mt19937_64 g(seed);
    std::vector<int> cells(static_cast<std::size_t>(side * side));
    for (int i = 0; i < side * side; ++i) cells[static_cast<std::size_t>(i)] = i;
    std::shuffle(cells.begin(), cells.end(), g);
    Points p(n, 2);
    for (int i = 0; i < n; ++i) p(i, 0) = cells[static_cast<std::size_t>(i)] % side, p(i, 1) = cells[static_cast<std::size_t>(i)] / side;
    return p;
}

bool connected(const nw::Network& net) {
    const auto c = nw::components(net.adj);
    return c.empty() || *std::max_element(c.begin(), c.end()) == 0;
}

}  // namespace

TEST_CASE("segments_intersect: proper, touching, collinear, near misses") {
    const Vec2 o(0, 0), a(10, 0);
    CHECK(nw::segments_intersect(o, a, Vec2(5, -1), Vec2(5, 1)));
    CHECK(nw::segments_intersect(o, a, Vec2(5, 0), Vec2(5, 1)));      // touches at an end
    CHECK(nw::segments_intersect(o, a, Vec2(10, 0), Vec2(12, 0)));    // collinear, shares an end
    CHECK(nw::segments_intersect(o, a, Vec2(2, 0), Vec2(3, 0)));      // collinear, inside
    CHECK_FALSE(nw::segments_intersect(o, a, Vec2(11, 0), Vec2(12, 0)));
    CHECK_FALSE(nw::segments_intersect(o, a, Vec2(5, 1e-300), Vec2(5, 1)));
    CHECK_FALSE(nw::segments_intersect(o, a, Vec2(std::nextafter(10.0, 11.0), -1), Vec2(std::nextafter(10.0, 11.0), 1)));
    // Nearly collinear (0.2 is not exactly halfway between the doubles 0.1 and 0.3): the obstacle from
    // r to (1, 0) meets p-q exactly when r is on or left of p -> q.
    const Vec2 p(0.1, 0.1), q(0.3, 0.3), r(0.2, 0.2);
    CHECK(nw::segments_intersect(p, q, r, Vec2(1, 0)) == (pred::orient(p, q, r) >= 0));
}

TEST_CASE("links: closed unit disk, obstacles cut, coincident nodes rejected") {
    Points p(3, 2);
    p << 0, 0, 3, 4, 3 + 5, 4;
    auto net = nw::make_network(p, 5.0);
    CHECK(net.linked(0, 1));
    CHECK(net.linked(1, 2));
    CHECK_FALSE(net.linked(0, 2));
    net = nw::make_network(p, 5.0, {{Vec2(5.5, 3), Vec2(5.5, 5)}});
    CHECK_FALSE(net.linked(1, 2));
    CHECK(net.blocked_links == 1);
    p.row(2) = p.row(0);
    CHECK_THROWS_AS(nw::make_network(p, 5.0), CoincidentError);
    CHECK_THROWS_AS(nw::make_network(p, -1.0), InputError);
}

TEST_CASE("simulator: reproducible, every try counted, budget") {
    const Points p = random_points(1, 60, 100.0);
    const auto net = nw::make_network(p, 25.0);
    nw::RunOptions ro;
    ro.loss = 0.25;
    ro.seed = 9;
    const auto a = nw::run_cc(net, ro), b = nw::run_cc(net, ro);
    CHECK(a.counts.sent == b.counts.sent);
    CHECK(a.counts.received == b.counts.received);
    CHECK(a.counts.total_sent() > a.counts.total_received());
    ro.loss = 0.0;
    const auto c = nw::run_cc(net, ro);
    CHECK(c.counts.total_sent() == c.counts.total_received());
    // Location broadcasts: one per link and direction.
    CHECK(c.counts.sent_of_type(0) == 2 * net.link_count());
    ro.budget = 50;
    CHECK_THROWS_AS(nw::run_cc(net, ro), nw::BudgetExceeded);
    ro.budget = 0;
    ro.loss = 1.0;
    CHECK_THROWS_AS(nw::run_cc(net, ro), InputError);
}

TEST_CASE("GPSR delivers to the node nearest the target (brute force)") {
    int checked = 0;
    for (std::uint64_t seed = 0; seed < 12; ++seed) {
        const Points p = random_points(seed, 100, 100.0);
        const auto net = nw::make_network(p, 16.0 + static_cast<double>(seed));
        if (!connected(net)) continue;
        const nw::Gpsr g(net);
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(-30.0, 130.0);
        std::vector<Index> path;
        for (int t = 0; t < 50; ++t) {
            const Vec2 target(u(rng), u(rng));
            const Index src = static_cast<Index>(rng() % 100);
            REQUIRE(g.route(src, target, path));
            Index best = 0;
            for (Index i = 1; i < 100; ++i)
                if ((net.pos(i) - target).squaredNorm() < (net.pos(best) - target).squaredNorm()) best = i;
            CHECK(path.back() == best);
            CHECK(path.front() == src);
            for (std::size_t h = 0; h + 1 < path.size(); ++h) CHECK(net.linked(path[h], path[h + 1]));
            ++checked;
        }
    }
    CHECK(checked >= 300);
}

TEST_CASE("node routing with obstacles: every packet reaches its addressee along links") {
    // Opaque bars make the graph non-planar for GPSR: where face routing cannot deliver, route
    // discovery takes over. Every packet arrives, along links, on every connected network.
    int routed = 0, discovered = 0;
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
        const Points p = random_points(seed, 100, 100.0);
        std::mt19937_64 rng(seed + 100);
        std::uniform_real_distribution<double> u(0.0, 100.0), ang(0.0, 6.283185307179586);
        std::vector<nw::Segment> bars;
        for (int b = 0; b < 50; ++b) {
            const Vec2 a(u(rng), u(rng));
            const double t = ang(rng);
            bars.push_back({a, a + 5.0 * Vec2(std::cos(t), std::sin(t))});
        }
        const auto net = nw::make_network(p, 18.0 + static_cast<double>(seed % 4) * 4.0, bars);
        if (!connected(net)) continue;
        nw::detail::NodeRouter router(net, nw::Routing::Gpsr);
        std::vector<Index> path;
        std::vector<std::pair<Index, Index>> discovery;
        for (Index from = 0; from < 100; ++from)
            for (Index to = 0; to < 100; ++to) {
                REQUIRE(router.route(from, to, path, discovery));
                CHECK(path.front() == from);
                CHECK(path.back() == to);
                for (std::size_t h = 0; h + 1 < path.size(); ++h) CHECK(net.linked(path[h], path[h + 1]));
                for (const auto& [a, b] : discovery) CHECK(net.linked(a, b));
                ++routed;
            }
        discovered += static_cast<int>(router.discoveries());
    }
    CHECK(routed >= 100000);
    CHECK(discovered > 0);  // the fallback was exercised, not only GPSR
}

TEST_CASE("CC is exact on lattices and cocircular sets when Theorem 2 holds") {
    int runs = 0;
    for (std::uint64_t seed = 0; seed < 12; ++seed) {
        const Points p = lattice_points(seed, 60, 11);
        for (double range : {1.5, 2.0, 3.0}) {
            const auto net = nw::make_network(p, range);
            const auto chk = nw::delaunay_check(net);
            if (!chk.condition) continue;
            for (int opt = 0; opt < 4; ++opt) {
                nw::CcOptions o;
                o.cap_adjacency = opt & 1;
                o.forward = (opt & 2) != 0;
                o.routing = seed % 2 ? nw::Routing::Gpsr : nw::Routing::Shortest;
                nw::RunOptions ro;
                ro.seed = seed * 4 + static_cast<std::uint64_t>(opt);
                const auto r = nw::run_cc(net, ro, o);
                CHECK(r.lost == 0);
                CHECK(nw::wrong_nodes(chk, r.neighbors, &r.on_hull).empty());
                ++runs;
            }
        }
    }
    CHECK(runs >= 40);
    // 20 points on one circle (Pythagorean triples of 25) and its centre.
    std::vector<Vec2> pts;
    for (auto [a, b] : {std::pair{7, 24}, {15, 20}, {20, 15}, {24, 7}, {0, 25}, {25, 0}})
        for (int sx : {-1, 1})
            for (int sy : {-1, 1}) {
                const Vec2 q(sx * a, sy * b);
                if (std::find(pts.begin(), pts.end(), q) == pts.end()) pts.push_back(q);
            }
    pts.push_back(Vec2(0, 0));
    Points c(static_cast<Index>(pts.size()), 2);
    for (std::size_t i = 0; i < pts.size(); ++i) c.row(static_cast<Index>(i)) = pts[i].transpose();
    const auto net = nw::make_network(c, 26.0);
    const auto chk = nw::delaunay_check(net);
    REQUIRE(chk.condition);
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
        nw::RunOptions ro;
        ro.seed = seed;
        CHECK(nw::wrong_nodes(chk, nw::run_cc(net, ro).neighbors).empty());
    }
}

TEST_CASE("BD07 cells tile the region; CC without a connected Delaunay subgraph is reported wrong") {
    const Points p = random_points(4, 80, 100.0);
    const auto net = nw::make_network(p, 22.0);
    REQUIRE(connected(net));
    const auto r = nw::run_bd07(net, nw::Box{0, 0, 100, 100}, nw::RunOptions{});
    double area = 0.0;
    for (const auto& c : r.cells) area += c.area();
    CHECK(area == doctest::Approx(1e4).epsilon(1e-12));
    const auto chk = nw::delaunay_check(net);
    for (Index i = 0; i < net.size(); ++i)
        for (Index j : r.neighbors[static_cast<std::size_t>(i)])
            CHECK(std::binary_search(chk.neighbors[static_cast<std::size_t>(i)].begin(), chk.neighbors[static_cast<std::size_t>(i)].end(), j));
    // Two clusters out of range of each other.
    Points two(20, 2);
    two.topRows(10) = random_points(5, 10, 10.0);
    two.bottomRows(10) = random_points(6, 10, 10.0).array() + 50.0;
    const auto split = nw::make_network(two, 8.0);
    const auto chk2 = nw::delaunay_check(split);
    CHECK_FALSE(chk2.condition);
    const auto cc = nw::run_cc(split, nw::RunOptions{});
    CHECK_FALSE(nw::wrong_nodes(chk2, cc.neighbors, &cc.on_hull).empty());
}

TEST_CASE("distributed Boundary Scan equals limited_cells; DV-Hop with every node an anchor is exact") {
    const Points p = random_points(8, 120, 100.0);
    const auto net = nw::make_network(p, 20.0);
    const auto bs = nw::run_distributed_bs(net, net.points, 10.0, nw::RunOptions{});
    const auto ref = limited_cells(p, 10.0);
    CHECK(bs.partition.indptr == ref.indptr);
    CHECK(bs.partition.indices == ref.indices);
    CHECK(bs.counts.sent_of_type(0) == 2 * net.link_count());
    std::vector<Index> all(120);
    for (Index i = 0; i < 120; ++i) all[static_cast<std::size_t>(i)] = i;
    const auto dv = nw::run_dv_hop(net, all, nw::RunOptions{});
    CHECK((dv.estimates - p).cwiseAbs().maxCoeff() == 0.0);
    std::vector<Index> twice{0, 0};
    CHECK_THROWS_AS(nw::run_dv_hop(net, twice, nw::RunOptions{}), InputError);
}
