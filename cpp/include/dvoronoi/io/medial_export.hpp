// JSON and SVG of the medial diagram of an occupancy grid, shared by `dvoronoi gvd MAP` and Python's
// OccupancyVoronoi.to_json() / to_svg() (one writer, the same document everywhere):
//
//   {"kind": "grid_voronoi", "diagram": "medial",
//    "map": {"rows": H, "cols": W, "resolution": m, "origin": [x, y]},   pixel (r, c): row 0 at the top
//    "options": {"min_separation": px, "prune_length": px},
//    "robot_radius": r,
//    "pixels": {"row": [...], "col": [...],                              diagram pixels, row-major order
//               "x": [...], "y": [...],                                  their centres (map units)
//               "clearance": [...], "blocked": [0/1, ...]},              distance to occupied; <= r
//    "path": {"found": bool, "length": ., "points": [[x, y], ...]}       when a path was asked for
//   }
//
// The SVG draws occupied pixels (dark grey, runs of a row merged), diagram pixels (blue; blocked ones
// light red) and a path (green), in map coordinates with y up; it scales to any size (viewBox).
#pragma once

#include "dvoronoi/gvd/grid_path.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace dvoronoi::io {

inline nlohmann::json medial_to_json(const gvd::MedialDiagram& m, double robot_radius) {
    using nlohmann::json;
    const gvd::OccupancyGrid& g = m.grid;
    json rows = json::array(), cols = json::array(), xs = json::array(), ys = json::array(), cl = json::array(),
         bl = json::array();
    for (std::int32_t r = 0; r < g.rows; ++r)
        for (std::int32_t c = 0; c < g.cols; ++c)
            if (m.mask(r, c)) {
                const Vec2 p = g.center(r, c);
                const double d = m.clearance(r, c);
                rows.push_back(r);
                cols.push_back(c);
                xs.push_back(p.x());
                ys.push_back(p.y());
                cl.push_back(d);
                bl.push_back(d <= robot_radius ? 1 : 0);
            }
    return {{"kind", "grid_voronoi"},
            {"diagram", "medial"},
            {"map", {{"rows", g.rows}, {"cols", g.cols}, {"resolution", g.resolution}, {"origin", {g.origin.x(), g.origin.y()}}}},
            {"options", {{"min_separation", m.options.min_separation}, {"prune_length", m.options.prune_length}}},
            {"robot_radius", robot_radius},
            {"pixels", {{"row", rows}, {"col", cols}, {"x", xs}, {"y", ys}, {"clearance", cl}, {"blocked", bl}}}};
}

/// A path's JSON, for either diagram (gvd::GridPath, gvd::PathResult: points, length, found()).
template <class Path>
nlohmann::json path_to_json(const Path& p) {
    nlohmann::json pts = nlohmann::json::array();
    for (const Vec2& q : p.points) pts.push_back({q.x(), q.y()});
    // no path: no length (JSON has no infinity; Python's stats say inf)
    return {{"found", p.found()}, {"length", p.found() ? nlohmann::json(p.length) : nlohmann::json(nullptr)}, {"points", pts}};
}

inline void write_medial_svg(std::ostream& os, const gvd::MedialDiagram& m, double robot_radius,
                             const std::vector<Vec2>& path = {}, double width = 1000.0) {
    const gvd::OccupancyGrid& g = m.grid;
    const double res = g.resolution, W = g.cols * res, H = g.rows * res;
    const double height = width * H / W;
    char buf[160];
    auto num = [&](double v) { std::snprintf(buf, sizeof buf, "%.6g", v); return std::string(buf); };
    // user units: map units, y flipped by the group transform; one pixel = res
    os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\"" << num(height)
       << "\" viewBox=\"0 0 " << num(W) << " " << num(H) << "\" shape-rendering=\"crispEdges\">\n";
    os << "<rect width=\"" << num(W) << "\" height=\"" << num(H) << "\" fill=\"white\"/>\n";
    auto runs = [&](const char* fill, const char* id, auto&& keep) {
        os << "<g id=\"" << id << "\" fill=\"" << fill << "\">\n";
        for (std::int32_t r = 0; r < g.rows; ++r) {
            std::int32_t c = 0;
            while (c < g.cols) {
                if (!keep(r, c)) { ++c; continue; }
                std::int32_t e = c;
                while (e + 1 < g.cols && keep(r, e + 1)) ++e;
                os << "<rect x=\"" << num(c * res) << "\" y=\"" << num(r * res) << "\" width=\"" << num((e - c + 1) * res)
                   << "\" height=\"" << num(res) << "\"/>\n";
                c = e + 1;
            }
        }
        os << "</g>\n";
    };
    runs("#424242", "occupied", [&](std::int32_t r, std::int32_t c) { return g.occ(r, c); });
    runs("#1e78b4", "diagram", [&](std::int32_t r, std::int32_t c) { return m.mask(r, c) && m.clearance(r, c) > robot_radius; });
    runs("#f4a6a6", "blocked", [&](std::int32_t r, std::int32_t c) { return m.mask(r, c) && m.clearance(r, c) <= robot_radius; });
    if (path.size() >= 2) {
        os << "<polyline id=\"path\" fill=\"none\" stroke=\"#2e7d32\" stroke-width=\"" << num(std::max(2.0 * res, 0.004 * W))
           << "\" stroke-linejoin=\"round\" stroke-linecap=\"round\" points=\"";
        for (const Vec2& p : path) os << num(p.x() - g.origin.x()) << "," << num(H - (p.y() - g.origin.y())) << " ";
        os << "\"/>\n";
    }
    os << "</svg>\n";
}

}  // namespace dvoronoi::io
