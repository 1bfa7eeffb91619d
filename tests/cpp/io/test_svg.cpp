// SVG: one path per cell with real arc commands, agents as dots, y flipped, viewBox holding the disks.
#include "dvoronoi/io/svg.hpp"

#include "io/io_test_data.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <regex>
#include <string>

namespace {

std::size_t count(const std::string& s, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t k = s.find(part); k != std::string::npos; k = s.find(part, k + 1)) ++n;
    return n;
}

double attr(const std::string& s, const std::string& element_start, const std::string& name) {
    const std::size_t e = s.find(element_start);
    REQUIRE(e != std::string::npos);
    const std::size_t a = s.find(name + "=\"", e);
    REQUIRE(a != std::string::npos);
    return std::strtod(s.c_str() + a + name.size() + 2, nullptr);
}

}  // namespace

TEST_CASE("one filled path per cell, arcs as A commands with sweep flag 0, one dot per agent") {
    const auto p = dvoronoi::limited_cells(io_test::mixed_points(), 0.8);
    const std::string svg = dvoronoi::io::to_svg(p);
    CHECK(svg.rfind("<?xml", 0) == 0);
    CHECK(svg.find("</svg>") != std::string::npos);
    CHECK(count(svg, "<path ") == static_cast<std::size_t>(p.size()));
    CHECK(count(svg, "<circle ") == static_cast<std::size_t>(p.size()));
    CHECK(svg.find("nan") == std::string::npos);
    std::size_t arcs = 0, edges = 0;
    for (std::size_t k = 0; k < p.piece_neighbor.size(); ++k) (p.piece_neighbor[k] < 0 ? arcs : edges)++;
    CHECK(count(svg, " L ") == edges);
    CHECK(count(svg, " A ") >= arcs);
    // Every arc: rx = ry = R, no rotation, small arc, sweep 0 (counter-clockwise after the y flip).
    const std::regex arc(" A ([^ ]+) ([^ ]+) ([01]) ([01]) ([01]) ");
    std::size_t seen = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), arc); it != std::sregex_iterator(); ++it) {
        CHECK(std::strtod((*it)[1].str().c_str(), nullptr) == doctest::Approx(0.8));
        CHECK((*it)[4].str() == "0");
        CHECK((*it)[5].str() == "0");
        ++seen;
    }
    CHECK(seen == count(svg, " A "));
}

TEST_CASE("y is flipped and the viewBox holds every disk") {
    dvoronoi::Points pts(2, 2);
    pts << 0.0, 0.0, 0.0, 10.0;
    const auto p = dvoronoi::limited_cells(pts, 2.0);
    const std::string svg = dvoronoi::io::to_svg(p);
    const double cy0 = attr(svg, "<circle ", "cy");
    const double cy1 = attr(svg.substr(svg.find("<circle ") + 1), "<circle ", "cy");
    CHECK(cy1 < cy0);                               // the higher agent is drawn higher
    CHECK(cy0 - cy1 == doctest::Approx(10.0));      // scale 1
    const std::smatch m = [&] {
        std::smatch r;
        std::regex_search(svg, r, std::regex("viewBox=\"0 0 ([^ ]+) ([^\"]+)\""));
        return r;
    }();
    REQUIRE(m.size() == 3);
    CHECK(std::strtod(m[1].str().c_str(), nullptr) >= 4.0);   // 2R wide
    CHECK(std::strtod(m[2].str().c_str(), nullptr) >= 14.0);  // 10 + 2R tall
    CHECK(cy1 >= 2.0);                                        // top disk inside the picture
    const double stroke = attr(svg, "<g class=\"cells\"", "stroke-width");
    CHECK(stroke > 0.0);
    CHECK(stroke < 0.1);
}

TEST_CASE("neighbouring cells get different colours") {
    const auto p = dvoronoi::limited_cells(io_test::lattice(6), 0.8);
    const std::string svg = dvoronoi::io::to_svg(p);
    std::vector<std::string> fill(static_cast<std::size_t>(p.size()));
    const std::regex path("<path id=\"cell-([0-9]+)\" fill=\"(#[0-9a-f]{6})\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), path); it != std::sregex_iterator(); ++it)
        fill[std::stoul((*it)[1].str())] = (*it)[2].str();
    for (std::size_t i = 0; i < fill.size(); ++i) {
        REQUIRE_FALSE(fill[i].empty());
        for (auto k = p.indptr[i]; k < p.indptr[i + 1]; ++k)
            CHECK(fill[i] != fill[static_cast<std::size_t>(p.indices[static_cast<std::size_t>(k)])]);
    }
}
