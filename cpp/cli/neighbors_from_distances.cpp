// `dvoronoi neighbors-from-distances DISTFILE`: every robot's Voronoi neighbours (Delaunay-path order)
// and hull flag from measured inter-robot distances only (Elwin, Freeman & Lynch), then the
// consistency step.
#include "common.hpp"

#include "dvoronoi/distances/neighbors_from_distances.hpp"
#include "dvoronoi/io/distance_file.hpp"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace dvoronoi::cli {
namespace {

struct DistOptions {
    std::string file;
    std::string output;
    long long n = -1;
    bool squared = false;
    bool average = false;
    bool no_consistency = false;
    int threads = 0;
    bool quiet = false;
};

void write(std::ostream& os, bool csv, const dist::DistanceNeighbors& r, bool squared, const std::vector<Index>& ids) {
    if (csv) {
        io::write_csv(os, r, ids);
    } else {
        io::write_json(os, r, squared, ids);
        os << '\n';
    }
}

int run_distances(const DistOptions& o) {
    const bool to_stdout = o.output.empty() || o.output == "-";
    bool csv = false;
    if (!to_stdout) {
        const Format f = output_format(o.output, "-o/--output");
        if (f == Format::GeoJson)
            throw UsageError("-o/--output: robots known only by distances have no coordinates, so no GeoJSON; use .json or .csv");
        csv = f == Format::Csv;
    }
    check_outputs(o.output, "", {{o.file, "DISTFILE"}});
    const io::DistanceFile file = io::read_distance_file(o.file);
    if (o.n >= 0)
        for (std::size_t k = 0; k < file.rows.size(); ++k)
            if (file.rows[k] >= o.n || file.cols[k] >= o.n)
                throw InputError(file.where(k) + ": robot index " + std::to_string(std::max(file.rows[k], file.cols[k])) +
                                 " is not below --n " + std::to_string(o.n));
    // The file's indices are robot IDs (serial numbers too): robots 0..n-1 in ascending ID order, so
    // memory follows the file, not the largest ID. With --n, robot k is ID k.
    const std::vector<Index> ids = o.n >= 0 ? std::vector<Index>{} : io::robot_ids(file);
    const dist::DistanceGraph g = o.n >= 0 ? io::distance_graph(file, static_cast<Index>(o.n), o.squared, o.average)
                                           : io::distance_graph(file, ids, o.squared, o.average);
    std::unique_ptr<io::AtomicFile> out;
    if (!to_stdout) out = open_output(o.output, "-o/--output");

    const dist::DistanceNeighbors result = [&] {
        try {
            return with_progress("neighbors", g.n, o.quiet, nullptr, [&](const ProgressFn& fn) {
                return dist::neighbors_from_distances(g, !o.no_consistency, o.threads, fn);
            });
        } catch (const RangeError& e) {  // "distances: robot 0: out of the exact range ...": name the file
            throw InputError(file.name + ": " + e.what());
        }
    }();
    std::unique_ptr<io::AtomicFile> no_svg;
    return deliver(out, no_svg, [&](std::ostream& os) { write(os, csv, result, g.squared, ids); });
}

}  // namespace

Command add_neighbors_from_distances(CLI::App& parent) {
    auto o = std::make_shared<DistOptions>();
    CLI::App* sub = parent.add_subcommand(
        "neighbors-from-distances",
        "every robot's Voronoi neighbours (Delaunay-path order) and hull flag from measured inter-robot "
        "distances only (Elwin, Freeman & Lynch), then the consistency step");
    sub->add_option("DISTFILE", o->file,
                    "distance file: 'i j d' per line (robot IDs i, j: non-negative integers such as serial "
                    "numbers; measured distance d > 0), whitespace- or comma-separated, '#' comments, optional "
                    "header; a pair once or in both directions; undetected pairs left out; '-' reads stdin. "
                    "Robots are the IDs in the file, in ascending ID order; outputs name them by ID (JSON: "
                    "\"ids\" gives row k's robot and \"indices\" are IDs, unless the IDs are exactly 0..n-1)")
        ->required();
    sub->add_option("-o,--output", o->output, "output file: .json or .csv (robot,on_hull,detected,neighbors); default or '-': JSON on stdout");
    sub->add_option("-n,--n", o->n, "number of robots: robots are IDs 0..n-1, those without a line isolated "
                                     "(default: the IDs in the file)")->check(count_check(0, 9223372036854775807LL));
    sub->add_flag("--squared", o->squared, "the values are squared distances (exact decisions for exact squared distances)");
    sub->add_flag("--average", o->average, "average the two directions of a pair, e_ij = (s_ij + s_ji) / 2 (default: they must agree)");
    sub->add_flag("--no-consistency", o->no_consistency, "skip the consistency step (the relation may then be asymmetric)");
    sub->add_option("-t,--threads", o->threads, "worker threads (0 = all cores)")->check(threads_check())->capture_default_str();
    sub->add_flag("-q,--quiet", o->quiet, "no progress counter on stderr");
    return {sub, [o] { return run_distances(*o); }};
}

}  // namespace dvoronoi::cli
