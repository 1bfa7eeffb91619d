// network::run (network/run.hpp) and its writers (io/network_json.hpp, io/network_csv.hpp): the
// typed result of each algorithm equals the algorithm run by hand, its cells are the exact core's,
// and the JSON document has the fields, order and nulls both faces (CLI, Python) rely on.
#include "dvoronoi/io/network_csv.hpp"
#include "dvoronoi/io/network_json.hpp"
#include "dvoronoi/network/run.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

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

nw::Options options(nw::Algorithm a, double range) {
    nw::Options o;
    o.algorithm = a;
    o.range = range;
    return o;
}

std::vector<Index> sorted(std::vector<Index> v) {
    std::sort(v.begin(), v.end());
    return v;
}

}  // namespace

TEST_CASE("run(cc): CC's answer, and the unbounded diagram's cells are the exact core's") {
    const Points p = random_points(11, 90, 100.0);
    nw::Options o = options(nw::Algorithm::Cc, 25.0);
    o.run.loss = 0.2;
    o.run.seed = 3;
    const auto r = std::get<nw::CcRun>(nw::run(p, o));
    const auto net = nw::make_network(p, 25.0);
    const auto by_hand = nw::run_cc(net, o.run, o.cc);
    CHECK(r.counts.sent == by_hand.counts.sent);
    CHECK(r.counts.received == by_hand.counts.received);
    CHECK(r.on_hull == by_hand.on_hull);
    REQUIRE(r.indptr.size() == 91);
    for (Index i = 0; i < 90; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const std::vector<Index> ccw(r.neighbors_ccw.begin() + r.indptr[ii], r.neighbors_ccw.begin() + r.indptr[ii + 1]);
        const std::vector<Index> asc(r.indices.begin() + r.indptr[ii], r.indices.begin() + r.indptr[ii + 1]);
        CHECK(ccw == by_hand.neighbors[ii]);
        CHECK(asc == sorted(by_hand.neighbors[ii]));
    }
    REQUIRE(r.condition.has_value());
    CHECK(*r.condition);
    CHECK(r.wrong_nodes->empty());
    // Interior cells: polygons of circumcentres, with the exact core's areas and centroids; hull
    // cells: no pieces, area +inf, centroid NaN.
    const VoronoiPartition exact = voronoi_cells(p);
    for (Index i = 0; i < 90; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const Index pieces = r.cells.piece_ptr[ii + 1] - r.cells.piece_ptr[ii];
        if (r.on_hull[ii]) {
            CHECK(pieces == 0);
            CHECK(std::isinf(r.cells.areas[ii]));
            CHECK(std::isnan(r.cells.centroids(i, 0)));
        } else {
            CHECK(pieces == r.indptr[ii + 1] - r.indptr[ii]);
            CHECK(r.cells.areas[ii] == doctest::Approx(exact.areas[ii]).epsilon(1e-10));
            CHECK(r.cells.centroids(i, 0) == doctest::Approx(exact.centroids(i, 0)).epsilon(1e-10));
            CHECK(r.cells.centroids(i, 1) == doctest::Approx(exact.centroids(i, 1)).epsilon(1e-10));
        }
    }
    // With bounds the cells are clipped and tile the box.
    o.bounds = nw::Box{0, 0, 100, 100};
    const auto clipped = std::get<nw::CcRun>(nw::run(p, o));
    double total = 0.0;
    for (double a : clipped.cells.areas) total += a;
    CHECK(total == doctest::Approx(1e4).epsilon(1e-12));
    CHECK(clipped.counts.sent == r.counts.sent);  // the box changes the cells, not the run
}

TEST_CASE("run(bd07): default region, empty network, verify off") {
    const Points p = random_points(4, 80, 100.0);
    nw::Options o = options(nw::Algorithm::Bd07, 22.0);
    o.verify = false;
    const auto r = std::get<nw::Bd07Run>(nw::run(p, o));
    REQUIRE(r.bounds.has_value());
    const nw::Box b = nw::detail::default_box(p);
    CHECK(r.bounds->xmin == b.xmin);
    CHECK(r.bounds->ymax == b.ymax);
    double total = 0.0;
    for (double a : r.cells.areas) total += a;
    CHECK(total == doctest::Approx((b.xmax - b.xmin) * (b.ymax - b.ymin)).epsilon(1e-12));
    CHECK_FALSE(r.condition.has_value());
    const auto empty = std::get<nw::Bd07Run>(nw::run(Points(0, 2), o));
    CHECK_FALSE(empty.bounds.has_value());
    CHECK(empty.indptr == std::vector<Index>{0});
    o.run.budget = 50;
    CHECK_THROWS_AS(nw::run(p, o), nw::BudgetExceeded);
}

TEST_CASE("run(bs): the centralised limited cells; anchors by fraction are seeded and counted") {
    const Points p = random_points(8, 100, 100.0);
    nw::Options o = options(nw::Algorithm::Bs, 20.0);
    const auto r = std::get<nw::BsRun>(nw::run(p, o));
    const auto ref = limited_cells(p, 10.0);
    CHECK(r.radius == 10.0);
    CHECK(r.indices == ref.indices);
    CHECK(r.cells.areas == ref.areas);
    CHECK_FALSE(r.anchors.has_value());
    CHECK(r.dv_hop_counts.types.empty());
    CHECK(r.total_transmissions() == 100);
    o.anchor_fraction = 0.3;
    o.run.seed = 2;
    const auto a = std::get<nw::BsRun>(nw::run(p, o));
    const auto b = std::get<nw::BsRun>(nw::run(p, o));
    REQUIRE(a.anchors.has_value());
    CHECK(a.anchors->size() == 30);
    CHECK(*a.anchors == *b.anchors);
    CHECK(a.localised);
    CHECK(a.total_transmissions() == a.counts.total_sent() + a.dv_hop_counts.total_sent());
    o.anchor_fraction = 1.5;
    CHECK_THROWS_AS(nw::run(p, o), InputError);
    CHECK_THROWS_AS(nw::parse_algorithm("flood"), InputError);
}

TEST_CASE("the JSON document: fields in order, nulls for what is not there, one row per node") {
    const Points p = random_points(5, 30, 100.0);
    const auto cc = nw::run(p, options(nw::Algorithm::Cc, 30.0));
    const auto j = io::network_json(cc);
    std::vector<std::string> keys;
    for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
    REQUIRE(keys.size() >= 6);
    CHECK(keys[0] == "kind");
    CHECK(keys[1] == "algorithm");
    CHECK(keys.back() == "total_deliveries");
    CHECK(j["kind"] == "network_cc");
    CHECK(j["bounds"].is_null());
    const auto& hull = std::get<nw::CcRun>(cc).on_hull;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        CHECK(j["areas"][i].is_null() == (hull[i] != 0));
        CHECK(j["on_hull"][i].get<bool>() == (hull[i] != 0));
    }
    CHECK(j["sent"].size() == 30);
    CHECK(j["total_transmissions"].get<std::int64_t>() == std::get<nw::CcRun>(cc).total_transmissions());
    // The text round-trips: the same document parsed back.
    CHECK(nlohmann::ordered_json::parse(io::network_json_text(cc)) == j);
    CHECK(io::network_json_text(cc, 2).find("\n  \"algorithm\"") != std::string::npos);

    nw::Options o = options(nw::Algorithm::Bs, 30.0);
    const auto bs = io::network_json(nw::run(p, o));
    CHECK(bs["anchors"].is_null());
    CHECK(bs["dv_hop_sent"].size() == 30);
    CHECK(bs["dv_hop_sent"][0].empty());
    o.anchors = std::vector<Index>{0, 1, 2, 3};
    const auto loc = nw::run(p, o);
    const auto dj = io::network_json(loc);
    CHECK(dj["anchors"] == nlohmann::ordered_json::array({0, 1, 2, 3}));
    CHECK(dj["dv_hop_types"] == nlohmann::ordered_json::array({"anchor_flood", "hop_size"}));
    CHECK(dj["total_transmissions"].get<std::int64_t>() == std::get<nw::BsRun>(loc).total_transmissions());

    std::ostringstream csv;
    io::write_network_csv(csv, loc);
    const std::string text = csv.str();
    const std::string header = text.substr(0, text.find('\n'));
    CHECK(header == "agent,x,y,neighbors,area,sent_anchor_flood,received_anchor_flood,sent_hop_size,"
                    "received_hop_size,sent_position,received_position");
}
