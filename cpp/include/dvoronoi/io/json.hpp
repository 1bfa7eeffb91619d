// The JSON form of results: one schema shared by the CLI (`dvoronoi cells`) and Python
// (`LimitedPartition.to_json()` binds exactly these functions), so both write the same document.
//
// Limited partition (keys in nlohmann::json's order, which is alphabetical):
//
//   {"kind": "limited_partition", "method": "scan" | "chords", "radius": R,
//    "points": [[x, y], ...],                  agents in input order
//    "indptr": [...], "indices": [...],        limited neighbours, CSR (scipy's layout), ascending
//    "areas": [...], "perimeters": [...], "centroids": [[x, y], ...],
//    "cells": [{"agent": i, "pieces": [piece, ...]}, ...]}
//
// A piece is one step of the cell's counter-clockwise boundary cycle:
//
//   {"type": "edge", "neighbor": j, "start": [x, y], "end": [x, y]}
//   {"type": "arc", "start": [x, y], "end": [x, y], "center": [x, y], "radius": R, "span": phi}
//
// `span` is the counter-clockwise angle swept, in (0, 2 pi]; a full disk is one arc with
// start == end and span == 2 pi. Doubles are written with the shortest text that reads back to the
// same double (nlohmann's dump), so the JSON round-trips exactly.
#pragma once

#include "dvoronoi/partition/limited_partition.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <functional>
#include <map>
#include <ostream>
#include <sstream>
#include <string>

namespace dvoronoi::io {

namespace detail {

using json = nlohmann::json;

inline json xy(const Vec2& v) { return json::array({v.x(), v.y()}); }
inline json xy(double x, double y) { return json::array({x, y}); }

inline json piece_json(const Vec2& start, const Vec2& end, Index neighbor, double span,
                       const Vec2& center, double radius) {
    json p = json::object();
    if (neighbor >= 0) {
        p["type"] = "edge";
        p["neighbor"] = neighbor;
        p["start"] = xy(start);
        p["end"] = xy(end);
    } else {
        p["type"] = "arc";
        p["start"] = xy(start);
        p["end"] = xy(end);
        p["center"] = xy(center);
        p["radius"] = radius;
        p["span"] = span;
    }
    return p;
}

inline json pieces_json(const LimitedCell& c) {
    json out = json::array();
    for (std::size_t k = 0; k < c.pieces.size(); ++k) {
        const Piece& p = c.pieces[k];
        out.push_back(piece_json(p.start, c.piece_end(k), p.neighbor, p.arc_span, c.center, c.radius));
    }
    return out;
}

/// Agent i's entry of "cells", read straight from the partition's flat arrays.
inline json partition_cell_json(const LimitedPartition& p, Index i) {
    json pieces = json::array();
    const Index lo = p.piece_ptr[static_cast<std::size_t>(i)];
    const Index hi = p.piece_ptr[static_cast<std::size_t>(i) + 1];
    const Vec2 center = p.points.row(i).transpose();
    for (Index k = lo; k < hi; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const auto next = static_cast<std::size_t>(k + 1 < hi ? k + 1 : lo);
        pieces.push_back(piece_json(Vec2(p.piece_x[kk], p.piece_y[kk]),
                                    Vec2(p.piece_x[next], p.piece_y[next]), p.piece_neighbor[kk],
                                    p.piece_span[kk], center, p.radius));
    }
    json c = json::object();
    c["agent"] = i;
    c["pieces"] = std::move(pieces);
    return c;
}

/// Writes the elements 0..count-1 of a JSON array as `dump()` would, building only a block of
/// elements at a time (memory O(block) instead of O(count)).
inline void stream_array(std::ostream& os, Index count, const std::function<json(Index)>& element,
                         Index block = 2048) {
    os << '[';
    for (Index lo = 0; lo < count; lo += block) {
        const Index hi = std::min(count, lo + block);
        json chunk = json::array();
        for (Index k = lo; k < hi; ++k) chunk.push_back(element(k));
        const std::string text = chunk.dump();
        if (lo > 0) os << ',';
        os.write(text.data() + 1, static_cast<std::streamsize>(text.size() - 2));  // strip [ ]
    }
    os << ']';
}

/// Writes a JSON object whose small members are in `small` and whose large arrays are produced by
/// `large` (name -> (count, element)); key order is nlohmann::json's, so the text equals dump().
struct LargeArray {
    Index count;
    std::function<json(Index)> element;
};

inline void stream_object(std::ostream& os, json small, const std::map<std::string, LargeArray>& large) {
    for (const auto& kv : large) small[kv.first] = json::array();  // placeholders fix the key order
    os << '{';
    bool first = true;
    for (auto it = small.begin(); it != small.end(); ++it) {
        if (!first) os << ',';
        first = false;
        os << json(it.key()).dump() << ':';
        const auto big = large.find(it.key());
        if (big != large.end())
            stream_array(os, big->second.count, big->second.element);
        else
            os << it.value().dump();
    }
    os << '}';
}

}  // namespace detail

/// One cell as JSON: {"kind": "limited_cell", "center", "radius", "area", "centroid", "perimeter",
/// "neighbors" (ascending), "pieces" (as in the partition schema)}.
inline nlohmann::json to_json(const LimitedCell& cell) {
    using detail::json;
    const CellMeasures m = cell.measures();
    json j = json::object();
    j["kind"] = "limited_cell";
    j["center"] = detail::xy(cell.center);
    j["radius"] = cell.radius;
    j["area"] = m.area;
    j["centroid"] = detail::xy(m.centroid);
    j["perimeter"] = m.perimeter;
    j["neighbors"] = cell.neighbors();
    j["pieces"] = detail::pieces_json(cell);
    return j;
}

namespace detail {

inline json partition_header(const LimitedPartition& p, Method method) {
    json j = json::object();
    j["kind"] = "limited_partition";
    j["method"] = method_name(method);
    j["radius"] = p.radius;
    return j;
}

inline std::map<std::string, LargeArray> partition_arrays(const LimitedPartition& p) {
    std::map<std::string, LargeArray> large;
    const auto ints = [](const std::vector<Index>& v) {
        return LargeArray{static_cast<Index>(v.size()),
                          [&v](Index k) { return json(v[static_cast<std::size_t>(k)]); }};
    };
    const auto reals = [](const std::vector<double>& v) {
        return LargeArray{static_cast<Index>(v.size()),
                          [&v](Index k) { return json(v[static_cast<std::size_t>(k)]); }};
    };
    large["indptr"] = ints(p.indptr);
    large["indices"] = ints(p.indices);
    large["areas"] = reals(p.areas);
    large["perimeters"] = reals(p.perimeters);
    large["points"] = {p.size(), [&p](Index i) { return xy(p.points(i, 0), p.points(i, 1)); }};
    large["centroids"] = {p.size(), [&p](Index i) { return xy(p.centroids(i, 0), p.centroids(i, 1)); }};
    large["cells"] = {p.size(), [&p](Index i) { return partition_cell_json(p, i); }};
    return large;
}

}  // namespace detail

/// The whole partition as JSON (the schema at the top of this header).
/// \note Builds the document in memory (roughly 1 kB per agent); for large partitions prefer
///       write_json, which streams the same text. Thread-safe.
inline nlohmann::json to_json(const LimitedPartition& p, Method method) {
    using detail::json;
    json j = detail::partition_header(p, method);
    for (const auto& kv : detail::partition_arrays(p)) {
        json arr = json::array();
        for (Index i = 0; i < kv.second.count; ++i) arr.push_back(kv.second.element(i));
        j[kv.first] = std::move(arr);
    }
    return j;
}

/// Writes `to_json(p, method).dump()` to `os` without building the whole document (memory
/// O(block of cells)). No trailing newline.
inline void write_json(std::ostream& os, const LimitedPartition& p, Method method) {
    detail::stream_object(os, detail::partition_header(p, method), detail::partition_arrays(p));
}

/// The compact JSON text of the partition (equal to `to_json(p, method).dump()`).
inline std::string to_json_string(const LimitedPartition& p, Method method) {
    std::ostringstream os;
    write_json(os, p, method);
    return os.str();
}

}  // namespace dvoronoi::io
