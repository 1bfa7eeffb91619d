// Occupancy-grid map files: ROS map_server YAML (with its PGM or PNG image), PGM (P2/P5), PNG and the
// MovingAI benchmark `.map` text format (docs/spec.md, "Grid diagram on occupancy grids").
//
// Grey images follow map_server's trinary rule (ROS1 map_server's image_loader.cpp, nav2's
// map_io.cpp): v is the mean of all the pixel's channels as stored, scaled to [0, 1]; the occupancy
// probability is p = 1 - v (p = v with `negate`); p > occupied_thresh is occupied, p < free_thresh
// free, anything between unknown. Alpha counts as a channel ("Alpha will be averaged in with color
// channels when using trinary mode"), and a grey+alpha pixel is R = G = B = grey plus alpha as
// map_server sees it: v = (r + g + b + a) / 4 and (3 grey + a) / 4, so a transparent pixel reads
// darker. Unknown pixels count as occupied unless the caller says otherwise. MovingAI maps: `.` and
// `G` free, `@ O T S W` blocked, any other character an error naming the line and column.
//
// PNG samples are read as stored, as map_server does: no gamma, sRGB or ICC conversion (gAMA, cHRM,
// sRGB and iCCP are ignored); 1, 2 and 4-bit grey is scaled to 8 bits, a palette is looked up (its
// tRNS entries give alpha). 16-bit samples keep their precision, v = s / 65535 as for 16-bit PGM
// (nav2 reads them at full precision; ROS1 keeps the high byte, which can differ only for a pixel
// within 1/255 of a threshold). A tRNS colour key on a grey or RGB image is not a channel: SDL_image,
// ROS1's loader, makes it a colour key, and it is ignored here.
//
// Errors: InputError whose message starts with `FILE:` (and `LINE:` for text formats). PNG needs
// libpng: the CLI and the Python module are built with it when CMake finds it
// (DVORONOI_HAVE_PNG); other builds refuse PNG files with a clear message.
#pragma once

#include "dvoronoi/gvd/occupancy_grid.hpp"
#include "dvoronoi/io/quote.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#ifdef DVORONOI_HAVE_PNG
#include <png.h>
#endif

namespace dvoronoi::io {

struct MapReadOptions {
    bool unknown_occupied = true;  ///< unknown pixels (between the thresholds) count as occupied
    double resolution = 1.0;       ///< map units per pixel (images without YAML); finite, > 0
    Vec2 origin = Vec2(0.0, 0.0);  ///< lower-left corner (images without YAML); finite
    double occupied_thresh = 0.65; ///< in [0, 1]
    double free_thresh = 0.196;    ///< in [0, 1], at most occupied_thresh
    bool negate = false;
    std::string movingai_free = ".G";  ///< MovingAI characters that are free (the rest of .G@OTSW blocked; the SPEC's rule)
};

/// A loaded map and what the loader saw.
struct LoadedMap {
    gvd::OccupancyGrid grid;
    std::size_t unknown = 0;  ///< pixels between the thresholds (counted as set by unknown_occupied)
    std::string image;        ///< the image file a YAML pointed to
    double occupied_thresh = 0.65;  ///< the threshold the map was read with (a YAML's own)
};

namespace detail {

/// The file's bytes. A folder, a missing file and a failed read are named as such (a folder opens on
/// some systems and reads as nothing: it would show as a truncated header).
inline std::string read_bytes(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a folder, not a file");
    errno = 0;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
        const int err = errno;
        throw InputError(path + ": cannot open file" +
                         (err == ENOENT ? std::string(": it does not exist") : err != 0 ? " (" + std::string(std::strerror(err)) + ")" : std::string()));
    }
    std::string data;
    char buf[1 << 16];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) data.append(buf, n);
    const bool failed = std::ferror(f) != 0;
    const int err = errno;
    std::fclose(f);
    if (failed) throw InputError(path + ": cannot read file" + (err != 0 ? " (" + std::string(std::strerror(err)) + ")" : std::string()));
    return data;
}

inline std::string lower_ext(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot);
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

using ::dvoronoi::detail::shortest_text;

/// One check of the options, whoever gave them (the caller or a YAML): the key at fault and `why`
/// ("KEY: ..."), or nullptr. NaN fails every comparison below, so it is refused too.
inline const char* bad_read_option(const MapReadOptions& o, std::string& why) {
    if (!(std::isfinite(o.resolution) && o.resolution > 0.0)) {
        why = "resolution: must be a positive finite number, got " + shortest_text(o.resolution);
        return "resolution";
    }
    if (!gvd::resolution_in_range(o.resolution)) {
        why = "resolution: must lie in " + gvd::resolution_range() + " so that map coordinates stay finite, got " + shortest_text(o.resolution);
        return "resolution";
    }
    if (!std::isfinite(o.origin.x()) || !std::isfinite(o.origin.y())) {
        why = "origin: must be finite, got (" + shortest_text(o.origin.x()) + ", " + shortest_text(o.origin.y()) + ")";
        return "origin";
    }
    for (const char* key : {"occupied_thresh", "free_thresh"}) {
        const double t = key[0] == 'o' ? o.occupied_thresh : o.free_thresh;
        if (!(t >= 0.0 && t <= 1.0)) {
            why = std::string(key) + ": expected a number in [0, 1], got " + shortest_text(t);
            return key;
        }
    }
    if (o.free_thresh > o.occupied_thresh) {
        why = "free_thresh is larger than occupied_thresh (" + shortest_text(o.free_thresh) + " > " + shortest_text(o.occupied_thresh) + ")";
        return "free_thresh";
    }
    return nullptr;
}

/// Grey levels in [0, 1] (row 0 at the top) to occupancy by map_server's trinary rule.
inline LoadedMap from_grey(const std::vector<double>& grey, std::int32_t h, std::int32_t w, const MapReadOptions& o) {
    LoadedMap out;
    out.grid = gvd::OccupancyGrid(h, w, o.resolution, o.origin);
    out.occupied_thresh = o.occupied_thresh;
    for (std::size_t i = 0; i < grey.size(); ++i) {
        const double p = o.negate ? grey[i] : 1.0 - grey[i];
        if (p > o.occupied_thresh) {
            out.grid.occupied[i] = 1;
        } else if (!(p < o.free_thresh)) {
            ++out.unknown;
            out.grid.occupied[i] = o.unknown_occupied ? 1 : 0;
        }
    }
    return out;
}

inline void check_size(const std::string& path, long long w, long long h) {
    if (w < 1 || h < 1 || w > gvd::kMaxMapSide || h > gvd::kMaxMapSide)
        throw InputError(path + ": image of " + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels: each side must be between 1 and " + std::to_string(gvd::kMaxMapSide));
}

/// "LINE:COLUMN" (1-based) of byte `pos` of a text file.
inline std::string line_column(const std::string& data, std::size_t pos) {
    std::size_t line = 1, start = 0;
    for (std::size_t i = 0; i < pos && i < data.size(); ++i)
        if (data[i] == '\n') ++line, start = i + 1;
    return std::to_string(line) + ":" + std::to_string(pos - start + 1);
}

/// PGM, binary (P5) or plain (P2): grey levels in [0, 1].
inline std::vector<double> read_pgm(const std::string& path, std::int32_t& h, std::int32_t& w) {
    const std::string data = read_bytes(path);
    std::size_t pos = 0;
    auto token = [&](const char* what) {
        for (;;) {
            while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
            if (pos < data.size() && data[pos] == '#') {
                while (pos < data.size() && data[pos] != '\n' && data[pos] != '\r') ++pos;
                continue;
            }
            break;
        }
        const std::size_t start = pos;
        while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos])) && data[pos] != '#') ++pos;
        if (start == pos) throw InputError(path + ": truncated PGM header (no " + what + ")");
        return data.substr(start, pos - start);
    };
    const std::string magic = token("magic number");
    if (magic != "P5" && magic != "P2") throw InputError(path + ": not a PGM image (magic '" + printable(magic) + "', expected P5 or P2)");
    auto number = [&](const char* what, long long least = 1) {
        const std::string t = token(what);
        char* end = nullptr;
        const long long v = std::strtoll(t.c_str(), &end, 10);
        if (*end != '\0' || v < least) throw InputError(path + ": bad PGM " + what + " '" + printable(t) + "'");
        return v;
    };
    const long long W = number("width"), H = number("height"), maxval = number("maximum grey value");
    check_size(path, W, H);
    if (maxval > 65535) throw InputError(path + ": PGM maximum grey value " + std::to_string(maxval) + " exceeds 65535");
    w = static_cast<std::int32_t>(W);
    h = static_cast<std::int32_t>(H);
    const std::size_t n = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);
    // Checked before the pixels are allocated: a header of a few bytes may claim 16383 x 16383.
    if (magic == "P5") {
        ++pos;  // the single whitespace after the header
        const std::size_t bytes = maxval < 256 ? 1 : 2;
        if (data.size() < pos || data.size() - pos < n * bytes)
            throw InputError(path + ": truncated PGM data (" + std::to_string((data.size() > pos ? data.size() - pos : 0) / bytes) +
                             " of " + std::to_string(n) + " pixels)");
    } else if (data.size() - pos + 1 < 2 * n) {  // n values need n digits and n - 1 separators
        throw InputError(path + ": truncated PGM data (room for at most " + std::to_string((data.size() - pos + 1) / 2) +
                         " of " + std::to_string(n) + " pixels)");
    }
    // Pixels are named 0-based, row 0 at the top, as the grid's rows and columns.
    auto pixel = [W](std::size_t i) {
        return "row " + std::to_string(i / static_cast<std::size_t>(W)) + ", column " + std::to_string(i % static_cast<std::size_t>(W));
    };
    auto above_maxval = [&](long long v, std::size_t i) {
        return "PGM pixel value " + std::to_string(v) + " exceeds the maximum grey value " + std::to_string(maxval) + " (" +
               pixel(i) + ")";
    };
    const std::string longer = "the PGM raster is longer than its header's " + std::to_string(W) + " x " + std::to_string(H) + " pixels";
    std::vector<double> grey(n);
    if (magic == "P5") {
        const std::size_t bytes = maxval < 256 ? 1 : 2;
        // Extra bytes would shift every row if the header's width were wrong: refused, not dropped.
        if (const std::size_t extra = data.size() - pos - n * bytes; extra > 0)
            throw InputError(path + ": " + longer + " (" + std::to_string(extra) + " byte" + (extra == 1 ? "" : "s") +
                             " after the last pixel" +
                             (pos >= 1 && data[pos - 1] == '\r' && data[pos] == '\n'
                                  ? "; the header ends in CR LF, but one whitespace character ends a P5 header"
                                  : "") +
                             ")");
        for (std::size_t i = 0; i < n; ++i) {
            const auto* p = reinterpret_cast<const unsigned char*>(data.data() + pos + i * bytes);
            const unsigned v = bytes == 1 ? p[0] : (static_cast<unsigned>(p[0]) << 8 | p[1]);
            if (v > static_cast<unsigned>(maxval)) throw InputError(path + ": " + above_maxval(v, i));
            grey[i] = static_cast<double>(v) / static_cast<double>(maxval);
        }
    } else {
        // Plain PGM is text: its pixel errors name the line and column, as the other text formats do.
        for (std::size_t i = 0; i < n; ++i) {
            for (;;) {  // whitespace and, as netpbm allows, comments between the values
                while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
                if (pos >= data.size() || data[pos] != '#') break;
                while (pos < data.size() && data[pos] != '\n' && data[pos] != '\r') ++pos;
            }
            if (pos >= data.size())
                throw InputError(path + ":" + line_column(data, pos) + ": truncated PGM data (" + std::to_string(i) + " of " +
                                 std::to_string(n) + " pixels)");
            const std::size_t start = pos;
            while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos])) && data[pos] != '#') ++pos;
            const std::string t = data.substr(start, pos - start);
            char* end = nullptr;
            const long long v = std::strtoll(t.c_str(), &end, 10);
            if (t.empty() || *end != '\0' || v < 0 || !std::isdigit(static_cast<unsigned char>(t[0])))
                throw InputError(path + ":" + line_column(data, start) + ": bad PGM pixel value '" + printable(t) + "' (pixel " +
                                 std::to_string(i + 1) + " of " + std::to_string(n) + ")");
            if (v > maxval)  // strtoll saturates, so a huge value lands here too: quote the text
                throw InputError(path + ":" + line_column(data, start) + ": PGM pixel value '" + printable(t) +
                                 "' exceeds the maximum grey value " + std::to_string(maxval) + " (" + pixel(i) + ")");
            grey[i] = static_cast<double>(v) / static_cast<double>(maxval);
        }
        for (;;) {  // after the last value only whitespace and comments
            while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
            if (pos >= data.size() || data[pos] != '#') break;
            while (pos < data.size() && data[pos] != '\n' && data[pos] != '\r') ++pos;
        }
        if (pos < data.size()) {
            std::size_t stop = pos;
            while (stop < data.size() && !std::isspace(static_cast<unsigned char>(data[stop])) && data[stop] != '#') ++stop;
            throw InputError(path + ":" + line_column(data, pos) + ": " + longer + " (" + in_quotes(std::string_view(data).substr(pos, stop - pos)) +
                             " after the last pixel value)");
        }
    }
    return grey;
}

#ifdef DVORONOI_HAVE_PNG
/// Refuses a PNG whose header claims more pixels than its bytes can hold, before anything is
/// allocated for them: deflate expands at most 1032-fold, and the image data are at least one filter
/// byte per row plus the rows' packed pixels (IHDR's bit depth and colour type).
inline void check_png_data(const std::string& path, const std::string& data, std::uint32_t w, std::uint32_t h) {
    if (data.size() < 33) return;  // libpng has read the header, so it is there; be safe anyway
    const auto depth = static_cast<std::uint64_t>(static_cast<unsigned char>(data[24]));
    const int colour = static_cast<unsigned char>(data[25]);
    const std::uint64_t channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
    const std::uint64_t row_bytes = (static_cast<std::uint64_t>(w) * depth * channels + 7) / 8;
    const std::uint64_t raw = static_cast<std::uint64_t>(h) * (1 + row_bytes);
    if (raw / 1032 > data.size())
        throw InputError(path + ": truncated PNG image (" + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels need at least " + std::to_string(raw / 1032) + " bytes of compressed data, the file has " +
                         std::to_string(data.size()) + ")");
}

/// What libpng's callbacks share: the file's bytes and libpng's last error message. Trivially
/// destructible, like every local of the functions libpng may longjmp out of.
struct PngSource {
    const char* data;
    std::size_t size;
    std::size_t pos;
    char message[200];
};

inline void png_read_memory(png_structp png, png_bytep out, png_size_t n) {
    auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
    if (src->size - src->pos < n) png_error(png, "the file ends inside a chunk");
    std::memcpy(out, src->data + src->pos, n);
    src->pos += n;
}

inline void png_keep_error(png_structp png, png_const_charp message) {
    auto* src = static_cast<PngSource*>(png_get_error_ptr(png));
    std::snprintf(src->message, sizeof src->message, "%s", message != nullptr ? message : "libpng error");
    png_longjmp(png, 1);
}

inline void png_no_warning(png_structp, png_const_charp) {}  // libpng would print to stderr

// libpng reports errors by longjmp to png_jmpbuf: the two steps below own nothing that needs
// destroying, so a jump out of libpng back into them leaks nothing; the caller frees the structs.
/// Reads the header and sets the transforms; false on a libpng error.
inline bool png_start(png_structp png, png_infop info) {
    if (setjmp(png_jmpbuf(png))) return false;
#ifdef PNG_HANDLE_AS_UNKNOWN_SUPPORTED
    // Colour management is not map_server's business: these chunks are skipped unread.
    static const png_byte ignored[] = {'c', 'H', 'R', 'M', 0, 'g', 'A', 'M', 'A', 0, 'i', 'C', 'C', 'P', 0, 's', 'R', 'G', 'B', 0};
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, ignored, 4);
#endif
    png_read_info(png, info);
    const int colour = png_get_color_type(png, info);
    if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);  // and its tRNS to alpha
    if (colour == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    return true;
}

/// Decodes the rows; false on a libpng error.
inline bool png_rows(png_structp png, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    return true;
}

inline std::vector<double> read_png(const std::string& path, std::int32_t& h, std::int32_t& w) {
    const std::string data = read_bytes(path);
    PngSource src{data.data(), data.size(), 0, {}};
    if (data.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data.data()), 0, 8) != 0)
        throw InputError(path + ": not a readable PNG image (no PNG signature)");
    struct Structs {
        png_structp png = nullptr;
        png_infop info = nullptr;
        ~Structs() { png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr); }
    } s;
    s.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, png_keep_error, png_no_warning);
    if (s.png != nullptr) s.info = png_create_info_struct(s.png);
    if (s.info == nullptr) throw InputError(path + ": cannot decode PNG image (out of memory)");
    png_set_read_fn(s.png, &src, png_read_memory);
    if (!png_start(s.png, s.info)) throw InputError(path + ": not a readable PNG image (" + printable(src.message) + ")");
    const png_uint_32 width = png_get_image_width(s.png, s.info), height = png_get_image_height(s.png, s.info);
    check_size(path, width, height);
    check_png_data(path, data, width, height);
    const int channels = png_get_channels(s.png, s.info);
    const bool wide = png_get_bit_depth(s.png, s.info) == 16;
    const std::size_t row_bytes = png_get_rowbytes(s.png, s.info);
    if (channels < 1 || channels > 4 || row_bytes != static_cast<std::size_t>(width) * static_cast<std::size_t>(channels) * (wide ? 2 : 1))
        throw InputError(path + ": cannot decode PNG image (unexpected pixel layout)");
    std::vector<unsigned char> px(row_bytes * height);
    std::vector<png_bytep> rows(height);
    for (png_uint_32 r = 0; r < height; ++r) rows[r] = px.data() + r * row_bytes;
    if (!png_rows(s.png, rows.data())) throw InputError(path + ": cannot decode PNG image (" + printable(src.message) + ")");
    w = static_cast<std::int32_t>(width);
    h = static_cast<std::int32_t>(height);
    // map_server's mean over the channels as stored, alpha included; grey+alpha is R = G = B = grey.
    const double top = wide ? 65535.0 : 255.0;
    const double denominator = (channels == 2 ? 4 : channels) * top;
    auto sample = [&](std::size_t k) { return wide ? static_cast<double>(px[2 * k] << 8 | px[2 * k + 1]) : static_cast<double>(px[k]); };
    std::vector<double> grey(static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < grey.size(); ++i) {
        const std::size_t first = i * static_cast<std::size_t>(channels);
        double sum = channels == 2 ? 2.0 * sample(first) : 0.0;
        for (std::size_t c = 0; c < static_cast<std::size_t>(channels); ++c) sum += sample(first + c);
        grey[i] = sum / denominator;
    }
    return grey;
}
#endif

/// The MovingAI `.map` format: a header of `type NAME`, `height H` and `width W` lines (any order,
/// keys in any case, each once), then `map`, then H rows of exactly W characters: `free` characters
/// (o.movingai_free, default `.` and `G`) are free, the others of `. G @ O T S W` blocked, anything else
/// an error. CRLF line ends are accepted, blank lines after the rows ignored. Every error names the
/// line. Rows are read one at a time before the grid is allocated: memory follows the file, not its
/// header. (Python's occupancy_maps.read_movingai_map is this reader.)
inline LoadedMap read_movingai(const std::string& path, const MapReadOptions& o) {
    const std::string data = read_bytes(path);
    int lineno = 0;
    auto fail = [&](int line, const std::string& why) -> void { throw InputError(path + ":" + std::to_string(line) + ": " + why); };
    for (std::size_t k = 0; k < data.size(); ++k)
        if (static_cast<unsigned char>(data[k]) >= 128)
            fail(static_cast<int>(std::count(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(k), '\n')) + 1,
                 "not an ASCII MovingAI map file");
    std::size_t pos = 0;
    auto next_line = [&](std::string& line) {  // false at the end of the data; the line without its CR LF
        if (pos >= data.size()) return false;
        std::size_t end = data.find('\n', pos);
        if (end == std::string::npos) end = data.size();
        line.assign(data, pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        pos = end + 1;
        ++lineno;
        return true;
    };
    std::string line;
    long long size[2] = {-1, -1};  // height, width
    bool typed = false;
    for (;;) {
        if (!next_line(line)) fail(lineno + 1, "header ends before the 'map' line");
        std::istringstream ls(line);
        std::vector<std::string> fields;
        for (std::string f; ls >> f;) fields.push_back(f);
        if (fields.empty()) fail(lineno, "empty line in the header");
        std::string key = fields[0];
        for (char& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (key == "map" && fields.size() == 1) break;
        if ((key != "type" && key != "height" && key != "width") || fields.size() != 2)
            fail(lineno, "expected 'type NAME', 'height H', 'width W' or 'map', got '" + printable(line) + "'");
        if (key == "type") {
            if (typed) fail(lineno, "'type' given twice");
            typed = true;
            continue;
        }
        long long& v = size[key == "height" ? 0 : 1];
        if (v >= 0) fail(lineno, "'" + key + "' given twice");
        char* end = nullptr;
        errno = 0;
        const long long n = std::strtoll(fields[1].c_str(), &end, 10);
        if (*end != '\0' || errno != 0 || n <= 0 || fields[1].find_first_not_of("+0123456789") != std::string::npos)
            fail(lineno, key + " must be a positive integer, got '" + printable(fields[1]) + "'");
        v = n;
    }
    if (size[0] < 0) fail(lineno, "header has no 'height' line");
    if (size[1] < 0) fail(lineno, "header has no 'width' line");
    const long long H = size[0], W = size[1];
    check_size(path, W, H);
    const std::string& free = o.movingai_free;
    std::vector<std::uint8_t> cells;
    for (long long r = 0; r < H; ++r) {
        if (!next_line(line))
            fail(lineno + 1, "expected " + std::to_string(H) + " map rows, the file has " + std::to_string(r));
        if (static_cast<long long>(line.size()) != W)
            fail(lineno, "map row " + std::to_string(r) + " has " + std::to_string(line.size()) + " characters, width is " +
                             std::to_string(W));
        for (long long c = 0; c < W; ++c) {
            const char ch = line[static_cast<std::size_t>(c)];
            const bool is_free = ch != '\0' && free.find(ch) != std::string::npos;
            // the whole alphabet is valid whatever `free` says: a `G` not free is blocked, not unknown
            if (!is_free && (ch == '\0' || std::strchr(".G@OTSW", ch) == nullptr))
                fail(lineno, "unknown character '" + printable(std::string(1, ch)) + "' in column " + std::to_string(c + 1) +
                                 " (free '" + printable(free) + "', blocked the rest of '.G@OTSW')");
            cells.push_back(is_free ? 0 : 1);
        }
    }
    while (next_line(line))
        if (line.find_first_not_of(" \t") != std::string::npos) fail(lineno, "text after the " + std::to_string(H) + " map rows");
    LoadedMap out;
    out.grid = gvd::OccupancyGrid(static_cast<std::int32_t>(H), static_cast<std::int32_t>(W), o.resolution, o.origin);
    std::copy(cells.begin(), cells.end(), out.grid.occupied.begin());
    return out;
}

inline std::string yaml_trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return std::string();
    const auto b = s.find_last_not_of(" \t\r\n");
    return s.substr(a, b - a + 1);
}

inline bool one_of(char c, const char* set) { return c != '\0' && std::strchr(set, c) != nullptr; }

/// A quote opens a quoted scalar only where a scalar starts (`it's` is plain text).
inline bool yaml_opens_quote(const std::string& s, std::size_t i) {
    while (i > 0 && one_of(s[i - 1], " \t\r\n")) --i;
    return i == 0 || one_of(s[i - 1], ":[{,-?");
}

/// Where a scan of a text stopped, so that it can go on when the text grows.
struct YamlScan {
    std::size_t next = 0;
    char quote = 0;
};

/// Walks `s` from `st.next` past quoted scalars, calling `stop(i)` at every other character; the
/// index where it returned true, or npos. Each character is looked at once over repeated calls.
template <class Stop>
std::size_t yaml_scan(const std::string& s, YamlScan& st, Stop&& stop) {
    std::size_t i = st.next;
    for (; i < s.size(); ++i) {
        const char c = s[i];
        if (st.quote != 0) {
            if (st.quote == '"' && c == '\\') ++i;
            else if (c == '\'' && st.quote == '\'' && i + 1 < s.size() && s[i + 1] == '\'') ++i;  // '' is a quote
            else if (c == st.quote) st.quote = 0;
        } else if ((c == '"' || c == '\'') && yaml_opens_quote(s, i)) {
            st.quote = c;
        } else if (stop(i)) {
            st.next = i + 1;
            return i;
        }
    }
    st.next = i;
    return std::string::npos;
}

template <class Stop>
std::size_t yaml_scan(const std::string& s, std::size_t from, Stop&& stop) {
    YamlScan st;
    st.next = from;
    return yaml_scan(s, st, stop);
}

/// `s` without its comment: `#` at the start or after a blank, outside quotes.
inline std::string yaml_uncomment(const std::string& s) {
    const std::size_t hash = yaml_scan(s, 0, [&](std::size_t i) { return s[i] == '#' && (i == 0 || one_of(s[i - 1], " \t")); });
    return hash == std::string::npos ? s : s.substr(0, hash);
}

/// Finds the bracket closing the one at s[0] of a text that may grow between calls (the index, or
/// npos): a flow collection read line by line costs one pass, not one per line.
struct YamlCloser {
    YamlScan scan;
    int depth = 0;
    std::size_t operator()(const std::string& s) {
        return yaml_scan(s, scan, [&](std::size_t i) {
            if (one_of(s[i], "[{")) ++depth;
            else if (one_of(s[i], "]}")) return --depth == 0;
            return false;
        });
    }
};

inline std::size_t yaml_close(const std::string& s) { return YamlCloser()(s); }

/// The [begin, end) pieces of s[from, to) between the commas outside brackets and quotes.
inline std::vector<std::pair<std::size_t, std::size_t>> yaml_split(const std::string& s, std::size_t from, std::size_t to) {
    std::vector<std::pair<std::size_t, std::size_t>> pieces;
    std::size_t start = from;
    int depth = 0;
    yaml_scan(s.substr(0, to), from, [&](std::size_t i) {
        if (one_of(s[i], "[{")) ++depth;
        else if (one_of(s[i], "]}")) --depth;
        else if (s[i] == ',' && depth == 0) pieces.emplace_back(start, i), start = i + 1;
        return false;
    });
    pieces.emplace_back(start, to);
    return pieces;
}

/// The quoted scalar starting at s[i]: its text in `out`, and the index just past its closing quote.
template <class Fail>
std::size_t yaml_quoted(const std::string& s, std::size_t i, std::string& out, Fail&& fail) {
    const char quote = s[i++];
    out.clear();
    while (i < s.size()) {
        const char c = s[i++];
        if (c == quote) {
            if (quote == '\'' && i < s.size() && s[i] == '\'') {
                out += '\'';
                ++i;
                continue;
            }
            return i;
        }
        if (c == '\\' && quote == '"' && i < s.size()) {
            const char e = s[i++];
            if (e == 't') out += '\t';
            else if (one_of(e, "\"\\/ ")) out += e;
            else fail("unsupported escape '\\" + printable(std::string(1, e)) + "' in a quoted string");
            continue;
        }
        out += c;
    }
    fail("unterminated quoted string " + printable(s.substr(0, 40)));
    return s.size();
}

/// A scalar value as text: unquoted, and refused if it is YAML this reader does not follow.
template <class Fail>
std::string yaml_scalar(const std::string& raw, const std::string& key, Fail&& fail) {
    const std::string t = yaml_trim(raw);
    if (t.empty()) return t;
    if (t[0] == '"' || t[0] == '\'') {
        std::string out;
        const std::size_t end = yaml_quoted(t, 0, out, fail);
        if (end != t.size()) fail(printable(key) + ": text after the quoted value in '" + printable(t) + "'");
        return out;
    }
    if (one_of(t[0], "&*!|>%@`"))
        fail(printable(key) + ": YAML anchors, aliases, tags and block scalars are not supported, got '" + printable(t) + "'");
    if (one_of(t[0], "[{")) fail(printable(key) + ": expected a single value, got '" + printable(t) + "'");
    return t;
}

/// Splits `key: value` (the key plain or quoted); false if `t` is no such pair.
template <class Fail>
bool yaml_key_value(const std::string& t, std::string& key, std::string& value, Fail&& fail) {
    std::size_t colon = 0;
    if (t[0] == '"' || t[0] == '\'') {
        colon = yaml_quoted(t, 0, key, fail);
        while (colon < t.size() && one_of(t[colon], " \t")) ++colon;
        if (colon >= t.size() || t[colon] != ':') return false;
    } else {
        // a plain key ends at ': ' (`image: C:/maps/a.pgm`); `key:value`, which map_server's YAML
        // parser would take for one scalar, is read as a pair too
        colon = t.find(':');
        for (std::size_t c = colon; c != std::string::npos; c = t.find(':', c + 1))
            if (c + 1 == t.size() || one_of(t[c + 1], " \t\r\n")) {
                colon = c;
                break;
            }
        if (colon == std::string::npos) return false;
        key = yaml_trim(t.substr(0, colon));
    }
    value = yaml_trim(t.substr(colon + 1));
    return true;
}

/// A decimal number as yaml-cpp reads one into a double (C++ stream extraction, the whole text):
/// an optional sign, digits with an optional point, an optional exponent. Not hexadecimal, not
/// inf or nan (strtod takes them; nav2 refuses them). False when `v` is not one.
inline bool yaml_decimal(const std::string& v, double& x) {
    std::size_t i = 0, digits = 0;
    if (i < v.size() && (v[i] == '+' || v[i] == '-')) ++i;
    for (; i < v.size() && std::isdigit(static_cast<unsigned char>(v[i])); ++i) ++digits;
    if (i < v.size() && v[i] == '.')
        for (++i; i < v.size() && std::isdigit(static_cast<unsigned char>(v[i])); ++i) ++digits;
    if (digits == 0) return false;
    if (i < v.size() && (v[i] == 'e' || v[i] == 'E')) {
        std::size_t e = i + 1;
        if (e < v.size() && (v[e] == '+' || v[e] == '-')) ++e;
        const std::size_t first = e;
        while (e < v.size() && std::isdigit(static_cast<unsigned char>(v[e]))) ++e;
        if (e == first) return false;
        i = e;
    }
    if (i != v.size()) return false;
    x = std::strtod(v.c_str(), nullptr);
    return true;
}

/// map_server's `negate` as nav2 reads it: an integer first (nonzero: true, as ROS1's int), then a
/// YAML 1.1 boolean as yaml-cpp reads one (y/yes/true/on and n/no/false/off, in lower case,
/// Capitalised or UPPER CASE): 1 for true, 0 for false, -1 otherwise.
inline int yaml_flag(const std::string& v) {
    const std::size_t digits = v.find_first_not_of("0123456789", v.empty() || (v[0] != '+' && v[0] != '-') ? 0 : 1);
    if (!v.empty() && digits == std::string::npos && v.find_first_of("0123456789") != std::string::npos)
        return v.find_first_of("123456789") != std::string::npos ? 1 : 0;
    auto all = [&](std::size_t from, bool upper) {
        return std::all_of(v.begin() + static_cast<std::ptrdiff_t>(from), v.end(), [&](char c) {
            return upper ? std::isupper(static_cast<unsigned char>(c)) != 0 : std::islower(static_cast<unsigned char>(c)) != 0;
        });
    };
    if (v.empty() || !(all(0, false) || (std::isupper(static_cast<unsigned char>(v[0])) && (all(1, false) || all(1, true)))))
        return -1;
    std::string low = v;
    for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* t : {"y", "yes", "true", "on"})
        if (low == t) return 1;
    for (const char* f : {"n", "no", "false", "off"})
        if (low == f) return 0;
    return -1;
}

/// One key of map_server's flat mapping: its value's text on the key's line, or the items of a
/// block list (`- x` lines) under it.
struct YamlEntry {
    std::string key, value;
    int line = 0;
    std::vector<std::pair<std::string, int>> items;  // text and line
    int item_indent = -1;
    int nested = 0;  // the first line indented under the key that is not one of its list items
};

/// map_server's YAML: `image`, `resolution`, `origin: [x, y, yaw]`, `negate`, `occupied_thresh`,
/// `free_thresh` (all required, as map_server and nav2 require them), `mode` (optional: trinary;
/// scale and raw are refused). Numbers are decimal, as yaml-cpp reads them. A reader of that flat schema in the
/// YAML its files are written in: `key: value` lines or one flow mapping `{key: value, ...}`, plain
/// or quoted scalars, `#` comments, `origin` as `[x, y, yaw]` or a block list of `- x` lines,
/// `negate` as an integer or a YAML 1.1 boolean (as nav2 reads it), a UTF-8 byte order mark, `---` and `...`
/// (the first document is read, as yaml-cpp's LoadFile does). Lines indented under a key that is not
/// read are skipped with it. Anything else is an error naming the line. Written here, not with
/// yaml-cpp: the schema is seven flat keys, and the CLI and the wheel carry no YAML dependency for it.
inline LoadedMap read_ros_yaml(const std::string& path, MapReadOptions o) {
    std::string data = read_bytes(path);
    if (data.compare(0, 3, "\xEF\xBB\xBF") == 0) data.erase(0, 3);
    std::vector<std::string> lines;
    for (std::size_t a = 0; a <= data.size();) {
        std::size_t b = data.find('\n', a);
        if (b == std::string::npos) b = data.size();
        lines.push_back(data.substr(a, b - a));
        a = b + 1;
    }
    int lineno = 0;
    auto fail = [&](const std::string& why) -> void {
        throw InputError(path + (lineno > 0 ? ":" + std::to_string(lineno) : std::string()) + ": " + why);
    };
    auto number = [&](const std::string& key, const std::string& v) {
        double x = 0.0;
        if (!yaml_decimal(v, x) || !std::isfinite(x)) fail(printable(key) + ": expected a finite decimal number, got '" + printable(v) + "'");
        return x;
    };

    std::vector<YamlEntry> entries;
    int base = -1;               // the mapping's indentation
    bool open = false;           // the last key's value is still to come (nothing after its colon)
    bool started = false, flow = false;
    for (std::size_t k = 0; k < lines.size(); ++k) {
        lineno = static_cast<int>(k) + 1;
        std::string text = yaml_uncomment(lines[k]);
        std::string t = yaml_trim(text);
        if (t.empty() || (!started && t[0] == '%')) continue;  // a directive (%YAML 1.1) before `---`
        const std::size_t indent = text.find_first_not_of(" \t");
        if (indent == 0 && t.compare(0, 3, "---") == 0 && (t.size() == 3 || one_of(t[3], " \t"))) {
            if (started) break;  // a second document
            started = true;
            t = yaml_trim(t.substr(3));
            if (t.empty()) continue;
            if (t[0] != '{') fail("expected a new line after '---', got '" + printable(t) + "'");
        } else if (indent == 0 && t == "...") {
            break;
        }
        started = true;
        if (flow) fail("text after the flow mapping '{...}': '" + printable(t) + "'");
        if (t[0] == '{' && entries.empty()) {
            // one flow mapping, perhaps over several lines; `at` holds each character's line
            std::string acc = t;
            std::vector<int> at(acc.size(), lineno);
            const int first = lineno;
            YamlCloser closer;
            std::size_t close = std::string::npos;
            while ((close = closer(acc)) == std::string::npos) {
                if (++k >= lines.size()) {
                    lineno = first;
                    fail("the flow mapping '{' is not closed");
                }
                const std::string more = "\n" + yaml_uncomment(lines[k]);
                acc += more;
                at.insert(at.end(), more.size(), static_cast<int>(k) + 1);
            }
            lineno = at[close];
            if (!yaml_trim(acc.substr(close + 1)).empty())
                fail("text after the flow mapping '{...}': '" + printable(yaml_trim(acc.substr(close + 1))) + "'");
            for (const auto& [a, b] : yaml_split(acc, 1, close)) {
                const std::string item = yaml_trim(acc.substr(a, b - a));
                if (item.empty()) {
                    if (b == close) continue;  // `{a: 1, }`
                    lineno = at[a];
                    fail("empty entry in the flow mapping");
                }
                YamlEntry e;
                e.line = lineno = at[acc.find_first_not_of(" \t\r\n", a)];
                if (!yaml_key_value(item, e.key, e.value, fail)) fail("expected 'key: value', got '" + printable(item) + "'");
                entries.push_back(std::move(e));
            }
            flow = true;
            continue;
        }
        const int ind = static_cast<int>(indent);
        if (base < 0) base = ind;
        const bool item = t[0] == '-' && (t.size() == 1 || one_of(t[1], " \t"));
        if (!entries.empty() && ind >= base && (ind > base || (item && open))) {
            // under the last key: its list items, or lines that matter only if the key is read
            YamlEntry& e = entries.back();
            if (item && open && e.nested == 0 && (e.items.empty() || ind == e.item_indent)) {
                e.item_indent = ind;
                e.items.emplace_back(yaml_trim(t.substr(1)), lineno);
            } else if (e.nested == 0) {
                e.nested = lineno;
            }
            continue;
        }
        if (ind != base) fail("unexpected indentation (expected the flat 'key: value' lines of a map_server YAML)");
        YamlEntry e;
        e.line = lineno;
        // a key that is a collection, complex (`? `), an anchor or a tag is not map_server's schema
        if (item || one_of(t[0], "[{?&*!|>%@`") || !yaml_key_value(t, e.key, e.value, fail))
            fail("expected 'key: value', got '" + printable(t) + "'");
        // a flow list may go on over the next lines
        YamlCloser closer;
        if (!e.value.empty() && one_of(e.value[0], "[{"))
            while (closer(e.value) == std::string::npos) {
                if (k + 1 == lines.size()) fail(printable(e.key) + ": '" + e.value.substr(0, 1) + "' is not closed");
                e.value += " " + yaml_trim(yaml_uncomment(lines[++k]));
            }
        open = e.value.empty();
        entries.push_back(std::move(e));
    }
    static const char* const read_keys[] = {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"};
    int key_line[7] = {0, 0, 0, 0, 0, 0, 0};
    auto key_index = [&](const std::string& key) -> int {
        for (int i = 0; i < 7; ++i)
            if (key == read_keys[i]) return i;
        return -1;
    };
    std::string image;
    for (const YamlEntry& e : entries) {
        lineno = e.line;
        const int ki = key_index(e.key);
        if (ki < 0) continue;  // other keys: ignored, as map_server does
        if (key_line[ki] != 0) fail("duplicate key '" + e.key + "' (first at line " + std::to_string(key_line[ki]) + ")");
        key_line[ki] = e.line;
        if (e.nested != 0) {
            if (e.value.empty()) fail(e.key + ": expected " + (e.key == "origin" ? "[x, y, yaw] or a list of numbers" : "a value on the key's line"));
            yaml_scalar(e.value, e.key, fail);  // a block scalar (`|`, `>`) says so
            lineno = e.nested;
            fail(e.key + ": unexpected indented line under its value");
        }
        if (e.key == "origin") {
            std::vector<std::pair<std::string, int>> items = e.items;
            if (items.empty()) {
                if (e.value.size() < 2 || e.value.front() != '[' || yaml_close(e.value) != e.value.size() - 1)
                    fail("origin: expected [x, y, yaw], got '" + printable(e.value) + "'");
                const auto pieces = yaml_split(e.value, 1, e.value.size() - 1);
                for (std::size_t i = 0; i < pieces.size(); ++i) {
                    const std::string piece = yaml_trim(e.value.substr(pieces[i].first, pieces[i].second - pieces[i].first));
                    if (piece.empty() && i + 1 == pieces.size() && i > 0) break;  // `[1, 2, 0, ]`
                    items.emplace_back(piece, e.line);
                }
                if (items.size() == 1 && items[0].first.empty()) items.clear();  // `[]`
            }
            std::vector<double> xs;
            for (const auto& [text, line] : items) {
                lineno = line;
                xs.push_back(number("origin", yaml_scalar(text, "origin", fail)));
            }
            lineno = e.line;
            if (xs.size() != 3)  // map_server and nav2 read three
                fail("origin: expected [x, y, yaw], got " + std::to_string(xs.size()) + " number" + (xs.size() == 1 ? "" : "s"));
            if (xs[2] != 0.0) fail("origin: a rotated map (yaw " + shortest_text(xs[2]) + ") is not supported");
            o.origin = Vec2(xs[0], xs[1]);
            continue;
        }
        if (!e.items.empty()) fail(e.key + ": expected a single value, got a list");
        const std::string val = yaml_scalar(e.value, e.key, fail);
        if (e.key == "image") {
            if (val.empty()) fail("image: expected the image's file name");
            image = val;
        } else if (e.key == "resolution") {
            o.resolution = number(e.key, val);
        } else if (e.key == "negate") {
            // an int for ROS1's map_server; an int or a boolean for nav2's
            const int flag = yaml_flag(val);
            if (flag < 0) fail("negate: expected an integer (0: false, others: true), true or false, got '" + printable(val) + "'");
            o.negate = flag == 1;
        } else if (e.key == "occupied_thresh" || e.key == "free_thresh") {
            (e.key == "occupied_thresh" ? o.occupied_thresh : o.free_thresh) = number(e.key, val);
        } else if (e.key == "mode") {
            // scale and raw give in-between pixels probabilities, not "unknown": no occupied/free rule here
            if (val != "trinary") fail("mode: '" + printable(val) + "' is not supported (trinary); convert the map or give the array");
        }
    }
    lineno = 0;
    // map_server and nav2 refuse a file without these (mode is optional): a forgotten origin would
    // place the map at (0, 0) without a word
    for (int i = 0; i < 6; ++i)
        if (key_line[i] == 0)
            fail("missing '" + std::string(read_keys[i]) +
                 "' (a map_server YAML gives image, resolution, origin, negate, occupied_thresh and free_thresh)");
    std::string why;
    if (const char* key = bad_read_option(o, why)) {
        lineno = key_line[key_index(key)];
        fail(why);
    }
    std::string img = image;
    if (img.front() != '/') {
        const auto slash = path.find_last_of('/');
        if (slash != std::string::npos) img = path.substr(0, slash + 1) + img;
    }
    std::int32_t h = 0, w = 0;
    const std::string ext = lower_ext(img);
    std::vector<double> grey;
    try {
        if (ext == ".pgm") grey = read_pgm(img, h, w);
#ifdef DVORONOI_HAVE_PNG
        else if (ext == ".png") grey = read_png(img, h, w);
#endif
    } catch (const InputError& e) {
        throw InputError(path + ": image: " + e.what());  // e.what() names the image file
    }
    if (ext != ".pgm"
#ifdef DVORONOI_HAVE_PNG
        && ext != ".png"
#endif
    )
        throw InputError(path + ": image '" + printable(image) + "': only PGM" +
#ifdef DVORONOI_HAVE_PNG
                          std::string(" and PNG") +
#else
                          std::string(" (PNG needs a build with libpng)") +
#endif
                          " images are read");
    LoadedMap out = from_grey(grey, h, w, o);
    out.image = img;
    return out;
}

inline LoadedMap read_by_extension(const std::string& path, const std::string& ext, const MapReadOptions& o) {
    if (ext == ".yaml" || ext == ".yml") return read_ros_yaml(path, o);
    std::string why;
    if (bad_read_option(o, why)) throw InputError(path + ": " + why);
    if (ext == ".map") return read_movingai(path, o);
    std::int32_t h = 0, w = 0;
    if (ext == ".pgm") {
        const auto grey = read_pgm(path, h, w);
        return from_grey(grey, h, w, o);
    }
    if (ext == ".png") {
#ifdef DVORONOI_HAVE_PNG
        const auto grey = read_png(path, h, w);
        return from_grey(grey, h, w, o);
#else
        throw InputError(path + ": PNG maps need a build with libpng (install libpng-dev and rebuild), or convert to PGM");
#endif
    }
    throw InputError(path + ": unknown map format '" + ext + "' (expected .yaml, .pgm, .png or .map)");
}

}  // namespace detail

/// Reads a map by its extension: `.yaml`/`.yml` (map_server), `.pgm`, `.png`, `.map` (MovingAI).
/// The options are checked first (resolution finite and positive, origin finite, thresholds in
/// [0, 1] with free_thresh <= occupied_thresh); a YAML's own values are checked the same way, and the
/// grid as the diagrams will (gvd::check_grid), so that a map they would refuse names its file here.
/// \throws InputError naming the file (and line) for unreadable or malformed files or bad options.
inline LoadedMap read_occupancy_map(const std::string& path, const MapReadOptions& o = {}) {
    LoadedMap out = detail::read_by_extension(path, detail::lower_ext(path), o);
    try {
        gvd::check_grid(out.grid);
    } catch (const InputError& e) {
        throw InputError(path + ": " + e.what());
    }
    return out;
}

}  // namespace dvoronoi::io
