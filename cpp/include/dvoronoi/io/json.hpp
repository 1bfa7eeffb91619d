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
//   heterogeneous teams add "radii": [...] (one per agent; "radius" is then the largest, and an
//   empty cell has no pieces).
//
// A piece is one step of the cell's counter-clockwise boundary cycle:
//
//   {"type": "edge", "neighbor": j, "start": [x, y], "end": [x, y]}
//   {"type": "arc", "start": [x, y], "end": [x, y], "center": [x, y], "radius": R, "span": phi}
//
// `span` is the counter-clockwise angle swept, in (0, 2 pi]; a full disk is one arc with
// start == end and span == 2 pi. Doubles are written with the shortest text that reads back to the
// same double (nlohmann's Grisu2, exactly as `nlohmann::json::dump` writes them), so the JSON
// round-trips exactly.
//
// One implementation: the text is written directly (write_json, streaming, O(1) extra memory per
// cell); to_json parses that text, so `to_json(p, m).dump() == to_json_string(p, m)` byte for byte.
#pragma once

#include "dvoronoi/partition/limited_partition.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <ostream>
#include <sstream>
#include <string>

namespace dvoronoi::io {

namespace detail {

/// A buffer of JSON text, flushed to a stream in large blocks.
class JsonText {
public:
    explicit JsonText(std::ostream* os = nullptr) : os_(os) { s_.reserve(kFlush + 4096); }

    /// A double exactly as nlohmann::json::dump writes it ("null" for NaN/inf, "1.0" for 1).
    void num(double x) {
        if (!std::isfinite(x)) {
            s_ += "null";
            return;
        }
#if NLOHMANN_JSON_VERSION_MAJOR == 3 && NLOHMANN_JSON_VERSION_MINOR >= 1
        char buf[64];
        char* end = ::nlohmann::detail::to_chars(buf, buf + sizeof buf, x);
        s_.append(buf, end);
#else
        s_ += nlohmann::json(x).dump();
#endif
    }
    void num(Index i) {
        char buf[24];
        const auto r = std::to_chars(buf, buf + sizeof buf, i);
        s_.append(buf, r.ptr);
    }
    /// `"name":` (names are plain ASCII, no escaping needed).
    void key(const char* name) {
        s_ += '"';
        s_ += name;
        s_ += "\":";
    }
    void str(const char* value) {
        s_ += '"';
        s_ += value;
        s_ += '"';
    }
    void xy(double x, double y) {
        s_ += '[';
        num(x);
        s_ += ',';
        num(y);
        s_ += ']';
    }
    void xy(const Vec2& v) { xy(v.x(), v.y()); }
    void raw(char ch) { s_ += ch; }
    void raw(const char* text) { s_ += text; }

    /// Writes the buffer to the stream when it is large (call between elements).
    void maybe_flush() {
        if (os_ && s_.size() >= kFlush) flush();
    }
    void flush() {
        if (!os_) return;
        os_->write(s_.data(), static_cast<std::streamsize>(s_.size()));
        s_.clear();
    }
    const std::string& text() const noexcept { return s_; }
    std::string take() { return std::move(s_); }

private:
    static constexpr std::size_t kFlush = std::size_t{1} << 16;
    std::ostream* os_;
    std::string s_;
};

/// One piece, keys in alphabetical order.
inline void write_piece(JsonText& w, const Vec2& start, const Vec2& end, Index neighbor, double span,
                        const Vec2& center, double radius) {
    if (neighbor >= 0) {
        w.raw('{');
        w.key("end");
        w.xy(end);
        w.raw(',');
        w.key("neighbor");
        w.num(neighbor);
        w.raw(',');
        w.key("start");
        w.xy(start);
        w.raw(",\"type\":\"edge\"}");
    } else {
        w.raw('{');
        w.key("center");
        w.xy(center);
        w.raw(',');
        w.key("end");
        w.xy(end);
        w.raw(',');
        w.key("radius");
        w.num(radius);
        w.raw(',');
        w.key("span");
        w.num(span);
        w.raw(',');
        w.key("start");
        w.xy(start);
        w.raw(",\"type\":\"arc\"}");
    }
}

inline void write_pieces(JsonText& w, const LimitedCell& c) {
    w.raw('[');
    for (std::size_t k = 0; k < c.pieces.size(); ++k) {
        if (k) w.raw(',');
        const Piece& p = c.pieces[k];
        write_piece(w, p.start, c.piece_end(k), p.neighbor, p.arc_span, c.center, c.radius);
    }
    w.raw(']');
}

/// Agent i's entry of "cells", read straight from the partition's flat arrays.
inline void write_partition_cell(JsonText& w, const LimitedPartition& p, Index i) {
    const Index lo = p.piece_ptr[static_cast<std::size_t>(i)];
    const Index hi = p.piece_ptr[static_cast<std::size_t>(i) + 1];
    const Vec2 center = p.points.row(i).transpose();
    w.raw('{');
    w.key("agent");
    w.num(i);
    w.raw(",\"pieces\":[");
    for (Index k = lo; k < hi; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const auto next = static_cast<std::size_t>(k + 1 < hi ? k + 1 : lo);
        if (k > lo) w.raw(',');
        write_piece(w, Vec2(p.piece_x[kk], p.piece_y[kk]), Vec2(p.piece_x[next], p.piece_y[next]),
                    p.piece_neighbor[kk], p.piece_span[kk], center, p.radius_of(i));
    }
    w.raw("]}");
}

template <class T>
void write_numbers(JsonText& w, const std::vector<T>& v) {
    w.raw('[');
    for (std::size_t k = 0; k < v.size(); ++k) {
        if (k) w.raw(',');
        w.num(v[k]);
        if ((k & 1023) == 0) w.maybe_flush();
    }
    w.raw(']');
}

inline void write_rows(JsonText& w, const Points& m) {
    w.raw('[');
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        if (i) w.raw(',');
        w.xy(m(i, 0), m(i, 1));
        if ((i & 1023) == 0) w.maybe_flush();
    }
    w.raw(']');
}

inline void write_partition(JsonText& w, const LimitedPartition& p, Method method) {
    w.raw('{');
    w.key("areas");
    write_numbers(w, p.areas);
    w.raw(',');
    w.key("cells");
    w.raw('[');
    for (Index i = 0; i < p.size(); ++i) {
        if (i) w.raw(',');
        write_partition_cell(w, p, i);
        w.maybe_flush();
    }
    w.raw("],");
    w.key("centroids");
    write_rows(w, p.centroids);
    w.raw(',');
    w.key("indices");
    write_numbers(w, p.indices);
    w.raw(',');
    w.key("indptr");
    write_numbers(w, p.indptr);
    w.raw(",\"kind\":\"limited_partition\",");
    w.key("method");
    w.str(method_name(method));
    w.raw(',');
    w.key("perimeters");
    write_numbers(w, p.perimeters);
    w.raw(',');
    w.key("points");
    write_rows(w, p.points);
    w.raw(',');
    if (!p.radii.empty()) {  // heterogeneous teams: one radius per agent ("radius" is the largest)
        w.key("radii");
        write_numbers(w, p.radii);
        w.raw(',');
    }
    w.key("radius");
    w.num(p.radius);
    w.raw('}');
}

}  // namespace detail

/// Writes the partition's JSON (the schema at the top of this header), compact, no trailing newline.
/// \note Streams: memory O(1) beyond the partition. Thread-safe. The stream's state is the caller's
///       to check.
inline void write_json(std::ostream& os, const LimitedPartition& p, Method method) {
    detail::JsonText w(&os);
    detail::write_partition(w, p, method);
    w.flush();
}

/// The compact JSON text of the partition.
inline std::string to_json_string(const LimitedPartition& p, Method method) {
    detail::JsonText w;
    detail::write_partition(w, p, method);
    return w.take();
}

/// The partition as a JSON document (parsed from to_json_string, so `dump()` gives the same text).
/// \note Holds the whole document in memory (about 1 kB per agent); prefer write_json for files.
inline nlohmann::json to_json(const LimitedPartition& p, Method method) {
    return nlohmann::json::parse(to_json_string(p, method));
}

/// The JSON text of one cell: {"area", "center", "centroid", "kind": "limited_cell", "neighbors"
/// (ascending), "perimeter", "pieces" (as in the partition schema), "radius"}.
inline std::string to_json_string(const LimitedCell& cell) {
    const CellMeasures m = cell.measures();
    detail::JsonText w;
    w.raw('{');
    w.key("area");
    w.num(m.area);
    w.raw(',');
    w.key("center");
    w.xy(cell.center);
    w.raw(',');
    w.key("centroid");
    w.xy(m.centroid);
    w.raw(",\"kind\":\"limited_cell\",");
    w.key("neighbors");
    detail::write_numbers(w, cell.neighbors());
    w.raw(',');
    w.key("perimeter");
    w.num(m.perimeter);
    w.raw(',');
    w.key("pieces");
    detail::write_pieces(w, cell);
    w.raw(',');
    w.key("radius");
    w.num(cell.radius);
    w.raw('}');
    return w.take();
}

/// One cell as a JSON document (see to_json_string(const LimitedCell&)).
inline nlohmann::json to_json(const LimitedCell& cell) { return nlohmann::json::parse(to_json_string(cell)); }

}  // namespace dvoronoi::io
