// `dvoronoi voronoi POINTS [--bounds XMIN YMIN XMAX YMAX]`: every agent's exact Voronoi cell by
// Adjust-Sensing-Radius (neighbours, hull flags, cells clipped to the bounds).
#include "common.hpp"

#include "dvoronoi/io/voronoi_export.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace dvoronoi::cli {
namespace {

struct VoronoiOptions {
    std::string points;
    std::string inner = "auto";
    std::vector<double> bounds;
    std::string columns;
    int threads = 0;
    std::string output;
    std::string svg;
    bool quiet = false;
};

void write_result(std::ostream& os, Format format, const VoronoiPartition& p, AsrInner inner) {
    switch (format) {
        case Format::Json:
            io::write_json(os, p, inner);
            os << '\n';
            break;
        case Format::GeoJson:
            io::write_geojson(os, p);
            os << '\n';
            break;
        case Format::Csv: io::write_csv(os, p); break;
    }
}

int run_voronoi(const VoronoiOptions& o) {
    // Everything that can be checked without the data is checked before reading it.
    ConvexRegion region;
    if (!o.bounds.empty()) {
        try {
            region = ConvexRegion::box(o.bounds[0], o.bounds[1], o.bounds[2], o.bounds[3], "--bounds");
        } catch (const InputError& e) {
            throw UsageError(e.what());
        }
    }
    const AsrInner inner = o.inner == "evt" ? AsrInner::Evt : o.inner == "scan" ? AsrInner::Scan : AsrInner::Auto;
    const bool to_stdout = o.output.empty() || o.output == "-";
    const Format format = to_stdout ? Format::Json : output_format(o.output, "-o/--output");
    check_outputs(o.output, o.svg, {{o.points, "POINTS"}});

    const io::PointFile file = read_points_argument(o.points, o.columns);

    // Create the output files now, so an unwritable destination fails before the computation.
    std::unique_ptr<io::AtomicFile> out, svg;
    if (!to_stdout) out = open_output(o.output, "-o/--output");
    if (!o.svg.empty()) svg = open_output(o.svg, "--svg");

    const VoronoiPartition result =
        with_progress("voronoi", file.points.rows(), o.quiet, &file, [&](const ProgressFn& fn) {
            return voronoi_cells(file.points, inner, o.threads, fn, region);
        });
    return deliver(
        out, svg, [&](std::ostream& os) { write_result(os, format, result, inner); },
        [&](std::ostream& os) { io::write_svg(os, result); });
}

}  // namespace

Command add_voronoi(CLI::App& parent) {
    auto o = std::make_shared<VoronoiOptions>();
    CLI::App* sub = parent.add_subcommand(
        "voronoi",
        "every agent's exact Voronoi cell by Adjust-Sensing-Radius: Voronoi neighbours, hull flags "
        "(unbounded cells), areas and centroids of the cells clipped to --bounds");
    add_points_options(sub, o->points, o->columns, o->threads);
    sub->add_option("--bounds", o->bounds,
                    "XMIN YMIN XMAX YMAX: clip every cell to this box (hull agents' cells are "
                    "unbounded; without bounds they have no area and are drawn as rays)")
        ->expected(4);
    sub->add_option("--inner", o->inner,
                    "auto (our fast path: one certified clipping per agent, a Delaunay triangulation of "
                    "the few it leaves), or ASR on every agent with inner step scan (Boundary Scan, "
                    "ASR+BS) or evt (exact tessellation of the agents in range, ASR+EVT); same cells")
        ->check(CLI::IsMember({"auto", "scan", "evt"}))
        ->capture_default_str();
    sub->add_option("-o,--output", o->output,
                    "output file, format from its extension: .json, .geojson (polygons; null for "
                    "unbounded cells) or .csv (per-agent table); default or '-': JSON on stdout");
    sub->add_option("--svg", o->svg, "also draw the cells into this SVG file");
    sub->add_flag("-q,--quiet", o->quiet, "no progress counter on stderr");
    return {sub, [o] { return run_voronoi(*o); }};
}

}  // namespace dvoronoi::cli
