// Export of exact Voronoi cells (VoronoiPartition): JSON, GeoJSON, CSV and SVG, the formats of the
// limited cells with the same field names where they mean the same.
//
// JSON (keys as Python's VoronoiPartition.to_json writes them):
//   {"kind": "voronoi_partition", "inner": "scan"|"evt", "bounds": [[x, y], ...] | null,
//    "points": [[x, y], ...], "indptr": [...], "indices": [...], "on_hull": [bool, ...],
//    "radius_steps": [...], "agents_used": [...], "areas": [a | null, ...],
//    "centroids": [[x, y] | null, ...]}
// areas/centroids measure the cells clipped to `bounds`, or the bounded cells when there are no
// bounds (null for hull agents: their cells are unbounded and never given an invented boundary).
// GeoJSON: one Feature per agent, a Polygon (closed, counter-clockwise) of the clipped or bounded
// cell, null geometry for an unbounded cell without bounds; properties agent, on_hull, area, neighbors.
// CSV: agent,x,y,on_hull,area,centroid_x,centroid_y,radius_steps,agents_used,neighbors.
// SVG: the clipped (or bounded) cells, hull agents' rays up to the picture's edge, agents as dots
// (hull agents circled).
#pragma once

#include "dvoronoi/io/csv.hpp"
#include "dvoronoi/io/json.hpp"
#include "dvoronoi/io/svg.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace dvoronoi::io {

namespace detail {

inline const char* inner_name(AsrInner inner) {
    return inner == AsrInner::Evt ? "evt" : inner == AsrInner::Scan ? "scan" : "auto";
}

/// The polygon drawn and exported for a cell: the clipped cell, or the bounded cell; empty for an
/// unbounded cell without bounds (or a cell that misses the region).
inline std::vector<Vec2> cell_polygon(const VoronoiCell& c) {
    if (c.is_clipped) return c.clipped.vertices;
    std::vector<Vec2> out;
    if (!c.on_hull)
        for (const VoronoiEdge& e : c.edges) out.push_back(e.start);
    return out;
}

template <class Rows>
void write_index_list(JsonText& w, const Rows& v) {
    w.raw('[');
    for (std::size_t k = 0; k < v.size(); ++k) {
        if (k) w.raw(',');
        w.num(static_cast<Index>(v[k]));
    }
    w.raw(']');
}

}  // namespace detail

/// The partition's JSON (schema above), compact, no trailing newline. Streams.
inline void write_json(std::ostream& os, const VoronoiPartition& p, AsrInner inner) {
    detail::JsonText w(&os);
    const Index n = p.size();
    w.raw('{');
    w.key("kind");
    w.str("voronoi_partition");
    w.raw(',');
    w.key("inner");
    w.str(detail::inner_name(inner));
    w.raw(',');
    w.key("bounds");
    if (p.bounds.empty()) {
        w.raw("null");
    } else {
        w.raw('[');
        for (std::size_t k = 0; k < p.bounds.vertices().size(); ++k) {
            if (k) w.raw(',');
            w.xy(p.bounds.vertices()[k]);
        }
        w.raw(']');
    }
    w.raw(',');
    w.key("points");
    w.raw('[');
    for (Index i = 0; i < n; ++i) {
        if (i) w.raw(',');
        w.xy(p.points(i, 0), p.points(i, 1));
        w.maybe_flush();
    }
    w.raw("],");
    w.key("indptr");
    detail::write_index_list(w, p.indptr);
    w.raw(',');
    w.key("indices");
    detail::write_index_list(w, p.indices);
    w.raw(',');
    w.key("on_hull");
    w.raw('[');
    for (Index i = 0; i < n; ++i) {
        if (i) w.raw(',');
        w.raw(p.on_hull[static_cast<std::size_t>(i)] ? "true" : "false");
    }
    w.raw("],");
    w.key("radius_steps");
    detail::write_index_list(w, p.radius_steps);
    w.raw(',');
    w.key("agents_used");
    detail::write_index_list(w, p.agents_used);
    w.raw(',');
    w.key("areas");
    w.raw('[');
    for (Index i = 0; i < n; ++i) {
        if (i) w.raw(',');
        w.num(p.areas[static_cast<std::size_t>(i)]);  // NaN -> null
    }
    w.raw("],");
    w.key("centroids");
    w.raw('[');
    for (Index i = 0; i < n; ++i) {
        if (i) w.raw(',');
        if (std::isnan(p.centroids(i, 0)))
            w.raw("null");
        else
            w.xy(p.centroids(i, 0), p.centroids(i, 1));
        w.maybe_flush();
    }
    w.raw("]}");
    w.flush();
}

/// The cells as a GeoJSON FeatureCollection (see the top of this header), no trailing newline.
inline void write_geojson(std::ostream& os, const VoronoiPartition& p) {
    detail::JsonText w(&os);
    w.raw("{\"type\":\"FeatureCollection\",\"features\":[");
    for (Index i = 0; i < p.size(); ++i) {
        if (i) w.raw(',');
        w.raw("{\"type\":\"Feature\",\"geometry\":");
        const std::vector<Vec2> poly = detail::cell_polygon(p.cell(i));
        if (poly.size() < 3) {
            w.raw("null");
        } else {
            w.raw("{\"type\":\"Polygon\",\"coordinates\":[[");
            for (std::size_t k = 0; k <= poly.size(); ++k) {
                if (k) w.raw(',');
                w.xy(poly[k % poly.size()]);
            }
            w.raw("]]}");
        }
        const auto ii = static_cast<std::size_t>(i);
        w.raw(",\"properties\":{");
        w.key("agent");
        w.num(i);
        w.raw(',');
        w.key("on_hull");
        w.raw(p.on_hull[ii] ? "true" : "false");
        w.raw(',');
        w.key("area");
        w.num(p.areas[ii]);
        w.raw(',');
        w.key("neighbors");
        const auto [b, e] = p.neighbors(i);
        detail::write_index_list(w, std::vector<Index>(b, e));
        w.raw("}}");
        w.maybe_flush();
    }
    w.raw("]}");
    w.flush();
}

/// The per-agent CSV (header plus one line per agent).
inline void write_csv(std::ostream& os, const VoronoiPartition& p) {
    os << "agent,x,y,on_hull,area,centroid_x,centroid_y,radius_steps,agents_used,neighbors\n";
    std::string row;
    for (Index i = 0; i < p.size(); ++i) {
        const auto ii = static_cast<std::size_t>(i);
        row.clear();
        row += std::to_string(i);
        for (const double v : {p.points(i, 0), p.points(i, 1)}) {
            row += ',';
            detail::append_double(row, v);
        }
        row += p.on_hull[ii] ? ",1" : ",0";
        for (const double v : {p.areas[ii], p.centroids(i, 0), p.centroids(i, 1)}) {
            row += ',';
            if (!std::isnan(v)) detail::append_double(row, v);  // empty field: not measured
        }
        row += ',' + std::to_string(p.radius_steps[ii]) + ',' + std::to_string(p.agents_used[ii]) + ',';
        for (Index k = p.indptr[ii]; k < p.indptr[ii + 1]; ++k) {
            if (k > p.indptr[ii]) row += ' ';
            row += std::to_string(p.indices[static_cast<std::size_t>(k)]);
        }
        row += '\n';
        os << row;
    }
}

/// An SVG picture of the cells. The view is the bounds' box, else the agents' box with a margin.
inline void write_svg(std::ostream& os, const VoronoiPartition& p, const SvgOptions& opt = {}) {
    const Index n = p.size();
    double minx = 0, maxx = 1, miny = 0, maxy = 1;
    if (!p.bounds.empty()) {
        minx = maxx = p.bounds.vertices()[0].x();
        miny = maxy = p.bounds.vertices()[0].y();
        for (const Vec2& v : p.bounds.vertices()) {
            minx = std::min(minx, v.x());
            maxx = std::max(maxx, v.x());
            miny = std::min(miny, v.y());
            maxy = std::max(maxy, v.y());
        }
    } else if (n > 0) {
        minx = p.points.col(0).minCoeff();
        maxx = p.points.col(0).maxCoeff();
        miny = p.points.col(1).minCoeff();
        maxy = p.points.col(1).maxCoeff();
    }
    const double extent0 = std::max({maxx - minx, maxy - miny, 1e-300});
    const double margin = (p.bounds.empty() ? 0.08 : 0.02) * extent0;
    const double x0 = minx - margin, ytop = maxy + margin;
    const double W = maxx - minx + 2 * margin, H = maxy - miny + 2 * margin;
    const double extent = std::max(W, H);
    const double stroke = 1.2e-3 * extent;
    const double dot = std::min(4e-3 * extent, 0.25 * extent / std::sqrt(static_cast<double>(std::max<Index>(n, 1))));
    const double px_w = W >= H ? opt.width : opt.width * W / H;
    const double px_h = W >= H ? opt.width * H / W : opt.width;

    std::string s;
    const auto put = [&](std::string& out, const Vec2& v) {
        detail::append_num(out, v.x() - x0);
        out += ' ';
        detail::append_num(out, ytop - v.y());
    };
    const auto pt = [&](const Vec2& v) { put(s, v); };
    detail::open_svg(s, px_w, px_h, W, H);
    s += "<title>dvoronoi: exact Voronoi cells of " + std::to_string(n) + " agents" +
         (p.bounds.empty() ? std::string(" (hull agents' cells are unbounded: rays)") : std::string(", clipped")) +
         "</title>\n<g class=\"cells\" stroke=\"#333333\" stroke-width=\"";
    detail::append_num(s, stroke);
    s += "\" stroke-linejoin=\"round\">\n";
    os << s;
    const std::vector<std::size_t> colour = detail::colour_cells(p);
    std::string rays;
    for (Index i = 0; i < n; ++i) {
        s.clear();
        const VoronoiCell c = p.cell(i);
        const std::vector<Vec2> poly = detail::cell_polygon(c);
        if (c.on_hull && !c.is_clipped) {
            // Unbounded: the chain of edges, rays drawn out past the picture's edge.
            const double reach = 2.0 * extent;
            rays += "<path d=\"M ";
            for (std::size_t k = 0; k < c.edges.size(); ++k) {
                const VoronoiEdge& e = c.edges[k];
                const Vec2 a = e.from_infinity ? Vec2(e.start - reach * e.direction) : e.start;
                const Vec2 b = e.to_infinity ? Vec2(e.end + reach * e.direction) : e.end;
                if (k == 0) put(rays, a);
                rays += " L ";
                put(rays, b);
            }
            rays += "\"/>\n";
        }
        if (poly.size() < 3) continue;
        s += "<path id=\"cell-" + std::to_string(i) + "\" fill=\"";
        s += detail::light_colour(colour[static_cast<std::size_t>(i)]);
        s += "\" d=\"M ";
        pt(poly[0]);
        for (std::size_t k = 1; k < poly.size(); ++k) {
            s += " L ";
            pt(poly[k]);
        }
        s += " Z\"><title>agent " + std::to_string(i) + "</title></path>\n";
        os << s;
    }
    os << "</g>\n";
    if (!rays.empty()) {
        os << "<g class=\"rays\" fill=\"none\" stroke=\"#333333\" stroke-width=\"";
        s.clear();
        detail::append_num(s, stroke);
        os << s << "\">\n" << rays << "</g>\n";
    }
    if (!p.bounds.empty()) {
        s.clear();
        s += "<path class=\"bounds\" fill=\"none\" stroke=\"#000000\" stroke-width=\"";
        detail::append_num(s, 2 * stroke);
        s += "\" d=\"M ";
        const auto& bv = p.bounds.vertices();
        pt(bv[0]);
        for (std::size_t k = 1; k < bv.size(); ++k) {
            s += " L ";
            pt(bv[k]);
        }
        s += " Z\"/>\n";
        os << s;
    }
    if (opt.dots && n > 0) {
        s.clear();
        s += "<g class=\"agents\" fill=\"#000000\">\n";
        for (Index i = 0; i < n; ++i) {
            s += "<circle cx=\"";
            detail::append_num(s, p.points(i, 0) - x0);
            s += "\" cy=\"";
            detail::append_num(s, ytop - p.points(i, 1));
            s += "\" r=\"";
            detail::append_num(s, dot);
            s += p.on_hull[static_cast<std::size_t>(i)] ? "\" stroke=\"#d62728\" fill-opacity=\"0.4\"/>\n" : "\"/>\n";
            if (s.size() > (1u << 16)) {
                os << s;
                s.clear();
            }
        }
        s += "</g>\n";
        os << s;
    }
    os << "</svg>\n";
}

}  // namespace dvoronoi::io
