// The grid Voronoi diagram of obstacles (Mendes, Aude, Pinto & Aude, "Construction of the Voronoi
// diagram by a team of cooperative robots"), traced by K slice workers running as threads.
//
//   Scene scene = make_scene(obstacles, box_area(0, 0, 10, 10));
//   GridVoronoi r = grid_voronoi(scene, {/*resolution*/ 1024, /*robot_radius*/ 0.2, /*workers*/ 2});
//
// The result is exactly the set of cells the definition marks (cells of the working area whose
// corners carry two or more labels), isolated pieces included, for every worker count and both
// approaches. The area's bounding box is cut into vertical slices of whole columns, one per worker.
// Each worker traces its slice (slice_tracer.hpp) from the area's corners (the paper's seeds), from
// the obstacles (walks right from each obstacle's rightmost point and from each traced piece, and
// the places where obstacles of different labels meet: added, because on real maps the area's
// corners lie inside walls and loops around islands touch none of them), from the cells the area's
// boundary cuts, and from the border lines. Section 3's two approaches differ in who scans a
// border line:
//  - Independent: both neighbours scan it (no communication, the line is labelled twice).
//  - Cooperative: the right worker scans it and sends the rows where it may be crossed to the left
//    one, which puts the cells beside them in its queue once its own queue is empty.
// Each slice finds exactly its own cells of the diagram, so the join (slice_merge.hpp) keeps every
// traced cell. The MPI executable dvoronoi_gvd_mpi runs the same per-slice function (run_slice)
// with messages instead of futures.
#pragma once

#include "dvoronoi/gvd/obstacle_index.hpp"
#include "dvoronoi/gvd/result.hpp"
#include "dvoronoi/gvd/slice_merge.hpp"
#include "dvoronoi/gvd/slice_tracer.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <future>
#include <vector>

namespace dvoronoi::gvd {

/// Options of grid_voronoi.
struct GvdOptions {
    std::int64_t resolution = 512;  ///< cells along the longer side of the area's bounding box
    double robot_radius = 0.0;      ///< cells with a corner within this distance of an obstacle are blocked
    int workers = 1;                ///< slice workers (threads); clamped to the column count
    SliceMode mode = SliceMode::Cooperative;
    bool visibility = true;         ///< the paper's visibility test for polygon edges
    bool graph = true;              ///< build the cell adjacency and the roadmap now (else build_graph later)
};

/// First column of each of the K slices, plus nx at the end (slices of near-equal width).
inline std::vector<std::int32_t> slice_bounds(std::int32_t nx, int workers) {
    std::vector<std::int32_t> b(static_cast<std::size_t>(workers) + 1);
    for (int k = 0; k <= workers; ++k)
        b[static_cast<std::size_t>(k)] =
            static_cast<std::int32_t>(static_cast<std::int64_t>(nx) * k / workers);
    return b;
}

/// How a slice worker talks to its neighbours in the cooperative approach.
struct BorderChannel {
    std::function<void(const std::vector<std::int32_t>&)> send_left;  ///< rows found on my left line
    std::function<std::vector<std::int32_t>()> receive_right;          ///< rows found on my right line
};

/// One slice worker's whole job (Sections 2 and 3): seeds, border scans, tracing.
/// Returns its summary for the join; `tracer` holds the traced cells.
inline SliceSummary run_slice(SliceTracer& tracer, int k, int workers, SliceMode mode,
                              const BorderChannel& channel, std::uint64_t& lines_scanned) {
    const std::int32_t left = tracer.c0(), right = tracer.c1();
    std::vector<std::int32_t> rows_left, rows_right;
    if (k > 0) {  // both approaches scan the left line; cooperative ones then share it (first: the
                  // left neighbour waits for it)
        rows_left = tracer.scan_line(left);
        ++lines_scanned;
        if (mode == SliceMode::Cooperative) channel.send_left(rows_left);
        for (std::int32_t j : rows_left) tracer.seed(left, j);
    }
    // Section 2: the working area's corners are Voronoi vertices.
    tracer.seed_area_corners();
    tracer.seed_area_boundary();  // added: cells the area's boundary cuts (slice_tracer.hpp)
    // Added (issue 19): seeds from the obstacles themselves. On real maps the area's corners lie
    // inside walls and the loops around islands touch no corner; sub-cell slivers leave cells joined
    // to nothing. Walks right from every obstacle's rightmost point, and the places where obstacles
    // of different labels meet, find every other piece (slice_tracer.hpp says why).
    tracer.seed_contacts();
    tracer.seed_obstacle_walks();
    if (k + 1 < workers && mode == SliceMode::Independent) {
        rows_right = tracer.scan_line(right);
        ++lines_scanned;
        for (std::int32_t j : rows_right) tracer.seed(right - 1, j);
    }
    tracer.trace();
    if (k + 1 < workers && mode == SliceMode::Cooperative) {
        rows_right = channel.receive_right();  // the right neighbour's scan of our shared line
        for (std::int32_t j : rows_right) tracer.seed(right - 1, j);
        tracer.trace();
    }
    // Added: a walk from the rightmost cell of every traced piece reaches the piece enclosing it.
    while (tracer.walk_from_new_pieces()) tracer.trace();
    SliceSummary s;
    // Every slice traced exactly its part of the diagram (slice_tracer.hpp): one anchored whole.
    s.n_components = tracer.single_component();
    s.anchored = tracer.anchored();
    for (std::int32_t j : rows_left) s.left_links.push_back(tracer.component_at(left, j));
    for (std::int32_t j : rows_right) s.right_links.push_back(tracer.component_at(right - 1, j));
    return s;
}

/// The kept cells of one slice (moved out of the tracer when it keeps them all: read its
/// statistics first).
inline void append_kept(SliceTracer& t, const std::vector<std::uint8_t>& keep, std::vector<TracedCell>& out) {
    if (out.empty() && std::all_of(keep.begin(), keep.end(), [](std::uint8_t x) { return x != 0; })) {
        out = t.take_cells();  // all of them: no copy
        return;
    }
    out.reserve(out.size() + t.size());
    const auto& comp = t.components();
    for (std::size_t c = 0; c < t.size(); ++c)
        if (keep[static_cast<std::size_t>(comp[c])]) out.push_back(t.cell(c));
}

inline void check_options(const GvdOptions& o) {
    if (!std::isfinite(o.robot_radius) || o.robot_radius < 0.0)
        throw InputError("robot_radius must be a finite number >= 0");
    if (o.workers < 1) throw InputError("workers must be at least 1, got " + std::to_string(o.workers));
}

/// The grid Voronoi diagram of `scene` with `options.workers` slice threads.
///
/// \throws InputError for resolution < 1, workers < 1, a negative or non-finite robot radius.
/// \note Work and memory are proportional to the traced cells (plus the scanned border lines), not
/// to the grid's area. Thread-safe (no shared state); the result is identical for every worker count
/// and both approaches.
inline GridVoronoi grid_voronoi(const Scene& scene, const GvdOptions& options) {
    check_options(options);
    const GridSpec grid = make_grid(scene, options.resolution);
    const int workers = std::min<int>({options.workers, grid.nx, ::dvoronoi::detail::max_team()});  // the answer is the same for any count
    const ObstacleIndex index(scene, options.visibility, workers);
    const auto bounds = slice_bounds(grid.nx, workers);

    std::vector<SliceTracer> tracers(static_cast<std::size_t>(workers));  // each built by its worker
    std::vector<SliceSummary> summaries(static_cast<std::size_t>(workers));
    std::vector<std::promise<std::vector<std::int32_t>>> mail(static_cast<std::size_t>(workers));
    std::vector<double> seconds(static_cast<std::size_t>(workers), 0.0), cpu(static_cast<std::size_t>(workers), 0.0);
    std::vector<std::uint64_t> lines(static_cast<std::size_t>(workers), 0);
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));

    auto work = [&](int k) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = thread_cpu_seconds();
        const auto uk = static_cast<std::size_t>(k);
        try {
            tracers[uk] = SliceTracer(scene, index, grid, bounds[uk], bounds[uk + 1]);
            BorderChannel ch;
            ch.send_left = [&](const std::vector<std::int32_t>& rows) { mail[uk].set_value(rows); };  // mail[k]: for k-1
            ch.receive_right = [&]() { return mail[uk + 1].get_future().get(); };
            summaries[uk] = run_slice(tracers[uk], k, workers, options.mode, ch, lines[uk]);
        } catch (...) {
            errors[uk] = std::current_exception();
            try { if (k > 0 && options.mode == SliceMode::Cooperative) mail[uk].set_value({}); } catch (...) {}
        }
        seconds[uk] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        cpu[uk] = thread_cpu_seconds() - c0;
    };
    run_team(workers, work);
    for (auto& e : errors)
        if (e) std::rethrow_exception(e);

    const auto keep = keep_components(summaries);
    GvdStats st;
    st.workers = workers;
    st.mode = options.mode;
    for (int k = 0; k < workers; ++k) {
        const auto uk = static_cast<std::size_t>(k);
        const QueryContext& c = tracers[uk].context();
        st.corners_labelled += c.queries;
        st.part_evaluations += c.counters.part_evaluations;
        st.edge_evaluations += c.counters.edge_evaluations;
        st.worker_evaluations.push_back(c.counters.part_evaluations + c.counters.edge_evaluations);
        st.traced_cells += tracers[uk].size();
        st.bridged_cells += tracers[uk].explored() - tracers[uk].size();
        st.obstacle_walks += tracers[uk].seed_counts().walks;
        st.walk_cells += tracers[uk].seed_counts().walk_cells;
        st.walk_seeds += tracers[uk].seed_counts().walk_seeds;
        st.contact_seeds += tracers[uk].seed_counts().contact_seeds;
        st.boundary_seeds += tracers[uk].seed_counts().boundary_seeds;
        st.border_lines_scanned += lines[uk];
        st.peak_worker_bytes = std::max<std::uint64_t>(st.peak_worker_bytes, tracers[uk].memory_bytes());
    }
    // Each worker hands over its kept cells (labels and exact clearance) and frees its slice.
    std::vector<std::vector<TracedCell>> kept(static_cast<std::size_t>(workers));
    auto hand_over = [&](int k) {
        const auto uk = static_cast<std::size_t>(k);
        const double c0 = thread_cpu_seconds();
        append_kept(tracers[uk], keep[uk], kept[uk]);
        tracers[uk] = SliceTracer();
        cpu[uk] += thread_cpu_seconds() - c0;
    };
    run_team(workers, hand_over);
    std::size_t n_kept = 0;
    for (const auto& v : kept) n_kept += v.size();
    st.discarded_cells = st.traced_cells - n_kept;
    st.worker_seconds = seconds;
    st.worker_cpu_seconds = cpu;
    tracers.clear();
    GridVoronoi r = assemble(scene, grid, std::move(kept), options.robot_radius);
    r.stats = std::move(st);
    if (options.graph) build_graph(r);
    return r;
}

}  // namespace dvoronoi::gvd
