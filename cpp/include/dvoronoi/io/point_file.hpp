// Reading agent positions from files: text (`x y` per line, whitespace- or comma-separated, `#`
// comments, an optional header line, optional column selection) and numpy `.npy` arrays.
//
// Error policy: a malformed file throws dvoronoi::InputError whose message starts with
// `FILE:LINE:COLUMN:` (1-based line and byte column of the offending token), so editors and terminals
// can jump to it. `.npy` errors name the file and, for values, the row and column of the array.
// An empty file (or one with only comments and a header) is valid and gives 0 points; PointFile says
// which line was taken for the header, so a caller can tell "x y" from a wrong file ("hello world").
#pragma once

#include "dvoronoi/core/types.hpp"
#include "dvoronoi/io/quote.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace dvoronoi::io {

/// Which fields of a text line hold x and y. Indices are 0-based (`mote_id x y` -> x = 1, y = 2);
/// names select fields by the file's header line. Default: the line must have exactly two fields.
struct Columns {
    int x = -1, y = -1;          ///< 0-based field indices, -1 = not given
    std::string x_name, y_name;  ///< header names, used when the indices are not given
    /// Optional third column: each agent's radius (heterogeneous teams), by index or header name.
    int r = -1;
    std::string r_name;

    bool has_radius() const noexcept { return r >= 0 || !r_name.empty(); }

    bool given() const noexcept { return x >= 0 || !x_name.empty(); }
};

/// Parses a column selection such as "1,2" (0-based indices) or "lon,lat" (header names); with
/// `allow_radius`, also "1,2,3" or "x,y,r" (a third column: each agent's radius).
/// \throws InputError naming `what` (e.g. "--columns") if the text is not two (or three) distinct
///         columns.
inline Columns parse_columns(std::string_view spec, const std::string& what = "columns", bool allow_radius = false) {
    const auto fail = [&]() -> Columns {
        throw InputError(what + ": expected two comma-separated column indices (0-based) or header "
                                "names, e.g. \"1,2\" or \"x,y\"" +
                         std::string(allow_radius ? " (or three with the radius, e.g. \"x,y,r\")" : "") + ", got \"" +
                         printable(spec) + "\"");
    };
    if (allow_radius) {
        const std::size_t last = spec.rfind(',');
        if (last != std::string_view::npos && spec.substr(0, last).find(',') != std::string_view::npos) {
            Columns c = parse_columns(spec.substr(0, last), what, false);
            std::string_view t = spec.substr(last + 1);
            while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
            while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
            if (t.empty()) return fail();
            int ir = -1;
            const auto res = std::from_chars(t.data(), t.data() + t.size(), ir);
            const bool numeric = res.ec == std::errc() && res.ptr == t.data() + t.size();
            if (numeric != (c.x >= 0)) return fail();
            if (numeric) {
                if (ir < 0 || ir == c.x || ir == c.y) return fail();
                c.r = ir;
            } else {
                if (t == c.x_name || t == c.y_name) return fail();
                c.r_name = std::string(t);
            }
            return c;
        }
    }
    const auto trim = [](std::string_view s) {
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
        while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
        return s;
    };
    const std::size_t comma = spec.find(',');
    if (comma == std::string_view::npos || spec.find(',', comma + 1) != std::string_view::npos)
        return fail();
    const std::string_view a = trim(spec.substr(0, comma)), b = trim(spec.substr(comma + 1));
    if (a.empty() || b.empty()) return fail();
    const auto as_index = [](std::string_view s, int& out) {
        const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
        return r.ec == std::errc() && r.ptr == s.data() + s.size();
    };
    Columns c;
    int ia = -1, ib = -1;
    const bool na = as_index(a, ia), nb = as_index(b, ib);
    if (na != nb) return fail();
    if (na) {
        if (ia < 0 || ib < 0 || ia == ib) return fail();
        c.x = ia;
        c.y = ib;
    } else {
        if (a == b) return fail();
        c.x_name = std::string(a);
        c.y_name = std::string(b);
    }
    return c;
}

/// Points read from a file, with where each came from (for messages about agent i).
struct PointFile {
    std::string name;         ///< the file name as given
    Points points;            ///< n x 2, in file order
    std::vector<Index> line;  ///< 1-based line of each point (text files); empty for .npy
    std::size_t header_line = 0;  ///< 1-based line of the header (text files), 0 = none
    std::string header;           ///< that line's content (comment removed)
    std::vector<double> radii;    ///< each point's radius when a radius column was selected, else empty

    /// "FILE:LINE" for point i of a text file, "FILE (row i)" for an array file.
    std::string where(Index i) const {
        if (i >= 0 && static_cast<std::size_t>(i) < line.size())
            return name + ":" + std::to_string(line[static_cast<std::size_t>(i)]);
        return name + " (row " + std::to_string(i) + ")";
    }
};

namespace detail {

inline InputError file_error(const std::string& name, std::size_t line, std::size_t col,
                             const std::string& what) {
    return InputError(name + ":" + std::to_string(line) + ":" + std::to_string(col) + ": " + what);
}

enum class NumberStatus { Ok, NotNumber, NotFinite, OutOfRange };

/// Parses one whole token as a double, locale-independently ("1.5", "-2e3", "+.5"; not hex).
inline NumberStatus parse_number(std::string_view tok, double& out) {
    std::string_view s = tok;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
    if (s.empty()) return NumberStatus::NotNumber;
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out, std::chars_format::general);
    if (r.ptr != s.data() + s.size()) return NumberStatus::NotNumber;
    if (r.ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
    if (r.ec != std::errc()) return NumberStatus::NotNumber;
#else
    // Fallback for standard libraries without floating-point from_chars (strtod; the CLI never
    // changes LC_NUMERIC, so the decimal point is '.'). Hex floats are rejected like from_chars does.
    if (s.find_first_of("xX") != std::string_view::npos) return NumberStatus::NotNumber;
    const std::string buf(s);
    char* end = nullptr;
    errno = 0;
    out = std::strtod(buf.c_str(), &end);
    if (end != buf.c_str() + buf.size()) return NumberStatus::NotNumber;
    if (errno == ERANGE && std::isinf(out)) return NumberStatus::OutOfRange;
#endif
    if (!std::isfinite(out)) return NumberStatus::NotFinite;
    return NumberStatus::Ok;
}

inline bool is_number_token(std::string_view tok) {
    double v;
    const NumberStatus st = parse_number(tok, v);
    return st != NumberStatus::NotNumber;
}

struct Field {
    std::string_view text;
    std::size_t col;  // 1-based byte column of the first character
};

inline bool is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\v' || ch == '\f'; }

/// Splits the content of a line (comment already removed) into fields. A line with a comma is
/// comma-separated (fields trimmed; an empty field is an error); otherwise whitespace-separated.
inline void split_fields(std::string_view content, const std::string& name, std::size_t line_no,
                         std::vector<Field>& out) {
    out.clear();
    const std::size_t n = content.size();
    if (content.find(',') != std::string_view::npos) {
        std::size_t pos = 0;
        bool any = false;
        for (std::size_t k = 0; k < n; ++k) any = any || !is_blank(content[k]);
        if (!any) return;
        while (true) {
            const std::size_t comma = std::min(content.find(',', pos), n);
            std::size_t a = pos, b = comma;
            while (a < b && is_blank(content[a])) ++a;
            while (b > a && is_blank(content[b - 1])) --b;
            if (a == b)
                throw file_error(name, line_no, a + 1,
                                 "empty field (two commas in a row, or a comma at the start or end "
                                 "of the line)");
            out.push_back({content.substr(a, b - a), a + 1});
            if (comma == n) break;
            pos = comma + 1;
        }
        return;
    }
    std::size_t k = 0;
    while (k < n) {
        while (k < n && is_blank(content[k])) ++k;
        if (k == n) break;
        const std::size_t a = k;
        while (k < n && !is_blank(content[k])) ++k;
        out.push_back({content.substr(a, k - a), a + 1});
    }
}

inline double field_value(const Field& f, const std::string& name, std::size_t line_no,
                          const char* axis) {
    double v = 0.0;
    switch (parse_number(f.text, v)) {
        case NumberStatus::Ok: return v;
        case NumberStatus::NotFinite:
            throw file_error(name, line_no, f.col,
                             std::string(axis) + " value " + in_quotes(f.text) +
                                 " is not finite (NaN and inf are not positions)");
        case NumberStatus::OutOfRange:
            throw file_error(name, line_no, f.col,
                             std::string(axis) + " value " + in_quotes(f.text) +
                                 " is out of the range of a double");
        case NumberStatus::NotNumber: break;
    }
    throw file_error(name, line_no, f.col,
                     std::string(axis) + " value " + in_quotes(f.text) + " is not a number");
}

/// Resolves header names to indices; returns the index or throws naming the header line.
inline int header_index(const std::vector<Field>& header, const std::string& wanted,
                        const std::string& name, std::size_t line_no) {
    int found = -1;
    for (std::size_t k = 0; k < header.size(); ++k)
        if (header[k].text == wanted) {
            if (found >= 0)
                throw file_error(name, line_no, header[k].col,
                                 "column name " + in_quotes(wanted) + " appears twice in the header");
            found = static_cast<int>(k);
        }
    if (found < 0) {
        std::string names;
        for (const Field& f : header) names += (names.empty() ? "" : ", ") + printable(f.text);
        throw file_error(name, line_no, 1,
                         "no column named " + in_quotes(wanted) + " in the header (columns: " + names + ")");
    }
    return found;
}

inline bool has_npy_magic(std::string_view bytes) {
    return bytes.size() >= 6 && bytes.substr(0, 6) == std::string_view("\x93NUMPY", 6);
}

}  // namespace detail

/// Parses the text of a point file. `name` is used in error messages.
///
/// Format: one point per line; fields separated by whitespace, or by commas when the line has one;
/// `#` starts a comment (whole line or trailing); blank lines are skipped; `\r\n` line ends are fine.
/// The first non-comment line is a header when none of its fields is a number (e.g. `x,y`).
/// Without `columns` every data line must have exactly two fields, x and y; with `columns` the line
/// needs at least the selected fields, and the others are not read.
///
/// \throws InputError "NAME:LINE:COLUMN: ..." for a token that is not a finite number, a wrong number
///         of fields, or a column name missing from the header.
/// \note Complexity O(size of the text). Thread-safe.
inline PointFile parse_point_text(std::string_view text, const std::string& name,
                                  const Columns& columns = {}) {
    PointFile out;
    out.name = name;
    std::vector<double> xy;
    std::vector<detail::Field> fields;
    int xi = columns.x, yi = columns.y, ri = columns.r;
    const bool by_name = columns.x < 0 && !columns.x_name.empty();
    bool first_content = true;
    std::size_t line_no = 0, pos = 0;
    if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // UTF-8 byte-order mark
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
            if (!any_number) {  // header line
                out.header_line = line_no;
                out.header = std::string(line);
                if (by_name) {
                    xi = detail::header_index(fields, columns.x_name, name, line_no);
                    yi = detail::header_index(fields, columns.y_name, name, line_no);
                    if (!columns.r_name.empty()) ri = detail::header_index(fields, columns.r_name, name, line_no);
                }
                continue;
            }
            if (by_name)
                throw detail::file_error(name, line_no, 1,
                                         "columns are selected by name (" + in_quotes(columns.x_name) + ", " +
                                             in_quotes(columns.y_name) +
                                             ") but the file has no header line before its data");
        }

        if (xi < 0) {
            if (fields.size() != 2) {
                const std::size_t col =
                    fields.size() > 2 ? fields[2].col : fields.back().col + fields.back().text.size();
                throw detail::file_error(
                    name, line_no, col,
                    "expected 2 fields (x y), found " + std::to_string(fields.size()) +
                        "; if the file has other columns, select x and y with --columns X,Y "
                        "(0-based field indices, e.g. --columns 1,2 for 'id x y')");
            }
            xy.push_back(detail::field_value(fields[0], name, line_no, "x"));
            xy.push_back(detail::field_value(fields[1], name, line_no, "y"));
        } else {
            const std::size_t need = static_cast<std::size_t>(std::max({xi, yi, ri})) + 1;
            if (fields.size() < need)
                throw detail::file_error(
                    name, line_no, fields.back().col + fields.back().text.size(),
                    "too few fields: found " + std::to_string(fields.size()) +
                        ", the selected columns (x = " + std::to_string(xi) + ", y = " +
                        std::to_string(yi) + (ri >= 0 ? ", r = " + std::to_string(ri) : std::string()) +
                        ", 0-based) need " + std::to_string(need));
            xy.push_back(detail::field_value(fields[static_cast<std::size_t>(xi)], name, line_no, "x"));
            xy.push_back(detail::field_value(fields[static_cast<std::size_t>(yi)], name, line_no, "y"));
            if (ri >= 0) {
                const detail::Field& f = fields[static_cast<std::size_t>(ri)];
                const double r = detail::field_value(f, name, line_no, "radius");
                if (!(r > 0.0))
                    throw detail::file_error(name, line_no, f.col, "radius must be positive, got " + std::string(f.text));
                out.radii.push_back(r);
            }
        }
        out.line.push_back(static_cast<Index>(line_no));
    }
    const Eigen::Index n = static_cast<Eigen::Index>(xy.size() / 2);
    out.points = Eigen::Map<const Points>(xy.data(), n, 2);
    return out;
}

/// Parses the bytes of a numpy `.npy` file holding an `n x 2` array of float64, float32, int64 or
/// int32 (either byte order, C or Fortran order). `columns` is not supported for arrays.
///
/// \throws InputError "NAME: ..." for another dtype or shape, a truncated file, or a value that is
///         NaN or inf (naming its row and column).
inline PointFile parse_npy(std::string_view bytes, const std::string& name) {
    const auto fail = [&](const std::string& what) -> InputError {
        return InputError(name + ": " + what);
    };
    if (!detail::has_npy_magic(bytes)) throw fail("not a .npy file (the magic string \\x93NUMPY is missing)");
    if (bytes.size() < 10) throw fail("truncated .npy header");
    const auto u8 = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[k])); };
    const unsigned major = u8(6);
    std::size_t header_len = 0, header_start = 0;
    if (major == 1) {
        header_len = u8(8) | (u8(9) << 8);
        header_start = 10;
    } else if (major == 2 || major == 3) {
        if (bytes.size() < 12) throw fail("truncated .npy header");
        header_len = u8(8) | (u8(9) << 8) | (u8(10) << 16) | (u8(11) << 24);
        header_start = 12;
    } else {
        throw fail("unsupported .npy format version " + std::to_string(major));
    }
    if (bytes.size() < header_start + header_len) throw fail("truncated .npy header");
    const std::string_view header = bytes.substr(header_start, header_len);
    const auto value_of = [&](std::string_view key) -> std::string_view {
        const std::size_t k = header.find(key);
        if (k == std::string_view::npos) throw fail("the .npy header has no " + std::string(key));
        std::size_t v = header.find(':', k + key.size());
        if (v == std::string_view::npos) throw fail("malformed .npy header");
        ++v;
        while (v < header.size() && header[v] == ' ') ++v;
        return header.substr(v);
    };
    // descr: '<f8' and friends.
    std::string_view descr = value_of("'descr'");
    if (descr.empty() || (descr[0] != '\'' && descr[0] != '"')) throw fail("malformed .npy descr");
    const std::size_t dend = descr.find(descr[0], 1);
    if (dend == std::string_view::npos) throw fail("malformed .npy descr");
    descr = descr.substr(1, dend - 1);
    const bool fortran = value_of("'fortran_order'").substr(0, 4) == "True";
    // shape: (n, 2)
    const std::string_view shape_text = value_of("'shape'");
    const std::size_t close = shape_text.find(')');
    if (shape_text.empty() || shape_text[0] != '(' || close == std::string_view::npos)
        throw fail("malformed .npy shape");
    std::vector<std::int64_t> shape;
    {
        std::string_view s = shape_text.substr(1, close - 1);
        while (!s.empty()) {
            while (!s.empty() && (s.front() == ' ' || s.front() == ',')) s.remove_prefix(1);
            if (s.empty()) break;
            std::int64_t d = 0;
            const auto r = std::from_chars(s.data(), s.data() + s.size(), d);
            if (r.ec != std::errc() || d < 0) throw fail("malformed .npy shape");
            shape.push_back(d);
            s.remove_prefix(static_cast<std::size_t>(r.ptr - s.data()));
            while (!s.empty() && s.front() == 'L') s.remove_prefix(1);  // Python 2 longs
        }
    }
    std::string shape_str = "(";
    for (std::size_t k = 0; k < shape.size(); ++k) shape_str += (k ? ", " : "") + std::to_string(shape[k]);
    shape_str += shape.size() == 1 ? ",)" : ")";
    if (shape.size() != 2 || shape[1] != 2)
        throw fail("the array must have shape (n, 2), got " + shape_str);

    if (descr.size() != 3) throw fail("unsupported .npy dtype '" + std::string(descr) + "'");
    const char order = descr[0], kind = descr[1];
    const int size = descr[2] - '0';
    const bool ok_kind = (kind == 'f' && (size == 4 || size == 8)) || (kind == 'i' && (size == 4 || size == 8));
    if (!ok_kind || (order != '<' && order != '>' && order != '=' && order != '|'))
        throw fail("unsupported .npy dtype '" + std::string(descr) +
                   "' (float64, float32, int64 or int32 are read)");
    const std::uint16_t probe = 1;
    unsigned char first_byte;
    std::memcpy(&first_byte, &probe, 1);
    const bool host_little = first_byte == 1;
    const bool swap = (order == '<' && !host_little) || (order == '>' && host_little);

    const std::int64_t n = shape[0];
    const std::size_t data_start = header_start + header_len;
    const std::size_t have = bytes.size() - data_start;
    const std::size_t per_row = 2u * static_cast<std::size_t>(size);
    // n is compared by division: n * 16 may overflow (a shape of (2**60, 2) would need 0 bytes)
    if (static_cast<std::uint64_t>(n) > have / per_row)
        throw fail("truncated .npy data: " + std::to_string(n) + " rows need " +
                   (static_cast<std::uint64_t>(n) > SIZE_MAX / per_row ? std::string("more bytes than a file can hold")
                                                                       : std::to_string(static_cast<std::size_t>(n) * per_row) + " bytes") +
                   ", found " + std::to_string(have));
    const char* data = bytes.data() + data_start;
    const auto read = [&](std::size_t k) -> double {
        unsigned char b[8];
        std::memcpy(b, data + k * static_cast<std::size_t>(size), static_cast<std::size_t>(size));
        if (swap)
            for (int a = 0, z = size - 1; a < z; ++a, --z) std::swap(b[a], b[z]);
        if (kind == 'f' && size == 8) { double v; std::memcpy(&v, b, 8); return v; }
        if (kind == 'f') { float v; std::memcpy(&v, b, 4); return static_cast<double>(v); }
        if (size == 8) { std::int64_t v; std::memcpy(&v, b, 8); return static_cast<double>(v); }
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return static_cast<double>(v);
    };
    PointFile out;
    out.name = name;
    out.points.resize(static_cast<Eigen::Index>(n), 2);
    for (std::int64_t i = 0; i < n; ++i)
        for (int d = 0; d < 2; ++d) {
            const std::size_t k = fortran ? static_cast<std::size_t>(d * n + i)
                                          : static_cast<std::size_t>(2 * i + d);
            const double v = read(k);
            if (!std::isfinite(v))
                throw fail("points[" + std::to_string(i) + ", " + std::to_string(d) +
                           "] is not finite (NaN or inf)");
            out.points(static_cast<Eigen::Index>(i), d) = v;
        }
    return out;
}

/// Reads a whole file into memory. `path` "-" reads standard input.
/// \throws InputError "PATH: cannot open/read: reason".
inline std::string read_file_bytes(const std::string& path) {
    std::FILE* f = path == "-" ? stdin : std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
    std::string data;
    char buf[1 << 16];
    std::size_t got;
    errno = 0;
    while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) data.append(buf, got);
    const bool bad = std::ferror(f) != 0;
    const int err = errno;
    if (f != stdin) std::fclose(f);
    if (bad) throw InputError(path + ": cannot read: " + std::strerror(err ? err : EIO));
    return data;
}

/// Reads a point file: `.npy` when the file starts with numpy's magic string, text otherwise.
/// `path` "-" reads standard input (named "<stdin>" in messages).
///
/// \throws InputError naming the file (and line and column for text files); see parse_point_text
///         and parse_npy. Column selection on a `.npy` file is an error.
/// \note Reads the whole file into memory first; O(file size).
inline PointFile read_point_file(const std::string& path, const Columns& columns = {}) {
    const std::string name = path == "-" ? "<stdin>" : path;
    const std::string bytes = read_file_bytes(path);
    if (detail::has_npy_magic(bytes)) {
        if (columns.given())
            throw InputError(name + ": column selection applies to text files, not .npy arrays");
        return parse_npy(bytes, name);
    }
    const bool npy_name = name.size() >= 4 && name.compare(name.size() - 4, 4, ".npy") == 0;
    if (npy_name && !bytes.empty())
        throw InputError(name + ": not a .npy file (the magic string \\x93NUMPY is missing)");
    return parse_point_text(bytes, name, columns);
}

/// The points of a point file (see read_point_file).
inline Points read_points(const std::string& path, const Columns& columns = {}) {
    return read_point_file(path, columns).points;
}

}  // namespace dvoronoi::io
