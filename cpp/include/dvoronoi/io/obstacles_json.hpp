// The JSON obstacle format of the grid Voronoi diagram, and its schema-checked loader.
//
//   {
//     "area": {"box": [xmin, ymin, xmax, ymax]}          axis-aligned box, or
//             {"polygon": [[x, y], ...]},                 a convex polygon (any orientation)
//     "obstacles": [                                      one label each, in this order (0, 1, ...)
//       {"type": "polygon", "vertices": [[x, y], ...]},   simple polygon, convex or not
//       {"type": "circle", "center": [x, y], "radius": r},
//       {"type": "point", "position": [x, y]},
//       {"type": "segment", "vertices": [[x, y], [x, y]]},
//       {"type": "union", "parts": [shape, ...]},         several shapes sharing one label
//       ...
//     ]
//   }
//
// Every obstacle may also carry "name" (a string, kept for the user, ignored here). Any other key is
// an error, so a typo ("raduis") does not pass silently. The area's edges become labels
// n, n + 1, ... (counter-clockwise from its first vertex; a box starts at (xmin, ymin)).
//
// Errors: a JSON syntax error, a key repeated within one object and a number beyond the range of a
// double name FILE:LINE:COLUMN (io/strict_json.hpp); a schema error names FILE and the JSON path of
// the offending field, e.g. "map.json: obstacles[3].radius: must be a positive finite number, got -1".
// The same loader serves the CLI, the MPI executable and Python (dv.grid_voronoi passes its obstacle
// list here as JSON text), so there is one schema and one set of messages.
#pragma once

#include "dvoronoi/gvd/obstacles.hpp"
#include "dvoronoi/io/quote.hpp"
#include "dvoronoi/io/strict_json.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace dvoronoi::io {

/// A parsed obstacle file.
struct ObstacleFile {
    std::vector<gvd::Obstacle> obstacles;
    std::vector<Vec2> area;
    bool area_is_box = false;
    std::vector<std::string> names;  ///< per obstacle ("" when absent)
    gvd::Scene scene;                ///< compiled (convex parts, area edges)
};

namespace detail {

using nlohmann::json;

inline std::string type_name(const json& j) { return j.type_name(); }

inline double number(const json& j, const std::string& path) {
    if (!j.is_number()) throw InputError(path + ": expected a number, got " + type_name(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) throw InputError(path + ": must be finite");
    return v;
}

/// A point [x, y]; `path` and `at` name it in messages ("path[at]", or "path" when at < 0). The
/// name is built only for a message: a map has thousands of points.
inline Vec2 point(const json& j, const std::string& path, std::ptrdiff_t at = -1) {
    const auto name = [&] { return at < 0 ? path : path + "[" + std::to_string(at) + "]"; };
    if (!j.is_array() || j.size() != 2) throw InputError(name() + ": expected a point [x, y], got " + (j.is_array() ? "an array of " + std::to_string(j.size()) : type_name(j)));
    double v[2];
    for (std::size_t k = 0; k < 2; ++k) {
        const json& c = j[k];
        v[k] = c.is_number() ? c.get<double>() : 0.0;
        if (!c.is_number() || !std::isfinite(v[k])) number(c, name() + "[" + std::to_string(k) + "]");  // throws
    }
    return Vec2(v[0], v[1]);
}

inline std::vector<Vec2> points(const json& j, const std::string& path, std::size_t at_least) {
    if (!j.is_array()) throw InputError(path + ": expected an array of points [[x, y], ...], got " + type_name(j));
    if (j.size() < at_least) throw InputError(path + ": needs at least " + std::to_string(at_least) + " points, got " + std::to_string(j.size()));
    std::vector<Vec2> out;
    out.reserve(j.size());
    for (std::size_t k = 0; k < j.size(); ++k) out.push_back(point(j[k], path, static_cast<std::ptrdiff_t>(k)));
    return out;
}

inline void only_keys(const json& j, const std::string& path, const std::set<std::string>& allowed) {
    for (auto it = j.begin(); it != j.end(); ++it)
        if (!allowed.count(it.key())) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            throw InputError(path + ": unknown field " + in_quotes(it.key()) + " (expected " + list + ")");
        }
}

inline const json& field(const json& j, const std::string& path, const char* key) {
    auto it = j.find(key);
    if (it == j.end()) throw InputError(path + ": missing field '" + key + "'");
    return *it;
}

inline gvd::Shape shape(const json& j, const std::string& path, bool allow_union, std::vector<gvd::Shape>* parts) {
    if (!j.is_object()) throw InputError(path + ": expected an object {\"type\": ...}, got " + type_name(j));
    const json& t = field(j, path, "type");
    if (!t.is_string()) throw InputError(path + ".type: expected a string");
    const std::string type = t.get<std::string>();
    if (type == "polygon") {
        only_keys(j, path, {"type", "vertices", "name"});
        return gvd::Shape::polygon(points(field(j, path, "vertices"), path + ".vertices", 3));
    }
    if (type == "circle") {
        only_keys(j, path, {"type", "center", "radius", "name"});
        const Vec2 c = point(field(j, path, "center"), path + ".center");
        const json& r = field(j, path, "radius");
        const double rv = number(r, path + ".radius");
        if (!(rv > 0.0)) {
            std::ostringstream s;
            s << rv;
            throw InputError(path + ".radius: must be a positive finite number, got " + s.str());
        }
        return gvd::Shape::circle(c, rv);
    }
    if (type == "point") {
        only_keys(j, path, {"type", "position", "name"});
        return gvd::Shape::point(point(field(j, path, "position"), path + ".position"));
    }
    if (type == "segment") {
        only_keys(j, path, {"type", "vertices", "name"});
        const auto v = points(field(j, path, "vertices"), path + ".vertices", 2);
        if (v.size() != 2) throw InputError(path + ".vertices: a segment has exactly 2 points, got " + std::to_string(v.size()));
        return gvd::Shape::segment(v[0], v[1]);
    }
    if (type == "union" && allow_union) {
        only_keys(j, path, {"type", "parts", "name"});
        const json& p = field(j, path, "parts");
        if (!p.is_array() || p.empty()) throw InputError(path + ".parts: expected a non-empty array of shapes");
        for (std::size_t k = 0; k < p.size(); ++k)
            parts->push_back(shape(p[k], path + ".parts[" + std::to_string(k) + "]", false, nullptr));
        return gvd::Shape{};
    }
    throw InputError(path + ".type: unknown obstacle type " + in_quotes(type) + " (expected polygon, circle, point, segment" +
                     (allow_union ? ", union)" : ")"));
}

}  // namespace detail

inline ObstacleFile obstacles_from_json(const nlohmann::json& doc, const std::string& name);

/// Parses obstacle JSON text. `name` prefixes every message (a file name, or "obstacles").
/// \throws InputError as described above; also for a key repeated within an object or a number
///         beyond the range of a double, naming FILE:LINE:COLUMN (io/strict_json.hpp).
inline ObstacleFile parse_obstacles(const std::string& text, const std::string& name) {
    return obstacles_from_json(parse_json(text, name), name);
}

/// The same from a parsed document (e.g. converted from Python objects without a text round trip).
inline ObstacleFile obstacles_from_json(const nlohmann::json& doc, const std::string& name) {
    using nlohmann::json;
    ObstacleFile out;
    try {
        if (!doc.is_object()) throw InputError("expected an object {\"area\": ..., \"obstacles\": [...]}");
        detail::only_keys(doc, "top level", {"area", "obstacles"});
        const json& area = detail::field(doc, "top level", "area");
        if (!area.is_object()) throw InputError("area: expected {\"box\": [xmin, ymin, xmax, ymax]} or {\"polygon\": [[x, y], ...]}");
        detail::only_keys(area, "area", {"box", "polygon"});
        if (area.contains("box") == area.contains("polygon"))
            throw InputError("area: give exactly one of 'box' or 'polygon'");
        if (area.contains("box")) {
            const json& b = area["box"];
            if (!b.is_array() || b.size() != 4) throw InputError("area.box: expected [xmin, ymin, xmax, ymax]");
            const double x0 = detail::number(b[0], "area.box[0]"), y0 = detail::number(b[1], "area.box[1]");
            const double x1 = detail::number(b[2], "area.box[2]"), y1 = detail::number(b[3], "area.box[3]");
            if (!(x1 > x0 && y1 > y0)) throw InputError("area.box: xmax must exceed xmin and ymax must exceed ymin");
            out.area = gvd::box_area(x0, y0, x1, y1);
            out.area_is_box = true;
        } else {
            out.area = detail::points(area["polygon"], "area.polygon", 3);
        }
        const json& obs = detail::field(doc, "top level", "obstacles");
        if (!obs.is_array()) throw InputError("obstacles: expected an array");
        for (std::size_t i = 0; i < obs.size(); ++i) {
            const std::string path = "obstacles[" + std::to_string(i) + "]";
            std::vector<gvd::Shape> parts;
            gvd::Shape s = detail::shape(obs[i], path, true, &parts);
            out.obstacles.push_back(parts.empty() ? gvd::Obstacle(std::move(s)) : gvd::Obstacle(std::move(parts)));
            const auto it = obs[i].find("name");
            if (it != obs[i].end() && !it->is_string()) throw InputError(path + ".name: expected a string");
            out.names.push_back(it != obs[i].end() ? it->get<std::string>() : std::string());
        }
        out.scene = gvd::make_scene(out.obstacles, out.area, out.area_is_box);  // geometry checks, same paths
    } catch (const InputError& e) {
        throw InputError(name + ": " + e.what());
    }
    return out;
}

/// Reads and parses an obstacle file. \throws InputError naming the file.
inline ObstacleFile read_obstacles(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_obstacles(s.str(), path);
}

}  // namespace dvoronoi::io
