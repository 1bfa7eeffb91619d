// CSV: header, one row per agent, numbers that read back exactly, neighbours as the CSR row.
#include "dvoronoi/io/csv.hpp"

#include "io/io_test_data.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : s) {
        if (ch == sep) {
            out.push_back(cur);
            cur.clear();
        } else {
            cur += ch;
        }
    }
    out.push_back(cur);
    return out;
}

}  // namespace

TEST_CASE("CSV rows match the partition exactly") {
    const auto p = dvoronoi::limited_cells(io_test::mixed_points(), 0.8);
    const std::string text = dvoronoi::io::to_csv(p);
    std::istringstream in(text);
    std::string line;
    REQUIRE(std::getline(in, line));
    CHECK(line == "agent,x,y,area,centroid_x,centroid_y,perimeter,neighbors");
    dvoronoi::Index i = 0;
    while (std::getline(in, line)) {
        const auto f = split(line, ',');
        REQUIRE(f.size() == 8);
        const auto ii = static_cast<std::size_t>(i);
        CHECK(std::stoll(f[0]) == i);
        CHECK(std::strtod(f[1].c_str(), nullptr) == p.points(i, 0));
        CHECK(std::strtod(f[2].c_str(), nullptr) == p.points(i, 1));
        CHECK(std::strtod(f[3].c_str(), nullptr) == p.areas[ii]);
        CHECK(std::strtod(f[4].c_str(), nullptr) == p.centroids(i, 0));
        CHECK(std::strtod(f[5].c_str(), nullptr) == p.centroids(i, 1));
        CHECK(std::strtod(f[6].c_str(), nullptr) == p.perimeters[ii]);
        std::vector<dvoronoi::Index> nb;
        if (!f[7].empty())
            for (const auto& s : split(f[7], ' ')) nb.push_back(std::stoll(s));
        CHECK(nb == std::vector<dvoronoi::Index>(p.indices.begin() + p.indptr[ii],
                                                 p.indices.begin() + p.indptr[ii + 1]));
        ++i;
    }
    CHECK(i == p.size());
    // The isolated agent (last) has no neighbours: an empty last field.
    CHECK(text.substr(text.size() - 2) == ",\n");
}
