// SVG picture of a limited partition: each cell filled with a light colour (neighbouring cells get
// different colours), its boundary drawn with straight segments for edges and true SVG elliptical-arc
// commands for arcs, and the agents as dots.
//
// Geometry: y points up in the data and down in SVG, so y is flipped; coordinates are translated so
// the picture starts at (0, 0), and the viewBox holds every agent's disk B(p_i, R) plus a 2% margin.
// Stroke width and dot size scale with the picture (and with R, so dense partitions stay legible).
#pragma once

#include "dvoronoi/partition/limited_partition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace dvoronoi::io {

/// Options of write_svg.
struct SvgOptions {
    double width = 1000.0;  ///< size in pixels of the picture's longer side
    bool dots = true;       ///< draw the agents
    bool labels = false;    ///< write each agent's index next to it
};

namespace detail {

/// Twelve light colours (ColorBrewer Set3).
inline const char* light_colour(std::size_t k) {
    static const char* const palette[] = {"#8dd3c7", "#ffffb3", "#bebada", "#fb8072",
                                          "#80b1d3", "#fdb462", "#b3de69", "#fccde5",
                                          "#d9d9d9", "#bc80bd", "#ccebc5", "#ffed6f"};
    return palette[k % 12];
}

/// Greedy colouring of the limited-neighbour graph: each agent takes the first palette colour no
/// earlier neighbour has (distinct for neighbours whenever an agent has fewer than 12 neighbours).
/// Any partition with size(), indptr and indices.
template <class Partition>
std::vector<std::size_t> colour_cells(const Partition& p) {
    const auto n = static_cast<std::size_t>(p.size());
    std::vector<std::size_t> colour(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        unsigned used = 0;
        for (Index k = p.indptr[i]; k < p.indptr[i + 1]; ++k) {
            const auto j = static_cast<std::size_t>(p.indices[static_cast<std::size_t>(k)]);
            if (j < i) used |= 1u << colour[j];
        }
        std::size_t c = 0;
        while (c < 12 && (used >> c & 1u)) ++c;
        colour[i] = c < 12 ? c : i % 12;
    }
    return colour;
}

inline void append_num(std::string& out, double v) {
    char buf[32];
    if (std::abs(v) < 1e-12) v = 0.0;  // no "-0" or "1e-17" noise
    const int len = std::snprintf(buf, sizeof buf, "%.9g", v);
    out.append(buf, static_cast<std::size_t>(len));
}

/// The XML declaration and the opening <svg> tag: size in pixels, viewBox 0 0 W H.
inline void open_svg(std::string& s, double px_w, double px_h, double W, double H) {
    s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
    append_num(s, px_w);
    s += "\" height=\"";
    append_num(s, px_h);
    s += "\" viewBox=\"0 0 ";
    append_num(s, W);
    s += ' ';
    append_num(s, H);
    s += "\">\n";
}

}  // namespace detail

/// Writes an SVG document showing the partition.
/// \note O(total number of pieces); streams cell by cell.
inline void write_svg(std::ostream& os, const LimitedPartition& p, const SvgOptions& opt = {}) {
    const double pi = 3.14159265358979323846;
    const Index n = p.size();
    const double R = p.radius;
    double minx = 0, maxx = 1, miny = 0, maxy = 1;
    if (n > 0) {
        minx = p.points.col(0).minCoeff() - R;
        maxx = p.points.col(0).maxCoeff() + R;
        miny = p.points.col(1).minCoeff() - R;
        maxy = p.points.col(1).maxCoeff() + R;
    }
    const double extent0 = std::max(maxx - minx, maxy - miny);
    const double margin = 0.02 * extent0;
    const double x0 = minx - margin, ytop = maxy + margin;
    const double W = maxx - minx + 2 * margin, H = maxy - miny + 2 * margin;
    const double extent = std::max(W, H);
    const double scale_ref = n > 0 ? R : extent;
    const double stroke = std::min(1.5e-3 * extent, 0.03 * scale_ref);
    const double dot = std::min(4e-3 * extent, 0.06 * scale_ref);
    const double px_w = W >= H ? opt.width : opt.width * W / H;
    const double px_h = W >= H ? opt.width * H / W : opt.width;

    std::string s;
    const auto X = [&](double x) { detail::append_num(s, x - x0); };
    const auto Y = [&](double y) { detail::append_num(s, ytop - y); };
    const auto pt = [&](double x, double y) {
        X(x);
        s += ' ';
        Y(y);
    };

    detail::open_svg(s, px_w, px_h, W, H);
    s += "<title>dvoronoi: " + std::to_string(n) + " range-limited Voronoi cells, R = ";
    detail::append_num(s, R);
    s += "</title>\n<g class=\"cells\" stroke=\"#333333\" stroke-width=\"";
    detail::append_num(s, stroke);
    s += "\" stroke-linejoin=\"round\">\n";
    os << s;

    const std::vector<std::size_t> colour = detail::colour_cells(p);
    for (Index i = 0; i < n; ++i) {
        s.clear();
        const Index lo = p.piece_ptr[static_cast<std::size_t>(i)];
        const Index hi = p.piece_ptr[static_cast<std::size_t>(i) + 1];
        if (hi <= lo) continue;
        const double cx = p.points(i, 0), cy = p.points(i, 1);
        s += "<path id=\"cell-" + std::to_string(i) + "\" fill=\"";
        s += detail::light_colour(colour[static_cast<std::size_t>(i)]);
        s += "\" d=\"M ";
        pt(p.piece_x[static_cast<std::size_t>(lo)], p.piece_y[static_cast<std::size_t>(lo)]);
        for (Index k = lo; k < hi; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            const auto next = static_cast<std::size_t>(k + 1 < hi ? k + 1 : lo);
            const double ex = p.piece_x[next], ey = p.piece_y[next];
            if (p.piece_neighbor[kk] >= 0 || p.piece_span[kk] <= 0.0) {  // edges; walls of clipped cells
                s += " L ";
                pt(ex, ey);
                continue;
            }
            // An arc, counter-clockwise in the data = clockwise on screen after the y flip, so
            // sweep-flag 0. Split into sub-arcs of at most pi/2: never large-arc, never a full turn
            // with equal endpoints, never an ambiguous half circle.
            const double span = p.piece_span[kk];
            const int m = std::max(1, static_cast<int>(std::ceil(span / (0.5 * pi) - 1e-9)));
            const double a0 = std::atan2(p.piece_y[kk] - cy, p.piece_x[kk] - cx);
            for (int j = 1; j <= m; ++j) {
                double qx = ex, qy = ey;
                if (j < m) {
                    const double a = a0 + span * j / m;
                    qx = cx + R * std::cos(a);
                    qy = cy + R * std::sin(a);
                }
                s += " A ";
                detail::append_num(s, R);
                s += ' ';
                detail::append_num(s, R);
                s += " 0 0 0 ";
                pt(qx, qy);
            }
        }
        s += " Z\"><title>agent " + std::to_string(i) + "</title></path>\n";
        os << s;
    }
    os << "</g>\n";

    if (opt.dots && n > 0) {
        s.clear();
        s += "<g class=\"agents\" fill=\"#000000\">\n";
        for (Index i = 0; i < n; ++i) {
            s += "<circle cx=\"";
            X(p.points(i, 0));
            s += "\" cy=\"";
            Y(p.points(i, 1));
            s += "\" r=\"";
            detail::append_num(s, dot);
            s += "\"/>\n";
            if (s.size() > (1u << 16)) {
                os << s;
                s.clear();
            }
        }
        s += "</g>\n";
        os << s;
    }
    if (opt.labels && n > 0) {
        s.clear();
        s += "<g class=\"labels\" font-family=\"sans-serif\" font-size=\"";
        detail::append_num(s, 3 * dot);
        s += "\" fill=\"#000000\">\n";
        for (Index i = 0; i < n; ++i) {
            s += "<text x=\"";
            X(p.points(i, 0) + dot);
            s += "\" y=\"";
            Y(p.points(i, 1) + dot);
            s += "\">" + std::to_string(i) + "</text>\n";
        }
        s += "</g>\n";
        os << s;
    }
    os << "</svg>\n";
}

/// The SVG document as a string.
inline std::string to_svg(const LimitedPartition& p, const SvgOptions& opt = {}) {
    std::ostringstream os;
    write_svg(os, p, opt);
    return os.str();
}

}  // namespace dvoronoi::io
