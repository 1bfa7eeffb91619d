// CSV export of per-agent results, one row per agent in input order:
//
//   agent,x,y,area,centroid_x,centroid_y,perimeter,neighbors
//   0,1.5,2,3.14159...,1.49,2.01,6.28...,1 4 7
//
// `neighbors` holds the limited neighbours, ascending, separated by spaces (empty for none). Doubles
// are written with the shortest text that reads back to the same double.
#pragma once

#include "dvoronoi/partition/limited_partition.hpp"

#include <charconv>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>

namespace dvoronoi::io {

namespace detail {

/// Shortest round-trip text of a double ("%.17g" where std::to_chars for doubles is missing).
inline void append_double(std::string& out, double v) {
    char buf[32];
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
#else
    const int len = std::snprintf(buf, sizeof buf, "%.17g", v);
    out.append(buf, static_cast<std::size_t>(len));
#endif
}

}  // namespace detail

/// The CSV header line (without newline).
inline const char* csv_header() {
    return "agent,x,y,area,centroid_x,centroid_y,perimeter,neighbors";
}

/// Writes the per-agent CSV (header plus one line per agent, each ending in '\n').
/// \note O(n + number of neighbour pairs); streams row by row.
inline void write_csv(std::ostream& os, const LimitedPartition& p) {
    os << csv_header() << '\n';
    std::string row;
    for (Index i = 0; i < p.size(); ++i) {
        const auto ii = static_cast<std::size_t>(i);
        row.clear();
        row += std::to_string(i);
        for (const double v : {p.points(i, 0), p.points(i, 1), p.areas[ii], p.centroids(i, 0),
                               p.centroids(i, 1), p.perimeters[ii]}) {
            row += ',';
            detail::append_double(row, v);
        }
        row += ',';
        for (Index k = p.indptr[ii]; k < p.indptr[ii + 1]; ++k) {
            if (k > p.indptr[ii]) row += ' ';
            row += std::to_string(p.indices[static_cast<std::size_t>(k)]);
        }
        row += '\n';
        os.write(row.data(), static_cast<std::streamsize>(row.size()));
    }
}

/// The CSV as a string.
inline std::string to_csv(const LimitedPartition& p) {
    std::ostringstream os;
    write_csv(os, p);
    return os.str();
}

}  // namespace dvoronoi::io
