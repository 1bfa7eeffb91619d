// The map options of `dvoronoi gvd MAP` and `dvoronoi_gvd_mpi MAP` (one set of flags, checks and
// messages for both programs): how a map file is read and the medial diagram's parameters; the checks
// both programs make of their other options, and the medial diagram's JSON with its path.
#pragma once

#include "common.hpp"
#include "dvoronoi/gvd/grid_path.hpp"
#include "dvoronoi/gvd/medial_diagram.hpp"
#include "dvoronoi/gvd/path.hpp"
#include "dvoronoi/io/medial_export.hpp"
#include "dvoronoi/io/occupancy_map.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace dvoronoi::cli_maps {

inline bool is_map_file(const std::string& path) {
    const std::string e = io::detail::lower_ext(path);
    return e == ".yaml" || e == ".yml" || e == ".pgm" || e == ".png" || e == ".map";
}

/// The first check of INPUT in both programs, before any option check, so that a wrong file is not
/// taken for an obstacle document missing --grid: a folder; and, for an input that is no map file by
/// its extension, a missing file or one that is not JSON (an obstacle document is a JSON object). A
/// missing or unreadable map is named by its reader, after the option checks. \throws InputError
inline void check_input(const std::string& input) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(input, ec))
        throw InputError("'" + input + "' is a folder: give a map file (.yaml, .pgm, .png, .map) or an obstacle document (.json)");
    if (is_map_file(input)) return;
    if (!fs::exists(input, ec) && !ec) throw InputError(input + ": cannot open file: it does not exist");
    if (io::detail::lower_ext(input) == ".json") return;  // the JSON reader names what is wrong, with line and column
    std::ifstream in(input, std::ios::binary);
    if (!in) return;  // unreadable: the reader says so
    char bom[3] = {};
    if (!in.read(bom, 3) || std::string(bom, 3) != "\xEF\xBB\xBF") {  // a UTF-8 byte order mark is skipped
        in.clear();
        in.seekg(0);
    }
    in >> std::ws;
    if (in.peek() != '{')
        throw InputError(input + ": neither a map file nor an obstacle document (not JSON): maps are read from .yaml/.yml "
                                 "(map_server), .pgm, .png and .map (MovingAI) files, obstacle documents from JSON (.json)");
}

struct MapOptions {
    double resolution = 1.0;  // images without YAML
    bool resolution_given = false;
    std::vector<double> origin;
    std::string unknown = "occupied";
    double min_separation = 1.5, prune_length = 8.0;
    /// Were the medial diagram's parameters given other values than the defaults?
    bool medial_changed() const { return min_separation != 1.5 || prune_length != 8.0; }
    /// Were the options that say how a map file is read (--resolution, --origin, --unknown) given
    /// (or, for --unknown, given another value than the default)? Obstacle files refuse them.
    bool reading_given() const { return resolution_given || !origin.empty() || unknown != "occupied"; }

    /// Registers --resolution, --origin, --unknown, --min-separation and --prune-length on `app`.
    void add_to(CLI::App& app) {
        app.add_option("--resolution", resolution, "map files without YAML: map units per pixel (default 1)")
            ->each([this](const std::string&) { resolution_given = true; });
        app.add_option("--origin", origin, "map files without YAML: map coordinates X Y of the lower-left corner")->expected(2);
        app.add_option("--unknown", unknown, "map files: unknown pixels count as occupied or free")
            ->check(CLI::IsMember({"occupied", "free"}))
            ->capture_default_str();
        app.add_option("--min-separation", min_separation,
                       "medial diagram: nearest points of a pair farther apart than this (pixels)")
            ->capture_default_str();
        app.add_option("--prune-length", prune_length,
                       "medial diagram: pairs whose nearest points are this close and joined by walls are dropped (pixels)")
            ->capture_default_str();
    }

    /// \throws InputError naming the option.
    void check(const std::string& input) const {
        auto num = [](double v) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.17g", v);
            return std::string(buf);
        };
        if (resolution_given && !(resolution > 0.0 && std::isfinite(resolution)))
            throw InputError("--resolution: must be a positive number (map units per pixel), got " + num(resolution));
        if (resolution_given && !gvd::resolution_in_range(resolution))
            throw InputError("--resolution: must lie in " + gvd::resolution_range() +
                             " (map units per pixel) so that map coordinates stay finite, got " + num(resolution));
        const std::string ext = io::detail::lower_ext(input);
        if ((ext == ".yaml" || ext == ".yml") && (resolution_given || !origin.empty()))
            throw InputError("--resolution/--origin: a map_server YAML brings its own resolution and origin");
        if (ext == ".map" && unknown != "occupied")
            throw InputError("--unknown: a MovingAI map has no unknown cells");
        if (!origin.empty() && origin.size() != 2) throw InputError("--origin: expects X Y");
        for (double v : origin)
            if (!std::isfinite(v)) throw InputError("--origin: coordinates must be finite, got " + num(v));
        if (!(min_separation >= 1.0 && min_separation <= 32768.0))
            throw InputError("--min-separation: must be a number in [1, 32768] (pixels), got " + num(min_separation));
        if (!std::isfinite(prune_length) || prune_length < 0.0 || prune_length > 256.0)
            throw InputError("--prune-length: must be a finite number in [0, 256] (pixels), got " + num(prune_length));
    }

    io::MapReadOptions read_options() const {
        io::MapReadOptions ro;
        ro.unknown_occupied = unknown == "occupied";
        if (resolution_given) ro.resolution = resolution;
        if (!origin.empty()) ro.origin = Vec2(origin[0], origin[1]);
        return ro;
    }

    gvd::MedialOptions medial(int workers) const {
        gvd::MedialOptions mo;
        mo.min_separation = min_separation;
        mo.prune_length = prune_length;
        mo.workers = workers;
        return mo;
    }

    /// The warning when a map (or an obstacle file drawn on pixels, `document`) gives no diagram pixel,
    /// naming why (`unknown` pixels counted as occupied or free by --unknown).
    void warn_empty(const char* program, const gvd::OccupancyGrid& g, std::size_t unknown_pixels, bool document = false) const {
        const bool full = std::all_of(g.occupied.begin(), g.occupied.end(), [](std::uint8_t v) { return v != 0; });
        if (full && document) {
            std::fprintf(stderr, "%s: warning: no diagram pixel: every pixel of the obstacle file drawn on %d x %d pixels meets "
                                 "an obstacle (no free space, or none a pixel wide: a larger --grid draws finer)\n",
                         program, g.rows, g.cols);
            return;
        }
        if (full) {
            std::fprintf(stderr, "%s: warning: no diagram pixel: every pixel of the %d x %d map is occupied (check the map's "
                                 "negate and thresholds%s)\n",
                         program, g.rows, g.cols,
                         unknown_pixels > 0 && unknown == "occupied"
                             ? ("; " + std::to_string(unknown_pixels) + " of them are unknown, which --unknown free would make free").c_str()
                             : "");
            return;
        }
        std::fprintf(stderr, "%s: warning: no diagram pixel: no two neighbouring free pixels have nearest walls more than "
                             "--min-separation %.3g pixels apart that are not joined by walls within --prune-length %.3g "
                             "pixels (the free space is under 2 pixels wide, or only small pockets)\n",
                     program, min_separation, prune_length);
    }
};

/// The checks of an obstacle file's options in both programs (after the folder check): --grid is
/// required, and an option this input or diagram does not read is an error, not silently dropped.
/// \throws InputError naming the option.
inline void check_document_options(const MapOptions& map, const std::string& input, std::int64_t grid, bool medial,
                                   const std::string& mode, bool no_visibility) {
    if (grid < 1) throw InputError("--grid: required for obstacle files, at least 1, got " + std::to_string(grid));
    if (map.reading_given())
        throw InputError("--resolution, --origin and --unknown are for map files: an obstacle file has its own "
                         "coordinates and no unknown pixels");
    if (medial && (mode != "cooperative" || no_visibility))
        throw InputError("--mode and --no-visibility are the labelled diagram's; --diagram medial does not use them");
    if (!medial && map.medial_changed())
        throw InputError("--min-separation and --prune-length are the medial diagram's; add --diagram medial");
    if (medial) map.check(input);
}

/// The checks of --robot-radius, --path and -o in both programs, for either input; returns whether
/// the JSON goes to stdout. \throws InputError naming the option.
inline bool check_run_options(double robot_radius, const std::vector<double>& path, const std::string& output) {
    if (!std::isfinite(robot_radius) || robot_radius < 0.0)
        throw InputError("--robot-radius: must be a finite number >= 0, got " + cli::show(robot_radius));
    if (!path.empty() && path.size() != 4) throw InputError("--path: expects SX SY GX GY");
    for (double v : path)
        if (!std::isfinite(v)) throw InputError("--path: coordinates must be finite");
    const bool to_stdout = output.empty() || output == "-";
    if (!to_stdout && io::detail::lower_ext(output) != ".json")
        throw InputError("-o/--output: the grid diagram is written as JSON; use a .json file or '-'");
    return to_stdout;
}

/// The medial diagram's JSON, with the path of --path SX SY GX GY (when given) planned for the robot
/// radius; its points go to `points` for the picture. One function, so that both programs write the
/// same bytes. \throws InputError naming --path.
inline nlohmann::json medial_json(const gvd::MedialDiagram& m, double robot_radius, const std::vector<double>& path,
                                  std::vector<Vec2>& points) {
    nlohmann::json doc = io::medial_to_json(m, robot_radius);
    if (path.empty()) return doc;
    gvd::GridPath p;
    try {
        p = gvd::find_grid_path(m, Vec2(path[0], path[1]), Vec2(path[2], path[3]), robot_radius);
    } catch (const InputError& e) {
        throw InputError(std::string("--path: ") + e.what());
    }
    points = p.points;
    doc["path"] = io::path_to_json(p);
    return doc;
}

/// Adds to the labelled diagram's JSON `doc` the path of --path SX SY GX GY (when given) among the
/// scene's obstacles; its points go to `points` for the picture. One function, so that both programs
/// write the same bytes. \throws InputError naming --path.
inline void add_labelled_path(nlohmann::json& doc, const gvd::GridVoronoi& r, const gvd::Scene& scene,
                              const std::vector<double>& path, std::vector<Vec2>& points) {
    if (path.empty()) return;
    const gvd::ObstacleIndex index(scene);
    gvd::PathResult p;
    try {
        p = gvd::find_path(r, scene, index, Vec2(path[0], path[1]), Vec2(path[2], path[3]));
    } catch (const InputError& e) {
        throw InputError(std::string("--path: ") + e.what());
    }
    points = p.points;
    doc["path"] = io::path_to_json(p);  // as the medial diagram's
}

}  // namespace dvoronoi::cli_maps
