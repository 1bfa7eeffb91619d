// Occupancy-grid map files: ROS map_server YAML (with its PGM or PNG image), PGM (P2/P5), PNG and the
// MovingAI benchmark `.map` text format (docs/spec.md, "Grid diagram on occupancy grids").
//
// Grey images follow map_server's trinary rule: with v the grey level scaled to [0, 1] (the mean of
// the colour channels, alpha ignored), the occupancy probability is p = 1 - v (p = v with `negate`); p > occupied_thresh is
// occupied, p < free_thresh free, anything between unknown. Unknown pixels count as occupied unless
// the caller says otherwise. MovingAI maps: `.` and `G` free, `@ O T S W` blocked, any other character
// an error naming the line and column.
//
// Errors: InputError whose message starts with `FILE:` (and `LINE:` for text formats). PNG needs
// libpng: the CLI and the Python module are built with it when CMake finds it
// (DVORONOI_HAVE_PNG); other builds refuse PNG files with a clear message.
#pragma once

#include "dvoronoi/gvd/occupancy_grid.hpp"
#include "dvoronoi/io/quote.hpp"

#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifdef DVORONOI_HAVE_PNG
#include <png.h>
#endif

namespace dvoronoi::io {

struct MapReadOptions {
    bool unknown_occupied = true;  ///< unknown pixels (between the thresholds) count as occupied
    double resolution = 1.0;       ///< map units per pixel (images without YAML)
    Vec2 origin = Vec2(0.0, 0.0);  ///< lower-left corner (images without YAML)
    double occupied_thresh = 0.65;
    double free_thresh = 0.196;
    bool negate = false;
};

/// A loaded map and what the loader saw.
struct LoadedMap {
    gvd::OccupancyGrid grid;
    std::size_t unknown = 0;  ///< pixels between the thresholds (counted as set by unknown_occupied)
    std::string image;        ///< the image file a YAML pointed to
};

namespace detail {

inline std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline std::string lower_ext(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot);
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

/// Grey levels in [0, 1] (row 0 at the top) to occupancy by map_server's trinary rule.
inline LoadedMap from_grey(const std::vector<double>& grey, std::int32_t h, std::int32_t w, const MapReadOptions& o) {
    LoadedMap out;
    out.grid = gvd::OccupancyGrid(h, w, o.resolution, o.origin);
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
    std::vector<double> grey(n);
    if (magic == "P5") {
        const std::size_t bytes = maxval < 256 ? 1 : 2;
        for (std::size_t i = 0; i < n; ++i) {
            const auto* p = reinterpret_cast<const unsigned char*>(data.data() + pos + i * bytes);
            const unsigned v = bytes == 1 ? p[0] : (static_cast<unsigned>(p[0]) << 8 | p[1]);
            grey[i] = static_cast<double>(std::min<unsigned>(v, static_cast<unsigned>(maxval))) / static_cast<double>(maxval);
        }
    } else {
        for (std::size_t i = 0; i < n; ++i) {
            while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
            if (pos >= data.size()) throw InputError(path + ": truncated PGM data (" + std::to_string(i) + " of " + std::to_string(n) + " pixels)");
            const long long v = number("pixel value", 0);
            grey[i] = static_cast<double>(std::min(v, maxval)) / static_cast<double>(maxval);
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

inline std::vector<double> read_png(const std::string& path, std::int32_t& h, std::int32_t& w) {
    png_image img;
    std::memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    const std::string data = read_bytes(path);
    if (!png_image_begin_read_from_memory(&img, data.data(), data.size()))
        throw InputError(path + ": not a readable PNG image (" + img.message + ")");
    check_size(path, img.width, img.height);
    check_png_data(path, data, img.width, img.height);
    // As map_server reads images: the mean of the colour channels as stored, alpha ignored (libpng's
    // own grey conversion would weight by luminance and composite alpha onto black).
    img.format = PNG_FORMAT_RGBA;
    std::vector<unsigned char> px(PNG_IMAGE_SIZE(img));
    if (!png_image_finish_read(&img, nullptr, px.data(), 0, nullptr))
        throw InputError(path + ": cannot decode PNG image (" + img.message + ")");
    w = static_cast<std::int32_t>(img.width);
    h = static_cast<std::int32_t>(img.height);
    std::vector<double> grey(px.size() / 4);
    for (std::size_t i = 0; i < grey.size(); ++i)
        grey[i] = (px[4 * i] + px[4 * i + 1] + px[4 * i + 2]) / (3.0 * 255.0);
    return grey;
}
#endif

/// The MovingAI `.map` format: `type`, `height H`, `width W`, `map`, then H lines of W characters.
inline LoadedMap read_movingai(const std::string& path, const MapReadOptions& o) {
    std::istringstream in(read_bytes(path));
    std::string line;
    int lineno = 0;
    long long H = -1, W = -1;
    auto fail = [&](const std::string& why) -> void { throw InputError(path + ":" + std::to_string(lineno) + ": " + why); };
    auto strip = [](std::string& s) {
        while (!s.empty() && (s.back() == '\r' || s.back() == '\n' || s.back() == ' ' || s.back() == '\t')) s.pop_back();
    };
    for (;;) {
        if (!std::getline(in, line)) { ++lineno; fail("missing 'map' line (expected 'type', 'height', 'width', 'map')"); }
        ++lineno;
        strip(line);
        if (line.empty()) continue;
        std::istringstream ls(line);
        std::string key;
        ls >> key;
        if (key == "map") break;
        if (key == "type") continue;
        if (key == "height" || key == "width") {
            long long v = -1;
            std::string rest;
            if (!(ls >> v) || (ls >> rest)) fail("expected '" + printable(key) + " N', got '" + printable(line) + "'");
            (key == "height" ? H : W) = v;
        } else {
            fail("unknown header line '" + printable(line) + "'");
        }
    }
    if (H < 0 || W < 0) fail("header lacks 'height' or 'width'");
    check_size(path, W, H);
    // The rows are read before the grid is allocated: memory follows the file, not its header.
    std::vector<std::uint8_t> cells;
    for (std::int32_t r = 0; r < H; ++r) {
        ++lineno;
        if (!std::getline(in, line)) fail("map ends after " + std::to_string(r) + " of " + std::to_string(H) + " rows");
        strip(line);
        if (static_cast<long long>(line.size()) != W)
            fail("row " + std::to_string(r) + " has " + std::to_string(line.size()) + " characters, expected " + std::to_string(W));
        for (std::int32_t c = 0; c < W; ++c) {
            const char ch = line[static_cast<std::size_t>(c)];
            if (std::strchr(".G@OTSW", ch) == nullptr || ch == '\0')
                fail("column " + std::to_string(c + 1) + ": unknown map character (code " +
                     std::to_string(static_cast<int>(static_cast<unsigned char>(ch))) + "); expected one of . G @ O T S W");
            cells.push_back(ch == '.' || ch == 'G' ? 0 : 1);
        }
    }
    LoadedMap out;
    out.grid = gvd::OccupancyGrid(static_cast<std::int32_t>(H), static_cast<std::int32_t>(W), o.resolution, o.origin);
    for (std::int32_t r = 0; r < H; ++r)
        for (std::int32_t c = 0; c < W; ++c)
            out.grid.occupied[out.grid.at(r, c)] = cells[static_cast<std::size_t>(r) * static_cast<std::size_t>(W) + static_cast<std::size_t>(c)];
    while (std::getline(in, line)) {
        ++lineno;
        strip(line);
        if (!line.empty()) fail("text after the map's " + std::to_string(H) + " rows");
    }
    return out;
}

/// map_server's YAML: `image`, `resolution`, `origin: [x, y, yaw]`, `negate`, `occupied_thresh`,
/// `free_thresh`, `mode` (trinary; scale and raw are refused). A line-based reader of that flat schema.
inline LoadedMap read_ros_yaml(const std::string& path, MapReadOptions o) {
    std::istringstream in(read_bytes(path));
    std::string line, image;
    int lineno = 0;
    bool has_resolution = false;
    auto fail = [&](const std::string& why) -> void {
        throw InputError(path + (lineno > 0 ? ":" + std::to_string(lineno) : std::string()) + ": " + why);
    };
    auto trim = [](std::string s) {
        const auto a = s.find_first_not_of(" \t\r\n");
        if (a == std::string::npos) return std::string();
        const auto b = s.find_last_not_of(" \t\r\n");
        return s.substr(a, b - a + 1);
    };
    auto number = [&](const std::string& key, const std::string& v) {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0' || !std::isfinite(x)) fail(printable(key) + ": expected a finite number, got '" + printable(v) + "'");
        return x;
    };
    while (std::getline(in, line)) {
        ++lineno;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line = line.substr(0, hash);
        line = trim(line);
        if (line.empty()) continue;
        const auto colon = line.find(':');
        if (colon == std::string::npos) fail("expected 'key: value', got '" + printable(line) + "'");
        const std::string key = trim(line.substr(0, colon));
        std::string val = trim(line.substr(colon + 1));
        if (val.size() >= 2 && (val.front() == '"' || val.front() == '\'') && val.back() == val.front())
            val = val.substr(1, val.size() - 2);
        if (key == "image") {
            image = val;
        } else if (key == "resolution") {
            o.resolution = number(key, val);
            if (!(o.resolution > 0)) fail("resolution: must be positive, got '" + printable(val) + "'");
            has_resolution = true;
        } else if (key == "origin") {
            if (val.size() < 2 || val.front() != '[' || val.back() != ']') fail("origin: expected [x, y, yaw], got '" + printable(val) + "'");
            std::vector<double> xs;
            std::stringstream ss(val.substr(1, val.size() - 2));
            std::string item;
            while (std::getline(ss, item, ',')) xs.push_back(number("origin", trim(item)));
            if (xs.size() != 3 && xs.size() != 2) fail("origin: expected [x, y, yaw], got '" + printable(val) + "'");
            if (xs.size() == 3 && xs[2] != 0.0) fail("origin: a rotated map (yaw " + printable(trim(val)) + ") is not supported");
            o.origin = Vec2(xs[0], xs[1]);
        } else if (key == "negate") {
            const double v = number(key, val);
            if (v != 0.0 && v != 1.0) fail("negate: expected 0 or 1, got '" + printable(val) + "'");
            o.negate = v != 0.0;
        } else if (key == "occupied_thresh" || key == "free_thresh") {
            const double v = number(key, val);
            if (v < 0.0 || v > 1.0) fail(key + ": expected a number in [0, 1], got '" + printable(val) + "'");
            (key == "occupied_thresh" ? o.occupied_thresh : o.free_thresh) = v;
        } else if (key == "mode") {
            // scale and raw give in-between pixels probabilities, not "unknown": no occupied/free rule here
            if (val != "trinary") fail("mode: '" + printable(val) + "' is not supported (trinary); convert the map or give the array");
        }  // other keys: ignored, as map_server does
    }
    lineno = 0;
    if (image.empty()) fail("missing 'image'");
    if (!has_resolution) fail("missing 'resolution'");
    if (o.free_thresh > o.occupied_thresh) fail("free_thresh is larger than occupied_thresh");
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

}  // namespace detail

/// Reads a map by its extension: `.yaml`/`.yml` (map_server), `.pgm`, `.png`, `.map` (MovingAI).
/// \throws InputError naming the file (and line) for unreadable or malformed files.
inline LoadedMap read_occupancy_map(const std::string& path, const MapReadOptions& o = {}) {
    const std::string ext = detail::lower_ext(path);
    if (ext == ".yaml" || ext == ".yml") return detail::read_ros_yaml(path, o);
    if (ext == ".map") return detail::read_movingai(path, o);
    std::int32_t h = 0, w = 0;
    if (ext == ".pgm") {
        const auto grey = detail::read_pgm(path, h, w);
        return detail::from_grey(grey, h, w, o);
    }
    if (ext == ".png") {
#ifdef DVORONOI_HAVE_PNG
        const auto grey = detail::read_png(path, h, w);
        return detail::from_grey(grey, h, w, o);
#else
        throw InputError(path + ": PNG maps need a build with libpng (install libpng-dev and rebuild), or convert to PGM");
#endif
    }
    throw InputError(path + ": unknown map format '" + ext + "' (expected .yaml, .pgm, .png or .map)");
}

}  // namespace dvoronoi::io
