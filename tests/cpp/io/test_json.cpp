// The JSON schema shared by the CLI and Python: fields, exact round trip, consistent pieces, and
// write_json == to_json().dump().
#include "dvoronoi/io/json.hpp"

#include "io/io_test_data.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <sstream>
#include <string>

using dvoronoi::Index;
using dvoronoi::LimitedPartition;
using dvoronoi::Method;
using dvoronoi::Vec2;
using json = nlohmann::json;

namespace {

const double kTwoPi = 6.283185307179586;

Vec2 vec(const json& a) {
    REQUIRE(a.is_array());
    REQUIRE(a.size() == 2);
    return Vec2(a[0].get<double>(), a[1].get<double>());
}

/// Checks the document against the partition it came from; R-relative tolerance for geometry.
void check_document(const json& j, const LimitedPartition& p, Method method) {
    const std::set<std::string> keys{"kind",    "method", "radius",    "points",     "indptr",
                                      "indices", "areas",  "perimeters", "centroids", "cells"};
    std::set<std::string> got;
    for (auto it = j.begin(); it != j.end(); ++it) got.insert(it.key());
    CHECK(got == keys);
    CHECK(j["kind"] == "limited_partition");
    CHECK(j["method"] == (method == Method::Scan ? "scan" : "chords"));
    CHECK(j["radius"].get<double>() == p.radius);
    const Index n = p.size();
    REQUIRE(j["points"].size() == static_cast<std::size_t>(n));
    REQUIRE(j["cells"].size() == static_cast<std::size_t>(n));
    CHECK(j["indptr"].get<std::vector<Index>>() == p.indptr);
    CHECK(j["indices"].get<std::vector<Index>>() == p.indices);
    CHECK(j["areas"].get<std::vector<double>>() == p.areas);
    CHECK(j["perimeters"].get<std::vector<double>>() == p.perimeters);
    const double R = p.radius, eps = 1e-9 * R;
    for (Index i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        // Doubles survive the text exactly.
        CHECK(vec(j["points"][ii]) == Vec2(p.points(i, 0), p.points(i, 1)));
        CHECK(vec(j["centroids"][ii]) == Vec2(p.centroids(i, 0), p.centroids(i, 1)));
        const json& cell = j["cells"][ii];
        CHECK(cell["agent"].get<Index>() == i);
        const json& pieces = cell["pieces"];
        REQUIRE(pieces.size() >= 1);
        const Vec2 center(p.points(i, 0), p.points(i, 1));
        double length = 0.0;
        std::set<Index> edge_neighbors;
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const json& pc = pieces[k];
            const Vec2 a = vec(pc["start"]), b = vec(pc["end"]);
            // The cycle is closed: each piece ends where the next starts.
            CHECK(b == vec(pieces[(k + 1) % pieces.size()]["start"]));
            if (pc["type"] == "edge") {
                CHECK(pc.size() == 4);
                const Index nb = pc["neighbor"].get<Index>();
                CHECK(nb >= 0);
                CHECK(nb < n);
                CHECK(nb != i);
                edge_neighbors.insert(nb);
                length += (b - a).norm();
            } else {
                REQUIRE(pc["type"] == "arc");
                CHECK(pc.size() == 6);
                CHECK(vec(pc["center"]) == center);
                CHECK(pc["radius"].get<double>() == R);
                const double span = pc["span"].get<double>();
                CHECK(span > 0.0);
                CHECK(span <= kTwoPi + 1e-12);
                CHECK(std::abs((a - center).norm() - R) <= eps);
                CHECK(std::abs((b - center).norm() - R) <= eps);
                length += R * span;
            }
        }
        // Edges plus arcs make up the whole perimeter.
        CHECK(length == doctest::Approx(p.perimeters[ii]).epsilon(1e-12));
        // The edge neighbours are exactly the agent's CSR row.
        const std::set<Index> row(p.indices.begin() + p.indptr[ii], p.indices.begin() + p.indptr[ii + 1]);
        CHECK(edge_neighbors == row);
    }
}

}  // namespace

TEST_CASE("to_json of a random partition: fields, exact numbers, closed cycles, perimeters") {
    const auto pts = io_test::mixed_points();
    for (const Method m : {Method::Scan, Method::Chords}) {
        const LimitedPartition p = dvoronoi::limited_cells(pts, 0.8, m);
        const json j = dvoronoi::io::to_json(p, m);
        check_document(j, p, m);
        // Through text and back: the same document.
        CHECK(json::parse(j.dump()) == j);
    }
}

TEST_CASE("both methods give the same neighbours; only the method field differs") {
    const auto pts = io_test::lattice(5);
    const LimitedPartition s = dvoronoi::limited_cells(pts, 0.9, Method::Scan);
    const LimitedPartition c = dvoronoi::limited_cells(pts, 0.9, Method::Chords);
    json js = dvoronoi::io::to_json(s, Method::Scan), jc = dvoronoi::io::to_json(c, Method::Chords);
    check_document(js, s, Method::Scan);
    check_document(jc, c, Method::Chords);
    CHECK(js["indices"] == jc["indices"]);
    CHECK(js["indptr"] == jc["indptr"]);
    CHECK(js["method"] != jc["method"]);
    // Lattice diagonals touch in a point only: an interior agent has exactly 4 limited neighbours.
    const std::size_t center = 12;
    CHECK(js["indptr"][center + 1].get<Index>() - js["indptr"][center].get<Index>() == 4);
}

TEST_CASE("an isolated agent is one full-circle arc starting and ending at the same point") {
    dvoronoi::Points pts(2, 2);
    pts << 0.0, 0.0, 10.0, 0.0;
    const LimitedPartition p = dvoronoi::limited_cells(pts, 1.0);
    const json j = dvoronoi::io::to_json(p, Method::Scan);
    check_document(j, p, Method::Scan);
    const json& pieces = j["cells"][0]["pieces"];
    REQUIRE(pieces.size() == 1);
    CHECK(pieces[0]["type"] == "arc");
    CHECK(pieces[0]["span"].get<double>() == doctest::Approx(kTwoPi));
    CHECK(pieces[0]["start"] == pieces[0]["end"]);
    CHECK(j["indptr"] == json::array({0, 0, 0}));
}

TEST_CASE("empty input gives an empty document with indptr [0]") {
    const dvoronoi::Points pts(0, 2);
    const LimitedPartition p = dvoronoi::limited_cells(pts, 1.0);
    const json j = dvoronoi::io::to_json(p, Method::Scan);
    check_document(j, p, Method::Scan);
    CHECK(j["indptr"] == json::array({0}));
    CHECK(j["cells"].empty());
    CHECK(dvoronoi::io::to_json_string(p, Method::Scan) == j.dump());
}

TEST_CASE("write_json streams exactly to_json().dump(), across block boundaries") {
    const auto pts = io_test::random_points(5000, 60.0, 3);  // > one block of 2048 cells
    const LimitedPartition p = dvoronoi::limited_cells(pts, 1.0, Method::Scan, 2);
    std::ostringstream os;
    dvoronoi::io::write_json(os, p, Method::Scan);
    const std::string streamed = os.str();
    CHECK(streamed == dvoronoi::io::to_json(p, Method::Scan).dump());
    CHECK(json::parse(streamed)["cells"][4999]["agent"] == 4999);
}

TEST_CASE("to_json of one cell: measures and pieces") {
    const auto pts = io_test::lattice(3);
    const LimitedPartition p = dvoronoi::limited_cells(pts, 0.6);
    const auto cell = p.cell(4);
    const json j = dvoronoi::io::to_json(cell);
    CHECK(j["kind"] == "limited_cell");
    CHECK(vec(j["center"]) == Vec2(1.0, 1.0));
    CHECK(j["radius"].get<double>() == 0.6);
    CHECK(j["neighbors"] == json::array({1, 3, 5, 7}));
    CHECK(j["area"].get<double>() == doctest::Approx(p.areas[4]).epsilon(1e-14));
    CHECK(j["perimeter"].get<double>() == doctest::Approx(p.perimeters[4]).epsilon(1e-14));
    CHECK(j["pieces"] == dvoronoi::io::to_json(p, Method::Scan)["cells"][4]["pieces"]);
    // The square's four edges and four arcs of the disk of radius 0.6 around (1, 1).
    CHECK(j["pieces"].size() == 8);
}
