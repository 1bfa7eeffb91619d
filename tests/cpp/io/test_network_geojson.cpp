// Network GeoJSON: one Feature per node, closed counter-clockwise rings whose area is the cell's
// (polygons exactly; Boundary Scan's arcs within tolerance x arc length, around the positions used),
// null geometry for unbounded and unlocalised cells, the run's neighbours, stream = string.
#include "dvoronoi/io/network_geojson.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <sstream>

using dvoronoi::Index;
using dvoronoi::Points;
namespace network = dvoronoi::network;
using json = nlohmann::json;

namespace {

Points uniform_nodes(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    Points p(n, 2);
    for (int i = 0; i < n; ++i) p(i, 0) = u(rng), p(i, 1) = u(rng);
    return p;
}

network::Options options(network::Algorithm a, double range) {
    network::Options o;
    o.algorithm = a;
    o.range = range;
    return o;
}

double shoelace(const json& ring) {
    double a = 0.0;
    for (std::size_t k = 0; k + 1 < ring.size(); ++k)
        a += ring[k][0].get<double>() * ring[k + 1][1].get<double>() - ring[k + 1][0].get<double>() * ring[k][1].get<double>();
    return 0.5 * a;
}

/// Checks the collection against the run; returns how many cells had a polygon.
int check_collection(const json& fc, const network::RunBase& r, double arc_radius, double tol) {
    CHECK(fc["type"] == "FeatureCollection");
    REQUIRE(fc["features"].size() == static_cast<std::size_t>(r.size()));
    int polygons = 0;
    for (Index i = 0; i < r.size(); ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const json& f = fc["features"][ii];
        CHECK(f["type"] == "Feature");
        CHECK(f["properties"]["agent"] == i);
        std::vector<Index> nb(r.indices.begin() + r.indptr[ii], r.indices.begin() + r.indptr[ii + 1]);
        CHECK(f["properties"]["neighbors"].get<std::vector<Index>>() == nb);
        const double area = r.cells.areas[ii];
        if (r.cells.piece_ptr[ii] == r.cells.piece_ptr[ii + 1]) {
            CHECK(f["geometry"].is_null());
            continue;
        }
        ++polygons;
        CHECK(f["properties"]["area"].get<double>() == area);
        const json& ring = f["geometry"]["coordinates"][0];
        REQUIRE(ring.size() >= 4);
        CHECK(ring.front() == ring.back());
        double arcs = 0.0;
        for (Index k = r.cells.piece_ptr[ii]; k < r.cells.piece_ptr[ii + 1]; ++k)
            arcs += arc_radius * r.cells.piece_span[static_cast<std::size_t>(k)];
        const double poly = shoelace(ring);
        CHECK(poly > 0.0);  // counter-clockwise
        CHECK(poly <= area * (1 + 1e-12) + 1e-12);
        CHECK(area - poly <= tol * arcs + 1e-9 * area);
    }
    return polygons;
}

}  // namespace

TEST_CASE("CC: polygons with their exact areas; unbounded hull cells have none") {
    const network::Result res = network::run(uniform_nodes(80, 1), options(network::Algorithm::Cc, 30.0));
    const auto& cc = std::get<network::CcRun>(res);
    const json fc = json::parse(dvoronoi::io::network_geojson_text(cc));
    int hull = 0;
    for (char h : cc.on_hull) hull += h ? 1 : 0;
    REQUIRE(hull > 0);
    CHECK(check_collection(fc, cc, 0.0, 0.0) == cc.size() - hull);
    for (Index i = 0; i < cc.size(); ++i)
        if (cc.on_hull[static_cast<std::size_t>(i)]) {
            CHECK(fc["features"][static_cast<std::size_t>(i)]["geometry"].is_null());
            CHECK(fc["features"][static_cast<std::size_t>(i)]["properties"]["area"].is_null());  // +inf
        }
    std::ostringstream os;
    dvoronoi::io::write_network_geojson(os, res);
    CHECK(os.str() == dvoronoi::io::network_geojson_text(cc));
}

TEST_CASE("BD07 and CC with bounds: every cell a polygon, together the region") {
    for (const auto algorithm : {network::Algorithm::Bd07, network::Algorithm::Cc}) {
        network::Options o = options(algorithm, 30.0);
        o.bounds = network::Box{0.0, 0.0, 100.0, 100.0};
        const network::Result res = network::run(uniform_nodes(60, 2), o);
        const network::RunBase& r = network::base(res);
        std::ostringstream os;
        dvoronoi::io::write_network_geojson(os, res);
        const json fc = json::parse(os.str());
        CHECK(check_collection(fc, r, 0.0, 0.0) == r.size());
        double total = 0.0;
        for (const json& f : fc["features"]) total += shoelace(f["geometry"]["coordinates"][0]);
        CHECK(total == doctest::Approx(1e4).epsilon(1e-9));
    }
}

TEST_CASE("Boundary Scan: arcs around the positions used, within the tolerance") {
    network::Options o = options(network::Algorithm::Bs, 25.0);
    o.anchor_fraction = 0.3;
    o.run.seed = 4;
    const network::Result res = network::run(uniform_nodes(70, 3), o);
    const auto& bs = std::get<network::BsRun>(res);
    REQUIRE(bs.localised);
    for (const double tol : {0.0, 0.5, 0.01}) {
        const json fc = json::parse(dvoronoi::io::network_geojson_text(bs, tol));
        const double used = tol == 0.0 ? dvoronoi::io::default_tolerance(bs.radius) : tol;
        int localized = 0;
        for (char l : bs.localized) localized += l ? 1 : 0;
        CHECK(check_collection(fc, bs, bs.radius, used) == localized);
        // Every vertex lies on or inside the circle around the position the node used.
        for (Index i = 0; i < bs.size(); ++i) {
            const json& g = fc["features"][static_cast<std::size_t>(i)]["geometry"];
            if (g.is_null()) continue;
            for (const json& v : g["coordinates"][0])
                CHECK(std::hypot(v[0].get<double>() - bs.positions(i, 0), v[1].get<double>() - bs.positions(i, 1)) <=
                      bs.radius * (1 + 1e-12));
        }
    }
    CHECK_THROWS_AS(dvoronoi::io::network_geojson_text(bs, -1.0), dvoronoi::InputError);
    CHECK_THROWS_AS(dvoronoi::io::network_geojson_text(bs, std::nan("")), dvoronoi::InputError);
}
