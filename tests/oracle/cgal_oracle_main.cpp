// dvoronoi_cgal_oracle POINTS_FILE RADIUS [XMIN YMIN XMAX YMAX]
//
// Runs the exact CGAL oracle (cgal_oracle.hpp) and prints JSON to stdout:
//   {"n": ..., "radius": ..., "dimension": ...,
//    "voronoi_neighbors": [[...], ...], "limited_neighbors": [[...], ...], "on_hull": [...],
//    "limited_areas": [...], "limited_centroids": [[x, y], ...],
//    "limited_pieces": [[neighbour or -1 for an arc, ...], ...]}   (ccw, from the smallest neighbour)
// With a box, also "clipped_areas": the exact Voronoi cells clipped to that box (exact clipping).
// POINTS_FILE holds whitespace- (or comma-) separated `x y` per line; `#` starts a comment.
// Doubles are printed so that they read back to the same double (shortest round-trip form).
#include "cgal_oracle.hpp"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<dvoronoi_oracle::XY> read_points(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::vector<dvoronoi_oracle::XY> pts;
    std::string line;
    for (std::size_t lineno = 1; std::getline(in, line); ++lineno) {
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        for (char& c : line)
            if (c == ',') c = ' ';
        double xy[2];
        const char* s = line.c_str();
        int got = 0;
        while (true) {
            while (*s == ' ' || *s == '\t' || *s == '\r') ++s;
            if (*s == '\0') break;
            const std::size_t col = static_cast<std::size_t>(s - line.c_str()) + 1;
            if (got == 2)
                throw std::runtime_error(path + ":" + std::to_string(lineno) + ":" +
                                         std::to_string(col) + ": expected 2 columns (x y)");
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(s, &end);
            if (end == s || errno == ERANGE || !(*end == '\0' || *end == ' ' || *end == '\t' ||
                                                 *end == '\r'))
                throw std::runtime_error(path + ":" + std::to_string(lineno) + ":" +
                                         std::to_string(col) + ": not a number");
            xy[got++] = v;
            s = end;
        }
        if (got == 0) continue;
        if (got != 2)
            throw std::runtime_error(path + ":" + std::to_string(lineno) +
                                     ": expected 2 columns (x y)");
        pts.push_back({xy[0], xy[1]});
    }
    return pts;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3 && argc != 7) {
        std::cerr << "usage: dvoronoi_cgal_oracle POINTS_FILE RADIUS [XMIN YMIN XMAX YMAX]\n";
        return 2;
    }
    try {
        const auto pts = read_points(argv[1]);
        char* end = nullptr;
        const double radius = std::strtod(argv[2], &end);
        if (end == argv[2] || *end != '\0') throw std::runtime_error("RADIUS: not a number");
        const auto res = dvoronoi_oracle::compute_oracle(pts, radius);
        nlohmann::json j;
        j["n"] = pts.size();
        j["radius"] = radius;
        j["dimension"] = res.dimension;
        j["voronoi_neighbors"] = res.voronoi_neighbors;
        j["limited_neighbors"] = res.limited_neighbors;
        j["on_hull"] = res.on_hull;
        j["limited_areas"] = res.limited_areas;
        j["limited_centroids"] = res.limited_centroids;
        j["limited_pieces"] = res.limited_pieces;
        if (argc == 7) {
            double b[4];
            for (int k = 0; k < 4; ++k) {
                char* e = nullptr;
                b[k] = std::strtod(argv[3 + k], &e);
                if (e == argv[3 + k] || *e != '\0') throw std::runtime_error("box: not a number");
            }
            j["clipped_areas"] = dvoronoi_oracle::clipped_areas(pts, b[0], b[1], b[2], b[3]);
        }
        std::cout << j.dump() << '\n';
    } catch (const std::exception& e) {
        std::cerr << "dvoronoi_cgal_oracle: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
