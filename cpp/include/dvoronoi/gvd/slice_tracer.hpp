// One worker of the grid Voronoi diagram (Mendes et al., Sections 2 and 3): finds the diagram inside
// a vertical slice of columns [c0, c1), labelling cell corners lazily.
//
// Tracing as published: a cell is queued when its corners carry two or more labels; when it is taken
// from the queue, each of its four edges whose two corners have different labels leads to the
// neighbour across that edge (which then also has two labels), queued unless it was queued before
// ("never re-enter"; the entrance edge is one of those). Cells outside the slice or the working area
// are not entered. Corner labels are computed only for corners of queued cells, of the scanned
// border lines and of the seed searches below, and kept in lazily allocated tiles, so the work and
// the memory follow the diagram's length, not the grid's area (lazy_grid.hpp). Blocking by robot
// radius happens when results are assembled; a blocked cell is traced through like any other (the
// paper: "still inserted in the queue").
//
// Added (issue 19). The paper starts from the area's corners only. On real maps they lie inside
// walls, the loops around islands touch none of them, and regions thinner than a cell (a sliver
// behind a point close to a wall, the tip of a region in a wall's recess) leave diagram cells that
// no label change joins to anything. The worker finds every cell the definition marks in its slice:
//
// Z = the points where the two nearest labels are equally far (within rounding, err). A diagram cell
// has a label-changing edge, and that edge holds a point of Z.
//  1. Bridges. Each corner also stores its gap: how much farther than its own label A the nearest
//     other label is (among the parts that can be nearest in its index bucket, which hold every
//     label that can be nearest on an edge inside that bucket; obstacle_index.hpp). Distances are
//     1-Lipschitz, so an edge whose two corners carry A with gaps summing to more than 2h is A's at
//     every point (when both corners have the same nearest part P, the distance to P is convex along
//     the edge and a sharper bound applies: clear()). Such an edge is certified; tracing also
//     crosses every uncertified edge, into cells that may carry one label ("bridge" cells, explored,
//     not part of the diagram). An edge Z crosses is never certified, so all the cells that meet one
//     connected piece of Z are reached from any of them (through the edges, or around the corner,
//     Z passes). The cells reached from one seed form a "piece".
//  2. Walks from the obstacles. A piece of Z that touches no obstacle has no free end (bisectors of
//     disjoint sites end only at other bisectors), so it encloses a face, and the face's obstacle:
//     a whole convex part (every point's segment to its nearest point stays in its face). Take the
//     object inside that enclosure — a part, or a piece traced in this slice — whose rightmost
//     column is greatest; walking right along a grid row from its rightmost point (cell) it meets no
//     other object before the enclosing piece, so the first cell with an uncertified edge it reaches
//     is on that piece. So every part's rightmost point and every piece's rightmost cell start a walk
//     that seeds the first such cell. A walk stops early (soundly) when a corner of a cell it crossed
//     has a nearest part of a greater key (rightmost column, then index; a piece outranks a part of
//     its own column): that part lies inside the same enclosure, so this walk was not the one needed.
//  3. Contacts. A piece of Z that touches an obstacle touches two labels at once: parts of different
//     labels that meet or overlap (within the index's tolerance; an obstacle crossing the area's
//     boundary; the area's corners, where two area edges meet). The boundary of each part of such a
//     pair is sampled every h/2 near the other, and the cells within h/4 of samples within h/4 of the
//     other part are seeded: they hold the points of contact, which lie on the piece.
//  4. The area's corners (the paper's seeds); the cells the area's boundary cuts (a cell of the area
//     with corners outside it can carry two labels because of obstacles outside the area, with the
//     change outside: each is tested); and between slices, the border lines: every row where the
//     border edge is uncertified seeds the cells beside it.
// In a slice, a diagram cell is cut by the area's boundary (4) or holds a point of Z in the area,
// whose piece crosses a border line (4), touches an obstacle (3) or lies inside the slice with all
// it encloses (2). So every slice finds exactly its own cells of the diagram (whatever the walks
// that left the slice would have found elsewhere), and every traced cell is kept.
//
// Cost: the traced cells; a fringe of bridge cells (about one cell wide where the two nearest
// obstacles lie on opposite sides; wider where they are seen in nearly the same direction, e.g.
// behind a point close to a wall, and over the overlap of obstacles of different labels, where the
// gap is 0); the walks (a walk ends at the diagram or where another obstacle becomes nearest: about
// the distance from an obstacle to the diagram); the sampled contacts and the cut boundary cells.
// Proportional to the diagram and the obstacles' boundaries, not to the grid's area.
#pragma once

#include "dvoronoi/gvd/grid.hpp"
#include "dvoronoi/gvd/lazy_grid.hpp"
#include "dvoronoi/gvd/obstacle_index.hpp"
#include "dvoronoi/gvd/slice_merge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
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

/// What a slice worker's seed searches did.
struct SeedCounts {
    std::uint64_t walks = 0;          ///< walks from parts and from traced pieces
    std::uint64_t walk_cells = 0;     ///< cells the walks looked at
    std::uint64_t walk_seeds = 0;     ///< cells the walks queued
    std::uint64_t contact_seeds = 0;  ///< cells queued near where obstacles of different labels meet
    std::uint64_t boundary_seeds = 0;  ///< cells queued along the area's boundary
};

class SliceTracer {
public:
    SliceTracer() = default;
    SliceTracer(const Scene& scene, const ObstacleIndex& index, const GridSpec& grid, std::int32_t c0,
                std::int32_t c1)
        : scene_(&scene), index_(&index), grid_(grid), c0_(c0), c1_(c1), ctx_(index.context()),
          corners_(c0, static_cast<std::int64_t>(c1) - c0 + 1, static_cast<std::int64_t>(grid.ny) + 1, Corner{}),
          index_of_(c0, static_cast<std::int64_t>(c1) - c0, grid.ny, -1) {
        margin_ = 1e-9 * grid.h + index.tolerance();
        // Bucket column (row) of every corner column (row) of the slice, -1 outside the bucket grid.
        bcol_.resize(static_cast<std::size_t>(c1 - c0) + 1);
        for (std::int32_t i = c0; i <= c1; ++i) bcol_[static_cast<std::size_t>(i - c0)] = index.bucket_column(grid.corner(i, 0).x());
        brow_.resize(static_cast<std::size_t>(grid.ny) + 1);
        for (std::int32_t j = 0; j <= grid.ny; ++j) brow_[static_cast<std::size_t>(j)] = index.bucket_row(grid.corner(0, j).y());
        cap_ = 2.0 * grid.h + 4.0 * margin_;
        if (scene.area_is_box) {  // cell_in_area's test on a box, split by axis
            const Box& b = scene.box;
            col_in_box_.resize(static_cast<std::size_t>(c1 - c0));
            for (std::int32_t i = c0; i < c1; ++i)
                col_in_box_[static_cast<std::size_t>(i - c0)] = grid.corner(i, 0).x() < b.x1 && grid.corner(i + 1, 0).x() > b.x0;
            row_in_box_.resize(static_cast<std::size_t>(grid.ny));
            for (std::int32_t j = 0; j < grid.ny; ++j)
                row_in_box_[static_cast<std::size_t>(j)] = grid.corner(0, j).y() < b.y1 && grid.corner(0, j + 1).y() > b.y0;
        }
        // Rightmost point of each part: its column is the part's key for the walks.
        rcol_.resize(scene.parts.size());
        rrow_.resize(scene.parts.size());
        for (std::size_t k = 0; k < scene.parts.size(); ++k) {
            const ConvexPart& p = scene.parts[k];
            Vec2 r = p.center + Vec2(p.radius, 0.0);
            if (p.kind != ShapeKind::Circle) {
                const Vec2* v = scene.part_vertices(p);
                r = v[0];
                for (std::uint32_t t = 1; t < p.count; ++t)
                    if (v[t].x() > r.x()) r = v[t];
            }
            rcol_[k] = cell_index(r.x(), grid.x0);
            rrow_[k] = cell_index(r.y(), grid.y0);
        }
    }

    std::int32_t c0() const { return c0_; }
    std::int32_t c1() const { return c1_; }

    /// The convex part nearest to corner (i, j), c0 <= i <= c1, computed on first use. The part is
    /// stored with its squared distance rounded to float and its gap (12 bytes a corner): the label
    /// and the exact squared distance follow from the part.
    std::int32_t corner_part(std::int32_t i, std::int32_t j) { return corner(i, j).part; }

    /// The label (nearest obstacle) of corner (i, j).
    std::int32_t label(std::int32_t i, std::int32_t j) {
        return scene_->parts[static_cast<std::size_t>(corner_part(i, j))].label;
    }

    /// May the edge between adjacent corners a and b hold a point of Z (see the header)? True when
    /// their labels differ; otherwise false only when certified.
    bool uncertified(std::int32_t ia, std::int32_t ja, std::int32_t ib, std::int32_t jb) {
        return uncertified(corner(ia, ja), corner(ib, jb), ia, ja, ib, jb);
    }

    /// Does cell (i, j) have an edge that Z may cross?
    bool open_cell(std::int32_t i, std::int32_t j) {
        return uncertified(i, j, i + 1, j) || uncertified(i + 1, j, i + 1, j + 1) || uncertified(i, j + 1, i + 1, j + 1) ||
               uncertified(i, j, i, j + 1);
    }

    /// Rows j of the grid line x = x0 + line h whose edge from corner (line, j) to (line, j+1) is
    /// uncertified (a label change, or a same-label edge Z may cross) with a cell of the working area
    /// beside it. Labels ny + 1 corners.
    std::vector<std::int32_t> scan_line(std::int32_t line) {
        std::vector<std::int32_t> rows;
        for (std::int32_t j = 0; j < grid_.ny; ++j)
            if (uncertified(line, j, line, j + 1) &&
                (cell_in_area(*scene_, grid_, line - 1, j) || cell_in_area(*scene_, grid_, line, j)))
                rows.push_back(j);
        return rows;
    }

    /// Queues cell (i, j) if it lies in this slice and the working area, has an uncertified edge and
    /// was not queued before, and traces from it (trace()). Returns whether it was queued. A seed
    /// reached by no earlier one starts a piece of its own, traced whole before the next seed.
    bool seed(std::int32_t i, std::int32_t j) {
        if (i < c0_ || i >= c1_ || j < 0 || j >= grid_.ny) return false;
        if (index_of_.get(i, j) >= 0) return false;
        if (!in_area(i, j)) return false;
        if (!open_cell(i, j)) return false;
        add(i, j, pieces_++);
        trace();
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
                    if (lo.x() <= v.x() && v.x() <= hi.x() && lo.y() <= v.y() && v.y() <= hi.y()) seed(ci, cj);
                }
        }
    }

    /// Seeds the cells of this slice that cross the working area's boundary (header, 4): a cell of
    /// the area with a corner outside it can carry two labels because of obstacles outside the area.
    /// On a box area only the right and top sides can cut cells (the grid starts at the box's
    /// lower-left corner).
    void seed_area_boundary() {
        const double h = grid_.h;
        Box r;
        r.x0 = grid_.x0 + static_cast<double>(c0_) * h - h;
        r.x1 = grid_.x0 + static_cast<double>(c1_) * h + h;
        r.y0 = grid_.y0 - h;
        r.y1 = grid_.y0 + static_cast<double>(grid_.ny) * h + h;
        const auto& area = scene_->area;
        const std::size_t n = area.size();
        const bool right_cut = grid_.corner(grid_.nx, 0).x() > scene_->box.x1;
        const bool top_cut = grid_.corner(0, grid_.ny).y() > scene_->box.y1;
        for (std::size_t k = 0; k < n; ++k) {
            const Vec2 &a = area[k], &b = area[(k + 1) % n];
            if (scene_->area_is_box) {
                const bool right = a.x() == scene_->box.x1 && b.x() == scene_->box.x1;
                const bool top = a.y() == scene_->box.y1 && b.y() == scene_->box.y1;
                if (!((right && right_cut) || (top && top_cut))) continue;
            }
            sample_segment(a, b, r, [&](const Vec2& p) { seeds_.boundary_seeds += seed_around(p); });
        }
    }

    /// Seeds where parts of different labels meet or overlap (header, 3), in this slice.
    void seed_contacts() {
        const double h = grid_.h;
        const double x_lo = grid_.x0 + static_cast<double>(c0_) * h - h, x_hi = grid_.x0 + static_cast<double>(c1_) * h + h;
        index_->for_each_close_pair(x_lo, x_hi, [&](std::uint32_t a, std::uint32_t b) {
            sample_contact(a, b, x_lo, x_hi);
            sample_contact(b, a, x_lo, x_hi);
        });
    }

    /// Walks right from the rightmost point of every obstacle part in this slice (header, 2).
    void seed_obstacle_walks() {
        for (std::size_t k = 0; k < scene_->parts.size(); ++k) {
            if (scene_->parts[k].label >= scene_->n_obstacles) continue;  // area edges enclose nothing
            const std::int64_t i = rcol_[k], j = rrow_[k];
            if (i < c0_ || i >= c1_ || j < 0 || j >= grid_.ny) continue;
            walk(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j), static_cast<std::int64_t>(k));
        }
    }

    /// Runs the queue empty (Section 2's loop; also across uncertified same-label edges).
    void trace() {
        while (!waiting_.empty()) {
            const std::uint32_t k = waiting_.back();
            waiting_.pop_back();
            const Node c = nodes_[k];
            const std::int32_t i = c.i, j = c.j;
            const Corner q0 = corner(i, j), q1 = corner(i + 1, j), q2 = corner(i + 1, j + 1), q3 = corner(i, j + 1);
            const std::array<std::int32_t, 4> lab = {label_of(q0), label_of(q1), label_of(q2), label_of(q3)};
            if (!(lab[0] == lab[1] && lab[1] == lab[2] && lab[2] == lab[3])) {  // a diagram cell
                nodes_[k].cell = static_cast<std::int32_t>(cells_.size());
                // The clearance now, while the corners are in cache (the hand-over reads cells in order).
                cells_.push_back({i, j, lab, min_sq(i, j, {q0, q1, q2, q3})});
            }
            const bool b = fresh(i, j - 1), r = fresh(i + 1, j), t = fresh(i, j + 1), l = fresh(i - 1, j);
            if (b && uncertified(q0, q1, i, j, i + 1, j)) add(i, j - 1, c.comp);              // bottom edge
            if (r && uncertified(q1, q2, i + 1, j, i + 1, j + 1)) add(i + 1, j, c.comp);      // right edge
            if (t && uncertified(q3, q2, i, j + 1, i + 1, j + 1)) add(i, j + 1, c.comp);      // top edge
            if (l && uncertified(q0, q3, i, j, i, j + 1)) add(i - 1, j, c.comp);              // left edge
        }
    }

    /// Walks right from the rightmost cell of every piece traced since the last call (header, 2).
    /// Returns whether a walk found a new piece (then call this again).
    bool walk_from_new_pieces() {
        const std::size_t from = walked_nodes_, to = nodes_.size();
        walked_nodes_ = to;
        if (from == to) return false;
        // Pieces are traced whole one after the other: those since the last call are new ones.
        const std::int32_t first = nodes_[from].comp;
        std::vector<std::int32_t> best(static_cast<std::size_t>(pieces_ - first), -1);
        for (std::size_t k = from; k < to; ++k) {
            const auto r = static_cast<std::size_t>(nodes_[k].comp - first);
            const std::int32_t b = best[r];
            if (b < 0 || nodes_[k].i > nodes_[static_cast<std::size_t>(b)].i ||
                (nodes_[k].i == nodes_[static_cast<std::size_t>(b)].i && nodes_[k].j < nodes_[static_cast<std::size_t>(b)].j))
                best[r] = static_cast<std::int32_t>(k);
        }
        for (std::int32_t b : best)
            if (b >= 0) {
                const Node n = nodes_[static_cast<std::size_t>(b)];
                if (n.i + 1 < c1_) walk(n.i + 1, n.j, -1 - static_cast<std::int64_t>(n.i));
            }
        return nodes_.size() > to;
    }

    /// Every traced cell is part of the diagram and kept (header): one component, anchored.
    /// Returns the count (0 when nothing was traced).
    std::int32_t single_component() {
        component_.assign(cells_.size(), 0);
        anchored_.assign(cells_.empty() ? 0 : 1, 1);
        return cells_.empty() ? 0 : 1;
    }

    /// Component of traced diagram cell (i, j), or -1 if it is not one.
    std::int32_t component_at(std::int32_t i, std::int32_t j) const {
        if (i < c0_ || i >= c1_ || j < 0 || j >= grid_.ny) return -1;
        const std::int32_t k = index_of_.get(i, j);
        if (k < 0) return -1;
        const std::int32_t c = nodes_[static_cast<std::size_t>(k)].cell;
        return c >= 0 && static_cast<std::size_t>(c) < component_.size() ? component_[static_cast<std::size_t>(c)] : -1;
    }

    /// Diagram cells traced (cells with two or more labels).
    std::size_t size() const { return cells_.size(); }
    /// Cells explored: diagram cells and bridge cells.
    std::size_t explored() const { return nodes_.size(); }

    /// Traced cell k with its corner labels and exact smallest squared corner distance.
    const TracedCell& cell(std::size_t k) const { return cells_[k]; }

    /// Hands over every traced cell (the tracer is left without cells).
    std::vector<TracedCell> take_cells() { return std::move(cells_); }
    const std::vector<std::int32_t>& components() const { return component_; }
    const std::vector<std::uint8_t>& anchored() const { return anchored_; }
    std::size_t corners_labelled() const { return labelled_; }
    const SeedCounts& seed_counts() const { return seeds_; }
    const QueryContext& context() const { return ctx_; }
    std::size_t memory_bytes() const {
        return corners_.memory_bytes() + index_of_.memory_bytes() + cells_.capacity() * sizeof(TracedCell) +
               nodes_.capacity() * sizeof(Node) + component_.capacity() * sizeof(std::int32_t);
    }

private:
    struct Corner {
        std::int32_t part = -1;  // nearest convex part, -1 = not computed yet
        float sq = 0.0f;         // its squared distance, rounded to float
        float gap = 0.0f;        // distance to the nearest other label minus its own (bucket candidates), rounded down
    };
    struct Node {
        std::int32_t i = 0, j = 0;
        std::int32_t comp = 0;   // piece: the seed it was traced from
        std::int32_t cell = -1;  // index in cells_, -1 for a bridge cell
    };

    static std::int64_t cell_index(double x, double x0_grid, double h) {
        const double t = std::floor((x - x0_grid) / h);
        if (!(t > -1e18 && t < 1e18)) return -1;  // NaN or far away: never a valid cell
        return static_cast<std::int64_t>(t);
    }
    std::int64_t cell_index(double x, double x0_grid) const { return cell_index(x, x0_grid, grid_.h); }

    /// The same with the two corners' entries at hand.
    bool uncertified(const Corner& a, const Corner& b, std::int32_t ia, std::int32_t ja, std::int32_t ib, std::int32_t jb) {
        if (a.part == b.part) {
            if (!clear(a, b, a.gap, b.gap)) return true;
        } else {
            if (scene_->parts[static_cast<std::size_t>(a.part)].label != scene_->parts[static_cast<std::size_t>(b.part)].label) return true;
            if (!clear(a, b, a.gap, b.gap)) return true;
        }
        // Both gaps are over the same bucket's candidates: that bucket holds the whole edge.
        const int bia = bcol_[static_cast<std::size_t>(ia - c0_)], bja = brow_[static_cast<std::size_t>(ja)];
        const int bib = bcol_[static_cast<std::size_t>(ib - c0_)], bjb = brow_[static_cast<std::size_t>(jb)];
        const bool ina = bia >= 0 && bja >= 0, inb = bib >= 0 && bjb >= 0;
        if (ina && inb && bia == bib && bja == bjb) return false;
        const Vec2 qa = grid_.corner(ia, ja), qb = grid_.corner(ib, jb);
        std::size_t ba = 0, bb = 0;
        if (ina) index_->bucket_of(qa, ba);
        if (inb) index_->bucket_of(qb, bb);
        // The edge spans two buckets (or leaves the bucket grid): each end's gap over the labels
        // that can be nearest anywhere on the edge.
        const auto& pa = scene_->parts[static_cast<std::size_t>(a.part)];
        const auto& pb = scene_->parts[static_cast<std::size_t>(b.part)];
        const Nearest na{pa.label, sq_distance(*scene_, pa, qa, index_->visibility()), a.part};
        const Nearest nb{pb.label, sq_distance(*scene_, pb, qb, index_->visibility()), b.part};
        double ga, gb;
        if (ina && inb && grid_.h <= index_->bucket_size()) {
            ga = std::min<double>(a.gap, index_->bucket_gap(qa, na, bb, cap_, ctx_));
            gb = std::min<double>(b.gap, index_->bucket_gap(qb, nb, ba, cap_, ctx_));
        } else {
            ga = index_->global_gap(qa, na, cap_, ctx_);
            gb = index_->global_gap(qb, nb, cap_, ctx_);
        }
        return !clear(a, b, ga, gb);
    }

    /// Is every point of the edge from corner a to corner b (same label A, h apart) strictly A's,
    /// given lower bounds ga, gb on how much farther than A any other label is at a and b?
    /// Another label M is 1-Lipschitz: d_M(y) >= d_A(a) + ga - t h at the point y = a + t (b - a),
    /// and >= d_A(b) + gb - (1 - t) h. A is 1-Lipschitz too, so d_M - d_A > 0 on the edge when
    /// ga + gb > 2h; when a and b have the same nearest part P, d_A <= d_P, which is convex along the
    /// edge (P is convex), so d_A(y) <= (1 - t) d_A(a) + t d_A(b) and the bound is
    /// min over t of max(ga - t (h - D), gb - (1 - t) (h + D)) with D = d_A(a) - d_A(b) (|D| <= h):
    /// positive as soon as ga + gb > h when D = 0, and as soon as ga > 0 when the edge points
    /// straight at P (D = h). `margin_` absorbs rounding.
    bool clear(const Corner& a, const Corner& b, double ga, double gb) const {
        const double h = grid_.h;
        if (ga + gb > 2.0 * h + 2.0 * margin_) return true;
        if (a.part != b.part || !(std::max(ga, gb) > 2.0 * margin_)) return false;  // the bound is at most max(ga, gb)
        // D from the stored float squares: each within 2^-24 relative, so D within `slack`.
        const double da = std::sqrt(static_cast<double>(a.sq)), db = std::sqrt(static_cast<double>(b.sq));
        const double slack = 1e-7 * (da + db);
        const double d = std::clamp(da - db, -h, h);
        const double sa = h - d, sb = h + d;  // slopes, sa + sb = 2h
        const double t = std::clamp((ga - gb + sb) / (2.0 * h), 0.0, 1.0);
        return std::max(ga - sa * t, gb - sb * (1.0 - t)) > 2.0 * margin_ + slack;
    }

    /// Queues cell (i, j) for piece `comp` (its corners are looked at when it is taken).
    void add(std::int32_t i, std::int32_t j, std::int32_t comp) {
        const auto k = static_cast<std::int32_t>(nodes_.size());
        index_of_.at(i, j) = k;
        nodes_.push_back(Node{i, j, comp, -1});
        waiting_.push_back(static_cast<std::uint32_t>(k));
    }

    /// cell_in_area for a cell of this slice (c0 <= i < c1, 0 <= j < ny); on a box area from the
    /// column's and the row's overlap with the box, computed once.
    bool in_area(std::int32_t i, std::int32_t j) const {
        if (!scene_->area_is_box) return cell_in_area(*scene_, grid_, i, j);
        return col_in_box_[static_cast<std::size_t>(i - c0_)] && row_in_box_[static_cast<std::size_t>(j)];
    }

    /// Is cell (i, j) in this slice and the working area, and not queued before?
    bool fresh(std::int32_t i, std::int32_t j) {
        if (i < c0_ || i >= c1_ || j < 0 || j >= grid_.ny) return false;
        return index_of_.get(i, j) < 0 && in_area(i, j);
    }

    /// Walks right along row j from cell (i, j) to the slice's end: seeds the first cell with an
    /// uncertified edge, or stops where a corner's nearest part outranks the walk's object. `key`:
    /// a part index (>= 0: a part outranks it when its rightmost column is greater, or equal with a
    /// greater index), or -1 - m for a traced piece whose rightmost column is m (a part outranks it
    /// when its rightmost column is greater than m).
    void walk(std::int32_t i, std::int32_t j, std::int64_t key) {
        ++seeds_.walks;
        const bool from_part = key >= 0;
        const std::int64_t col = from_part ? rcol_[static_cast<std::size_t>(key)] : -1 - key;
        auto outranks = [&](std::int32_t part) {
            if (scene_->parts[static_cast<std::size_t>(part)].label >= scene_->n_obstacles) return true;  // area edge: not inside
            const std::int64_t c = rcol_[static_cast<std::size_t>(part)];
            if (c != col) return c > col;
            return from_part && part > key;
        };
        for (; i < c1_; ++i) {
            ++seeds_.walk_cells;
            if (index_of_.get(i, j) >= 0) return;  // reached a traced piece
            if (!in_area(i, j)) return;
            if (open_cell(i, j)) {
                if (seed(i, j)) ++seeds_.walk_seeds;
                return;
            }
            // Every corner of this cell is strictly its label's (its edges are certified).
            if (outranks(corner_part(i, j)) || outranks(corner_part(i, j + 1)) || outranks(corner_part(i + 1, j)) ||
                outranks(corner_part(i + 1, j + 1)))
                return;
        }
    }

    /// Seeds the cells of this slice within h/4 of point p (every cell holding a point within h/4
    /// of p). Returns how many it queued.
    std::uint64_t seed_around(const Vec2& p) {
        const double q = 0.25 * grid_.h * (1.0 + 1e-6) + margin_;
        const std::int64_t i0 = cell_index(p.x() - q, grid_.x0), i1 = cell_index(p.x() + q, grid_.x0);
        const std::int64_t j0 = cell_index(p.y() - q, grid_.y0), j1 = cell_index(p.y() + q, grid_.y0);
        std::uint64_t n = 0;
        for (std::int64_t jj = std::max<std::int64_t>(j0, 0); jj <= std::min<std::int64_t>(j1, grid_.ny - 1); ++jj)
            for (std::int64_t ii = std::max<std::int64_t>(i0, c0_); ii <= std::min<std::int64_t>(i1, c1_ - 1); ++ii)
                n += seed(static_cast<std::int32_t>(ii), static_cast<std::int32_t>(jj)) ? 1 : 0;
        return n;
    }

    /// Calls probe(s) for points s of segment pq clipped to box r, at most h/2 apart, the clipped
    /// ends included: every point of the clipped segment lies within h/4 of one.
    template <class F>
    void sample_segment(const Vec2& p, const Vec2& q, const Box& r, F&& probe) const {
        double t0 = 0.0, t1 = 1.0;  // Liang-Barsky
        const Vec2 d = q - p;
        const double pp[4] = {-d.x(), d.x(), -d.y(), d.y()};
        const double qq[4] = {p.x() - r.x0, r.x1 - p.x(), p.y() - r.y0, r.y1 - p.y()};
        for (int k = 0; k < 4; ++k) {
            if (pp[k] == 0.0) {
                if (qq[k] < 0.0) return;
            } else {
                const double t = qq[k] / pp[k];
                if (pp[k] < 0.0) t0 = std::max(t0, t);
                else t1 = std::min(t1, t);
            }
        }
        if (t0 > t1) return;
        const Vec2 u = p + t0 * d, w = p + t1 * d;
        const auto n = static_cast<std::int64_t>(std::ceil((w - u).norm() / (0.5 * grid_.h)));
        for (std::int64_t k = 0; k <= n; ++k) probe(n == 0 ? u : u + (w - u) * (static_cast<double>(k) / static_cast<double>(n)));
    }

    /// Samples the boundary of part a where it comes within the tolerance of part b (of another
    /// label) and seeds the cells around those samples.
    void sample_contact(std::uint32_t a, std::uint32_t b, double x_lo, double x_hi) {
        const Scene& s = *scene_;
        const ConvexPart& pa = s.parts[a];
        const ConvexPart& pb = s.parts[b];
        const double h = grid_.h, tol = index_->tolerance();
        const double reach = tol + 0.25 * h;  // a contact point lies within h/4 of a sample
        Box r = pb.box;
        r.x0 -= reach + h; r.y0 -= reach + h; r.x1 += reach + h; r.y1 += reach + h;
        r.x0 = std::max(r.x0, x_lo);
        r.x1 = std::min(r.x1, x_hi);
        // A probe farther than h/4 + margin_ beyond the grid's rows seeds nothing (seed_around keeps
        // to the grid): r need not reach further.
        const double beyond = h + 0.25 * h * (1.0 + 1e-6) + margin_;
        r.y0 = std::max(r.y0, grid_.y0 - beyond);
        r.y1 = std::min(r.y1, grid_.y0 + static_cast<double>(grid_.ny) * h + beyond);
        if (!(r.x0 <= r.x1 && r.y0 <= r.y1)) return;
        auto probe = [&](const Vec2& p) {
            if (p.x() < r.x0 || p.x() > r.x1 || p.y() < r.y0 || p.y() > r.y1) return;
            if (sq_distance(s, pb, p, false) > reach * reach) return;
            seeds_.contact_seeds += seed_around(p);
        };
        const Vec2* v = s.part_vertices(pa);
        switch (pa.kind) {
            case ShapeKind::Point: probe(v[0]); break;
            case ShapeKind::Segment: sample_segment(v[0], v[1], r, probe); break;
            case ShapeKind::Polygon:
                for (std::uint32_t k = 0; k < pa.count; ++k) sample_segment(v[k], v[k + 1 == pa.count ? 0 : k + 1], r, probe);
                break;
            case ShapeKind::Circle: {
                // Only the arc that can pass through r is sampled (probe ignores the rest), at most h/2
                // apart: the angles the box r subtends from the center, a step more on each side.
                // (Before: the whole circle, 2 pi R / (h/2) probes: a radius of 2^31 in a 16-cell grid
                // took an hour, and a larger one overflowed the count.)
                constexpr double pi = 3.14159265358979323846, two_pi = 2.0 * pi;
                const Vec2 c = pa.center;
                const double R = pa.radius;
                const double gx = std::max({r.x0 - c.x(), 0.0, c.x() - r.x1}), gy = std::max({r.y0 - c.y(), 0.0, c.y() - r.y1});
                double far = 0.0;
                const Vec2 box_corner[4] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
                for (const Vec2& q : box_corner) far = std::max(far, (q - c).norm());
                if (std::sqrt(gx * gx + gy * gy) > R * (1.0 + 1e-9) + h || far + h < R * (1.0 - 1e-9)) break;  // the circle misses r
                const double step = 0.5 * h / R;
                double t_lo = 0.0, t_hi = two_pi;
                if (gx > 0.0 || gy > 0.0) {  // c outside r: r lies within less than pi as seen from c
                    const double mid = std::atan2(0.5 * (r.y0 + r.y1) - c.y(), 0.5 * (r.x0 + r.x1) - c.x());
                    double lo = 0.0, hi = 0.0;
                    for (const Vec2& q : box_corner) {
                        double turn = std::atan2(q.y() - c.y(), q.x() - c.x()) - mid;
                        if (turn > pi) turn -= two_pi;
                        if (turn < -pi) turn += two_pi;
                        lo = std::min(lo, turn);
                        hi = std::max(hi, turn);
                    }
                    t_lo = mid + lo - step;
                    t_hi = mid + hi + step;
                }
                const double count = std::ceil((t_hi - t_lo) / step);
                if (!(count < 1e9)) break;  // not reached: r is at most the grid, the arc through it ~ r / (h/2)
                const auto n = static_cast<std::int64_t>(count) + 1;
                for (std::int64_t k = 0; k < n; ++k) {
                    const double t = t_lo + (t_hi - t_lo) * static_cast<double>(k) / static_cast<double>(n);
                    probe(c + R * Vec2(std::cos(t), std::sin(t)));
                }
                break;
            }
        }
    }

    /// Cell (i, j)'s smallest squared corner distance, exact. Rounding to float is monotone, so it
    /// is at a corner whose float equals the smallest float: only those are recomputed (with the
    /// index's own distance function: the same doubles).
    double min_sq(std::int32_t i, std::int32_t j, const std::array<Corner, 4>& q) const {
        const std::int32_t ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
        float fmin = std::numeric_limits<float>::infinity();
        for (int k = 0; k < 4; ++k) fmin = std::min(fmin, q[k].sq);
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
            double gap = 0.0;
            bool global = false;
            const Nearest n = index_->nearest_gap(grid_.corner(i, j), cap_, ctx_, gap, global);
            c.part = n.part;
            c.sq = static_cast<float>(n.sq);
            // Rounded down: the nearest float to gap (1 - 2^-22) lies below gap (gap >= 0).
            c.gap = static_cast<float>(gap * (1.0 - 0x1p-22));
            ++labelled_;
        }
        return c;
    }

    std::int32_t label_of(const Corner& c) const { return scene_->parts[static_cast<std::size_t>(c.part)].label; }

    const Scene* scene_ = nullptr;
    const ObstacleIndex* index_ = nullptr;
    GridSpec grid_;
    std::int32_t c0_ = 0, c1_ = 0;
    QueryContext ctx_;
    double margin_ = 0.0, cap_ = 0.0;
    LazyGrid<Corner> corners_;         // corner columns [c0, c1]
    LazyGrid<std::int32_t> index_of_;  // cell -> position in nodes_, -1 when not explored
    std::size_t labelled_ = 0;
    std::vector<TracedCell> cells_;    // diagram cells, in the order they were found
    std::vector<Node> nodes_;          // every explored cell
    std::int32_t pieces_ = 0;          // seeds that started a piece
    std::size_t walked_nodes_ = 0;     // nodes_ before this index have had their piece walked from
    std::vector<std::int64_t> rcol_, rrow_;  // per part: cell of its rightmost point
    std::vector<int> bcol_, brow_;           // per corner column / row: its bucket column / row (-1 outside)
    std::vector<std::uint8_t> col_in_box_, row_in_box_;  // box areas: per cell column / row, overlaps the box
    SeedCounts seeds_;
    // Cells queued and not yet taken, taken last-in first-out: the trace then follows one branch of
    // the diagram at a time, so consecutive cells share corner tiles, obstacle buckets and the
    // previous nearest part (a first-in first-out queue hops between all branches' fronts). The
    // traced set is what is reachable from the seeds, whatever the order.
    std::vector<std::uint32_t> waiting_;
    std::vector<std::int32_t> component_;
    std::vector<std::uint8_t> anchored_;
};

}  // namespace dvoronoi::gvd
