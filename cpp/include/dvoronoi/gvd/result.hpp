// The grid Voronoi diagram as returned to users: the traced cells with their corner labels,
// clearance and blocked flags, the Voronoi vertices, and the roadmap graph along the diagram.
//
// Assembled from the cells every worker kept (threads or MPI ranks), sorted by (row, column), so the
// result does not depend on the number of workers or the approach.
#pragma once

#include "dvoronoi/gvd/grid.hpp"
#include "dvoronoi/gvd/lazy_grid.hpp"
#include "dvoronoi/gvd/slice_tracer.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <limits>
#include <vector>

namespace dvoronoi::gvd {

/// Slice approaches of Section 3.
enum class SliceMode {
    Independent,  ///< no communication: each worker scans both border lines of its slice
    Cooperative,  ///< each border line scanned once (by the right worker), seeds sent to the left one
};

/// What a run did (summed over workers unless stated).
struct GvdStats {
    std::int32_t workers = 1;
    SliceMode mode = SliceMode::Cooperative;
    std::uint64_t corners_labelled = 0;   ///< nearest-obstacle queries (lazy corner labels)
    std::uint64_t part_evaluations = 0;   ///< convex-part distance evaluations
    std::uint64_t edge_evaluations = 0;   ///< polygon edge / segment distance evaluations
    std::uint64_t traced_cells = 0;       ///< diagram cells traced before the slices were joined
    std::uint64_t discarded_cells = 0;    ///< traced but not kept: 0 (every slice traces exactly its diagram cells)
    std::uint64_t bridged_cells = 0;      ///< cells entered across same-label edges a sliver may cross, not on the diagram
    std::uint64_t obstacle_walks = 0;     ///< walks right from obstacles' rightmost points and from traced pieces
    std::uint64_t walk_cells = 0;         ///< cells those walks looked at
    std::uint64_t walk_seeds = 0;         ///< cells the walks queued
    std::uint64_t contact_seeds = 0;      ///< cells queued where obstacles of different labels meet
    std::uint64_t boundary_seeds = 0;     ///< cells queued along the area's boundary where it cuts cells
    std::uint64_t border_lines_scanned = 0;
    std::uint64_t peak_worker_bytes = 0;  ///< largest per-worker tracing memory (labels, cells)
    std::vector<double> worker_seconds;   ///< wall time per worker
    std::vector<double> worker_cpu_seconds;  ///< CPU time per worker thread (not inflated by other load)
    /// Distance evaluations (convex parts + edges) per worker: the work the paper's cost is made of,
    /// counted exactly, so a model of K workers' time does not depend on the machine's load.
    std::vector<std::uint64_t> worker_evaluations;
};

/// CPU time of the calling thread in seconds (0 where the platform has no per-thread clock).
inline double thread_cpu_seconds() {
#if defined(__linux__) || defined(__APPLE__)
    timespec ts{};
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0) return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
#endif
    return 0.0;
}

/// The roadmap: nodes at Voronoi vertices, junctions and ends of the traced diagram; edges along the
/// chains of traced cells between them.
struct Roadmap {
    std::vector<std::int64_t> node_cell;  ///< traced-cell index of each node
    std::vector<std::uint8_t> node_kind;  ///< 0 vertex (>= 3 labels), 1 end (<= 1 neighbour), 2 junction
    std::vector<std::int64_t> edge_u, edge_v;   ///< node indices
    std::vector<double> edge_length;            ///< along cell centers
    std::vector<double> edge_min_clearance;     ///< smallest cell clearance along the edge (ends included)
    std::vector<std::uint8_t> edge_blocked;     ///< some cell on the edge is blocked
    std::vector<std::int64_t> chain_ptr{0};     ///< CSR: interior cells of edge e are
    std::vector<std::int64_t> chain_cells;      ///<   chain_cells[chain_ptr[e] .. chain_ptr[e+1])
};

/// The result of grid_voronoi.
struct GridVoronoi {
    GridSpec grid;
    double robot_radius = 0.0;
    std::int32_t n_obstacles = 0, n_labels = 0;
    std::vector<std::int32_t> col, row;       ///< traced cells, sorted by (row, col)
    std::vector<std::int32_t> labels;         ///< 4 per cell: corner labels BL, BR, TR, TL
    std::vector<double> clearance;            ///< per cell: smallest corner distance to its nearest obstacle
    std::vector<std::uint8_t> blocked;        ///< per cell: clearance <= robot_radius
    std::vector<std::int64_t> vertices;       ///< cells whose corners carry >= 3 labels
    std::vector<std::array<std::int32_t, 4>> neighbors;  ///< per cell: traced neighbours across label changes (-1 none)
    Roadmap roadmap;
    bool has_graph = false;  ///< neighbors and roadmap are built (build_graph)
    GvdStats stats;

    std::size_t size() const { return col.size(); }
    Vec2 center(std::size_t k) const { return grid.center(col[k], row[k]); }
    int distinct_labels(std::size_t k) const {
        const std::int32_t* l = &labels[4 * k];
        int d = 1;
        for (int a = 1; a < 4; ++a) {
            bool seen = false;
            for (int b = 0; b < a; ++b) seen |= l[a] == l[b];
            d += !seen;
        }
        return d;
    }
};

namespace detail {

inline void build_roadmap(GridVoronoi& r) {
    const std::size_t n = r.size();
    Roadmap& m = r.roadmap;
    std::vector<std::int64_t> node_of(n, -1);
    auto degree = [&](std::size_t k) {
        int d = 0;
        for (std::int32_t x : r.neighbors[k]) d += x >= 0;
        return d;
    };
    auto add_node = [&](std::size_t k) {
        node_of[k] = static_cast<std::int64_t>(m.node_cell.size());
        m.node_cell.push_back(static_cast<std::int64_t>(k));
        const int d = degree(k);
        m.node_kind.push_back(r.distinct_labels(k) >= 3 ? 0 : (d <= 1 ? 1 : 2));
    };
    for (std::size_t k = 0; k < n; ++k)
        if (degree(k) != 2 || r.distinct_labels(k) >= 3) add_node(k);
    std::vector<std::uint8_t> on_chain(n, 0);
    std::vector<std::int64_t> chain;
    auto walk_from = [&](std::size_t u) {
        for (std::int32_t first : r.neighbors[u]) {
            if (first < 0) continue;
            chain.clear();
            std::size_t prev = u, cur = static_cast<std::size_t>(first);
            while (node_of[cur] < 0) {
                chain.push_back(static_cast<std::int64_t>(cur));
                std::size_t next = cur;
                for (std::int32_t x : r.neighbors[cur])
                    if (x >= 0 && static_cast<std::size_t>(x) != prev) { next = static_cast<std::size_t>(x); break; }
                if (next == cur) break;  // cannot happen for degree-2 cells
                prev = cur;
                cur = next;
            }
            if (node_of[cur] < 0) continue;
            // Each chain is added once: a direct node-node step from the lower node, a longer chain
            // from the end that walks it first (its cells are then marked).
            if (chain.empty() ? !(node_of[u] < node_of[cur]) : on_chain[static_cast<std::size_t>(chain.front())] != 0)
                continue;
            double minc = std::min(r.clearance[u], r.clearance[cur]);
            bool blocked = r.blocked[u] || r.blocked[cur];
            for (std::int64_t c : chain) {
                on_chain[static_cast<std::size_t>(c)] = 1;
                minc = std::min(minc, r.clearance[static_cast<std::size_t>(c)]);
                blocked = blocked || r.blocked[static_cast<std::size_t>(c)];
            }
            m.edge_u.push_back(node_of[u]);
            m.edge_v.push_back(node_of[cur]);
            m.edge_length.push_back(static_cast<double>(chain.size() + 1) * r.grid.h);
            m.edge_min_clearance.push_back(minc);
            m.edge_blocked.push_back(blocked ? 1 : 0);
            m.chain_cells.insert(m.chain_cells.end(), chain.begin(), chain.end());
            m.chain_ptr.push_back(static_cast<std::int64_t>(m.chain_cells.size()));
        }
    };
    const std::size_t initial_nodes = m.node_cell.size();
    for (std::size_t t = 0; t < initial_nodes; ++t) walk_from(static_cast<std::size_t>(m.node_cell[t]));
    // Closed loops without any node: make one of their cells a node.
    for (std::size_t k = 0; k < n; ++k)
        if (node_of[k] < 0 && !on_chain[k]) {
            add_node(k);
            walk_from(k);
        }
}

}  // namespace detail

/// Builds the result from the kept cells of every worker (without the graph: see build_graph).
/// Slices that are column ranges from left to right (what the workers and MPI ranks hand over) are
/// ordered and written by one thread each: a row's cells are slice 0's, then slice 1's, ...; any
/// other split is first joined into one.
/// \note O(cells + rows x slices).
inline GridVoronoi assemble(const Scene& scene, const GridSpec& grid, std::vector<std::vector<TracedCell>> slices,
                            double robot_radius) {
    // Column ranges from left to right?
    bool ordered = true;
    std::int32_t right = std::numeric_limits<std::int32_t>::min();
    for (const auto& v : slices) {
        if (v.empty()) continue;
        std::int32_t lo = v.front().i, hi = v.front().i;
        for (const TracedCell& c : v) lo = std::min(lo, c.i), hi = std::max(hi, c.i);
        ordered = ordered && lo > right;
        right = hi;
    }
    if (!ordered) {
        std::vector<TracedCell> all;
        for (auto& v : slices) {
            all.insert(all.end(), v.begin(), v.end());
            std::vector<TracedCell>().swap(v);
        }
        slices.assign(1, std::move(all));
    }
    const std::size_t K = slices.size();
    const auto ny = static_cast<std::size_t>(grid.ny);
    auto run = [K](auto&& fn) {  // fn(k) for every slice, one thread each
        run_team(static_cast<int>(K), [&](int k) { fn(static_cast<std::size_t>(k)); });
    };
    // Per slice: order by (row, col) (counting sort by row, then each row by column: rows hold few
    // cells) and count the cells of each row. The keys are (column << 32 | cell), so sorting
    // compares integers instead of reading cells in trace order (a cache miss each).
    std::vector<std::vector<std::uint64_t>> order(K);
    std::vector<std::vector<std::size_t>> start(K);
    run([&](std::size_t k) {
        const auto& cells = slices[k];
        auto& st = start[k];
        auto& ord = order[k];
        st.assign(ny + 1, 0);
        for (const TracedCell& c : cells) ++st[static_cast<std::size_t>(c.j) + 1];
        for (std::size_t j = 1; j <= ny; ++j) st[j] += st[j - 1];
        ord.resize(cells.size());
        std::vector<std::size_t> fill(st.begin(), st.end() - 1);
        for (std::size_t t = 0; t < cells.size(); ++t)
            ord[fill[static_cast<std::size_t>(cells[t].j)]++] = static_cast<std::uint64_t>(static_cast<std::uint32_t>(cells[t].i)) << 32 | t;
        for (std::size_t j = 0; j < ny; ++j)
            std::sort(ord.begin() + static_cast<std::ptrdiff_t>(st[j]), ord.begin() + static_cast<std::ptrdiff_t>(st[j + 1]));
    });
    // Where each slice's part of each row goes.
    std::vector<std::vector<std::size_t>> offset(K, std::vector<std::size_t>(ny));
    std::size_t n = 0;
    for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t k = 0; k < K; ++k) {
            offset[k][j] = n;
            n += start[k][j + 1] - start[k][j];
        }
    GridVoronoi r;
    r.grid = grid;
    r.robot_radius = robot_radius;
    r.n_obstacles = scene.n_obstacles;
    r.n_labels = scene.n_labels;
    r.col.resize(n);
    r.row.resize(n);
    r.labels.resize(4 * n);
    r.clearance.resize(n);
    r.blocked.resize(n);
    const double r2 = robot_radius * robot_radius;
    std::vector<std::vector<std::int64_t>> vertices(K);
    run([&](std::size_t k) {
        const auto& cells = slices[k];
        for (std::size_t j = 0; j < ny; ++j) {
            std::size_t out = offset[k][j];
            for (std::size_t t = start[k][j]; t < start[k][j + 1]; ++t, ++out) {
                // Cells are read in row order, scattered over the trace order: fetch a few ahead.
                constexpr std::size_t kAhead = 8;
                if (t + kAhead < order[k].size()) ::dvoronoi::detail::prefetch(&cells[order[k][t + kAhead] & 0xffffffffu]);
                const TracedCell& c = cells[order[k][t] & 0xffffffffu];
                r.col[out] = c.i;
                r.row[out] = c.j;
                for (int q = 0; q < 4; ++q) r.labels[4 * out + static_cast<std::size_t>(q)] = c.labels[static_cast<std::size_t>(q)];
                r.clearance[out] = std::sqrt(c.min_sq);
                // Paper: free only when every corner is farther than r from its nearest obstacle.
                r.blocked[out] = c.min_sq <= r2 ? 1 : 0;
                if (r.distinct_labels(out) >= 3) vertices[k].push_back(static_cast<std::int64_t>(out));
            }
        }
        std::vector<TracedCell>().swap(slices[k]);
    });
    for (const auto& v : vertices) r.vertices.insert(r.vertices.end(), v.begin(), v.end());
    std::sort(r.vertices.begin(), r.vertices.end());
    return r;
}

/// A diagram computed in pixel units placed in map units: cell (i, j) of `r`'s grid moves to
/// offset + scale * (its place), clearances scale, and cells are blocked as assemble blocks them, by
/// `robot_radius` (map units). An occupancy map's labelled diagram is computed so: its obstacles and
/// cell corners lie on the integer lattice, where exact ties are everywhere and distances are exact,
/// while in map units rounding would break the ties one way or the other (the diagram would depend
/// on the resolution and origin). The graph is built afterwards, in map units.
inline GridVoronoi placed(GridVoronoi r, double scale, const Vec2& offset, double robot_radius) {
    r.grid.x0 = offset.x() + scale * r.grid.x0;
    r.grid.y0 = offset.y() + scale * r.grid.y0;
    r.grid.h *= scale;
    r.robot_radius = robot_radius;
    for (std::size_t k = 0; k < r.size(); ++k) {
        r.clearance[k] *= scale;
        r.blocked[k] = r.clearance[k] <= robot_radius ? 1 : 0;
    }
    r.neighbors.clear();
    r.roadmap = Roadmap{};
    r.has_graph = false;
    return r;
}

/// Builds the cell adjacency (neighbours across label-changing edges) and the roadmap, once.
/// grid_voronoi does it unless told not to (Python builds it on first use of the roadmap or a path).
/// \note O(cells).
inline void build_graph(GridVoronoi& r) {
    if (r.has_graph) return;
    const std::size_t n = r.size();
    const GridSpec& grid = r.grid;
    LazyGrid<std::int32_t> where(0, grid.nx, grid.ny, -1);
    for (std::size_t k = 0; k < n; ++k) where.at(r.col[k], r.row[k]) = static_cast<std::int32_t>(k);
    r.neighbors.assign(n, {{-1, -1, -1, -1}});
    for (std::size_t k = 0; k < n; ++k) {
        const std::int32_t* l = &r.labels[4 * k];
        const std::int32_t i = r.col[k], j = r.row[k];
        auto at = [&](std::int32_t a, std::int32_t b) -> std::int32_t {
            if (a < 0 || b < 0 || a >= grid.nx || b >= grid.ny) return -1;
            return where.get(a, b);
        };
        if (l[0] != l[1]) r.neighbors[k][0] = at(i, j - 1);
        if (l[1] != l[2]) r.neighbors[k][1] = at(i + 1, j);
        if (l[3] != l[2]) r.neighbors[k][2] = at(i, j + 1);
        if (l[0] != l[3]) r.neighbors[k][3] = at(i - 1, j);
    }
    r.roadmap = Roadmap{};
    detail::build_roadmap(r);
    r.has_graph = true;
}

}  // namespace dvoronoi::gvd
