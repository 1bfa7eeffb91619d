// `dvoronoi cells POINTS --radius R`: every agent's range-limited Voronoi cell.
#include "common.hpp"

#include "dvoronoi/io/csv.hpp"
#include "dvoronoi/io/geojson.hpp"
#include "dvoronoi/io/json.hpp"
#include "dvoronoi/io/svg.hpp"
#include "dvoronoi/partition/limited_partition.hpp"
#include "dvoronoi/partition/power_partition.hpp"

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

namespace dvoronoi::cli {
namespace {

struct CellsOptions {
    std::string points;
    double radius = 0.0;
    bool radius_given = false;
    std::string method = "auto";
    std::string columns;
    int threads = 0;
    std::string output;
    std::string svg;
    double tolerance = 0.0;
    bool quiet = false;
};

void write_result(std::ostream& os, Format format, const LimitedPartition& p, Method method,
                  double tolerance) {
    switch (format) {
        case Format::Json:
            io::write_json(os, p, method);
            os << '\n';
            break;
        case Format::GeoJson:
            io::write_geojson(os, p, tolerance);
            os << '\n';
            break;
        case Format::Csv: io::write_csv(os, p); break;
    }
}

int run_cells(const CellsOptions& o) {
    // Everything that can be checked without the data is checked before reading it.
    // --columns X,Y,R reads one radius per agent (heterogeneous teams); otherwise --radius is needed.
    const bool radius_column = !o.columns.empty() && io::parse_columns(o.columns, "--columns", true).has_radius();
    if (radius_column && o.radius_given)
        throw UsageError("--radius: not with a radius column (--columns X,Y,R); give one or the other");
    if (!radius_column && !o.radius_given)
        throw UsageError("--radius: required (or one radius per agent with --columns X,Y,R)");
    if (o.radius_given && (!std::isfinite(o.radius) || !(o.radius > 0.0)))
        throw UsageError("--radius: must be a positive finite number, got " + show(o.radius));
    if (!std::isfinite(o.tolerance) || o.tolerance < 0.0)
        throw UsageError("--tolerance: must be a finite number >= 0, got " + show(o.tolerance));
    const Method method = parse_method(o.method);
    const bool to_stdout = o.output.empty() || o.output == "-";
    const Format format = to_stdout ? Format::Json : output_format(o.output, "-o/--output");
    check_outputs(o.output, o.svg, {{o.points, "POINTS"}});

    const io::PointFile file = read_points_argument(o.points, o.columns, true);

    // Create the output files now, so an unwritable destination fails before the computation.
    std::unique_ptr<io::AtomicFile> out, svg;
    if (!to_stdout) out = open_output(o.output, "-o/--output");
    if (!o.svg.empty()) svg = open_output(o.svg, "--svg");

    const LimitedPartition result =
        with_progress("cells", file.points.rows(), o.quiet, &file, [&](const ProgressFn& fn) {
            return radius_column ? limited_cells(file.points, file.radii, method, o.threads, fn)
                                 : limited_cells(file.points, o.radius, method, o.threads, fn);
        });
    return deliver(
        out, svg, [&](std::ostream& os) { write_result(os, format, result, method, o.tolerance); },
        [&](std::ostream& os) { io::write_svg(os, result); });
}

}  // namespace

Command add_cells(CLI::App& parent) {
    auto o = std::make_shared<CellsOptions>();
    CLI::App* sub = parent.add_subcommand(
        "cells",
        "every agent's Voronoi cell clipped to the disk of radius R around it (pieces, limited "
        "neighbours, areas, centroids, perimeters)");
    add_points_options(sub, o->points, o->columns, o->threads);
    sub->add_option_function<double>(
        "-r,--radius",
        [o](const double& r) {
            o->radius = r;
            o->radius_given = true;
        },
        "cell radius R > 0 (each cell is clipped to the disk of radius R; agents within 2R shape it); "
        "or one radius per agent from the file with --columns X,Y,R (power cells clipped to each disk)");
    sub->add_option("-m,--method", o->method,
                    "algorithm: auto (our certified clipping fast path, Boundary Scan where it gives "
                    "up), scan (Boundary Scan on every agent, O(m log m)) or chords (RCVC on every "
                    "agent, O(m^2) worst case); same cells. With a radius column all three run on the "
                    "radical axes (auto's fallback is the exact power-cell clipping)")
        ->check(CLI::IsMember({"auto", "scan", "chords"}))
        ->capture_default_str();
    sub->add_option("-o,--output", o->output,
                    "output file, format from its extension: .json, .geojson (arcs densified) or "
                    ".csv (per-agent table); default or '-': JSON on stdout");
    sub->add_option("--svg", o->svg, "also draw the partition into this SVG file");
    sub->add_option("--tolerance", o->tolerance,
                    "GeoJSON: largest distance between an arc and its chords (default 1e-3 R)");
    sub->add_flag("-q,--quiet", o->quiet, "no progress counter on stderr");
    return {sub, [o] { return run_cells(*o); }};
}

}  // namespace dvoronoi::cli
