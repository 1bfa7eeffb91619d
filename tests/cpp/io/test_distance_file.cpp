// Distance files: the indices are robot IDs (serial numbers too), numbered 0..n-1 in ascending ID
// order; memory follows the file, not the largest ID; outputs name robots by ID, and files whose IDs
// are exactly 0..n-1 write what they always wrote.
#include "dvoronoi/io/distance_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

using namespace dvoronoi;

namespace {

struct Written {
    std::string json, csv;
};

Written run(const std::string& text, bool by_ids = true) {
    const io::DistanceFile f = io::parse_distance_text(text, "d.txt");
    const std::vector<Index> ids = io::robot_ids(f);
    const dist::DistanceGraph g = by_ids ? io::distance_graph(f, ids, false, false)
                                         : io::distance_graph(f, ids.empty() ? 0 : ids.back() + 1, false, false);
    const dist::DistanceNeighbors r = dist::neighbors_from_distances(g, true, 1);
    std::ostringstream json, csv;
    io::write_json(json, r, false, by_ids ? ids : std::vector<Index>{});
    io::write_csv(csv, r, by_ids ? ids : std::vector<Index>{});
    return {json.str(), csv.str()};
}

}  // namespace

TEST_CASE("a robot ID of two billion is an ID, not a size") {
    const io::DistanceFile f = io::parse_distance_text("0 2000000000 1\n", "d.txt");
    const std::vector<Index> ids = io::robot_ids(f);
    CHECK(ids == std::vector<Index>{0, 2000000000});
    const dist::DistanceGraph g = io::distance_graph(f, ids, false, false);
    CHECK(g.n == 2);
    CHECK(g.indptr.size() == 3);
    const Written w = run("0 2000000000 1\n");
    CHECK(w.json.find("\"n\": 2, \"ids\": [0, 2000000000],") != std::string::npos);
    CHECK(w.json.find("\"indices\": [2000000000, 0]") != std::string::npos);
    CHECK(w.csv == "robot,on_hull,detected,neighbors\n0,1,1,2000000000\n2000000000,1,1,0\n");
}

TEST_CASE("serial numbers give the relation of the file renumbered in ascending ID order") {
    // Four robots on a unit square plus its centre (exact squared distances are not needed: the
    // relation is the same for both files by construction).
    const std::vector<Vec2> p = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2), Vec2(1, 0.9)};
    const std::vector<long long> serial = {1000017, 1000003, 9000000000042, 1000018, 5000000};  // robot k's ID
    std::vector<long long> sorted = serial;
    std::sort(sorted.begin(), sorted.end());
    std::string by_serial, renumbered;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            char d[32];
            std::snprintf(d, sizeof d, "%.17g", (p[i] - p[j]).norm());
            const auto rank = [&](std::size_t k) { return std::find(sorted.begin(), sorted.end(), serial[k]) - sorted.begin(); };
            by_serial += std::to_string(serial[j]) + " " + std::to_string(serial[i]) + " " + d + "\n";
            renumbered += std::to_string(rank(j)) + " " + std::to_string(rank(i)) + " " + d + "\n";
        }
    const Written a = run(by_serial), b = run(renumbered);
    CHECK(b.json.find("\"ids\"") == std::string::npos);  // IDs 0..n-1: written as before
    // Replace every renumbered robot by its serial number and the outputs agree.
    std::string csv;
    std::istringstream lines(b.csv);
    std::string line;
    std::getline(lines, line);
    csv += line + "\n";
    while (std::getline(lines, line)) {
        std::vector<std::string> f;
        std::string cur;
        for (char ch : line) {
            if (ch == ',') {
                f.push_back(cur);
                cur.clear();
            } else {
                cur += ch;
            }
        }
        f.push_back(cur);
        std::string nb;
        std::istringstream ns(f[3]);
        for (std::string t; ns >> t;) nb += (nb.empty() ? "" : " ") + std::to_string(sorted[std::stoul(t)]);
        csv += std::to_string(sorted[std::stoul(f[0])]) + "," + f[1] + "," + f[2] + "," + nb + "\n";
    }
    CHECK(a.csv == csv);
}

TEST_CASE("IDs exactly 0..n-1 write what robot indices always wrote") {
    const std::string text = "0 1 1.0\n1 2 1.0\n0 2 1.5\n2 3 1.2\n1 3 1.3\n";
    const Written by_ids = run(text, true), by_index = run(text, false);
    CHECK(by_ids.json == by_index.json);
    CHECK(by_ids.csv == by_index.csv);
    CHECK(by_ids.json.find("\"ids\"") == std::string::npos);
}

TEST_CASE("errors name robots by ID") {
    const io::DistanceFile f = io::parse_distance_text("1000003 1000017 1.0\n1000017 1000003 2.0\n", "d.txt");
    try {
        io::distance_graph(f, io::robot_ids(f), false, false);
        FAIL("no error");
    } catch (const InputError& e) {
        const std::string msg = e.what();
        CHECK(msg.find("d.txt:2:1") != std::string::npos);
        CHECK(msg.find("(1000003, 1000017)") != std::string::npos);
    }
}
