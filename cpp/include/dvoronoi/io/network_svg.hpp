// SVG picture of a simulated network: cells (polygons, optional), links, obstacles, nodes. Used by
// `dvoronoi network --svg`.
#pragma once

#include "dvoronoi/io/svg.hpp"
#include "dvoronoi/network/bounded_cell.hpp"
#include "dvoronoi/network/network.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace dvoronoi::io {

/// Draws `net` (links grey, obstacles red, nodes black, `highlight` nodes circled red) over `cells`
/// (one polygon per node, may be empty) in the frame `box`.
inline void write_network_svg(std::ostream& os, const network::Network& net,
                              const std::vector<network::Polygon>& cells, const network::Box& box,
                              const std::vector<char>& highlight = {}, double width = 1000.0) {
    const double W0 = box.xmax - box.xmin, H0 = box.ymax - box.ymin;
    const double margin = 0.03 * std::max(W0, H0);
    const double x0 = box.xmin - margin, ytop = box.ymax + margin;
    const double W = W0 + 2 * margin, H = H0 + 2 * margin;
    const double extent = std::max(W, H);
    std::string s;
    const auto num = [&](double v) { detail::append_num(s, v); };
    const auto pt = [&](const Vec2& p) {
        num(p.x() - x0);
        s += ' ';
        num(ytop - p.y());
    };
    detail::open_svg(s, W >= H ? width : width * W / H, W >= H ? width * H / W : width, W, H);
    s += "<title>dvoronoi network: " + std::to_string(net.size()) + " nodes, " +
         std::to_string(net.link_count()) + " links</title>\n";
    s += "<g class=\"cells\" stroke=\"#333333\" stroke-width=\"";
    num(1.5e-3 * extent);
    s += "\">\n";
    for (std::size_t i = 0; i < cells.size(); ++i) {
        if (cells[i].vertices.empty()) continue;
        s += "<path fill=\"";
        s += detail::light_colour(i % 12);
        s += "\" d=\"M";
        for (std::size_t k = 0; k < cells[i].vertices.size(); ++k) {
            if (k) s += " L";
            pt(cells[i].vertices[k]);
        }
        s += " Z\"/>\n";
    }
    s += "</g>\n<g class=\"links\" stroke=\"#999999\" stroke-width=\"";
    num(1e-3 * extent);
    s += "\">\n";
    for (Index i = 0; i < net.size(); ++i)
        for (Index j : net.adj[static_cast<std::size_t>(i)]) {
            if (j < i) continue;
            s += "<path d=\"M";
            pt(net.pos(i));
            s += " L";
            pt(net.pos(j));
            s += "\"/>\n";
        }
    s += "</g>\n<g class=\"obstacles\" stroke=\"#d62728\" stroke-width=\"";
    num(4e-3 * extent);
    s += "\">\n";
    for (const auto& o : net.obstacles) {
        s += "<path d=\"M";
        pt(o.a);
        s += " L";
        pt(o.b);
        s += "\"/>\n";
    }
    s += "</g>\n<g class=\"nodes\" fill=\"#000000\">\n";
    for (Index i = 0; i < net.size(); ++i) {
        s += "<circle cx=\"";
        num(net.pos(i).x() - x0);
        s += "\" cy=\"";
        num(ytop - net.pos(i).y());
        s += "\" r=\"";
        num(4e-3 * extent);
        s += "\"";
        if (!highlight.empty() && highlight[static_cast<std::size_t>(i)]) {
            s += " stroke=\"#d62728\" stroke-width=\"";
            num(2e-3 * extent);
            s += "\"";
        }
        s += "/>\n";
    }
    s += "</g>\n</svg>\n";
    os << s;
}

}  // namespace dvoronoi::io
