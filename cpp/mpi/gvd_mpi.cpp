// dvoronoi_gvd_mpi: the grid Voronoi diagram computed by a team of MPI ranks, in two modes chosen by
// the input's extension, as `dvoronoi gvd` chooses them.
//
//   mpirun -n K dvoronoi_gvd_mpi OBSTACLES.json --grid N [--mode cooperative|independent]
//          [--robot-radius R] [--path SX SY GX GY] [-o OUT.json] [--svg OUT.svg] [-q]
//   mpirun -n K dvoronoi_gvd_mpi OBSTACLES.json --grid N --diagram medial [--min-separation S]
//          [--prune-length L] [--robot-radius R] [--path SX SY GX GY] [-o OUT.json] [--svg OUT.svg] [-q]
//   mpirun -n K dvoronoi_gvd_mpi MAP.{yaml,pgm,png,map} [--robot-radius R] [--min-separation S]
//          [--prune-length L] [--unknown occupied|free] [--resolution M] [--origin X Y]
//          [--path SX SY GX GY] [-o OUT.json] [--svg OUT.svg] [-q]
//
// The options, checks, messages and outputs are `dvoronoi gvd`'s (workers are ranks here).
//
// Obstacle files: one vertical slice per rank (Mendes et al., Section 3), as the paper ran it on a
// cluster. Rank 0 reads the obstacle file and broadcasts it (the paper broadcasts the obstacle data to
// every robot). Each rank runs gvd::run_slice on its slice: in the cooperative approach a rank sends
// the rows of the label changes on its left border to its left neighbour (one small message). Each
// rank then sends a summary of its traced components to rank 0, which joins them across the borders
// and answers which to keep; the kept cells go to rank 0, which writes the same JSON as `dvoronoi gvd`.
//
// Map files, and obstacle files with --diagram medial (drawn on --grid pixels by rank 0): the medial
// diagram (medial_diagram.hpp), one band of rows per rank. Rank 0 reads the map and broadcasts it;
// every rank runs the column pass of the nearest-point transform over the whole map (it needs whole
// columns, and is cheap), the row pass over its band and one halo row on each side,
// and marks its band. Rank 0 gathers the bands and the nearest points of the diagram pixels (of every
// pixel for a path: the search reads clearances anywhere) and writes the bytes `dvoronoi gvd` writes.
//
// The diagram is identical for every K (and both approaches).
//
// Exit codes as the CLI: 0 success, 2 bad command line or input (rank 0 prints the message), 1 other.
#include "../cli/common.hpp"
#include "../cli/map_options.hpp"
#include "dvoronoi/gvd/grid_voronoi.hpp"
#include "dvoronoi/gvd/path.hpp"
#include "dvoronoi/gvd/rasterize.hpp"
#include "dvoronoi/io/atomic_write.hpp"
#include "dvoronoi/io/gvd_json.hpp"
#include "dvoronoi/io/gvd_svg.hpp"
#include "dvoronoi/io/medial_export.hpp"
#include "dvoronoi/io/obstacles_json.hpp"
#include "dvoronoi/io/occupancy_map.hpp"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace dvoronoi;

struct Args {
    std::string input;
    std::int64_t grid = 0;
    std::string mode = "cooperative";
    double robot_radius = 0.0;
    bool no_visibility = false;
    std::string diagram;  // empty: medial for maps, labels for obstacle files
    std::vector<double> path;
    std::string output, svg;
    bool quiet = false;
    cli_maps::MapOptions map;  // map files, as `dvoronoi gvd MAP`
};

using cli_maps::is_map_file;

std::vector<std::int32_t> pack(const gvd::SliceSummary& s) {
    std::vector<std::int32_t> v{s.n_components};
    for (auto a : s.anchored) v.push_back(a);
    v.push_back(static_cast<std::int32_t>(s.left_links.size()));
    v.insert(v.end(), s.left_links.begin(), s.left_links.end());
    v.push_back(static_cast<std::int32_t>(s.right_links.size()));
    v.insert(v.end(), s.right_links.begin(), s.right_links.end());
    return v;
}

gvd::SliceSummary unpack(const std::int32_t* v) {
    gvd::SliceSummary s;
    std::size_t k = 0;
    s.n_components = v[k++];
    for (std::int32_t c = 0; c < s.n_components; ++c) s.anchored.push_back(static_cast<std::uint8_t>(v[k++]));
    const std::int32_t nl = v[k++];
    s.left_links.assign(v + k, v + k + nl);
    k += static_cast<std::size_t>(nl);
    const std::int32_t nr = v[k++];
    s.right_links.assign(v + k, v + k + nr);
    return s;
}

/// Gathers variable-length arrays of T (as bytes) on rank 0.
template <class T>
std::vector<T> gather(const std::vector<T>& mine, int rank, int size, std::vector<int>* counts_out = nullptr) {
    const int bytes = static_cast<int>(mine.size() * sizeof(T));
    std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
    MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<T> all;
    if (rank == 0) {
        int total = 0;
        for (int r = 0; r < size; ++r) {
            displs[static_cast<std::size_t>(r)] = total;
            total += counts[static_cast<std::size_t>(r)];
        }
        all.resize(static_cast<std::size_t>(total) / sizeof(T));
    }
    MPI_Gatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
    if (counts_out) *counts_out = counts;
    return all;
}

/// Rank 0: opens the outputs before any work, as the CLI does (--svg naming the -o file by another
/// path, ./a.json or a link, is refused: one would be lost; so is an output naming INPUT or a YAML's
/// `image`).
void open_outputs(const Args& a, bool to_stdout, std::unique_ptr<io::AtomicFile>& out, std::unique_ptr<io::AtomicFile>& svg,
                  const std::string& image = std::string()) {
    cli::check_outputs(to_stdout ? std::string() : a.output, a.svg, {{a.input, "INPUT"}, {image, "the image of INPUT"}});
    if (!to_stdout) out = cli::open_output(a.output, "-o/--output");
    if (!a.svg.empty()) svg = cli::open_output(a.svg, "--svg");
}

/// Rank 0 runs `read` (which reads the input and opens the outputs); an InputError there ends every
/// rank with its message.
template <class Read>
void on_rank0(int rank, Read&& read) {
    int ok = 1;
    std::string error;
    if (rank == 0) {
        try {
            read();
        } catch (const InputError& e) {
            ok = 0;
            error = e.what();
        } catch (const cli::UsageError& e) {
            ok = 0;
            error = e.what();
        }
    }
    MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!ok) throw InputError(error);
}

int run_medial(const Args& a, int rank, int size, gvd::OccupancyGrid grid, std::size_t unknown, bool document,
               std::unique_ptr<io::AtomicFile> out, std::unique_ptr<io::AtomicFile> svg);

int run_obstacles(const Args& a, int rank, int size) {
    // the same checks and messages as `dvoronoi gvd`, on every rank alike
    const bool medial = a.diagram == "medial";
    cli_maps::check_document_options(a.map, a.input, a.grid, medial, a.mode, a.no_visibility);
    const bool to_stdout = cli_maps::check_run_options(a.robot_radius, a.path, a.output);
    // Rank 0 reads and parses the file, then opens the outputs (as the CLI: a bad file is named first,
    // an unwritable output fails before any work). For the labelled diagram it broadcasts the text and
    // every rank parses it (same scene everywhere); for the medial diagram rank 0 draws it on --grid
    // pixels (as `dvoronoi gvd` and Python's diagram="medial") and hands the map on.
    std::string text;
    std::optional<io::ObstacleFile> parsed;
    std::unique_ptr<io::AtomicFile> out, svg;
    gvd::OccupancyGrid drawn;
    on_rank0(rank, [&] {
        std::ifstream in(a.input, std::ios::binary);
        if (!in) throw InputError(a.input + ": cannot open file");
        std::ostringstream s;
        s << in.rdbuf();
        text = s.str();
        parsed = io::parse_obstacles(text, a.input);
        if (medial) {
            try {
                drawn = gvd::rasterize(parsed->scene, a.grid);
            } catch (const InputError& e) {  // e.g. an area too wide for a grid: name the file
                throw InputError(a.input + ": " + e.what());
            }
            gvd::check_grid(drawn);  // resolution and origin in range, as the CLI's medial_diagram checks
        }
        open_outputs(a, to_stdout, out, svg);
    });
    if (medial) return run_medial(a, rank, size, std::move(drawn), 0, true, std::move(out), std::move(svg));
    unsigned long long len = text.size();
    MPI_Bcast(&len, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    text.resize(len);
    MPI_Bcast(text.data(), static_cast<int>(len), MPI_CHAR, 0, MPI_COMM_WORLD);
    if (rank != 0) parsed = io::parse_obstacles(text, a.input);
    const io::ObstacleFile& file = *parsed;

    gvd::GvdOptions opt;
    opt.resolution = a.grid;
    opt.robot_radius = a.robot_radius;
    opt.workers = size;
    opt.mode = a.mode == "independent" ? gvd::SliceMode::Independent : gvd::SliceMode::Cooperative;
    opt.visibility = !a.no_visibility;
    gvd::check_options(opt);
    const gvd::GridSpec grid = [&] {
        try {
            return gvd::make_grid(file.scene, opt.resolution);
        } catch (const InputError& e) {  // e.g. an area too wide for a grid: name the file
            throw InputError(a.input + ": " + e.what());
        }
    }();
    if (size > grid.nx) throw InputError("more ranks (" + std::to_string(size) + ") than grid columns (" + std::to_string(grid.nx) + ")");

    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = gvd::thread_cpu_seconds();
    const gvd::ObstacleIndex index(file.scene, opt.visibility);
    const auto bounds = gvd::slice_bounds(grid.nx, size);
    gvd::SliceTracer tracer(file.scene, index, grid, bounds[static_cast<std::size_t>(rank)], bounds[static_cast<std::size_t>(rank) + 1]);
    MPI_Request send_req = MPI_REQUEST_NULL;
    std::vector<std::int32_t> outbox;
    gvd::BorderChannel ch;
    ch.send_left = [&](const std::vector<std::int32_t>& rows) {
        outbox = rows;
        MPI_Isend(outbox.data(), static_cast<int>(outbox.size()), MPI_INT32_T, rank - 1, 1, MPI_COMM_WORLD, &send_req);
    };
    ch.receive_right = [&]() {
        MPI_Status st;
        MPI_Probe(rank + 1, 1, MPI_COMM_WORLD, &st);
        int n = 0;
        MPI_Get_count(&st, MPI_INT32_T, &n);
        std::vector<std::int32_t> rows(static_cast<std::size_t>(n));
        MPI_Recv(rows.data(), n, MPI_INT32_T, rank + 1, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        return rows;
    };
    std::uint64_t lines = 0;
    const gvd::SliceSummary summary = gvd::run_slice(tracer, rank, size, opt.mode, ch, lines);
    MPI_Wait(&send_req, MPI_STATUS_IGNORE);
    const double traced_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double traced_cpu = gvd::thread_cpu_seconds() - cpu0;

    // Join on rank 0: summaries in, keep flags out.
    std::vector<int> counts;
    const std::vector<std::int32_t> packed = gather(pack(summary), rank, size, &counts);
    std::vector<std::uint8_t> keep_all;
    std::vector<int> keep_counts(static_cast<std::size_t>(size)), keep_displs(static_cast<std::size_t>(size));
    if (rank == 0) {
        std::vector<gvd::SliceSummary> all;
        std::size_t off = 0;
        for (int r = 0; r < size; ++r) {
            all.push_back(unpack(packed.data() + off));
            off += static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]) / sizeof(std::int32_t);
        }
        const auto keep = gvd::keep_components(all);
        int total = 0;
        for (int r = 0; r < size; ++r) {
            keep_counts[static_cast<std::size_t>(r)] = static_cast<int>(keep[static_cast<std::size_t>(r)].size());
            keep_displs[static_cast<std::size_t>(r)] = total;
            total += keep_counts[static_cast<std::size_t>(r)];
            keep_all.insert(keep_all.end(), keep[static_cast<std::size_t>(r)].begin(), keep[static_cast<std::size_t>(r)].end());
        }
    }
    std::vector<std::uint8_t> keep(static_cast<std::size_t>(summary.n_components));
    MPI_Scatterv(keep_all.data(), keep_counts.data(), keep_displs.data(), MPI_UINT8_T, keep.data(), summary.n_components,
                 MPI_UINT8_T, 0, MPI_COMM_WORLD);
    const unsigned long long traced = tracer.size(), traced_bytes = tracer.memory_bytes();  // before the hand-over
    std::vector<gvd::TracedCell> mine;
    gvd::append_kept(tracer, keep, mine);
    std::vector<gvd::TracedCell> cells = gather(mine, rank, size);  // same binary on every rank: bytes are fine

    // Statistics.
    const gvd::QueryContext& c = tracer.context();
    unsigned long long local[6] = {c.queries, c.counters.part_evaluations, c.counters.edge_evaluations,
                                   traced, lines, traced_bytes};
    unsigned long long sum[6] = {0, 0, 0, 0, 0, 0}, peak = 0;
    MPI_Reduce(local, sum, 5, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    MPI_Reduce(&local[5], &peak, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, 0, MPI_COMM_WORLD);
    std::vector<double> seconds(static_cast<std::size_t>(size));
    MPI_Gather(&traced_seconds, 1, MPI_DOUBLE, seconds.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    std::vector<unsigned long long> evaluations(static_cast<std::size_t>(size));
    const unsigned long long my_evaluations = local[1] + local[2];
    MPI_Gather(&my_evaluations, 1, MPI_UNSIGNED_LONG_LONG, evaluations.data(), 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    std::vector<double> cpu_seconds(static_cast<std::size_t>(size));
    MPI_Gather(&traced_cpu, 1, MPI_DOUBLE, cpu_seconds.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (rank != 0) return 0;

    const std::size_t kept = cells.size();
    std::vector<std::vector<gvd::TracedCell>> slices(1);
    slices[0].swap(cells);
    gvd::GridVoronoi r = gvd::assemble(file.scene, grid, std::move(slices), opt.robot_radius);
    r.stats.workers = size;
    r.stats.mode = opt.mode;
    r.stats.corners_labelled = sum[0];
    r.stats.part_evaluations = sum[1];
    r.stats.edge_evaluations = sum[2];
    r.stats.traced_cells = sum[3];
    r.stats.border_lines_scanned = sum[4];
    r.stats.discarded_cells = sum[3] - kept;
    r.stats.peak_worker_bytes = peak;
    r.stats.worker_seconds = seconds;
    r.stats.worker_cpu_seconds = cpu_seconds;
    r.stats.worker_evaluations.assign(evaluations.begin(), evaluations.end());
    gvd::build_graph(r);
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json doc = io::gvd_to_json(r);
    doc["stats"]["total_seconds"] = total;
    std::vector<Vec2> path_points;
    cli_maps::add_labelled_path(doc, r, file.scene, a.path, path_points);  // as `dvoronoi gvd` plans it
    // As the CLI delivers: each file appears whole or not at all
    const int code = cli::deliver(
        out, svg, [&](std::ostream& os) { os << doc.dump() << '\n'; },
        [&](std::ostream& os) { io::write_gvd_svg(os, file.scene, r, path_points); }, "dvoronoi_gvd_mpi");
    if (!a.quiet)
        std::fprintf(stderr, "dvoronoi_gvd_mpi: %zu diagram cells, %d ranks (%s), %.3f s\n", r.size(), size,
                     io::mode_name(opt.mode), total);
    if (r.size() == 0)  // the CLI's warning, shown with -q too
        std::fprintf(stderr, "dvoronoi_gvd_mpi: warning: no diagram cell: the corners of every cell share one nearest "
                             "obstacle (an obstacle covers the working area)\n");
    return code;
}

int run_map(const Args& a, int rank, int size) {
    // The same checks and messages as `dvoronoi gvd MAP`; every rank sees the same arguments, so all
    // throw together.
    if (a.diagram == "labels")
        throw InputError("--diagram: dvoronoi_gvd_mpi draws the medial diagram of map files; for the labelled diagram use "
                         "Python's dv.grid_voronoi(map, diagram=\"labels\")");
    if (a.grid != 0 || a.mode != "cooperative" || a.no_visibility)
        throw InputError("--grid, --mode and --no-visibility are for obstacle files: a map's diagram grid is its pixels");
    a.map.check(a.input);
    const bool to_stdout = cli_maps::check_run_options(a.robot_radius, a.path, a.output);
    // Rank 0 reads the map and opens the outputs (an unwritable output fails before any work).
    io::LoadedMap map;
    std::unique_ptr<io::AtomicFile> out, svg;
    on_rank0(rank, [&] {
        map = io::read_occupancy_map(a.input, a.map.read_options());
        try {
            gvd::check_grid(map.grid);
        } catch (const InputError& e) {
            throw InputError(a.input + ": " + e.what());
        }
        open_outputs(a, to_stdout, out, svg, map.image);
    });
    return run_medial(a, rank, size, std::move(map.grid), map.unknown, false, std::move(out), std::move(svg));
}

/// The medial diagram of `grid` (complete on rank 0: a map's, or an obstacle file drawn on its
/// pixels, `document`), one band of rows per rank, written by rank 0 as `dvoronoi gvd` writes it.
int run_medial(const Args& a, int rank, int size, gvd::OccupancyGrid grid, std::size_t unknown, bool document,
               std::unique_ptr<io::AtomicFile> out, std::unique_ptr<io::AtomicFile> svg) {
    const gvd::MedialOptions mo = a.map.medial(1);
    // Broadcast: sizes, resolution, origin, then the occupancy bytes.
    std::int32_t dims[2] = {grid.rows, grid.cols};
    double geom[3] = {grid.resolution, grid.origin.x(), grid.origin.y()};
    MPI_Bcast(dims, 2, MPI_INT32_T, 0, MPI_COMM_WORLD);
    MPI_Bcast(geom, 3, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (rank != 0) grid = gvd::OccupancyGrid(dims[0], dims[1], geom[0], Vec2(geom[1], geom[2]));
    const std::int32_t H = dims[0], W = dims[1];
    MPI_Bcast(grid.occupied.data(), static_cast<int>(grid.size()), MPI_UINT8_T, 0, MPI_COMM_WORLD);

    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = std::chrono::steady_clock::now();
    gvd::MedialDiagram m;
    m.grid = std::move(grid);
    m.options = mo;
    m.features = gvd::feature_map_for(m.grid);  // this rank writes (and reads) only its band's rows
    gvd::FeatureMap& f = m.features;
    m.mask = gvd::PixelMask(H, W);
    m.boxed = gvd::PixelMask(H, W);
    // Bands as medial_diagram splits rows over threads; with more ranks than rows some are empty.
    auto band = [&](int k) { return static_cast<std::int32_t>(static_cast<std::int64_t>(H) * k / size); };
    const std::int32_t r0 = band(rank), r1 = band(rank + 1);
    // the box rule reads walls anywhere near the band's nearest points; a path's segment tests anywhere
    if (rank == 0 || r0 < r1) m.bits = gvd::OccupancyBits(m.grid);
    const bool with_path = !a.path.empty();
    std::vector<std::int16_t> nearest;  // fx, fy of the band's diagram pixels, row-major
    if (r0 < r1) {
        // marking reads the nearest points of rows r0-1 .. r1: the passes cover the bands of rows that
        // hold them (a halo row each side), their starts read from the edges of all bands
        const gvd::detail::BandEdges edges(m.grid, 1);
        gvd::detail::BandWorker passes;
        const std::int32_t B = gvd::detail::BandEdges::kRows;
        for (std::int32_t b = std::max(0, r0 - 1) / B; b * B < std::min(H, r1 + 1); ++b)
            passes(m.grid, f, edges, b * B, std::min(H, (b + 1) * B));
        gvd::detail::RowMarker(m).mark(r0, r1);
        if (!with_path)
            for (std::int32_t r = r0; r < r1; ++r)
                for (std::int32_t c = 0; c < W; ++c)
                    if (m.mask(r, c)) {
                        nearest.push_back(f.fx[f.at(r, c)]);
                        nearest.push_back(f.fy[f.at(r, c)]);
                    }
    }

    // Rank 0 gathers the bands' rows (every row is whole words) into its own arrays, in place.
    auto gather_rows = [&](auto* data, std::int64_t per_row, MPI_Datatype type) {
        std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
        for (int k = 0; k < size; ++k) {
            counts[static_cast<std::size_t>(k)] = static_cast<int>(static_cast<std::int64_t>(band(k + 1) - band(k)) * per_row);
            displs[static_cast<std::size_t>(k)] = static_cast<int>(static_cast<std::int64_t>(band(k)) * per_row);
        }
        MPI_Gatherv(rank == 0 ? MPI_IN_PLACE : data + r0 * per_row, counts[static_cast<std::size_t>(rank)], type, data,
                    counts.data(), displs.data(), type, 0, MPI_COMM_WORLD);
    };
    gather_rows(m.mask.row_words(0), static_cast<std::int64_t>(m.mask.words_per_row()), MPI_UINT64_T);
    // ... and the nearest points: of the diagram pixels for the writers (they read those clearances
    // only), of every pixel for a path
    std::vector<std::int16_t> all;
    if (with_path) {
        gather_rows(f.fx.data(), W, MPI_INT16_T);
        gather_rows(f.fy.data(), W, MPI_INT16_T);
    } else {
        all = gather(nearest, rank, size);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (rank != 0) return 0;

    if (!with_path) {
        std::size_t k = 0;  // bands arrive in rank order, so the pairs follow the mask's row-major order
        for (std::int32_t r = 0; r < H; ++r)
            for (std::int32_t c = 0; c < W; ++c)
                if (m.mask(r, c)) {
                    f.fx[f.at(r, c)] = all[k++];
                    f.fy[f.at(r, c)] = all[k++];
                }
        if (k != all.size()) throw std::logic_error("gathered nearest points do not match the gathered mask");
    }
    std::vector<Vec2> path_points;
    const nlohmann::json doc = cli_maps::medial_json(m, a.robot_radius, a.path, path_points);  // as `dvoronoi gvd`
    const std::size_t n = m.count();
    if (!a.quiet) {
        if (document)
            std::fprintf(stderr, "dvoronoi_gvd_mpi: obstacle file drawn on %d x %d pixels, %zu diagram pixels, %d ranks, %.3f s\n",
                         H, W, n, size, seconds);
        else
            std::fprintf(stderr, "dvoronoi_gvd_mpi: %d x %d map, %zu diagram pixels, %zu unknown pixels (%s), %d ranks, %.3f s\n",
                         H, W, n, unknown, a.map.unknown == "occupied" ? "occupied" : "free", size, seconds);
    }
    if (n == 0) a.map.warn_empty("dvoronoi_gvd_mpi", m.grid, unknown, document);  // shown with -q too
    // As the CLI delivers: each file appears whole or not at all
    return cli::deliver(
        out, svg, [&](std::ostream& os) { os << doc.dump() << '\n'; },
        [&](std::ostream& os) { io::write_medial_svg(os, m, a.robot_radius, path_points); }, "dvoronoi_gvd_mpi");
}

int run(const Args& a, int rank, int size) {
    // the CLI's first word on a folder, a missing file or a JPEG, before any option check
    on_rank0(rank, [&] { cli_maps::check_input(a.input); });
    return is_map_file(a.input) ? run_map(a, rank, size) : run_obstacles(a, rank, size);
}

}  // namespace

int main(int argc, char** argv) {
    std::ios::sync_with_stdio(false);  // as the CLI: std::cout's own buffer, so a failed write shows at its flush
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    Args a;
    CLI::App app{"dvoronoi_gvd_mpi: grid Voronoi diagram of obstacles (one slice per MPI rank) or medial diagram of "
                 "an occupancy map (one band of rows per MPI rank)", "dvoronoi_gvd_mpi"};
    app.add_option("INPUT", a.input, "an occupancy map (.yaml map_server, .pgm, .png, MovingAI .map) or an obstacle "
                                     "file (JSON), as for `dvoronoi gvd`")->required();
    app.add_option("-g,--grid", a.grid, "obstacle files: cells along the longer side of the working area");
    app.add_option("-m,--mode", a.mode, "cooperative or independent")->check(CLI::IsMember({"cooperative", "independent"}));
    app.add_option("-r,--robot-radius", a.robot_radius, "robot radius (map units): diagram cells or pixels this close to an obstacle are blocked");
    app.add_flag("--no-visibility", a.no_visibility, "turn the paper's edge visibility test off");
    app.add_option("--diagram", a.diagram, "medial (map files' default; obstacle files drawn on --grid pixels) or labels "
                                           "(obstacle files' default: Mendes et al.)")
        ->check(CLI::IsMember({"medial", "labels"}));
    a.map.add_to(app);
    app.add_option("--path", a.path, "also plan a path SX SY GX GY along the diagram")->expected(4);
    app.add_option("-o,--output", a.output, "output JSON file (default or '-': stdout)");
    app.add_option("--svg", a.svg, "also draw the diagram into this SVG file");
    app.add_flag("-q,--quiet", a.quiet, "no summary line on stderr");
    app.failure_message([](const CLI::App*, const CLI::Error& e) {  // as the CLI words it
        return std::string("dvoronoi_gvd_mpi: error: ") + e.what() + "\nRun with --help for more information.\n";
    });
    int code = 0;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        code = rank == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 2);
        if (code != 0) code = 2;
        MPI_Finalize();
        return code;
    }
    try {
        code = run(a, rank, size);
    } catch (const InputError& e) {
        if (rank == 0) std::cerr << "dvoronoi_gvd_mpi: error: " << e.what() << "\n";
        code = 2;
    } catch (const std::exception& e) {
        std::cerr << "dvoronoi_gvd_mpi: error (rank " << rank << "): " << e.what() << "\n";
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    MPI_Finalize();
    return code;
}
