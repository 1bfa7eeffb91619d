// GeoJSON export of limited cells: a FeatureCollection with one Polygon Feature per agent, in input
// order, properties {"agent": i, "area": exact area, "neighbors": [limited neighbours, ascending]}.
// GeoJSON has no arcs, so each arc is replaced by a polyline whose chords deviate from the circle by at
// most `tolerance` (the sagitta R (1 - cos(theta / 2)) of every chord of angle theta). The ring is
// counter-clockwise (RFC 7946, section 3.1.6) and closed (its last position repeats the first). The
// exact area in the properties is that of the true cell; the polygon's own area is smaller by at most
// (arc length x tolerance).
#pragma once

#include "dvoronoi/io/json.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace dvoronoi::io {

/// The default densification tolerance: 1e-3 of the cell radius.
inline double default_tolerance(double radius) { return 1e-3 * radius; }

namespace detail {

/// Number of chords for an arc of angle `span` on a circle of radius `r` with sagitta <= tol.
inline Index arc_segments(double span, double r, double tol) {
    const double pi = 3.14159265358979323846;
    const double t = std::min(tol / r, 2.0);
    // Largest chord angle with sagitta <= tol, capped so a full circle keeps at least 3 chords.
    const double theta = std::min(2.0 * std::acos(1.0 - t), 2.0 * pi / 3.0);
    const double k = std::ceil(span / theta - 1e-12);
    if (!(k <= 1e7))
        throw InputError("tolerance " + std::to_string(tol) + " is too small: an arc would need " +
                         std::to_string(k) + " chords");
    return std::max<Index>(1, static_cast<Index>(k));
}

inline double check_tolerance(double tolerance, double radius) {
    if (std::isnan(tolerance) || tolerance < 0.0 || std::isinf(tolerance))
        throw InputError("tolerance must be a finite number >= 0 (0 = default 1e-3 * radius), got " +
                         std::to_string(tolerance));
    return tolerance == 0.0 ? default_tolerance(radius) : tolerance;
}

}  // namespace detail

/// The closed counter-clockwise ring approximating a cell: piece start points, plus points on every
/// arc so that each chord's sagitta is <= tolerance (0 = default_tolerance(radius)). Edge endpoints
/// are kept exactly; the last point repeats the first.
/// \throws InputError for a negative or non-finite tolerance.
inline std::vector<Vec2> densify(const LimitedCell& cell, double tolerance = 0.0) {
    const double tol = detail::check_tolerance(tolerance, cell.radius);
    std::vector<Vec2> ring;
    for (std::size_t k = 0; k < cell.pieces.size(); ++k) {
        const Piece& p = cell.pieces[k];
        ring.push_back(p.start);
        if (!p.is_arc()) continue;
        const Index m = detail::arc_segments(p.arc_span, cell.radius, tol);
        const Vec2 u = p.start - cell.center;
        const double a0 = std::atan2(u.y(), u.x());
        for (Index j = 1; j < m; ++j) {
            const double a = a0 + p.arc_span * static_cast<double>(j) / static_cast<double>(m);
            ring.push_back(cell.center + cell.radius * Vec2(std::cos(a), std::sin(a)));
        }
    }
    if (!ring.empty()) ring.push_back(ring.front());
    return ring;
}

namespace detail {

/// One Feature; `agent` < 0 leaves the agent property out.
inline void write_feature(JsonText& w, const LimitedCell& cell, double tolerance, Index agent,
                          double area) {
    const std::vector<Vec2> ring = densify(cell, tolerance);
    // An empty cell (heterogeneous teams) is an empty Polygon (RFC 7946 3.1: empty coordinates).
    w.raw(ring.empty() ? "{\"geometry\":{\"coordinates\":[" : "{\"geometry\":{\"coordinates\":[[");
    bool first = true;
    for (const Vec2& v : ring) {
        if (!first) w.raw(',');
        first = false;
        w.xy(v);
    }
    w.raw(ring.empty() ? "],\"type\":\"Polygon\"},\"properties\":{" : "]],\"type\":\"Polygon\"},\"properties\":{");
    if (agent >= 0) {
        w.key("agent");
        w.num(agent);
        w.raw(',');
    }
    w.key("area");
    w.num(area);
    w.raw(',');
    w.key("neighbors");
    write_numbers(w, cell.neighbors());
    w.raw("},\"type\":\"Feature\"}");
}

inline void write_collection(JsonText& w, const LimitedPartition& p, double tolerance) {
    const double tol = check_tolerance(tolerance, p.radius > 0 ? p.radius : 1.0);
    w.raw("{\"features\":[");
    for (Index i = 0; i < p.size(); ++i) {
        if (i) w.raw(',');
        write_feature(w, p.cell(i), tol, i, p.areas[static_cast<std::size_t>(i)]);
        w.maybe_flush();
    }
    w.raw("],\"type\":\"FeatureCollection\"}");
}

}  // namespace detail

/// Writes the partition as a GeoJSON FeatureCollection (see the top of this header), compact, no
/// trailing newline, streaming.
/// \param tolerance largest sagitta of an arc chord; 0 = default_tolerance(p.radius).
/// \throws InputError for a negative or non-finite tolerance, or one so small that an arc would
///         need more than 1e7 chords.
inline void write_geojson(std::ostream& os, const LimitedPartition& p, double tolerance = 0.0) {
    detail::JsonText w(&os);
    detail::write_collection(w, p, tolerance);
    w.flush();
}

/// The GeoJSON text of the partition.
inline std::string to_geojson_string(const LimitedPartition& p, double tolerance = 0.0) {
    detail::JsonText w;
    detail::write_collection(w, p, tolerance);
    return w.take();
}

/// The partition as a GeoJSON document (parsed from to_geojson_string).
inline nlohmann::json to_geojson(const LimitedPartition& p, double tolerance = 0.0) {
    return nlohmann::json::parse(to_geojson_string(p, tolerance));
}

/// One cell as a GeoJSON Feature (properties: area, neighbors).
inline nlohmann::json to_geojson(const LimitedCell& cell, double tolerance = 0.0) {
    detail::JsonText w;
    detail::write_feature(w, cell, tolerance, -1, cell.measures().area);
    return nlohmann::json::parse(w.take());
}

}  // namespace dvoronoi::io
