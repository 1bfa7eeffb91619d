// Incremental updates of the medial diagram (SPEC: "after any sequence of updates" the diagram is
// exactly what a full build on the new map gives): pixels become occupied or free, and only what the
// change can affect is recomputed.
//
// An update runs in two exact steps, removals first, then additions:
//  1. Columns: the vertical nearest squares (pass 1) are recomputed between the nearest pixels of the
//     column that stay occupied; the rows where a column's value changed are recorded.
//  2. Nearest points. A pixel's nearest point comes from its row's pass-1 squares, so only rows with
//     a changed column can change, and in them:
//     - removals: a pixel needs a new nearest point only if its old one lies on no occupied square any
//       more; that square was its column's pass-1 square, so the point's x lies in the changed columns'
//       span, and nearest points' x only grows along a row: the candidates are one interval, found by
//       binary search. They are recomputed from the row's squares in a window that the pixel's own
//       column bounds (its own square is at distance <= V, so no farther column can win).
//     - additions: squares only come closer; a pixel takes a changed column's square when it beats (or
//       ties with a smaller x) the one it has. Scanning outward from a run of changed columns stops at
//       the first pixel that keeps a nearest point lying beyond the run: parabolas of translates
//       differ by a linear function, so beyond that pixel the run never wins again.
//  3. Diagram: the pair rule reads a pixel's and its neighbours' nearest points and the occupancy in
//     a box spanned by two nearest points at most prune_length apart (grown by one pixel). Rechecked:
//     pixels whose nearest point or occupancy changed, their neighbours, and pixels of box-judged
//     pairs (MedialDiagram::boxed) whose nearest point lies within prune_length + 3 pixels of a
//     changed pixel (searched within the largest clearance of the map; skipped where no unchanged
//     wall is that near). They are re-marked in row segments, vectorised as a build marks rows.
#pragma once

#include "dvoronoi/gvd/medial_diagram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace dvoronoi::gvd {

/// What an update touched.
struct UpdateStats {
    std::uint64_t changed_pixels = 0;     ///< pixels whose occupancy flipped
    std::uint64_t column_cells = 0;       ///< pass-1 values recomputed
    std::uint64_t feature_changes = 0;    ///< pixels whose nearest point changed
    std::uint64_t mask_checks = 0;        ///< pixels whose diagram membership was rechecked
};

namespace detail {

/// First x in row r with fx >= lo (fx is non-decreasing along a row).
inline std::int32_t first_at_least(const FeatureMap& f, std::int32_t r, std::int32_t lo) {
    const std::int16_t* fx = &f.fx[f.at(r, 0)];
    return static_cast<std::int32_t>(std::lower_bound(fx, fx + f.cols, lo) - fx);
}

class Updater {
public:
    explicit Updater(MedialDiagram& m) : m_(m), g_(m.grid), f_(m.features) {}

    /// Sets the listed pixels (linear indices) to `occupied`; pixels already so are skipped.
    void apply(const std::vector<std::size_t>& pixels, bool occupied) {
        std::vector<std::size_t> todo;
        for (std::size_t i : pixels)
            if ((g_.occupied[i] != 0) != occupied) todo.push_back(i);
        std::sort(todo.begin(), todo.end());
        todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
        if (todo.empty()) return;
        stats.changed_pixels += todo.size();
        touched_.reserve(touched_.size() + 16 * todo.size());  // a blob's nearest points change around it
        for (std::size_t i : todo) {
            g_.occupied[i] = occupied ? 1 : 0;
            const auto r = static_cast<std::int32_t>(i / static_cast<std::size_t>(g_.cols));
            m_.bits.put(g_.rows - 1 - r, static_cast<std::int32_t>(i % static_cast<std::size_t>(g_.cols)), occupied);
            changed_.push_back(i);
            touched_.push_back(i);
        }
        const auto rows_changed = update_columns(todo, occupied);
        if (occupied) {
            for (const auto& rc : rows_changed) add_row(rc.first, rc.second);
        } else {
            for (const auto& rc : rows_changed) remove_row(rc.first, rc.second);
        }
    }

    /// Rechecks the diagram where the changes can reach it. A pixel's membership is a function of
    /// the final nearest points, so the pixels found are collected, then re-marked row segment by
    /// row segment as a build marks them.
    void refresh_mask() {
        if (changed_.empty()) return;
        const std::int32_t H = g_.rows, W = g_.cols;
        PixelMask redo(H, W);  // touched pixels and their 4-neighbours (they share a pair)
        for (std::size_t i : touched_) redo.set(i, true);
        redo = redo.dilated4();
        // Pixels whose nearest point lies near a change (the box rule): changed pixels grouped in
        // tiles, each tile's box grown by that margin, searched in the rows within the map's
        // largest clearance of it.
        // a grown box lies within prune_length + sqrt(2) + 1 pixels of either nearest point
        const std::int32_t margin = static_cast<std::int32_t>(std::ceil(m_.options.prune_length)) + 3;
        constexpr std::int32_t kTile = 32;
        const std::size_t tw = static_cast<std::size_t>((W + kTile - 1) / kTile);
        std::vector<std::size_t> tiles;
        for (std::size_t i : changed_) {
            const auto r = static_cast<std::int32_t>(i / static_cast<std::size_t>(W));
            const auto c = static_cast<std::int32_t>(i % static_cast<std::size_t>(W));
            tiles.push_back(static_cast<std::size_t>(r / kTile) * tw + static_cast<std::size_t>(c / kTile));
        }
        std::sort(tiles.begin(), tiles.end());
        tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
        const std::int64_t reach = static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(max_sq())) / 2.0)) + margin + 1;
        std::vector<std::size_t> changed = changed_;
        std::sort(changed.begin(), changed.end());
        for (std::size_t t : tiles) {
            const std::int32_t r0 = static_cast<std::int32_t>(t / tw) * kTile, c0 = static_cast<std::int32_t>(t % tw) * kTile;
            const std::int32_t r1 = std::min(H, r0 + kTile) - 1, c1 = std::min(W, c0 + kTile) - 1;
            // nearest points (doubled) in [xlo, xhi] x [ylo, yhi]
            const std::int32_t xlo = 2 * (c0 - margin), xhi = 2 * (c1 + 1 + margin);
            const std::int32_t ylo = 2 * (H - 1 - r1 - margin), yhi = 2 * (H - r0 + margin);
            if (!unchanged_walls_meet(changed, xlo, xhi, ylo, yhi)) continue;
            // Only pixels of box-judged pairs (m.boxed) can change without a touched neighbour, and
            // a pixel is within the largest clearance of its nearest point.
            const auto ra = static_cast<std::int32_t>(std::max<std::int64_t>(0, r0 - reach));
            const auto rb = static_cast<std::int32_t>(std::min<std::int64_t>(H - 1, r1 + reach));
            const auto ca = static_cast<std::int32_t>(std::max<std::int64_t>(0, c0 - reach));
            const auto cb = static_cast<std::int32_t>(std::min<std::int64_t>(W - 1, c1 + reach));
            for (std::int32_t r = ra; r <= rb; ++r) {
                const std::size_t base = f_.at(r, 0);
                for (std::int32_t x = m_.boxed.find(r, ca, true, cb + 1); x <= cb; x = m_.boxed.find(r, x + 1, true, cb + 1)) {
                    const std::size_t i = base + static_cast<std::size_t>(x);
                    const std::int32_t fx = f_.fx[i], fy = f_.fy[i];
                    if (fx >= xlo && fx <= xhi && fy >= ylo && fy <= yhi && !g_.occupied[i]) redo.set(r, x, true);
                }
            }
        }
        RowMarker marker(m_);
        for (std::int32_t r = 0; r < H; ++r)  // runs of set bits
            for (std::int32_t a = redo.find(r, 0, true); a < W; a = redo.find(r, a, true)) {
                const std::int32_t b = redo.find(r, a, false);
                stats.mask_checks += static_cast<std::uint64_t>(b - a);
                marker.mark_segment(r, a, b - 1);
                a = b;
            }
    }

    UpdateStats stats;

private:
    /// Does an occupied square that is not a changed pixel (or the outside) meet the zone
    /// [xlo, xhi] x [ylo, yhi] (doubled units)? If not, a pixel whose nearest point lies in the zone
    /// has it on a changed square only, so the update gave it that point (or took it away): the pixel
    /// was touched and is rechecked anyway. A blob put into open space (the common update) skips the
    /// search for pixels whose nearest point lies near it.
    bool unchanged_walls_meet(const std::vector<std::size_t>& changed, std::int32_t xlo, std::int32_t xhi,
                              std::int32_t ylo, std::int32_t yhi) const {
        const std::int32_t H = g_.rows, W = g_.cols;
        // square column c covers [2c, 2c + 2]: it meets [xlo, xhi] (even bounds) for xlo/2 - 1 <= c <= xhi/2;
        // columns and rows -1 and cols / rows are the outside (occupied in the bits)
        const std::int32_t c0 = std::max(-1, xlo / 2 - 1), c1 = std::min(W, xhi / 2);
        const std::int32_t j0 = std::max(-1, ylo / 2 - 1), j1 = std::min(H, yhi / 2);
        for (std::int32_t j = j0; j <= j1; ++j)
            for (std::int32_t c = c0; c <= c1; c += 64) {
                const std::int32_t n = std::min(64, c1 - c + 1);
                for (std::uint64_t w = m_.bits.row(j, c, n); w != 0; w &= w - 1) {
                    const std::int32_t cc = c + lowest_bit(w), r = H - 1 - j;
                    if (cc < 0 || cc >= W || r < 0 || r >= H) return true;
                    if (!std::binary_search(changed.begin(), changed.end(), g_.at(r, cc))) return true;
                }
            }
        return false;
    }

    /// Largest squared clearance (doubled units) now, an upper bound kept by the diagram.
    std::int64_t max_sq() {
        if (m_.max_sq < 0) m_.max_sq = largest_sq(f_, 0, f_.rows);  // the first update finds it
        for (std::size_t i : touched_) {
            const auto r = static_cast<std::int32_t>(i / static_cast<std::size_t>(g_.cols));
            const auto c = static_cast<std::int32_t>(i % static_cast<std::size_t>(g_.cols));
            m_.max_sq = std::max(m_.max_sq, f_.sq(r, c));
        }
        return m_.max_sq;
    }

    /// Pass 1 in the changed columns; returns (row, sorted changed columns) for every row that changed.
    std::vector<std::pair<std::int32_t, std::vector<std::int32_t>>> update_columns(const std::vector<std::size_t>& todo,
                                                                                   bool occupied) {
        const std::int32_t H = g_.rows, W = g_.cols;
        std::vector<std::pair<std::int32_t, std::int32_t>> cr;  // (column, row) of the changes
        for (std::size_t i : todo)
            cr.push_back({static_cast<std::int32_t>(i % static_cast<std::size_t>(W)), static_cast<std::int32_t>(i / static_cast<std::size_t>(W))});
        std::sort(cr.begin(), cr.end());
        auto is_new = [&](std::int32_t r, std::int32_t c) {
            return std::binary_search(cr.begin(), cr.end(), std::make_pair(c, r));
        };
        // an occupied pixel that bounds a column's range: occupied before and after
        auto stays_occupied = [&](std::int32_t r, std::int32_t c) {
            return r < 0 || r >= H || (g_.occ(r, c) && !(occupied && is_new(r, c)));
        };
        std::vector<std::pair<std::int32_t, std::int32_t>> cells;  // (row, column) whose pass-1 value changed
        std::vector<std::int16_t> up;
        std::size_t k = 0;
        while (k < cr.size()) {
            const std::int32_t c = cr[k].first;
            std::int32_t done_to = -1;  // rows <= done_to are done in this column
            for (; k < cr.size() && cr[k].first == c; ++k) {
                const std::int32_t r0 = cr[k].second;
                if (r0 <= done_to) continue;
                std::int32_t lo = r0 - 1, hi = r0 + 1;
                while (!stays_occupied(lo, c)) --lo;
                while (!stays_occupied(hi, c)) ++hi;
                // rows lo+1 .. hi-1 between two pixels occupied before and after (or the outside)
                const std::int32_t n = hi - lo - 1;
                up.assign(static_cast<std::size_t>(n), 0);
                std::int16_t run = 0;
                for (std::int32_t r = lo + 1; r < hi; ++r) {
                    run = g_.occ(r, c) ? std::int16_t(0) : static_cast<std::int16_t>(run + 1);
                    up[static_cast<std::size_t>(r - lo - 1)] = run;
                }
                run = 0;
                for (std::int32_t r = hi - 1; r > lo; --r) {
                    run = g_.occ(r, c) ? std::int16_t(0) : static_cast<std::int16_t>(run + 1);
                    const std::int16_t u = up[static_cast<std::size_t>(r - lo - 1)];
                    const std::int16_t v = run <= u ? run : static_cast<std::int16_t>(-u);
                    std::int16_t& cur = f_.vgap[f_.at(r, c)];
                    if (cur != v) {
                        cur = v;
                        cells.push_back({r, c});
                    }
                }
                stats.column_cells += static_cast<std::uint64_t>(n);
                done_to = hi - 1;
            }
        }
        // by row, columns ascending: the cells come column by column with rows ascending, so a stable
        // bucketing by row keeps each row's columns in order
        std::vector<std::size_t> start(static_cast<std::size_t>(H) + 1, 0);
        for (const auto& rc : cells) ++start[static_cast<std::size_t>(rc.first) + 1];
        std::vector<std::pair<std::int32_t, std::vector<std::int32_t>>> rows;
        std::vector<std::size_t> slot(static_cast<std::size_t>(H), 0);
        for (std::int32_t r = 0; r < H; ++r)
            if (start[static_cast<std::size_t>(r) + 1] != 0) {
                slot[static_cast<std::size_t>(r)] = rows.size();
                rows.push_back({r, {}});
                rows.back().second.reserve(start[static_cast<std::size_t>(r) + 1]);
            }
        for (const auto& rc : cells) rows[slot[static_cast<std::size_t>(rc.first)]].second.push_back(rc.second);
        return rows;
    }

    void set_feature(std::int32_t r, std::int32_t x, std::int32_t fx, std::int32_t fy) {
        const std::size_t i = f_.at(r, x);
        if (f_.fx[i] == fx && f_.fy[i] == fy) return;
        f_.fx[i] = static_cast<std::int16_t>(fx);
        f_.fy[i] = static_cast<std::int16_t>(fy);
        touched_.push_back(i);
        ++stats.feature_changes;
    }

    Candidate2 current(std::int32_t r, std::int32_t x) const {
        const std::size_t i = f_.at(r, x);
        return {f_.sq(r, x), f_.fx[i], f_.fy[i]};
    }

    /// Removals in row r with changed columns `cols`: recompute the pixels whose nearest point is gone.
    void remove_row(std::int32_t r, const std::vector<std::int32_t>& cols) {
        const std::int32_t W = g_.cols;
        const std::size_t base = f_.at(r, 0);
        std::vector<std::int32_t>& redo = redo_;  // kept between rows: no allocation a row
        redo.clear();
        // One interval of nearest x per run of adjacent changed columns: the runs of a row are often
        // far apart (blobs whose columns' changes reach the same row), and the pixels between their
        // intervals have nearest points on columns that did not change.
        std::int32_t from = 0;  // x ascends with the runs (nearest x does along a row)
        for (std::size_t a = 0; a < cols.size();) {
            std::size_t b = a;
            while (b + 1 < cols.size() && cols[b + 1] == cols[b] + 1) ++b;
            const std::int32_t xlo = 2 * cols[a], xhi = 2 * cols[b] + 2;
            std::int32_t x = std::max(from, first_at_least(f_, r, xlo));
            for (; x < W && f_.fx[base + static_cast<std::size_t>(x)] <= xhi; ++x) {
                const std::size_t i = base + static_cast<std::size_t>(x);
                if (g_.occupied[i]) continue;  // still occupied: its own centre
                if (!m_.bits.holds_point(f_.fx[i], f_.fy[i])) redo.push_back(x);
            }
            from = x;
            a = b + 1;
        }
        // one window per group of pixels with no occupied pixel between them
        const std::uint8_t* o = &g_.occupied[base];
        std::size_t a = 0;
        while (a < redo.size()) {
            std::size_t b = a + 1;
            while (b < redo.size() && !std::memchr(o + redo[b - 1] + 1, 1, static_cast<std::size_t>(redo[b] - redo[b - 1] - 1))) ++b;
            std::int64_t U = 0;
            for (std::size_t q = a; q < b; ++q) {
                const std::int64_t k = std::abs(static_cast<std::int32_t>(f_.vgap[base + static_cast<std::size_t>(redo[q])]));
                U = std::max(U, (2 * k - 1) * (2 * k - 1));
            }
            // A square of column c is at least |X - 2e| away for its nearer edge e, so columns more than
            // sqrt(U)/2 + 1 from every pixel cannot beat the pixels' own columns; nor can columns
            // beyond an occupied pixel of the row (its edge is nearer, at distance 0 in the row).
            const auto R = static_cast<std::int32_t>(std::sqrt(static_cast<double>(U)) / 2.0) + 2;
            std::int32_t ca = redo[a] - 1;
            while (ca >= 0 && !o[ca] && redo[a] - ca < R) --ca;
            std::int32_t cb = redo[b - 1] + 1;
            while (cb < W && !o[cb] && cb - redo[b - 1] < R) ++cb;
            env_.build(g_, f_, r, ca, cb);
            for (std::size_t q = a; q < b; ++q) {
                const Candidate2 n = env_.query(redo[q]);
                set_feature(r, redo[q], n.x, n.y);
            }
            a = b;
        }
    }

    /// Additions in row r with changed columns `cols`.
    void add_row(std::int32_t r, const std::vector<std::int32_t>& cols) {
        const std::int32_t W = g_.cols, Y = 2 * (g_.rows - 1 - r) + 1;
        for (std::int32_t c : cols)  // newly occupied pixels: their own centres
            if (g_.occ(r, c)) set_feature(r, c, 2 * c + 1, Y);
        std::size_t a = 0;
        while (a < cols.size()) {
            std::size_t b = a;
            while (b + 1 < cols.size() && cols[b + 1] == cols[b] + 1) ++b;
            const std::int32_t ca = cols[a], cb = cols[b];
            env_.build(g_, f_, r, ca, cb);
            auto offer = [&](std::int32_t x) {  // true when x took the run's square
                if (g_.occ(r, x)) return false;
                const Candidate2 n = env_.query(x);
                if (n < current(r, x)) {
                    set_feature(r, x, n.x, n.y);
                    return true;
                }
                return false;
            };
            for (std::int32_t x = ca - 1; x >= 0; --x)
                if (!offer(x) && f_.fx[f_.at(r, x)] < 2 * ca) break;
            for (std::int32_t x = ca; x <= cb; ++x) offer(x);
            for (std::int32_t x = cb + 1; x < W; ++x)
                if (!offer(x) && f_.fx[f_.at(r, x)] > 2 * cb + 2) break;
            a = b + 1;
        }
    }

    MedialDiagram& m_;
    OccupancyGrid& g_;
    FeatureMap& f_;
    RowEnvelope env_;
    std::vector<std::int32_t> redo_;    // remove_row: the row's pixels to recompute
    std::vector<std::size_t> changed_;  // pixels whose occupancy flipped
    std::vector<std::size_t> touched_;  // pixels whose occupancy or nearest point changed
};

}  // namespace detail

/// Sets `pixels` (linear indices r * cols + c) occupied (`occupied` true) or free, and updates the
/// nearest points and the diagram to exactly what medial_diagram gives on the new map.
/// \throws InputError naming the first pixel index out of range.
inline UpdateStats set_pixels(MedialDiagram& m, const std::vector<std::size_t>& pixels, bool occupied) {
    for (std::size_t i : pixels)
        if (i >= m.grid.size())
            throw InputError("pixel index " + std::to_string(i) + " is outside the " + std::to_string(m.grid.rows) +
                             " x " + std::to_string(m.grid.cols) + " map");
    detail::Updater u(m);
    u.apply(pixels, occupied);
    u.refresh_mask();
    return u.stats;
}

namespace detail {

/// Calls fn(i), in ascending order, for every i < n where a[i] and b[i] differ as occupancy (zero or
/// nonzero; b == nullptr: all zero). Eight bytes are compared at a time: a change touches few pixels.
template <class Fn>
void for_each_difference(const std::uint8_t* a, const std::uint8_t* b, std::size_t n, Fn&& fn) {
    auto at = [b](std::size_t k) { return b != nullptr && b[k] != 0; };
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        std::uint64_t x, y = 0;
        std::memcpy(&x, a + i, 8);
        if (b != nullptr) std::memcpy(&y, b + i, 8);
        if (x == y) continue;
        for (std::size_t k = i; k < i + 8; ++k)
            if ((a[k] != 0) != at(k)) fn(k);
    }
    for (; i < n; ++i)
        if ((a[i] != 0) != at(i)) fn(i);
}

}  // namespace detail

/// set_pixels for the pixels whose byte in `mask` (rows x cols, row-major) is nonzero.
inline UpdateStats set_pixels_where(MedialDiagram& m, const std::uint8_t* mask, bool occupied) {
    std::vector<std::size_t> pixels;
    detail::for_each_difference(mask, nullptr, m.grid.size(), [&](std::size_t i) { pixels.push_back(i); });
    return set_pixels(m, pixels, occupied);
}

/// Replaces the whole occupancy (same size) and updates only what changed: removals, then additions.
/// \throws InputError when the size differs.
inline UpdateStats update_occupancy(MedialDiagram& m, const std::vector<std::uint8_t>& occupied) {
    if (occupied.size() != m.grid.size())
        throw InputError("new occupancy has " + std::to_string(occupied.size()) + " pixels, the map has " +
                         std::to_string(m.grid.size()) + " (" + std::to_string(m.grid.rows) + " x " +
                         std::to_string(m.grid.cols) + ")");
    std::vector<std::size_t> freed, filled;
    detail::for_each_difference(occupied.data(), m.grid.occupied.data(), occupied.size(),
                                [&](std::size_t i) { (occupied[i] != 0 ? filled : freed).push_back(i); });
    detail::Updater u(m);
    u.apply(freed, false);
    u.apply(filled, true);
    u.refresh_mask();
    return u.stats;
}

}  // namespace dvoronoi::gvd
