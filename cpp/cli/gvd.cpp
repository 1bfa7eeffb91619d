// `dvoronoi gvd OBSTACLES.json --grid N`: the grid Voronoi diagram of obstacles (Mendes et al.),
// traced by K slice workers (threads), with clearance, roadmap and an optional path.
// `dvoronoi gvd MAP.{yaml,pgm,png,map}`: the medial diagram of an occupancy grid (docs/spec.md, "Grid diagram
// on occupancy grids"), with clearance and an optional path for a disk robot.
#include "common.hpp"
#include "map_options.hpp"

#include "dvoronoi/gvd/grid_path.hpp"
#include "dvoronoi/io/medial_export.hpp"
#include "dvoronoi/io/occupancy_map.hpp"

#include <filesystem>
#include <thread>

#include "dvoronoi/gvd/grid_voronoi.hpp"
#include "dvoronoi/gvd/rasterize.hpp"
#include "dvoronoi/io/gvd_json.hpp"
#include "dvoronoi/io/gvd_svg.hpp"
#include "dvoronoi/io/obstacles_json.hpp"

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace dvoronoi::cli {
namespace {

struct GvdCliOptions {
    std::string obstacles;
    std::int64_t grid = 0;
    int workers = 0;  // 0: all cores
    std::string mode = "cooperative";
    double robot_radius = 0.0;
    bool no_visibility = false;
    std::vector<double> path;
    std::string output;
    std::string svg;
    bool quiet = false;
    std::string diagram;  // empty: medial for maps, labels for obstacle files
    cli_maps::MapOptions map;  // occupancy maps
};

using cli_maps::is_map_file;

/// Checks shared by both inputs; returns whether the JSON goes to stdout.
bool check_common(const GvdCliOptions& o) {
    if (o.workers < 0) throw UsageError("--workers: must be 0 (all cores) or positive, got " + std::to_string(o.workers));
    const bool to_stdout = cli_maps::check_run_options(o.robot_radius, o.path, o.output);
    check_outputs(o.output, o.svg, {{o.obstacles, "INPUT"}});
    return to_stdout;
}

int workers_of(const GvdCliOptions& o) {
    return o.workers == 0 ? static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) : o.workers;
}

/// The medial diagram of `grid` (a map's, or an obstacle file drawn on its pixels: `document`) with
/// the optional path, written to the opened outputs.
int write_medial(const GvdCliOptions& o, const gvd::OccupancyGrid& grid, std::size_t unknown, bool document,
                 std::unique_ptr<io::AtomicFile> out, std::unique_ptr<io::AtomicFile> svg) {
    const gvd::MedialOptions mo = o.map.medial(workers_of(o));
    const auto t0 = std::chrono::steady_clock::now();
    const gvd::MedialDiagram m = gvd::medial_diagram(grid, mo);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<Vec2> path_points;
    const nlohmann::json doc = cli_maps::medial_json(m, o.robot_radius, o.path, path_points);
    const std::size_t n = m.count();
    if (!o.quiet) {
        if (document)
            std::fprintf(stderr, "gvd: obstacle file drawn on %d x %d pixels, %zu diagram pixels, %d worker(s), %.3f s\n",
                         m.grid.rows, m.grid.cols, n, mo.workers, seconds);
        else
            std::fprintf(stderr, "gvd: %d x %d map, %zu diagram pixels, %zu unknown pixels (%s), %d worker(s), %.3f s\n",
                         m.grid.rows, m.grid.cols, n, unknown, o.map.unknown == "occupied" ? "occupied" : "free", mo.workers,
                         seconds);
    }
    if (n == 0) o.map.warn_empty("gvd", m.grid, unknown, document);  // a warning, not the summary: shown with -q too
    return deliver(
        out, svg, [&](std::ostream& os) { os << doc.dump() << '\n'; },
        [&](std::ostream& os) { io::write_medial_svg(os, m, o.robot_radius, path_points); });
}

int run_map(const GvdCliOptions& o) {
    if (o.diagram == "labels")
        throw UsageError("--diagram: the CLI draws the medial diagram of map files; for the labelled diagram use "
                         "Python's dv.grid_voronoi(map, diagram=\"labels\")");
    if (o.grid != 0 || o.mode != "cooperative" || o.no_visibility)
        throw UsageError("--grid, --mode and --no-visibility are for obstacle files: a map's diagram grid is its pixels");
    o.map.check(o.obstacles);
    const bool to_stdout = check_common(o);
    const io::LoadedMap map = io::read_occupancy_map(o.obstacles, o.map.read_options());
    check_outputs(o.output, o.svg, {{map.image, "the image of INPUT"}});  // a YAML's image is known now
    std::unique_ptr<io::AtomicFile> out, svg;
    if (!to_stdout) out = open_output(o.output, "-o/--output");
    if (!o.svg.empty()) svg = open_output(o.svg, "--svg");
    return write_medial(o, map.grid, map.unknown, false, std::move(out), std::move(svg));
}

int run_gvd(const GvdCliOptions& o) {
    cli_maps::check_input(o.obstacles);  // a folder, a missing file, a JPEG: said before any option check
    if (is_map_file(o.obstacles)) return run_map(o);
    const bool medial = o.diagram == "medial";
    cli_maps::check_document_options(o.map, o.obstacles, o.grid, medial, o.mode, o.no_visibility);
    const bool to_stdout = check_common(o);

    const io::ObstacleFile file = io::read_obstacles(o.obstacles);
    std::unique_ptr<io::AtomicFile> out, svg;
    if (medial) {  // the file drawn on --grid pixels along the area's longer side, as Python's diagram="medial"
        gvd::OccupancyGrid grid;
        try {
            grid = gvd::rasterize(file.scene, o.grid);
        } catch (const InputError& e) {  // e.g. an area too wide for a grid: name the file
            throw InputError(o.obstacles + ": " + e.what());
        }
        if (!to_stdout) out = open_output(o.output, "-o/--output");
        if (!o.svg.empty()) svg = open_output(o.svg, "--svg");
        return write_medial(o, grid, 0, true, std::move(out), std::move(svg));
    }
    if (!to_stdout) out = open_output(o.output, "-o/--output");
    if (!o.svg.empty()) svg = open_output(o.svg, "--svg");

    gvd::GvdOptions opt;
    opt.resolution = o.grid;
    opt.workers = workers_of(o);
    opt.mode = o.mode == "independent" ? gvd::SliceMode::Independent : gvd::SliceMode::Cooperative;
    opt.robot_radius = o.robot_radius;
    opt.visibility = !o.no_visibility;
    const auto t0 = std::chrono::steady_clock::now();
    const gvd::GridVoronoi r = [&] {
        try {
            return gvd::grid_voronoi(file.scene, opt);
        } catch (const InputError& e) {  // coordinates out of range (exact tests, the grid): name the file
            throw InputError(o.obstacles + ": " + e.what());
        }
    }();
    nlohmann::json doc = io::gvd_to_json(r);
    std::vector<Vec2> path_points;
    cli_maps::add_labelled_path(doc, r, file.scene, o.path, path_points);
    if (!o.quiet)
        std::fprintf(stderr, "gvd: %zu diagram cells, %zu vertices, %llu corners labelled, %d worker(s), %.3f s\n",
                     r.size(), r.vertices.size(), static_cast<unsigned long long>(r.stats.corners_labelled),
                     r.stats.workers, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (r.size() == 0)  // as Python warns; shown with -q too
        std::fprintf(stderr, "gvd: warning: no diagram cell: the corners of every cell share one nearest obstacle (an "
                             "obstacle covers the working area)\n");
    return deliver(
        out, svg, [&](std::ostream& os) { os << doc.dump() << '\n'; },
        [&](std::ostream& os) { io::write_gvd_svg(os, file.scene, r, path_points); });
}

}  // namespace

Command add_gvd(CLI::App& parent) {
    auto o = std::make_shared<GvdCliOptions>();
    CLI::App* sub = parent.add_subcommand(
        "gvd", "grid Voronoi diagram of obstacles (Mendes et al.): diagram cells, clearance, blocked cells, "
               "Voronoi vertices, roadmap; slice-parallel workers");
    sub->add_option("INPUT", o->obstacles,
                    "an occupancy map (.yaml map_server, .pgm, .png, MovingAI .map: the medial diagram) or an "
                    "obstacle file (JSON: {\"area\": {\"box\": [x0, y0, x1, y1]}, \"obstacles\": [{\"type\": "
                    "\"polygon\"|\"circle\"|\"point\"|\"segment\"|\"union\", ...}]}; see the README)")
        ->required();
    sub->add_option("-g,--grid", o->grid, "obstacle files: cells along the longer side of the working area");
    sub->add_option("-w,--workers", o->workers, "worker threads (map files: 0 = all cores); same diagram for any count")->capture_default_str();
    sub->add_option("--diagram", o->diagram, "medial (map files' default; obstacle files drawn on --grid pixels) or labels "
                                             "(obstacle files' default: Mendes et al.)")
        ->check(CLI::IsMember({"medial", "labels"}));
o->map.add_to(*sub);
    sub->add_option("-m,--mode", o->mode, "slice approach: cooperative (each border scanned once, seeds sent "
                                          "to the left neighbour) or independent (no communication)")
        ->check(CLI::IsMember({"cooperative", "independent"}))
        ->capture_default_str();
    sub->add_option("-r,--robot-radius", o->robot_radius, "robot radius (map units): diagram cells this close to an "
                                                          "obstacle are blocked; paths keep this clearance")->capture_default_str();
    sub->add_flag("--no-visibility", o->no_visibility, "turn the paper's edge visibility test off");
    sub->add_option("--path", o->path, "also plan a path SX SY GX GY along the diagram")->expected(4);
    sub->add_option("-o,--output", o->output, "output JSON file (default or '-': stdout)");
    sub->add_option("--svg", o->svg, "also draw the diagram into this SVG file");
    sub->add_flag("-q,--quiet", o->quiet, "no summary line on stderr");
    return {sub, [o] { return run_gvd(*o); }};
}

}  // namespace dvoronoi::cli
