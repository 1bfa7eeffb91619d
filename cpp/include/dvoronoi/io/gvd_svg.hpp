// SVG picture of a grid Voronoi diagram: the working area, the obstacles (grey), the traced cells
// (free in blue, blocked by the robot radius in light red, runs of a row merged into one rectangle),
// the Voronoi vertex cells (dark red) and optionally a path (green). y points up in the data and down
// in SVG, so y is flipped.
#pragma once

#include "dvoronoi/gvd/result.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace dvoronoi::io {

inline void write_gvd_svg(std::ostream& os, const gvd::Scene& scene, const gvd::GridVoronoi& r,
                          const std::vector<Vec2>& path = {}, double width = 1000.0) {
    const gvd::Box& b = scene.box;
    const double w = b.x1 - b.x0, h = b.y1 - b.y0, margin = 0.02 * std::max(w, h);
    const double scale = width / (w + 2 * margin);
    auto X = [&](double x) { return (x - b.x0 + margin) * scale; };
    auto Y = [&](double y) { return (b.y1 + margin - y) * scale; };
    char buf[256];
    auto num = [&](double v) { std::snprintf(buf, sizeof buf, "%.2f", v); return std::string(buf); };
    os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\"" << num((h + 2 * margin) * scale)
       << "\" viewBox=\"0 0 " << num(width) << " " << num((h + 2 * margin) * scale) << "\">\n";
    os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<polygon fill=\"#fafafa\" stroke=\"black\" stroke-width=\"1\" points=\"";
    for (const Vec2& p : scene.area) os << num(X(p.x())) << "," << num(Y(p.y())) << " ";
    os << "\"/>\n<g fill=\"#9e9e9e\" stroke=\"#616161\" stroke-width=\"0.5\">\n";
    for (const auto& part : scene.parts) {
        if (part.label >= scene.n_obstacles) continue;
        const Vec2* v = scene.part_vertices(part);
        switch (part.kind) {
            case gvd::ShapeKind::Circle:
                os << "<circle cx=\"" << num(X(part.center.x())) << "\" cy=\"" << num(Y(part.center.y())) << "\" r=\"" << num(part.radius * scale) << "\"/>\n";
                break;
            case gvd::ShapeKind::Point:
                os << "<circle cx=\"" << num(X(v[0].x())) << "\" cy=\"" << num(Y(v[0].y())) << "\" r=\"2\"/>\n";
                break;
            case gvd::ShapeKind::Segment:
                os << "<line x1=\"" << num(X(v[0].x())) << "\" y1=\"" << num(Y(v[0].y())) << "\" x2=\"" << num(X(v[1].x())) << "\" y2=\"" << num(Y(v[1].y())) << "\" stroke-width=\"2\"/>\n";
                break;
            case gvd::ShapeKind::Polygon:
                os << "<polygon points=\"";
                for (std::uint32_t k = 0; k < part.count; ++k) os << num(X(v[k].x())) << "," << num(Y(v[k].y())) << " ";
                os << "\"/>\n";
                break;
        }
    }
    os << "</g>\n";
    const double hs = r.grid.h * scale;
    for (int pass = 0; pass < 2; ++pass) {
        os << "<g fill=\"" << (pass == 0 ? "#1f77b4" : "#f4a6a6") << "\" shape-rendering=\"crispEdges\">\n";
        for (std::size_t k = 0; k < r.size();) {
            if ((r.blocked[k] != 0) != (pass == 1)) { ++k; continue; }
            std::size_t e = k + 1;
            while (e < r.size() && r.row[e] == r.row[k] && r.col[e] == r.col[e - 1] + 1 && (r.blocked[e] != 0) == (pass == 1)) ++e;
            const Vec2 lo = r.grid.corner(r.col[k], r.row[k] + 1);
            os << "<rect x=\"" << num(X(lo.x())) << "\" y=\"" << num(Y(lo.y())) << "\" width=\"" << num(hs * static_cast<double>(e - k))
               << "\" height=\"" << num(hs) << "\"/>\n";
            k = e;
        }
        os << "</g>\n";
    }
    os << "<g fill=\"#b71c1c\">\n";
    for (std::int64_t v : r.vertices) {
        const Vec2 c = r.center(static_cast<std::size_t>(v));
        os << "<circle cx=\"" << num(X(c.x())) << "\" cy=\"" << num(Y(c.y())) << "\" r=\"" << num(std::max(1.5, hs)) << "\"/>\n";
    }
    os << "</g>\n";
    if (!path.empty()) {
        os << "<polyline fill=\"none\" stroke=\"#2e7d32\" stroke-width=\"2\" points=\"";
        for (const Vec2& p : path) os << num(X(p.x())) << "," << num(Y(p.y())) << " ";
        os << "\"/>\n";
    }
    os << "</svg>\n";
}

}  // namespace dvoronoi::io
