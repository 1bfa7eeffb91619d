// Reading measured inter-robot distances from text files (`i j d` per line) and writing the
// distance-only neighbour result as JSON (the same fields as Python's DistanceNeighbors.to_json) or
// CSV. Errors name FILE:LINE:COLUMN.
//
// i and j are robot IDs (serial numbers are normal input): the robots are the IDs that occur, numbered
// 0..n-1 in ascending ID order, and the outputs name them by ID. Memory follows the file, never the
// largest ID. A file whose IDs are exactly 0..n-1 reads and writes as robot indices, as before.
#pragma once

#include "dvoronoi/distances/neighbors_from_distances.hpp"
#include "dvoronoi/io/point_file.hpp"

#include <algorithm>
#include <charconv>
#include <ostream>
#include <string>
#include <vector>

namespace dvoronoi::io {

/// Measurements read from a distance file, with where each came from.
struct DistanceFile {
    std::string name;
    std::vector<Index> rows, cols;
    std::vector<double> values;
    std::vector<std::size_t> line, column;  ///< of each measurement (its first field)

    std::string where(std::size_t k) const {
        return name + ":" + std::to_string(line[k]) + ":" + std::to_string(column[k]);
    }
};

/// Parses `i j d` lines: whitespace- or comma-separated, `#` comments, blank lines, an optional header
/// line (no numeric field). i and j are robot IDs (non-negative integers), d > 0 a finite distance (or
/// squared distance). A pair may appear once or in both directions.
/// \throws InputError "NAME:LINE:COLUMN: ..." for a malformed line or value.
inline DistanceFile parse_distance_text(std::string_view text, const std::string& name) {
    DistanceFile out;
    out.name = name;
    std::vector<detail::Field> fields;
    bool first_content = true;
    std::size_t line_no = 0, pos = 0;
    if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;
    while (pos < text.size()) {
        ++line_no;
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string_view::npos) eol = text.size();
        std::string_view line = text.substr(pos, eol - pos);
        pos = eol + 1;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::size_t hash = line.find('#');
        if (hash != std::string_view::npos) line = line.substr(0, hash);
        detail::split_fields(line, name, line_no, fields);
        if (fields.empty()) continue;
        if (first_content) {
            first_content = false;
            bool any_number = false;
            for (const detail::Field& f : fields) any_number = any_number || detail::is_number_token(f.text);
            if (!any_number) continue;  // header line
        }
        if (fields.size() != 3) {
            const std::size_t col = fields.size() > 3 ? fields[3].col : fields.back().col + fields.back().text.size();
            throw detail::file_error(name, line_no, col,
                                     "expected 3 fields 'i j d' (two robot indices and a distance), found " +
                                         std::to_string(fields.size()));
        }
        Index ij[2];
        for (int t = 0; t < 2; ++t) {
            const detail::Field& f = fields[static_cast<std::size_t>(t)];
            long long v = -1;
            const auto r = std::from_chars(f.text.data(), f.text.data() + f.text.size(), v);
            if (r.ec != std::errc() || r.ptr != f.text.data() + f.text.size() || v < 0)
                throw detail::file_error(name, line_no, f.col,
                                         std::string("robot index ") + (t == 0 ? "i" : "j") + " " + in_quotes(f.text) +
                                             " is not a non-negative integer");
            ij[t] = static_cast<Index>(v);
        }
        const detail::Field& fd = fields[2];
        double d = 0.0;
        switch (detail::parse_number(fd.text, d)) {
            case detail::NumberStatus::Ok: break;
            case detail::NumberStatus::NotFinite:
                throw detail::file_error(name, line_no, fd.col, "distance " + in_quotes(fd.text) +
                                                                    " is not finite (leave undetected pairs out)");
            default: throw detail::file_error(name, line_no, fd.col, "distance " + in_quotes(fd.text) + " is not a number");
        }
        if (!(d > 0.0))
            throw detail::file_error(name, line_no, fd.col, "distance " + in_quotes(fd.text) + " must be positive" +
                                                                (d == 0.0 ? " (coinciding robots have no Voronoi cells)" : ""));
        if (ij[0] == ij[1])
            throw detail::file_error(name, line_no, fields[1].col, "a robot's distance to itself is not a measurement");
        out.rows.push_back(ij[0]);
        out.cols.push_back(ij[1]);
        out.values.push_back(d);
        out.line.push_back(line_no);
        out.column.push_back(fields[0].col);
    }
    return out;
}

/// Reads a distance file ("-" = standard input).
inline DistanceFile read_distance_file(const std::string& path) {
    const std::string name = path == "-" ? "<stdin>" : path;
    return parse_distance_text(read_file_bytes(path), name);
}

/// The robot IDs of a distance file: every ID in it once, ascending (robot k is ids[k]). O(m log m).
inline std::vector<Index> robot_ids(const DistanceFile& f) {
    std::vector<Index> ids;
    ids.reserve(2 * f.rows.size());
    ids.insert(ids.end(), f.rows.begin(), f.rows.end());
    ids.insert(ids.end(), f.cols.begin(), f.cols.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

namespace detail {
/// Robot k is ID k: no IDs given, or (ascending, distinct) IDs exactly 0..n-1.
inline bool ids_are_indices(const std::vector<Index>& ids) {
    return ids.empty() || ids.back() == static_cast<Index>(ids.size()) - 1;
}
}  // namespace detail

/// The detection graph of a distance file with robot k = ids[k] (`ids` from robot_ids: ascending).
/// \throws InputError naming FILE:LINE:COLUMN and robots by ID (a pair twice in one direction, two
///         different values of a pair without `average`).
inline dist::DistanceGraph distance_graph(const DistanceFile& f, const std::vector<Index>& ids, bool squared,
                                          bool average) {
    const auto position = [&ids](Index id) {
        return static_cast<Index>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
    };
    std::vector<Index> rows(f.rows.size()), cols(f.cols.size());
    for (std::size_t k = 0; k < f.rows.size(); ++k) {
        rows[k] = position(f.rows[k]);
        cols[k] = position(f.cols[k]);
    }
    return dist::make_distance_graph(static_cast<Index>(ids.size()), rows, cols, f.values, squared,
                                     average ? dist::Symmetry::Average : dist::Symmetry::Require,
                                     [&f](std::size_t k) { return f.where(k); },
                                     detail::ids_are_indices(ids) ? std::vector<Index>{} : ids);
}

/// The detection graph of a distance file with `n` robots 0..n-1, robot k being ID k (robots without
/// a measurement are isolated).
/// \throws InputError naming FILE:LINE:COLUMN (an ID outside [0, n), a pair twice in one direction, two
///         different values of a pair without `average`).
inline dist::DistanceGraph distance_graph(const DistanceFile& f, Index n, bool squared, bool average) {
    return dist::make_distance_graph(n, f.rows, f.cols, f.values, squared,
                                     average ? dist::Symmetry::Average : dist::Symmetry::Require,
                                     [&f](std::size_t k) { return f.where(k); });
}

/// The result as JSON: {"kind": "distance_neighbors", "n", "consistency", "squared", "indptr",
/// "indices", "on_hull", "path_length", "added", "detected"} (Python's to_json writes the same). With
/// robot IDs `ids` (robot k is ids[k], ascending) that are not 0..n-1, also "ids" after "n": row k is
/// robot ids[k], and "indices" lists neighbours by ID.
inline void write_json(std::ostream& os, const dist::DistanceNeighbors& r, bool squared,
                       const std::vector<Index>& ids = {}) {
    const bool by_id = !detail::ids_are_indices(ids);
    const auto list = [&os](const auto& v, auto&& item) {
        os << '[';
        for (std::size_t k = 0; k < v.size(); ++k) {
            if (k) os << ", ";
            item(v[k]);
        }
        os << ']';
    };
    const auto num = [&os](Index x) { os << x; };
    const auto id = [&](Index x) { os << (by_id ? ids[static_cast<std::size_t>(x)] : x); };
    os << "{\"kind\": \"distance_neighbors\", \"n\": " << r.n;
    if (by_id) {
        os << ", \"ids\": ";
        list(ids, num);
    }
    os << ", \"consistency\": " << (r.consistency ? "true" : "false")
       << ", \"squared\": " << (squared ? "true" : "false") << ", \"indptr\": ";
    list(r.indptr, num);
    os << ", \"indices\": ";
    list(r.indices, id);
    os << ", \"on_hull\": ";
    list(r.on_hull, [&os](char h) { os << (h ? "true" : "false"); });
    os << ", \"path_length\": ";
    list(r.path_length, num);
    os << ", \"added\": ";
    list(r.added, num);
    os << ", \"detected\": ";
    list(r.detected, num);
    os << "}";
}

/// The result as CSV: robot,on_hull,detected,neighbors (neighbours space-separated, path order first,
/// then the consistency additions), one row per robot in ascending ID order; with robot IDs `ids`
/// (robot k is ids[k]) robots and neighbours are written by ID.
inline void write_csv(std::ostream& os, const dist::DistanceNeighbors& r, const std::vector<Index>& ids = {}) {
    const bool by_id = !detail::ids_are_indices(ids);
    const auto id = [&](Index x) { return by_id ? ids[static_cast<std::size_t>(x)] : x; };
    os << "robot,on_hull,detected,neighbors\n";
    for (Index i = 0; i < r.n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        os << id(i) << ',' << (r.on_hull[ii] ? 1 : 0) << ',' << r.detected[ii] << ',';
        for (Index q = r.indptr[ii]; q < r.indptr[ii + 1]; ++q) os << (q > r.indptr[ii] ? " " : "") << id(r.indices[static_cast<std::size_t>(q)]);
        os << '\n';
    }
}

}  // namespace dvoronoi::io
