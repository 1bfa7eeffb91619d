// Occupancy-map files: map_server's trinary rule on PGM images (checked against the rule written out
// independently), the YAML forms map_server files use, the checks of the options, and error
// locations (FILE:LINE, FILE:LINE:COLUMN for plain PGM). PNG is tested from Python (tests/python/
// test_map_files_ros.py): these test executables are not linked with libpng.
#include "dvoronoi/io/occupancy_map.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

using dvoronoi::InputError;
using dvoronoi::io::LoadedMap;
using dvoronoi::io::MapReadOptions;
using dvoronoi::io::read_occupancy_map;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        std::random_device rd;
        path = fs::temp_directory_path() / ("dvoronoi_om_" + std::to_string(rd()) + std::to_string(rd()));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path / name, std::ios::binary) << bytes;
        return (path / name).string();
    }
};

/// The message of the InputError that reading `path` throws ("" if none).
std::string error_of(const std::string& path, const MapReadOptions& o = {}) {
    try {
        read_occupancy_map(path, o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// Each text, written as `name` in `d`, must make the reader fail with a message whose part after the
/// folder starts with its expected message ("": read without error).
void check_error_tails(TempDir& d, const std::string& name, const std::vector<std::pair<std::string, std::string>>& cases) {
    for (const auto& [text, want] : cases) {
        CAPTURE(text);
        const std::string err = error_of(d.write(name, text));
        const std::string tail = err.substr(err.find_last_of('/') + 1);
        if (want.empty()) CHECK_MESSAGE(err.empty(), err);
        else CHECK_MESSAGE(tail.compare(0, want.size(), want) == 0, tail);
    }
}

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// map_server's trinary rule as image_loader.cpp writes it: 1 occupied, 0 free, -1 unknown.
int map_server_cell(double colour_avg, bool negate, double occ_th = 0.65, double free_th = 0.196) {
    const double occ = negate ? colour_avg / 255.0 : (255.0 - colour_avg) / 255.0;
    return occ > occ_th ? 1 : occ < free_th ? 0 : -1;
}

/// A 1-row binary PGM holding `grey`.
std::string pgm_row(const std::vector<int>& grey, int maxval = 255) {
    std::string s = "P5\n" + std::to_string(grey.size()) + " 1\n" + std::to_string(maxval) + "\n";
    for (int g : grey) {
        if (maxval > 255) s += static_cast<char>(g >> 8);
        s += static_cast<char>(g & 0xff);
    }
    return s;
}

std::vector<int> cells(const LoadedMap& m) { return std::vector<int>(m.grid.occupied.begin(), m.grid.occupied.end()); }

const char* const kBase = "image: m.pgm\nresolution: 0.05\norigin: [1.5, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
/// The keys map_server requires besides image and resolution, for texts about other things.
const std::string kRest = "origin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

}  // namespace

TEST_CASE("every 8-bit grey level follows map_server's trinary rule, with and without negate") {
    TempDir d;
    std::vector<int> grey(256);
    for (int g = 0; g < 256; ++g) grey[static_cast<std::size_t>(g)] = g;
    const std::string path = d.write("levels.pgm", pgm_row(grey));
    for (bool negate : {false, true}) {
        MapReadOptions o;
        o.negate = negate;
        o.unknown_occupied = false;
        const LoadedMap m = read_occupancy_map(path, o);
        std::size_t unknown = 0;
        for (int g = 0; g < 256; ++g) {
            const int want = map_server_cell(g, negate);
            unknown += want == -1;
            CHECK_MESSAGE(m.grid.occupied[static_cast<std::size_t>(g)] == (want == 1 ? 1 : 0), "grey ", g, " negate ", negate);
        }
        CHECK(m.unknown == unknown);
        CHECK(unknown > 0);
    }
}

TEST_CASE("16-bit PGM keeps its precision: v = s / 65535") {
    TempDir d;
    // p = 1 - s / 65535 against 0.65 and 0.196; 22938 and 52691 fall the other way if only the high
    // byte were kept (89 and 205: occupied and unknown)
    const std::vector<int> grey = {22937, 22938, 205 * 257, 52690, 52691, 65535};
    const std::vector<int> want = {1, -1, -1, -1, 0, 0};
    MapReadOptions o;
    o.unknown_occupied = false;
    const LoadedMap m = read_occupancy_map(d.write("w.pgm", pgm_row(grey, 65535)), o);
    for (std::size_t i = 0; i < grey.size(); ++i) {
        const double p = 1.0 - grey[i] / 65535.0;
        REQUIRE((p > 0.65 ? 1 : p < 0.196 ? 0 : -1) == want[i]);  // the expectation is the rule's
        CHECK_MESSAGE(m.grid.occupied[i] == (want[i] == 1 ? 1 : 0), "sample ", grey[i]);
    }
    CHECK(m.unknown == 3);
}

TEST_CASE("map_server YAML written in the forms yaml-cpp accepts") {
    TempDir d;
    std::vector<int> grey = {0, 205, 254, 254};
    d.write("m.pgm", pgm_row(grey));
    const std::string base = kBase;
    auto replace = [&](const std::string& from, const std::string& to) {
        std::string s = base;
        s.replace(s.find(from), from.size(), to);
        return s;
    };
    const std::vector<std::pair<const char*, std::string>> forms = {
        {"plain", base},
        {"negate: false", replace("negate: 0", "negate: false")},
        {"negate: No", replace("negate: 0", "negate: No")},
        {"negate: OFF", replace("negate: 0", "negate: OFF")},
        {"block list origin", replace("origin: [1.5, -2.0, 0.0]", "origin:\n  - 1.5\n  - -2.0   # y\n  - 0.0")},
        {"block list at the key's indentation", replace("origin: [1.5, -2.0, 0.0]", "origin:\n- 1.5\n- -2.0\n- 0.0")},
        {"origin over two lines", replace("origin: [1.5, -2.0, 0.0]", "origin: [1.5,\n         -2.0, 0.0]")},
        {"document markers", "---\n" + base + "...\n"},
        {"directive and marker", "%YAML 1.1\n---   # the map\n" + base},
        {"byte order mark", "\xEF\xBB\xBF" + base},
        {"CRLF", [&] {
             std::string s;
             for (char c : base) s += c == '\n' ? std::string("\r\n") : std::string(1, c);
             return s;
         }()},
        {"flow mapping", "{image: m.pgm, resolution: 0.05, origin: [1.5, -2.0, 0.0], negate: 0, occupied_thresh: 0.65, free_thresh: 0.196}\n"},
        {"flow mapping over lines", "# header\n{image: \"m.pgm\",  # the image\n resolution: 0.05, origin: [1.5, -2.0, 0],\n extra: {a: [1, 2]},\n negate: 0, occupied_thresh: 0.65, free_thresh: 0.196}\n"},
        {"quoted values and keys", "'image': 'm.pgm'\n\"resolution\": \"0.05\"\norigin: ['1.5', \"-2.0\", 0]\nnegate: '0'\noccupied_thresh: \"0.65\"\nfree_thresh: 0.196\n"},
        {"numbers with signs, points and exponents", replace("resolution: 0.05", "resolution: +5e-2")},
        {"nested mapping under an ignored key", base + "meta:\n  author: someone\n  tags:\n    - a\n    - b\nmode: trinary\n"},
        {"a second document is not read", base + "---\nimage: elsewhere.pgm\n"},
    };
    for (const auto& [name, text] : forms) {
        CAPTURE(name);
        const std::string path = d.write("f.yaml", text);
        const std::string err = error_of(path);
        REQUIRE_MESSAGE(err.empty(), err);
        const LoadedMap m = read_occupancy_map(path);
        CHECK(m.grid.resolution == 0.05);
        CHECK(m.grid.origin.x() == 1.5);
        CHECK(m.grid.origin.y() == -2.0);
        CHECK(m.image == (d.path / "m.pgm").string());
        CHECK(m.unknown == 1);
        CHECK(cells(m) == std::vector<int>{1, 1, 0, 0});
    }
    MapReadOptions free_unknown;
    free_unknown.unknown_occupied = false;
    // nav2 reads an integer first (ROS1 an int: nonzero is true), then a YAML 1.1 boolean
    for (const char* yes : {"1", "2", "-1", "+7", "true", "True", "TRUE", "yes", "Yes", "y", "on", "On"}) {
        CAPTURE(yes);
        const LoadedMap m = read_occupancy_map(d.write("n.yaml", replace("negate: 0", std::string("negate: ") + yes)), free_unknown);
        CHECK(cells(m) == std::vector<int>{0, 1, 1, 1});  // with negate p = v: 205 and 254 occupied
    }
    for (const char* no : {"0", "00", "-0", "false", "No", "OFF"}) {
        CAPTURE(no);
        CHECK(cells(read_occupancy_map(d.write("n.yaml", replace("negate: 0", std::string("negate: ") + no)), free_unknown)) ==
              std::vector<int>{1, 0, 0, 0});
    }
}

TEST_CASE("a '#' inside a quoted or plain value is not a comment") {
    TempDir d;
    d.write("a#1.pgm", pgm_row({0, 254}));
    for (const char* text : {"image: 'a#1.pgm'  # c\nresolution: 1\n", "image: \"a#1.pgm\"\nresolution: 1\n", "image: a#1.pgm # c\nresolution: 1\n"}) {
        CAPTURE(text);
        const std::string err = error_of(d.write("q.yaml", text + kRest));
        CHECK(err.empty());
    }
}

TEST_CASE("YAML this reader does not follow is an error naming file and line, never a missing key") {
    TempDir d;
    d.write("m.pgm", pgm_row({0, 254}));
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"image: m.pgm\nresolution: 0.05\n  extra: 1\n", "f.yaml:3: resolution: unexpected indented line under its value"},
        {"  image: m.pgm\nresolution: 0.05\n", "f.yaml:2: unexpected indentation"},
        {"image: m.pgm\nresolution: &r 0.05\n", "f.yaml:2: resolution: YAML anchors, aliases, tags and block scalars are not supported"},
        {"image: m.pgm\nresolution: !!float 0.05\n", "f.yaml:2: resolution: YAML anchors"},
        {"image: |\n  m.pgm\nresolution: 1\n", "f.yaml:1: image: YAML anchors"},
        {"image: m.pgm\nresolution: 1\nnote: a plain scalar\n  over two lines\n" + kRest, ""},
        {"image:\n  m.pgm\nresolution: 1\n", "f.yaml:1: image: expected a value on the key's line"},
        {"image:\nresolution: 1\n", "f.yaml:1: image: expected the image's file name"},
        {"{image: m.pgm, resolution: 0.05\n", "f.yaml:1: the flow mapping '{' is not closed"},
        {"{image: m.pgm, resolution: 0.05}\nnegate: 0\n", "f.yaml:2: text after the flow mapping"},
        {"{image: m.pgm,\n resolution 0.05}\n", "f.yaml:2: expected 'key: value', got 'resolution 0.05'"},
        {"image: m.pgm\nresolution: 0.05\nfoo: [1, 2\nbar: 3\n", "f.yaml:3: foo: '[' is not closed"},
        {"image: m.pgm\nresolution: 1\nresolution: 2\n", "f.yaml:3: duplicate key 'resolution' (first at line 2)"},
        {"image: m.pgm\nresolution: 1\nnegate: maybe\n", "f.yaml:3: negate: expected an integer (0: false, others: true), true or false, got 'maybe'"},
        {"image: m.pgm\nresolution: 1\nnegate: 1.0\n", "f.yaml:3: negate: expected an integer (0: false, others: true), true or false, got '1.0'"},
        {"image: m.pgm\nresolution: 0x10\n", "f.yaml:2: resolution: expected a finite decimal number, got '0x10'"},
        {"image: m.pgm\nresolution: 1e\n", "f.yaml:2: resolution: expected a finite decimal number, got '1e'"},
        {"image: m.pgm\nresolution: inf\n", "f.yaml:2: resolution: expected a finite decimal number, got 'inf'"},
        {"image: m.pgm\nresolution: 1\n", "f.yaml: missing 'origin' (a map_server YAML gives image, resolution, origin, negate, occupied_thresh and free_thresh)"},
        {"image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n", "f.yaml: missing 'free_thresh'"},
        {"image: m.pgm\nresolution: 1\norigin: [1, 2]\n", "f.yaml:3: origin: expected [x, y, yaw], got 2 numbers"},
        {"image: m.pgm\nresolution: 1\norigin:\n  - 1\n  - [2]\n", "f.yaml:5: origin: expected a single value, got '[2]'"},
        {"image: m.pgm\nresolution: 1\norigin:\n  - 1\n  - x\n", "f.yaml:5: origin: expected a finite decimal number, got 'x'"},
        {"image: m.pgm\nresolution: 1\norigin:\n  x: 1\n", "f.yaml:3: origin: expected [x, y, yaw] or a list of numbers"},
        {"image: m.pgm\nresolution: 1\norigin: [1]\n", "f.yaml:3: origin: expected [x, y, yaw], got 1 number"},
        {"image: m.pgm\nresolution: 1\norigin: [1, 2, 0.5]\n", "f.yaml:3: origin: a rotated map (yaw 0.5) is not supported"},
        {"image: \"m.pgm\nresolution: 1\n", "f.yaml:1: unterminated quoted string"},
        {"image: \"m\\q.pgm\"\nresolution: 1\n", "f.yaml:1: unsupported escape '\\q'"},
        {"- image: m.pgm\n", "f.yaml:1: expected 'key: value', got '- image: m.pgm'"},
        {"image: m.pgm\n{resolution: 1}\n", "f.yaml:2: expected 'key: value', got '{resolution: 1}'"},
        {"image: m.pgm\n? resolution\n: 1\n", "f.yaml:2: expected 'key: value', got '? resolution'"},
        {"---\nimage: m.pgm\n--- x\n", "f.yaml: missing 'resolution'"},
        {"--- image: m.pgm\n", "f.yaml:1: expected a new line after '---'"},
        {"resolution: 1\n", "f.yaml: missing 'image'"},
        {"image: m.pgm\nresolution: 1\nmode: raw\n", "f.yaml:3: mode: 'raw' is not supported"},
    };
    check_error_tails(d, "f.yaml", cases);
}

TEST_CASE("thresholds, resolution and origin are checked for bare images, .map files and YAML alike") {
    TempDir d;
    const std::string pgm = d.write("m.pgm", pgm_row({0, 254}));
    const std::string map = d.write("m.map", "type octile\nheight 1\nwidth 2\nmap\n.@\n");
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    struct Case {
        MapReadOptions o;
        std::string want;
    };
    auto with = [](auto set) {
        MapReadOptions o;
        set(o);
        return o;
    };
    const std::vector<Case> cases = {
        {with([](MapReadOptions& o) { o.occupied_thresh = 2.0; }), "occupied_thresh: expected a number in [0, 1], got 2"},
        {with([&](MapReadOptions& o) { o.occupied_thresh = nan; }), "occupied_thresh: expected a number in [0, 1], got nan"},
        {with([&](MapReadOptions& o) { o.free_thresh = nan; }), "free_thresh: expected a number in [0, 1], got nan"},
        {with([](MapReadOptions& o) { o.free_thresh = -1.0; }), "free_thresh: expected a number in [0, 1], got -1"},
        {with([](MapReadOptions& o) { o.occupied_thresh = 0.1, o.free_thresh = 0.9; }), "free_thresh is larger than occupied_thresh (0.9 > 0.1)"},
        {with([](MapReadOptions& o) { o.resolution = 0.0; }), "resolution: must be a positive finite number, got 0"},
        {with([&](MapReadOptions& o) { o.resolution = inf; }), "resolution: must be a positive finite number, got inf"},
        {with([&](MapReadOptions& o) { o.resolution = nan; }), "resolution: must be a positive finite number, got nan"},
        {with([&](MapReadOptions& o) { o.origin = dvoronoi::Vec2(1.0, -inf); }), "origin: must be finite, got (1, -inf)"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.want);
        CHECK(error_of(pgm, c.o) == pgm + ": " + c.want);
        CHECK(error_of(map, c.o) == map + ": " + c.want);
    }
    MapReadOptions edge;  // the ends of the range are allowed
    edge.occupied_thresh = 1.0;
    edge.free_thresh = 1.0;
    CHECK(error_of(pgm, edge).empty());
    edge.occupied_thresh = edge.free_thresh = 0.0;
    CHECK(error_of(pgm, edge).empty());

    const std::string base = "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n";
    CHECK(ends_with(error_of(d.write("a.yaml", base + "occupied_thresh: 1.5\nfree_thresh: 0.196\n")), "a.yaml:5: occupied_thresh: expected a number in [0, 1], got 1.5"));
    CHECK(ends_with(error_of(d.write("b.yaml", base + "occupied_thresh: 0.65\nfree_thresh: -0.1\n")), "b.yaml:6: free_thresh: expected a number in [0, 1], got -0.1"));
    CHECK(ends_with(error_of(d.write("c.yaml", base + "occupied_thresh: 0.1\nfree_thresh: 0.5\n")),
                    "c.yaml:6: free_thresh is larger than occupied_thresh (0.5 > 0.1)"));
    CHECK(ends_with(error_of(d.write("f.yaml", "image: m.pgm\nresolution: -1\n" + kRest)), "f.yaml:2: resolution: must be a positive finite number, got -1"));
    CHECK(ends_with(error_of(d.write("g.yaml", "image: m.pgm\nresolution: .nan\n")), "g.yaml:2: resolution: expected a finite decimal number, got '.nan'"));
}

TEST_CASE("a map the diagrams would refuse (gvd::check_grid) is refused naming its file") {
    TempDir d;
    d.write("m.pgm", pgm_row({0, 254}));
    struct Case {
        const char* text;
        double resolution, origin_x;
    };
    for (const Case& c : {Case{"image: m.pgm\nresolution: 1\norigin: [1e300, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n", 1.0, 1e300},
                          Case{"image: m.pgm\nresolution: 1e300\n", 1e300, 0.0}}) {
        CAPTURE(c.text);
        const std::string path = d.write("f.yaml", c.text + (c.origin_x == 0.0 ? kRest : std::string()));
        const std::string err = error_of(path);
        bool diagram_accepts = true;
        try {
            dvoronoi::gvd::check_grid(dvoronoi::gvd::OccupancyGrid(1, 2, c.resolution, dvoronoi::Vec2(c.origin_x, 0.0)));
        } catch (const InputError&) {
            diagram_accepts = false;
        }
        CHECK(err.empty() == diagram_accepts);
        // the file first; a YAML's resolution out of the range is refused at its line ("f.yaml:2: ")
        if (!err.empty()) CHECK_MESSAGE(err.compare(0, path.size() + 1, path + ":") == 0, err);
    }
}

TEST_CASE("plain PGM errors name the line and column") {
    TempDir d;
    CHECK(error_of(d.write("a.pgm", "P2\n3 2\n255\n0 1 2\n3 x 5\n")) == (d.path / "a.pgm").string() + ":5:3: bad PGM pixel value 'x' (pixel 5 of 6)");
    CHECK(error_of(d.write("b.pgm", "P2\n3 2\n255\n0 1 2\n3 -4 5\n")) == (d.path / "b.pgm").string() + ":5:3: bad PGM pixel value '-4' (pixel 5 of 6)");
    CHECK(error_of(d.write("c.pgm", "P2\n3 2\n255\n0 1 2\n3\n# the end\n")) == (d.path / "c.pgm").string() + ":7:1: truncated PGM data (4 of 6 pixels)");
    // comments between the values are allowed, and the values after them are read
    const LoadedMap m = read_occupancy_map(d.write("d.pgm", "P2\n2 1\n255\n0 # a wall\n254\n"));
    CHECK(cells(m) == std::vector<int>{1, 0});
}

#ifndef DVORONOI_HAVE_PNG
TEST_CASE("without libpng a PNG map is refused with a clear message") {
    TempDir d;
    const std::string path = d.write("m.png", "\x89PNG\r\n\x1a\n");
    CHECK(error_of(path) == path + ": PNG maps need a build with libpng (install libpng-dev and rebuild), or convert to PGM");
}
#endif

TEST_CASE("MovingAI maps: one set of rules (Python's read_movingai_map is this reader), errors naming the line") {
    TempDir d;
    const std::string good = d.write("g.map", "Type octile\r\nHEIGHT 2\r\nwidth 3\r\nmap\r\n.GS\r\n@T.\r\n\r\n");
    const LoadedMap m = read_occupancy_map(good, {});
    CHECK(std::vector<std::uint8_t>(m.grid.occupied.begin(), m.grid.occupied.end()) == std::vector<std::uint8_t>{0, 0, 1, 1, 1, 0});
    MapReadOptions swamp;
    swamp.movingai_free = ".GS";
    CHECK(read_occupancy_map(good, swamp).grid.occupied[2] == 0);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"type octile\nheight 2\nwidth 3\nmap\n...\n... \n", "b.map:6: map row 1 has 4 characters, width is 3"},
        {"type octile\nheight 2\nwidth 3\nmap\n...\n\n...\n", "b.map:6: map row 1 has 0 characters, width is 3"},
        {"type octile\n\nheight 1\nwidth 3\nmap\n...\n", "b.map:2: empty line in the header"},
        {"type octile\nheight 1\nheight 1\nwidth 3\nmap\n...\n", "b.map:3: 'height' given twice"},
        {"type octile grid\nheight 1\nwidth 3\nmap\n...\n", "b.map:1: expected 'type NAME', 'height H', 'width W' or 'map'"},
        {"type octile\nheight -2\nwidth 3\nmap\n...\n", "b.map:2: height must be a positive integer, got '-2'"},
        {"type octile\nheight 1\nwidth 3\nmap\n...\n...\n", "b.map:6: text after the 1 map rows"},
        {"type octile\nheight 2\nwidth 3\nmap\n...\n", "b.map:6: expected 2 map rows, the file has 1"},
        {"type octile\nheight 1\nwidth 3\nmap\n.x.\n", "b.map:5: unknown character 'x' in column 2 (free '.G', blocked the rest of '.G@OTSW')"},
        {"type octile\nwidth 3\nmap\n...\n", "b.map:3: header has no 'height' line"},
        {"type octile\nheight 1\nwidth 3\n", "b.map:4: header ends before the 'map' line"},
        {"type octile\nheight 1\nwidth 2\nmap\n.\xc3\xa9\n", "b.map:5: not an ASCII MovingAI map file"},
    };
    check_error_tails(d, "b.map", cases);
}

TEST_CASE("a PGM raster longer than its header, or a sample above the maximum, is an error naming the file and pixel") {
    TempDir d;
    const std::string dir = d.path.string() + "/";
    // P5: one byte more than 3 x 1 would shear every row if read; a CR LF header leaves exactly one
    CHECK(error_of(d.write("a.pgm", pgm_row({0, 1, 2}) + "x")) ==
          dir + "a.pgm: the PGM raster is longer than its header's 3 x 1 pixels (1 byte after the last pixel)");
    CHECK(error_of(d.write("b.pgm", "P5\r\n3 1\r\n255\r\n\x01\x02\x03")) ==
          dir + "b.pgm: the PGM raster is longer than its header's 3 x 1 pixels (1 byte after the last pixel; the header "
                "ends in CR LF, but one whitespace character ends a P5 header)");
    CHECK(error_of(d.write("c.pgm", pgm_row({0, 150, 7}, 100))) ==
          dir + "c.pgm: PGM pixel value 150 exceeds the maximum grey value 100 (row 0, column 1)");
    CHECK(error_of(d.write("d.pgm", "P5\n2 2\n1000\n" + std::string("\x00\x01\x00\x02\x00\x03\x03\xe9", 8))) ==
          dir + "d.pgm: PGM pixel value 1001 exceeds the maximum grey value 1000 (row 1, column 1)");
    // P2: a value after the last, or above the maximum, names its line and column; comments may follow
    CHECK(error_of(d.write("e.pgm", "P2\n2 1\n255\n0 1\n2\n")) ==
          dir + "e.pgm:5:1: the PGM raster is longer than its header's 2 x 1 pixels ('2' after the last pixel value)");
    CHECK(error_of(d.write("f.pgm", "P2\n3 1\n100\n0 150 999\n")) ==
          dir + "f.pgm:4:3: PGM pixel value '150' exceeds the maximum grey value 100 (row 0, column 1)");
    CHECK(error_of(d.write("g.pgm", "P2\n2 1\n100\n0 100\n# the end\n\n")).empty());
    CHECK(cells(read_occupancy_map(d.write("h.pgm", pgm_row({0, 100}, 100)))) == std::vector<int>{1, 0});  // maxval itself is fine
}

TEST_CASE("a folder or a missing file named like a map says so") {
    TempDir d;
    fs::create_directories(d.path / "dir.pgm");
    fs::create_directories(d.path / "dir.map");
    CHECK(error_of((d.path / "dir.pgm").string()) == (d.path / "dir.pgm").string() + ": is a folder, not a file");
    CHECK(error_of((d.path / "dir.map").string()) == (d.path / "dir.map").string() + ": is a folder, not a file");
    CHECK(error_of((d.path / "nope.pgm").string()) == (d.path / "nope.pgm").string() + ": cannot open file: it does not exist");
    // a YAML whose image is a folder names both
    const std::string yaml = d.write("m.yaml", "image: dir.pgm\nresolution: 1\n" + kRest);
    CHECK(error_of(yaml) == yaml + ": image: " + (d.path / "dir.pgm").string() + ": is a folder, not a file");
}

TEST_CASE("the resolution's range is printed exactly: its printed ends are accepted") {
    TempDir d;
    const std::string pgm = d.write("m.pgm", pgm_row({0, 254}));
    MapReadOptions o;
    o.resolution = std::numeric_limits<double>::min() / 2;  // positive, finite, below the range
    const std::string err = error_of(pgm, o);
    const std::string want = "resolution: must lie in [2.2250738585072014e-308, 4.0874809539271057e+295]";
    REQUIRE_MESSAGE(err.find(want) != std::string::npos, err);
    for (const char* end : {"2.2250738585072014e-308", "4.0874809539271057e+295"}) {
        o.resolution = std::strtod(end, nullptr);
        CHECK_MESSAGE(error_of(pgm, o).empty(), end);
    }
    o.resolution = std::nextafter(std::strtod("4.0874809539271057e+295", nullptr), 1e300);
    CHECK(error_of(pgm, o).find(want) != std::string::npos);
}

TEST_CASE("MovingAI: every character of .G@OTSW is valid, those not free are blocked") {
    TempDir d;
    const std::string path = d.write("g.map", "type octile\nheight 1\nwidth 7\nmap\n.G@OTSW\n");
    MapReadOptions o;
    o.movingai_free = ".";
    CHECK(cells(read_occupancy_map(path, o)) == std::vector<int>{0, 1, 1, 1, 1, 1, 1});
    o.movingai_free = "TW";
    CHECK(cells(read_occupancy_map(path, o)) == std::vector<int>{1, 1, 1, 1, 0, 1, 0});
}
