// The output side of limited_cells: a LimitedPartition written by a team of threads while they
// compute cells in grid order. Each agent's scalars and counts go straight to their places in input
// order (the lines are prefetched for writing a few agents ahead); its pieces are appended to its
// thread's piece columns, which become the output columns, put into input order one column at a time.
// Why this layout: a fresh page costs a fault and a zeroing (and on a VM that hands freed memory back
// to the host, a host fault), so every byte of scratch is paid for; this keeps the scratch to one
// column of pieces, against three times the pieces' size when they were staged whole.
#pragma once

#include "dvoronoi/core/cell.hpp"
#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/core/parallel.hpp"
#include "dvoronoi/partition/detail/input_order.hpp"
#include "dvoronoi/partition/limited_result.hpp"

#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

namespace dvoronoi::detail {

/// A piece with a nonzero span (an arc), by its place in the output: the k-th piece of agent's cell.
struct ArcSpan {
    Index agent;
    Index k;
    double span;
};

/// Pieces as the columns of LimitedPartition's piece arrays; a thread appends its cells' pieces here
/// in the order it computes them. Spans are not a column: in a swarm only a few pieces per thousand
/// are arcs, so the arcs are listed apart and written into a zeroed column at the end. That saves
/// a column of fresh pages and a pass that would put it into input order.
struct PieceColumns {
    std::vector<double> x, y;
    std::vector<Index> neighbor;
    std::vector<ArcSpan> arcs;
    std::size_t mapped = 0;  // values up to here are on mapped pages

    Index size() const noexcept { return static_cast<Index>(x.size()); }
    void reserve(std::size_t pieces) {
        x.reserve(pieces);
        y.reserve(pieces);
        neighbor.reserve(pieces);
    }
    void append(Index agent, const std::vector<Piece>& pieces) {
        if (x.size() + pieces.size() > mapped) map_ahead();
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const Piece& p = pieces[k];
            x.push_back(p.start.x());
            y.push_back(p.start.y());
            neighbor.push_back(p.neighbor);
            if (p.arc_span != 0.0) arcs.push_back({agent, static_cast<Index>(k), p.arc_span});
        }
    }
    /// Maps the next pages of the reserved room in one call per column (see prefault).
    void map_ahead() {
        constexpr std::size_t kStep = std::size_t{1} << 17;  // values: 1 MB per column
        const std::size_t to = std::min(x.capacity(), std::max(mapped, x.size()) + kStep);
        if (to <= mapped) return;
        const std::size_t at = std::max(mapped, x.size());
        prefault(x.data() + at, (to - at) * sizeof(double));
        prefault(y.data() + at, (to - at) * sizeof(double));
        prefault(neighbor.data() + at, (to - at) * sizeof(Index));
        mapped = to;
    }
    /// parts[0] followed by parts[1], ... (each freed once appended); up to `team` threads copy
    /// the three columns.
    static PieceColumns concatenate(std::vector<PieceColumns>& parts, int team) {
        PieceColumns all = std::move(parts.front());
        std::size_t more = 0;
        for (std::size_t t = 1; t < parts.size(); ++t) more += parts[t].x.size();
        if (more > 0 && all.x.size() + more <= all.x.capacity())  // the pages the copies land on, by the team
            prefault_together({{all.x.data() + all.x.size(), more * sizeof(double)},
                               {all.y.data() + all.y.size(), more * sizeof(double)},
                               {all.neighbor.data() + all.neighbor.size(), more * sizeof(Index)}},
                              team);
        const auto join = [&](auto column) {
            auto& into = all.*column;
            for (std::size_t t = 1; t < parts.size(); ++t) {
                const auto part = std::move(parts[t].*column);  // freed once appended
                into.insert(into.end(), part.begin(), part.end());
            }
        };
#pragma omp parallel for num_threads(std::min(team, 3)) schedule(static, 1) if (parts.size() > 1)
        for (int c = 0; c < 3; ++c) {
            if (c == 0) join(&PieceColumns::x);
            if (c == 1) join(&PieceColumns::y);
            if (c == 2) join(&PieceColumns::neighbor);
        }
        join(&PieceColumns::arcs);
        return all;
    }
};

/// Writes the cells of a LimitedPartition from a team of threads: the constructor sizes the per-agent
/// arrays, store(agent, cell, thread, ahead) records one cell, stitch() lays the pieces and the
/// neighbour CSR out in input order. Threads store distinct agents; stitch() runs after them all.
class CellColumns {
public:
    /// `out` gets the points and zeroed per-agent arrays; room for about seven pieces per agent in
    /// each thread's columns (room that is never written costs address space only).
    CellColumns(LimitedPartition& out, PointsRef points, int team) : out_(out), team_(team), parts_(static_cast<std::size_t>(team)) {
        const Index n = points.rows();
        const auto un = static_cast<std::size_t>(n);
        // All but the points are written in scattered (input) order, so they get huge pages (see
        // advise_huge_pages); the team maps all their pages together first.
        out.points.resize(n, 2);
        out.centroids.resize(n, 2);
        const auto room = [](auto& v, std::size_t size) {
            v.reserve(size);
            advise_huge_pages(v.data(), size * sizeof(v[0]));
            return std::pair<const void*, std::size_t>(v.data(), size * sizeof(v[0]));
        };
        const std::size_t xy_bytes = 2 * un * sizeof(double);
        advise_huge_pages(out.centroids.data(), xy_bytes);
        prefault_together({{out.points.data(), xy_bytes}, {out.centroids.data(), xy_bytes}, room(out.areas, un),
                           room(out.perimeters, un), room(out.candidates, un), room(out.piece_ptr, un + 1),
                           room(out.indptr, un + 1), room(source_, un)},
                          team);
        out.points = points;
        out.areas.assign(un, 0.0);
        out.perimeters.assign(un, 0.0);
        out.candidates.assign(un, 0);
        out.piece_ptr.assign(un + 1, 0);  // counts until stitch()
        out.indptr.assign(un + 1, 0);
        source_.assign(un, 0);
        for (int t = 0; t < team; ++t)  // the first thread's columns take the others' in the end
            parts_[static_cast<std::size_t>(t)].reserve(static_cast<std::size_t>(t == 0 ? n : n / team + kBlock) * 7);
    }

    /// Agent a's cell, computed by `thread`; then the lines agent `ahead`'s results will go to are
    /// fetched for writing (ahead < 0: none), so they are in cache when its cell is done. The
    /// prefetches are here, in a function that writes, because GCC deletes a call to a function
    /// that only prefetches (it counts as pure) when it does not inline it first.
    void store(Index a, const LimitedCell& cell, int thread, Index ahead) {
        const CellMeasures m = cell.measures();
        const auto i = static_cast<std::size_t>(a);
        out_.areas[i] = m.area;
        out_.perimeters[i] = m.perimeter;
        out_.centroids(a, 0) = m.centroid.x();
        out_.centroids(a, 1) = m.centroid.y();
        out_.candidates[i] = cell.candidates;
        Index edges = 0;
        for (const Piece& p : cell.pieces) edges += p.is_arc() ? 0 : 1;
        out_.piece_ptr[i + 1] = static_cast<Index>(cell.pieces.size());
        out_.indptr[i + 1] = edges;
        PieceColumns& mine = parts_[static_cast<std::size_t>(thread)];
        source_[i] = column_place(mine.x.size(), team_, thread);
        mine.append(a, cell.pieces);
        if (ahead < 0) return;
        const auto j = static_cast<std::size_t>(ahead);
        prefetch_for_write(&out_.areas[j]);
        prefetch_for_write(&out_.perimeters[j]);
        prefetch_for_write(out_.centroids.data() + 2 * j);
        prefetch_for_write(&out_.candidates[j]);
        prefetch_for_write(&out_.piece_ptr[j + 1]);
        prefetch_for_write(&out_.indptr[j + 1]);
        prefetch_for_write(&source_[j]);
    }

    /// Counts to offsets, the threads' columns joined, each column put into input order (agent i's
    /// pieces move from source[i] to piece_ptr[i]) and the limited neighbours sorted out of the edges.
    void stitch() {
        LimitedPartition& out = out_;
        const auto n = static_cast<std::size_t>(out.size());
        for (std::size_t i = 0; i < n; ++i) {
            out.piece_ptr[i + 1] += out.piece_ptr[i];
            out.indptr[i + 1] += out.indptr[i];
        }
        std::vector<Index> sizes;
        for (const PieceColumns& part : parts_) sizes.push_back(part.size());
        to_joined(source_, sizes);
        PieceColumns all = PieceColumns::concatenate(parts_, team_);
        // x goes into fresh storage; the neighbours (of another type) are copied into x's old storage
        // and moved back; y goes into x's old storage; y's old storage, zeroed, takes the arcs' spans.
        // So one column of scratch serves all three.
        const auto from = [&](Index i) { return static_cast<std::size_t>(source_[static_cast<std::size_t>(i)]); };
        const auto nothing = [](Index, const void*, std::size_t) {};
        std::vector<double> free_column;
        const auto pieces = all.x.size(), edges = static_cast<std::size_t>(out.indptr.back());
        free_column.reserve(pieces);
        out.indices.reserve(edges);
        prefault_together({{free_column.data(), pieces * sizeof(double)}, {out.indices.data(), edges * sizeof(Index)}}, team_);
        free_column.assign(pieces, 0.0);
        out.indices.assign(edges, 0);
        move_runs(free_column.data(), all.x.data(), out.piece_ptr, from, team_, nothing);
        std::swap(free_column, all.x);
        std::memcpy(free_column.data(), all.neighbor.data(), all.neighbor.size() * sizeof(Index));
        // Limited neighbours: the edges' neighbours, ascending.
        move_runs(all.neighbor.data(), free_column.data(), out.piece_ptr, from, team_,
                  [&](Index i, const Index* run, std::size_t len) {
                      sorted_edge_neighbors(run, len, out.indices.data() + out.indptr[static_cast<std::size_t>(i)]);
                  });
        move_runs(free_column.data(), all.y.data(), out.piece_ptr, from, team_, nothing);
        std::swap(free_column, all.y);
        std::fill(free_column.begin(), free_column.end(), 0.0);
        for (const ArcSpan& a : all.arcs)
            free_column[static_cast<std::size_t>(out.piece_ptr[static_cast<std::size_t>(a.agent)] + a.k)] = a.span;
        out.piece_x = std::move(all.x);
        out.piece_y = std::move(all.y);
        out.piece_span = std::move(free_column);
        out.piece_neighbor = std::move(all.neighbor);
    }

private:
    LimitedPartition& out_;
    int team_;
    std::vector<PieceColumns> parts_;  // per thread
    // Where each agent's pieces start: its place in its thread's columns while storing (see
    // column_place), the offset in the joined columns after stitch().
    std::vector<Index> source_;
};

}  // namespace dvoronoi::detail
