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
    ro.loss = 0.0;
    const auto c = nw::run_cc(net, ro);
    // Location broadcasts: one transmission per node, one link delivery per link and direction.
    CHECK(c.counts.sent_of_type(0) == net.size());
    CHECK(c.counts.received_of_type(0) == 2 * net.link_count());
    // Notifications are unicasts: one transmission per hop and delivery, without loss.
    CHECK(c.counts.sent_of_type(1) == c.counts.received_of_type(1));
    // With loss, a broadcast is repeated until every neighbour has it (every try counted), a unicast
    // hop until it arrives; deliveries stay one per link.
    CHECK(a.counts.received_of_type(0) == 2 * net.link_count());
    CHECK(a.counts.sent_of_type(0) > net.size());
    CHECK(a.counts.sent_of_type(1) > a.counts.received_of_type(1));
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
        std::vector<Index> path, flood;
        std::vector<std::pair<Index, Index>> discovery;
        for (Index from = 0; from < 100; ++from)
            for (Index to = 0; to < 100; ++to) {
                REQUIRE(router.route(from, to, path, flood, discovery));
                CHECK(flood.size() == (discovery.empty() ? 0u : 100u));  // the whole (connected) network floods
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
    CHECK(bs.counts.sent_of_type(0) == net.size());  // one broadcast per node
    CHECK(bs.counts.received_of_type(0) == 2 * net.link_count());
    std::vector<Index> all(120);
    for (Index i = 0; i < 120; ++i) all[static_cast<std::size_t>(i)] = i;
    const auto dv = nw::run_dv_hop(net, all, nw::RunOptions{});
    CHECK((dv.estimates - p).cwiseAbs().maxCoeff() == 0.0);
    std::vector<Index> twice{0, 0};
    CHECK_THROWS_AS(nw::run_dv_hop(net, twice, nw::RunOptions{}), InputError);
}

namespace {
/// Four nodes on a path 0 - 1 - 2 - 3 (spacing 1, range 1: three links).
nw::Network path4() {
    Points p(4, 2);
    p << 0, 0, 1, 0, 2, 0, 3, 0;
    return nw::make_network(p, 1.0);
}
std::int64_t sent_by(const nw::TransmissionCounts& c, Index node, std::size_t type) {
    return c.sent[static_cast<std::size_t>(node) * c.types.size() + type];
}
}  // namespace

TEST_CASE("counts by hand on a path of four nodes: transmissions (a broadcast is one) and link deliveries") {
    const nw::Network net = path4();
    REQUIRE(net.link_count() == 3);
    // CC: four location broadcasts reach 1 + 2 + 2 + 1 neighbours. Collinear cells are strips with
    // no vertex, so there is nothing to notify.
    const auto cc = nw::run_cc(net, nw::RunOptions{});
    CHECK(cc.counts.sent_of_type(0) == 4);
    CHECK(cc.counts.received_of_type(0) == 6);
    CHECK(cc.counts.total_sent() == 4);
    CHECK(cc.counts.total_received() == 6);
    // Distributed Boundary Scan: the same four broadcasts.
    const auto bs = nw::run_distributed_bs(net, net.points, 0.5, nw::RunOptions{});
    CHECK(bs.counts.total_sent() == 4);
    CHECK(bs.counts.total_received() == 6);
    // DV-Hop, anchors 0 and 3, breadth-first rounds, anchors do not relay. Anchor 0's flood: 0 sends
    // (delivered to 1), 1 forwards (to 0 and 2), 2 forwards (to 1 and 3), 3 is an anchor and stops
    // it: 3 transmissions, 5 deliveries; the same for anchor 3's. Hop sizes: each anchor broadcasts
    // its own (3 m / 3 hops = 1), 1 and 2 each pass on the first they hear: 4 transmissions,
    // 1 + 1 + 2 + 2 = 6 deliveries.
    const std::vector<Index> anchors{0, 3};
    const auto dv = nw::run_dv_hop(net, anchors, nw::RunOptions{});
    CHECK(dv.counts.sent_of_type(0) == 6);
    CHECK(dv.counts.received_of_type(0) == 10);
    CHECK(dv.counts.sent_of_type(1) == 4);
    CHECK(dv.counts.received_of_type(1) == 6);
    CHECK(sent_by(dv.counts, 0, 0) == 1);  // the paper: an anchor broadcasts twice (position, hop size)
    CHECK(sent_by(dv.counts, 0, 1) == 1);
    CHECK(sent_by(dv.counts, 1, 0) == 2);  // a normal node forwards each anchor's flood once
    CHECK(dv.hop_size[1] == 1.0);
    // Anchors relaying: every node forwards each anchor's flood once, 4 x 2 = 8 transmissions,
    // 2 x (1 + 2 + 2 + 1) = 12 deliveries.
    nw::DvHopOptions relay;
    relay.anchors_relay = true;
    const auto dvr = nw::run_dv_hop(net, anchors, nw::RunOptions{}, relay);
    CHECK(dvr.counts.sent_of_type(0) == 8);
    CHECK(dvr.counts.received_of_type(0) == 12);
    // On a path no count ever improves: the asynchronous flood sends the same.
    relay.synchronous = false;
    const auto dva = nw::run_dv_hop(net, anchors, nw::RunOptions{ 0.0, 5, 0 }, relay);
    CHECK(dva.counts.sent_of_type(0) == 8);
    CHECK(dva.counts.received_of_type(0) == 12);
}

TEST_CASE("DV-Hop: rounds forward each anchor once and give the asynchronous flood's hop counts with fewer sends") {
    const Points p = random_points(18, 100, 100.0);
    const auto net = nw::make_network(p, 20.0);
    std::vector<Index> anchors;
    for (Index i = 0; i < 100; i += 3) anchors.push_back(i);
    const auto A = static_cast<std::int64_t>(anchors.size());
    nw::DvHopOptions sync, async;
    sync.anchors_relay = async.anchors_relay = true;
    async.synchronous = false;
    const auto s = nw::run_dv_hop(net, anchors, nw::RunOptions{}, sync);
    const auto a = nw::run_dv_hop(net, anchors, nw::RunOptions{0.0, 3, 0}, async);
    // Every node that hears an anchor (its component) forwards that anchor's flood exactly once.
    const auto comp = nw::components(net.adj);
    std::int64_t reach = 0;
    for (Index k : anchors)
        for (Index i = 0; i < 100; ++i) reach += comp[static_cast<std::size_t>(i)] == comp[static_cast<std::size_t>(k)];
    CHECK(s.counts.sent_of_type(0) == reach);
    CHECK(reach <= 100 * A);
    CHECK(a.counts.sent_of_type(0) > s.counts.sent_of_type(0));  // improvements re-flooded
    // The same minimum hop counts, hence the same estimates wherever a node ends with the same hop
    // size (which hop sizes reach a node depends on which one each neighbour passed on first).
    int same_size = 0;
    for (Index i = 0; i < 100; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        if (!(s.hop_size[ii] == a.hop_size[ii])) continue;
        ++same_size;
        CHECK(std::isfinite(s.estimates(i, 0)) == std::isfinite(a.estimates(i, 0)));
        if (std::isfinite(s.estimates(i, 0))) CHECK((s.estimates.row(i) - a.estimates.row(i)).norm() < 1e-9 * 100.0);
    }
    CHECK(same_size > 80);
    // Without anchor relays, anchors send exactly two broadcasts (their flood and their hop size).
    const auto q = nw::run_dv_hop(net, anchors, nw::RunOptions{});
    for (Index k : anchors) CHECK(sent_by(q.counts, k, 0) + sent_by(q.counts, k, 1) == 2);
}

TEST_CASE("route discovery: an option for CC and BD07 alike; its flood is one broadcast per node") {
    int cc_found = 0, bd_found = 0, cc_lost = 0, bd_lost = 0;
    for (std::uint64_t seed = 0; seed < 30; ++seed) {
        const Points p = random_points(seed, 100, 100.0);
        std::mt19937_64 rng(seed + 100);
        std::uniform_real_distribution<double> u(0.0, 100.0), ang(0.0, 6.283185307179586);
        std::vector<nw::Segment> bars;
        for (int b = 0; b < 50; ++b) {
            const Vec2 a(u(rng), u(rng));
            const double t = ang(rng);
            bars.push_back({a, a + 5.0 * Vec2(std::cos(t), std::sin(t))});
        }
        const auto net = nw::make_network(p, 18.0, bars);
        if (!connected(net)) continue;
        const nw::Box box{0, 0, 100, 100};
        nw::CcOptions on, off;
        off.route_discovery = false;
        nw::Bd07Options bon, boff;
        boff.route_discovery = false;
        const auto c1 = nw::run_cc(net, nw::RunOptions{}, on), c0 = nw::run_cc(net, nw::RunOptions{}, off);
        const auto b1 = nw::run_bd07(net, box, nw::RunOptions{}, bon), b0 = nw::run_bd07(net, box, nw::RunOptions{}, boff);
        CHECK(c1.lost == 0);  // connected: discovery always finds the addressee
        CHECK(b1.lost == 0);
        CHECK(c0.discoveries == 0);
        CHECK(b0.discoveries == 0);
        CHECK(c0.counts.sent_of_type(2) == 0);
        CHECK(b0.counts.sent_of_type(3) == 0);
        // Each discovery floods once through the network (n broadcasts, 2 x links deliveries) and the
        // answer is unicast (one transmission and one delivery per hop): deliveries - transmissions
        // = discoveries x (2 links - n).
        const std::int64_t per = 2 * net.link_count() - net.size();
        CHECK(c1.counts.received_of_type(2) - c1.counts.sent_of_type(2) == c1.discoveries * per);
        CHECK(b1.counts.received_of_type(3) - b1.counts.sent_of_type(3) == b1.discoveries * per);
        cc_found += c1.discoveries > 0;
        bd_found += b1.discoveries > 0;
        cc_lost += c0.lost > 0;
        bd_lost += b0.lost > 0;
    }
    CHECK(cc_found > 0);  // both fallbacks were exercised
    CHECK(bd_found > 0);
    CHECK(cc_lost > 0);   // and without them messages were lost
    CHECK(bd_lost > 0);
}
