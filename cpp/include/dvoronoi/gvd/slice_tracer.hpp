// One worker of the grid Voronoi diagram (Mendes et al., Sections 2 and 3): traces the diagram inside
// a vertical slice of columns [c0, c1), labelling cell corners lazily.
//
// Tracing as published: a cell is queued when its corners carry two or more labels; when it is taken
// from the queue, each of its four edges whose two corners have different labels leads to the
// neighbour across that edge (which then also has two labels), queued unless it was queued before
// ("never re-enter"; the entrance edge is one of those). Cells outside the slice or the working area
// are not entered. Corner labels are computed only for corners of queued cells and of the scanned
// border lines, and kept in lazily allocated tiles, so the work and the memory follow the diagram's length, not
// the grid's area (lazy_grid.hpp). Blocking by robot radius happens when results are assembled; a blocked cell is
// traced through like any other (the paper: "still inserted in the queue").
//
// Seeds: the cells at the working area's corners (anchors, all area corners are Voronoi vertices),
// and the cells next to a label change on a scanned border line. After tracing, the slice's cells are
// grouped into connected components (cells joined across label-changing edges), so the driver can
// keep exactly the components the single-worker run reaches from the area corners.
#pragma once

#include "dvoronoi/gvd/grid.hpp"
#include "dvoronoi/gvd/lazy_grid.hpp"
#include "dvoronoi/gvd/obstacle_index.hpp"
#include "dvoronoi/gvd/slice_merge.hpp"

#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

namespace dvoronoi::gvd {

/// A traced cell as handed to the result: position, corner labels (bottom-left, bottom-right,
/// top-right, top-left) and the smallest squared corner distance.
struct TracedCell {
    std::int32_t i = 0, j = 0;
    std::array<std::int32_t, 4> labels{{-1, -1, -1, -1}};
    double min_sq = 0.0;
};

class SliceTracer {
public:
    SliceTracer() = default;
    SliceTracer(const Scene& scene, const ObstacleIndex& index, const GridSpec& grid, std::int32_t c0,
                std::int32_t c1)
        : scene_(&scene), index_(&index), grid_(grid), c0_(c0), c1_(c1), ctx_(index.context()),
          corners_(c0, static_cast<std::int64_t>(c1) - c0 + 1, static_cast<std::int64_t>(grid.ny) + 1, Corner{}),
          index_of_(c0, static_cast<std::int64_t>(c1) - c0, grid.ny, -1) {}

    std::int32_t c0() const { return c0_; }
    std::int32_t c1() const { return c1_; }

    /// The convex part nearest to corner (i, j), c0 <= i <= c1, computed on first use. The part is
    /// stored with its squared distance rounded to float (8 bytes a corner): the label and the exact
    /// squared distance follow from the part.
    std::int32_t corner_part(std::int32_t i, std::int32_t j) { return corner(i, j).part; }

    /// The label (nearest obstacle) of corner (i, j).
    std::int32_t label(std::int32_t i, std::int32_t j) {
        return scene_->parts[static_cast<std::size_t>(corner_part(i, j))].label;
    }

    /// Rows j of the grid line x = x0 + line h where the edge from corner (line, j) to (line, j+1)
    /// changes label and both cells beside it, (line-1, j) and (line, j), lie in the working area.
    /// Labels ny + 1 corners.
    std::vector<std::int32_t> scan_line(std::int32_t line) {
        std::vector<std::int32_t> rows;
        std::int32_t prev = label(line, 0);
        for (std::int32_t j = 0; j < grid_.ny; ++j) {
            const std::int32_t next = label(line, j + 1);
            if (next != prev && cell_in_area(*scene_, grid_, line - 1, j) && cell_in_area(*scene_, grid_, line, j))
                rows.push_back(j);
            prev = next;
        }
        return rows;
    }

    /// Queues cell (i, j) if it lies in this slice and the working area, has corners with two or more
    /// labels, and was not queued before. Returns whether it was queued.
    bool seed(std::int32_t i, std::int32_t j, bool anchor = false) {
        if (i < c0_ || i >= c1_ || j < 0 || j >= grid_.ny) return false;
        if (index_of_.get(i, j) >= 0) return false;
        if (!cell_in_area(*scene_, grid_, i, j)) return false;
        const auto l = labels(i, j);
        if (l[0] == l[1] && l[1] == l[2] && l[2] == l[3]) return false;
        index_of_.at(i, j) = static_cast<std::int32_t>(cells_.size());
        if (anchor) anchors_.push_back(static_cast<std::uint32_t>(cells_.size()));
        waiting_.push_back(static_cast<std::uint32_t>(cells_.size()));
        // The clearance now, while the corners are in cache (the hand-over reads cells in order).
        cells_.push_back({i, j, l, min_sq(i, j)});
        return true;
    }

    /// Seeds the cells at the working area's vertices that fall in this slice.
    void seed_area_corners() {
        for (const Vec2& v : scene_->area) {
            std::int32_t i, j;
            grid_.locate(v, i, j);
            // v may lie on a cell edge or corner: try every cell whose closure holds it.
            for (std::int32_t di = -1; di <= 1; ++di)
                for (std::int32_t dj = -1; dj <= 1; ++dj) {
                    const std::int32_t ci = i + di, cj = j + dj;
                    const Vec2 lo = grid_.corner(ci, cj), hi = grid_.corner(ci + 1, cj + 1);
                    if (lo.x() <= v.x() && v.x() <= hi.x() && lo.y() <= v.y() && v.y() <= hi.y())
                        seed(ci, cj, true);
                }
        }
    }

    /// Runs the queue empty (Section 2's loop).
    void trace() {
        while (!waiting_.empty()) {
            const Cell c = cells_[waiting_.back()];
            waiting_.pop_back();
            const auto& l = c.labels;
            if (l[0] != l[1]) seed(c.i, c.j - 1);  // bottom edge
            if (l[1] != l[2]) seed(c.i + 1, c.j);  // right edge
            if (l[3] != l[2]) seed(c.i, c.j + 1);  // top edge
            if (l[0] != l[3]) seed(c.i - 1, c.j);  // left edge
        }
    }

    /// Groups the traced cells into components joined across label-changing edges; returns their
    /// count. component(k) is cell k's component, anchored(c) whether c holds an area-corner seed.
    std::int32_t label_components() {
        const std::size_t n = cells_.size();
        UnionFind sets(n);
        for (std::size_t k = 0; k < n; ++k) {
            const Cell& c = cells_[k];
            const auto& l = c.labels;
            auto join = [&](std::int32_t i, std::int32_t j) {
                const std::int32_t o = index_of_.get(i, j);
                if (o >= 0) sets.join(static_cast<std::int32_t>(k), o);
            };
            if (l[1] != l[2] && c.i + 1 < c1_) join(c.i + 1, c.j);
            if (l[3] != l[2] && c.j + 1 < grid_.ny) join(c.i, c.j + 1);
        }
        component_.assign(n, -1);
        std::vector<std::int32_t> id(n, -1);
        std::int32_t count = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const auto r = static_cast<std::size_t>(sets.find(static_cast<std::int32_t>(k)));
            if (id[r] < 0) id[r] = count++;
            component_[k] = id[r];
        }
        anchored_.assign(static_cast<std::size_t>(count), 0);
        for (std::uint32_t k : anchors_) anchored_[static_cast<std::size_t>(component_[k])] = 1;
        return count;
    }

    /// The same when every traced cell grew from an area-corner seed (a lone worker): one anchored
    /// component, without the union-find. Returns the count (0 when nothing was traced).
    std::int32_t single_component() {
        component_.assign(cells_.size(), 0);
        anchored_.assign(cells_.empty() ? 0 : 1, 1);
        return cells_.empty() ? 0 : 1;
    }

    /// Component of traced cell (i, j), or -1 if it was not traced.
    std::int32_t component_at(std::int32_t i, std::int32_t j) const {
        if (i < c0_ || i >= c1_ || j < 0 || j >= grid_.ny) return -1;
        const std::int32_t k = index_of_.get(i, j);
        return k >= 0 ? component_[static_cast<std::size_t>(k)] : -1;
    }

    std::size_t size() const { return cells_.size(); }

    /// Traced cell k with its corner labels and exact smallest squared corner distance.
    const TracedCell& cell(std::size_t k) const { return cells_[k]; }

    /// Hands over every traced cell (the tracer is left without cells).
    std::vector<TracedCell> take_cells() { return std::move(cells_); }
    const std::vector<std::int32_t>& components() const { return component_; }
    const std::vector<std::uint8_t>& anchored() const { return anchored_; }
    std::size_t corners_labelled() const { return labelled_; }
    const QueryContext& context() const { return ctx_; }
    std::size_t memory_bytes() const {
        return corners_.memory_bytes() + index_of_.memory_bytes() + cells_.capacity() * sizeof(Cell) +
               component_.capacity() * sizeof(std::int32_t);
    }

private:
    struct Corner {
        std::int32_t part = -1;  // nearest convex part, -1 = not computed yet
        float sq = 0.0f;         // its squared distance, rounded to float
    };

    /// Cell (i, j)'s smallest squared corner distance, exact. Rounding to float is monotone, so it
    /// is at a corner whose float equals the smallest float: only those are recomputed (with the
    /// index's own distance function: the same doubles).
    double min_sq(std::int32_t i, std::int32_t j) {
        const std::int32_t ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
        Corner q[4];
        float fmin = std::numeric_limits<float>::infinity();
        for (int k = 0; k < 4; ++k) {
            q[k] = corner(ci[k], cj[k]);
            fmin = std::min(fmin, q[k].sq);
        }
        double best = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 4; ++k)
            if (!(q[k].sq > fmin)) {
                const auto& part = scene_->parts[static_cast<std::size_t>(q[k].part)];
                best = std::min(best, sq_distance(*scene_, part, grid_.corner(ci[k], cj[k]), index_->visibility()));
            }
        return best;
    }

    Corner corner(std::int32_t i, std::int32_t j) {
        Corner& c = corners_.at(i, j);
        if (c.part < 0) {
            const Nearest n = index_->nearest(grid_.corner(i, j), ctx_);
            c.part = n.part;
            c.sq = static_cast<float>(n.sq);
            ++labelled_;
        }
        return c;
    }

    using Cell = TracedCell;  // the queue entry is the handed-over cell: a lone worker moves them out

    /// Labels of cell (i, j)'s corners: bottom-left, bottom-right, top-right, top-left.
    std::array<std::int32_t, 4> labels(std::int32_t i, std::int32_t j) {
        return {label(i, j), label(i + 1, j), label(i + 1, j + 1), label(i, j + 1)};
    }

    const Scene* scene_ = nullptr;
    const ObstacleIndex* index_ = nullptr;
    GridSpec grid_;
    std::int32_t c0_ = 0, c1_ = 0;
    QueryContext ctx_;
    LazyGrid<Corner> corners_;         // corner columns [c0, c1]
    LazyGrid<std::int32_t> index_of_;  // cell -> position in cells_, -1 when not traced
    std::size_t labelled_ = 0;
    std::vector<Cell> cells_;
    std::vector<std::uint32_t> anchors_;  // cells seeded at the area's corners
    // Cells queued and not yet taken, taken last-in first-out: the trace then follows one branch of
    // the diagram at a time, so consecutive cells share corner tiles, obstacle buckets and the
    // previous nearest part (a first-in first-out queue hops between all branches' fronts). The
    // traced set is what is reachable from the seeds, whatever the order.
    std::vector<std::uint32_t> waiting_;
    std::vector<std::int32_t> component_;
    std::vector<std::uint8_t> anchored_;
};

}  // namespace dvoronoi::gvd
