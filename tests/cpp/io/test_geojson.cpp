// GeoJSON: closed CCW rings, arcs densified within the stated tolerance, properties match.
#include "dvoronoi/io/geojson.hpp"

#include "io/io_test_data.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

using dvoronoi::Index;
using dvoronoi::LimitedPartition;
using dvoronoi::Vec2;
using json = nlohmann::json;

namespace {

double shoelace(const json& ring) {
    double a = 0.0;
    for (std::size_t k = 0; k + 1 < ring.size(); ++k)
        a += ring[k][0].get<double>() * ring[k + 1][1].get<double>() -
             ring[k + 1][0].get<double>() * ring[k][1].get<double>();
    return 0.5 * a;
}

/// Length of the arcs of agent i's cell.
double arc_length(const LimitedPartition& p, Index i) {
    double s = 0.0;
    for (const auto& pc : p.cell(i).pieces)
        if (pc.is_arc()) s += p.radius * pc.arc_span;
    return s;
}

void check_collection(const json& fc, const LimitedPartition& p, double tol) {
    CHECK(fc["type"] == "FeatureCollection");
    REQUIRE(fc["features"].size() == static_cast<std::size_t>(p.size()));
    const double R = p.radius;
    for (Index i = 0; i < p.size(); ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const json& f = fc["features"][ii];
        CHECK(f["type"] == "Feature");
        CHECK(f["properties"]["agent"] == i);
        CHECK(f["properties"]["area"].get<double>() == p.areas[ii]);
        CHECK(f["properties"]["neighbors"].get<std::vector<Index>>() ==
              std::vector<Index>(p.indices.begin() + p.indptr[ii], p.indices.begin() + p.indptr[ii + 1]));
        CHECK(f["geometry"]["type"] == "Polygon");
        REQUIRE(f["geometry"]["coordinates"].size() == 1);
        const json& ring = f["geometry"]["coordinates"][0];
        REQUIRE(ring.size() >= 4);
        CHECK(ring.front() == ring.back());  // closed
        const double area = shoelace(ring);
        CHECK(area > 0.0);  // counter-clockwise
        // Inscribed in the true cell: smaller, by at most (arc length x tolerance).
        const double deficit = p.areas[ii] - area;
        CHECK(deficit >= -1e-9 * R * R);
        CHECK(deficit <= arc_length(p, i) * tol + 1e-9 * R * R);
        // Every arc is replaced by chords no deeper than `tol` inside the circle: walk the ring from
        // each arc's start to the next piece's start.
        const Vec2 c(p.points(i, 0), p.points(i, 1));
        const auto cell = p.cell(i);
        const auto at = [&](std::size_t k) {
            return Vec2(ring[k][0].get<double>(), ring[k][1].get<double>());
        };
        std::size_t k = 0;
        for (std::size_t q = 0; q < cell.pieces.size(); ++q) {
            REQUIRE(k < ring.size());
            CHECK(at(k) == cell.pieces[q].start);  // piece starts are kept exactly, in order
            const Vec2 end = cell.piece_end(q);
            std::size_t next = k + 1;
            while (next + 1 < ring.size() && !(at(next) == end)) ++next;
            if (cell.pieces[q].is_arc()) {
                for (std::size_t t = k; t < next; ++t) {
                    CHECK(std::abs((at(t) - c).norm() - R) <= 1e-9 * R);
                    CHECK(R - (0.5 * (at(t) + at(t + 1)) - c).norm() <= tol * (1 + 1e-9));
                }
            } else {
                CHECK(next == k + 1);  // an edge is one segment
            }
            k = next;
        }
        CHECK(k == ring.size() - 1);
    }
}

}  // namespace

TEST_CASE("GeoJSON of a random partition with the default tolerance (1e-3 R)") {
    const LimitedPartition p = dvoronoi::limited_cells(io_test::mixed_points(), 0.8);
    const json fc = dvoronoi::io::to_geojson(p);
    check_collection(fc, p, 1e-3 * 0.8);
    std::ostringstream os;
    dvoronoi::io::write_geojson(os, p);
    CHECK(os.str() == fc.dump());
}

TEST_CASE("a smaller tolerance gives more vertices and a closer area") {
    const LimitedPartition p = dvoronoi::limited_cells(io_test::lattice(4), 0.7);
    const json coarse = dvoronoi::io::to_geojson(p, 1e-2);
    const json fine = dvoronoi::io::to_geojson(p, 1e-5);
    check_collection(coarse, p, 1e-2);
    check_collection(fine, p, 1e-5);
    const json& rc = coarse["features"][5]["geometry"]["coordinates"][0];
    const json& rf = fine["features"][5]["geometry"]["coordinates"][0];
    CHECK(rf.size() > rc.size());
    CHECK(std::abs(p.areas[5] - shoelace(rf)) < std::abs(p.areas[5] - shoelace(rc)));
}

TEST_CASE("a full disk is a polygon of at least 3 corners even with a huge tolerance") {
    dvoronoi::Points pts(1, 2);
    pts << 2.0, -1.0;
    const LimitedPartition p = dvoronoi::limited_cells(pts, 1.5);
    const json fc = dvoronoi::io::to_geojson(p, 100.0);
    const json& ring = fc["features"][0]["geometry"]["coordinates"][0];
    CHECK(ring.size() == 4);
    CHECK(shoelace(ring) > 0.0);
    check_collection(dvoronoi::io::to_geojson(p), p, 1.5e-3);
}

TEST_CASE("bad tolerances are InputErrors") {
    const LimitedPartition p = dvoronoi::limited_cells(io_test::lattice(2), 1.0);
    CHECK_THROWS_AS(dvoronoi::io::to_geojson(p, -1.0), dvoronoi::InputError);
    CHECK_THROWS_AS(dvoronoi::io::to_geojson(p, std::nan("")), dvoronoi::InputError);
    CHECK_THROWS_AS(dvoronoi::io::to_geojson(p, 1e-300), dvoronoi::InputError);  // too many chords
}

TEST_CASE("densify of one cell keeps the edge endpoints exactly") {
    const LimitedPartition p = dvoronoi::limited_cells(io_test::lattice(3), 0.6);
    const auto cell = p.cell(4);
    const auto ring = dvoronoi::io::densify(cell, 1e-4);
    for (const auto& pc : cell.pieces) {
        bool found = false;
        for (const Vec2& v : ring) found = found || v == pc.start;
        CHECK(found);
    }
    CHECK(ring.front() == ring.back());
    const json f = dvoronoi::io::to_geojson(cell);
    CHECK(f["type"] == "Feature");
    CHECK(f["properties"]["neighbors"] == json::array({1, 3, 5, 7}));
}
