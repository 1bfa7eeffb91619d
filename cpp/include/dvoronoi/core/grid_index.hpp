// Uniform-grid radius index: every agent strictly closer than 2R to a given agent, exactly.
//
// Cells are squares of side slightly above 2R, so the 3x3 block around an agent's cell holds every
// agent within 2R even after the rounding of the cell coordinates; the final test is the exact
// predicate within_2r. A dense cell array is used when the grid is small (the usual case), a sorted
// list of occupied cells otherwise (huge extents relative to R, e.g. two far-apart clusters).
#pragma once

#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace dvoronoi {

namespace detail {
/// How many k in [lo, hi) lie strictly within 2R of their centre, exactly: `d2(k)` is the rounded
/// squared distance, `exact(k)` the exact test (pred::within_2r > 0). Branch-free (inside or not is
/// a coin flip near the circle); only the rare agents within rounding of the circle take the exact
/// test, in a second pass.
template <class D2, class Exact>
Index count_within_2r(std::size_t lo, std::size_t hi, double radius, D2&& d2, Exact&& exact) {
    const double r2 = 4.0 * radius * radius, r2lo = r2 * (1.0 - 1e-9), r2hi = r2 * (1.0 + 1e-9);
    Index inside = 0;
    bool near_circle = false;
    for (std::size_t k = lo; k < hi; ++k) {
        const double d = d2(k);
        inside += d < r2lo;
        near_circle |= (d >= r2lo) & (d <= r2hi);
    }
    for (std::size_t k = lo; near_circle && k < hi; ++k) {
        const double d = d2(k);
        if (d >= r2lo && d <= r2hi) inside += exact(k);
    }
    return inside;
}

/// The bounding box of n >= 1 points in one pass. Two rows per step, each bound with its own
/// accumulator: a single running min or max is a chain of dependent instructions (Eigen's
/// colwise minCoeff/maxCoeff on this row-major layout were four such chains, a fifth of a grid build).
inline void bounding_box(const Points& pts, double& x0, double& y0, double& x1, double& y1) {
    const Index n = pts.rows();
    double lo[4] = {pts(0, 0), pts(0, 1), pts(0, 0), pts(0, 1)}, hi[4] = {lo[0], lo[1], lo[2], lo[3]};
    const double* p = pts.data();  // row-major: x, y, x, y, ...
    const std::size_t values = 2 * static_cast<std::size_t>(n);
    for (std::size_t k = 0; k + 4 <= values; k += 4)
        for (int j = 0; j < 4; ++j) {
            lo[j] = std::min(lo[j], p[k + static_cast<std::size_t>(j)]);
            hi[j] = std::max(hi[j], p[k + static_cast<std::size_t>(j)]);
        }
    if (n % 2 == 1) {  // the last row
        lo[0] = std::min(lo[0], p[values - 2]), lo[1] = std::min(lo[1], p[values - 1]);
        hi[0] = std::max(hi[0], p[values - 2]), hi[1] = std::max(hi[1], p[values - 1]);
    }
    x0 = std::min(lo[0], lo[2]), y0 = std::min(lo[1], lo[3]);
    x1 = std::max(hi[0], hi[2]), y1 = std::max(hi[1], hi[3]);
}
}  // namespace detail

class GridIndex {
public:
    /// Index `pts` (kept by reference: it must outlive the index) for queries of range `range` (2R).
    /// Up to `threads` OpenMP threads sort the points into cells (the result does not depend on it).
    GridIndex(const Points& pts, double range, int threads = 1) : pts_(pts) {
        const Index n = pts.rows();
        if (n == 0) return;
        detail::bounding_box(pts, x0_, y0_, x1_, y1_);
        const double xspan = x1_ - x0_;
        const double yspan = y1_ - y0_;
        // A margin of 2^-16 covers the relative rounding of (x - x0) / cell for up to 2^32 cells per
        // axis; beyond that the cells are made coarser (still correct, only slower).
        cell_ = range * (1.0 + std::ldexp(1.0, -16));
        const double max_cells = std::ldexp(1.0, 32);
        cell_ = std::max({cell_, xspan / max_cells, yspan / max_cells});
        nx_ = static_cast<std::int64_t>(std::floor(xspan / cell_)) + 1;
        ny_ = static_cast<std::int64_t>(std::floor(yspan / cell_)) + 1;

        constexpr Index kPerThread = Index{1} << 15;  // below this, a thread costs more than it saves
        const int sort_team = static_cast<int>(std::clamp<Index>(n / kPerThread, 1, std::max(threads, 1)));
        // Positions are kept in grid order too: a query reads a few contiguous runs, not scattered rows.
        const auto un = static_cast<std::size_t>(n);
        order_.reserve(un);
        xs_.reserve(un);
        ys_.reserve(un);
        detail::prefault_together({{order_.data(), un * sizeof(Index)}, {xs_.data(), un * sizeof(double)},
                                   {ys_.data(), un * sizeof(double)}},
                                  sort_team);
        order_.resize(un);
        xs_.resize(un);
        ys_.resize(un);
        dense_ = static_cast<double>(nx_) * static_cast<double>(ny_) <= 4.0 * static_cast<double>(n) + 1024.0;
        if (dense_) {
            // Counting sort into a dense cell array (CSR); within a cell, input order (deterministic
            // candidate order). Each thread counts and places a contiguous range of the input; its
            // places in a cell come after those of the ranges before it, so the order is the same for
            // any number of threads. The cells are recomputed in the placing pass rather than stored,
            // and that pass places the positions too (its reads are in input order; a gather after
            // it would read the points in scattered order).
            const auto cell_of = [&](double x, double y) {
                const Key k = key_inside(x, y);
                return static_cast<std::size_t>(k.cx * ny_ + k.cy);
            };
            const auto cells = static_cast<std::size_t>(nx_ * ny_);
            // Each thread counts in an array over all cells: at most about 2n entries in all.
            const int team = std::max(1, std::min(sort_team, static_cast<int>(std::min<std::size_t>(
                                                                  2 * un / std::max<std::size_t>(cells, 1), 1 << 16))));
            const auto first = [&](int t) { return n / team * t + std::min<Index>(t, n % team); };
            // Per thread and cell: the count, then the next place.
            std::vector<std::vector<Index>> place(static_cast<std::size_t>(team), std::vector<Index>(cells, 0));
#pragma omp parallel for num_threads(team) schedule(static, 1) if (team > 1)
            for (int t = 0; t < team; ++t) {
                std::vector<Index>& count = place[static_cast<std::size_t>(t)];
                const Index lo = first(t), hi = first(t + 1);  // locals: the stores below may alias n
                for (Index i = lo; i < hi; ++i) ++count[cell_of(pts(i, 0), pts(i, 1))];
            }
            start_.resize(cells + 1);
            Index at = 0;
            for (std::size_t c = 0; c < cells; ++c) {
                start_[c] = at;
                for (std::vector<Index>& p : place) at += std::exchange(p[c], at);  // count -> first place
            }
            start_[cells] = at;
#pragma omp parallel for num_threads(team) schedule(static, 1) if (team > 1)
            for (int t = 0; t < team; ++t) {
                std::vector<Index>& next = place[static_cast<std::size_t>(t)];
                const Index lo = first(t), hi = first(t + 1);
                for (Index i = lo; i < hi; ++i) {
                    const double x = pts(i, 0), y = pts(i, 1);
                    const auto s = static_cast<std::size_t>(next[cell_of(x, y)]++);
                    order_[s] = i;
                    xs_[s] = x;
                    ys_[s] = y;
                }
            }
        } else {
            std::vector<Key> keys(static_cast<std::size_t>(n));
            for (Index i = 0; i < n; ++i) keys[static_cast<std::size_t>(i)] = key_of(i);
            std::iota(order_.begin(), order_.end(), Index{0});
            std::sort(order_.begin(), order_.end(), [&](Index a, Index b) {
                const Key& ka = keys[static_cast<std::size_t>(a)];
                const Key& kb = keys[static_cast<std::size_t>(b)];
                return ka.cx != kb.cx ? ka.cx < kb.cx : (ka.cy != kb.cy ? ka.cy < kb.cy : a < b);
            });
            sorted_keys_.reserve(static_cast<std::size_t>(n));
            for (Index i : order_) sorted_keys_.push_back(keys[static_cast<std::size_t>(i)]);
            for (std::size_t s = 0; s < order_.size(); ++s) {
                xs_[s] = pts(order_[s], 0);
                ys_[s] = pts(order_[s], 1);
            }
        }
    }

    /// The lowest pair (i, j), i < j in lexicographic order, of agents with identical coordinates, or
    /// (-1, -1). Identical points share a grid cell, so only runs of one cell are compared: O(n)
    /// expected, O(k log k) for a crowded cell of k agents.
    std::pair<Index, Index> first_duplicate() const {
        std::pair<Index, Index> best{-1, -1};
        const auto consider = [&](Index a, Index b) {
            if (a > b) std::swap(a, b);
            if (best.first < 0 || a < best.first || (a == best.first && b < best.second)) best = {a, b};
        };
        std::vector<std::size_t> run;
        const std::size_t n = order_.size();
        std::size_t lo = 0, cell = 0;
        while (lo < n) {
            // [lo, hi): the agents of one cell.
            std::size_t hi = lo + 1;
            if (dense_) {
                while (static_cast<std::size_t>(start_[cell + 1]) <= lo) ++cell;
                hi = static_cast<std::size_t>(start_[cell + 1]);
            } else {
                const Key& k0 = sorted_keys_[lo];
                while (hi < n && sorted_keys_[hi].cx == k0.cx && sorted_keys_[hi].cy == k0.cy) ++hi;
            }
            if (hi - lo <= 32) {
                for (std::size_t a = lo; a < hi; ++a)
                    for (std::size_t b = a + 1; b < hi; ++b)
                        if (xs_[a] == xs_[b] && ys_[a] == ys_[b]) consider(order_[a], order_[b]);
            } else {
                run.resize(hi - lo);
                std::iota(run.begin(), run.end(), lo);
                std::sort(run.begin(), run.end(), [&](std::size_t a, std::size_t b) {
                    if (xs_[a] != xs_[b]) return xs_[a] < xs_[b];
                    if (ys_[a] != ys_[b]) return ys_[a] < ys_[b];
                    return order_[a] < order_[b];
                });
                for (std::size_t t = 0; t + 1 < run.size(); ++t) {
                    const std::size_t a = run[t], b = run[t + 1];
                    if (xs_[a] == xs_[b] && ys_[a] == ys_[b]) consider(order_[a], order_[b]);
                }
            }
            lo = hi;
        }
        return best;
    }

    /// The agents in grid order: processing agents in this order keeps queries cache-friendly.
    const std::vector<Index>& grid_order() const noexcept { return order_; }

    /// The position of the agent at position `pos` of grid_order(), from the index's contiguous copy
    /// (reading the input there instead is a cache miss per agent on large inputs).
    Vec2 point_at(std::size_t pos) const { return Vec2(xs_[pos], ys_[pos]); }

    /// Agents j != i with |p_j - p_i| < 2*radius (exact), appended to `out` (cleared first) in the
    /// index's deterministic traversal order.
    void within(Index i, double radius, std::vector<detail::Candidate>& out) const {
        const Key k = key_of(i);
        std::size_t lo, hi;  // i is in its cell's run
        column_run(k.cx, k.cy, k.cy, lo, hi);
        while (lo < hi && order_[lo] != i) ++lo;
        within_impl(pts_(i, 0), pts_(i, 1), k, lo, radius, out);
    }

    /// The same for the agent at position `pos` of grid_order(): reads only the index's own
    /// contiguous arrays (no scattered access to the input when agents are visited in grid order).
    /// Any radius works: beyond the indexed range more cells are scanned; an infinite radius
    /// returns every other agent.
    void within_at(std::size_t pos, double radius, std::vector<detail::Candidate>& out) const {
        within_impl(xs_[pos], ys_[pos], key_at(xs_[pos], ys_[pos]), pos, radius, out);
    }

    /// The same as within_at, handing the agents over in batches instead of collecting them:
    /// batch(xs, ys, ids, sel, count), agent t < count at (xs[sel[t]], ys[sel[t]]) with index
    /// ids[sel[t]]. Why batches: a loader's running state then stays in registers through a batch
    /// (stored per agent, it went through memory at every agent: the stores alias it).
    template <class Batch>
    void for_each_batch_within_at(std::size_t pos, double radius, Batch&& batch) const {
        visit_within(xs_[pos], ys_[pos], key_at(xs_[pos], ys_[pos]), pos, radius, batch);
    }

    /// The number of agents j != i strictly within 2*radius of the agent at position `pos` of
    /// grid_order() (exact; the same count as within_at). See count_around.
    Index count_within_at(std::size_t pos, double radius) const {
        if (!(radius > 0.0)) return 0;
        return count_around(Vec2(xs_[pos], ys_[pos]), radius) - 1;  // the agent itself is at distance 0
    }

    /// The number of agents strictly within 2*radius of the point c (exact; an agent at c counts).
    /// Runs of cells that lie certainly inside the disk are counted whole, so a wide disk costs
    /// O(columns + agents near the circle) instead of O(agents inside): ASR's agents-in-range count
    /// for cells with far vertices needs that.
    Index count_around(const Vec2& c, double radius) const {
        const auto n = static_cast<Index>(order_.size());
        const double x = c.x(), y = c.y();
        if (n == 0 || !(radius > 0.0)) return 0;
        if (!(radius < std::numeric_limits<double>::infinity())) return n;
        const double rr = 2.0 * radius;
        // The disk holds the agents' bounding box: every agent is in range.
        const double fx = std::max(x - x0_, x1_ - x), fy = std::max(y - y0_, y1_ - y);
        if (std::sqrt(fx * fx + fy * fy) * (1.0 + 1e-12) < rr * (1.0 - 1e-12)) return n;
        const double span = rr / cell_;
        if (!dense_ || !(span < static_cast<double>(n))) {
            Index count = 0;
            visit_within(x, y, key_at(x, y), kNone, radius,
                         [&](const double*, const double*, const Index*, const std::uint32_t*, std::size_t m) {
                             count += static_cast<Index>(m);
                         });
            return count;
        }
        constexpr double u = kUnitRoundoff;
        const double r2 = rr * rr;
        Index count = 0;
        const auto d2 = [&](std::size_t s) {
            const double dx = xs_[s] - x, dy = ys_[s] - y;
            return dx * dx + dy * dy;
        };
        const auto exact = [&](std::size_t s) { return pred::within_2r(c, Vec2(xs_[s], ys_[s]), radius) > 0; };
        // A disk inside the 3 x 3 cells around c's (the usual case: a radius step just beyond the
        // indexed range): count those cells' agents only, three column runs (no whole-cell bookkeeping).
        const Key k = key_at(x, y);
        if (k.cx >= 0 && k.cx < nx_ && k.cy >= 0 && k.cy < ny_) {
            const double rrm = rr * (1.0 + 1e-9);
            const auto fits = [&](double v, double v0, std::int64_t kv, std::int64_t nv) {
                // Agents keyed outside cells kv-1..kv+1 lie beyond [lo, hi] up to `slack` (none beyond the grid).
                const double lo = v0 + static_cast<double>(kv - 1) * cell_, hi = lo + 3.0 * cell_;
                const double slack = 8.0 * u * (std::fabs(v0) + std::fabs(v) + std::fabs(lo) + std::fabs(hi)) + 1e-9 * cell_;
                return (kv == 0 || v - rrm > lo + slack) && (kv + 1 >= nv || v + rrm < hi - slack);
            };
            if (fits(x, x0_, k.cx, nx_) && fits(y, y0_, k.cy, ny_)) {
                const std::int64_t cy0 = std::max<std::int64_t>(0, k.cy - 1), cy1 = std::min(ny_ - 1, k.cy + 1);
                for (std::int64_t cx = std::max<std::int64_t>(0, k.cx - 1); cx <= std::min(nx_ - 1, k.cx + 1); ++cx) {
                    std::size_t lo, hi;
                    column_run(cx, cy0, cy1, lo, hi);
                    count += detail::count_within_2r(lo, hi, radius, d2, exact);
                }
                return count;
            }
        }
        const auto scan = [&](std::int64_t cx, std::int64_t cy0, std::int64_t cy1) {
            if (cy0 > cy1) return;
            std::size_t lo, hi;
            column_run(cx, cy0, cy1, lo, hi);
            count += detail::count_within_2r(lo, hi, radius, d2, exact);
        };
        // Per column, the rows the disk reaches (bounds on the agents' keys, as in visit_within): the
        // rows whose agents lie certainly strictly inside are counted whole, the others scanned.
        const double rrm = rr * (1.0 + 1e-9);
        const double sy = 8.0 * u * (std::fabs(y0_) + std::fabs(y) + rr) + 1e-9 * cell_;
        const double rows_max = static_cast<double>(ny_ - 1);
        for (std::int64_t cx = key_lo(x, x0_, rrm, nx_), cx1 = key_hi(x, x0_, rrm, nx_); cx <= cx1; ++cx) {
            // Agents keyed in column cx lie in [xa, xb] up to the rounding of their keys (slack).
            const double xa = x0_ + static_cast<double>(cx) * cell_, xb = xa + cell_;
            const double slack = 8.0 * u * (std::fabs(x0_) + std::fabs(x) + std::fabs(xb)) + 1e-9 * cell_;
            const double dx = std::max({0.0, xa - x, x - xb}) - slack;
            if (dx >= rrm) continue;
            const double half = dx <= 0.0 ? rrm : std::sqrt(std::max(0.0, rrm * rrm - dx * dx)) * (1.0 + 1e-12);
            const std::int64_t ra = key_lo(y, y0_, half, ny_), rb = key_hi(y, y0_, half, ny_);
            // Rows [ia, ib]: their agents' y lie within [y - inner, y + inner] (up to sy), x within far.
            const double far = (std::max(std::fabs(xa - slack - x), std::fabs(xb + slack - x))) * (1.0 + 1e-12);
            std::int64_t ia = rb + 1, ib = rb;
            if (far < rr) {
                const double inner = std::sqrt(r2 - far * far) * (1.0 - 1e-9);
                const double lo = y - inner + sy, hi = y + inner - sy;  // rows must lie within [lo, hi]
                if (hi - lo > cell_) {
                    ia = static_cast<std::int64_t>(std::min(std::max(std::ceil((lo - y0_) / cell_), 0.0), rows_max + 1.0));
                    ib = static_cast<std::int64_t>(std::min(std::max(std::floor((hi - y0_) / cell_) - 1.0, -1.0), rows_max));
                    while (ia <= ib && y0_ + static_cast<double>(ia) * cell_ < lo) ++ia;
                    while (ib >= ia && y0_ + static_cast<double>(ib + 1) * cell_ > hi) --ib;
                    ia = std::max(ia, ra);
                    ib = std::min(ib, rb);
                }
            }
            if (ia > ib) {
                scan(cx, ra, rb);
                continue;
            }
            std::size_t lo, hi;
            column_run(cx, ia, ib, lo, hi);
            count += static_cast<Index>(hi - lo);
            scan(cx, ra, ia - 1);
            scan(cx, ib + 1, rb);
        }
        return count;
    }

    /// Calls fn(position, id) for every agent of the grid cells that meet the disk of radius r around
    /// `center` (a superset of the agents in the disk; the caller decides exactly) until fn returns
    /// false; returns false when it was stopped that way. Only the part of
    /// the disk over the agents' bounding box is scanned, column by column, so a huge disk that barely
    /// touches the agents costs little; when more cells than agents would be visited, every agent is.
    template <class Fn>
    bool for_each_in_disk(const Vec2& center, double r, Fn&& fn) const {
        const std::int64_t n = static_cast<std::int64_t>(order_.size());
        if (n == 0 || !(r >= 0.0)) return true;
        const auto clampf = [](double v, double lo, double hi) { return std::min(std::max(v, lo), hi); };
        // Column range (one cell of margin on each side covers the rounding of the keys).
        const double fx0 = std::floor((center.x() - r - x0_) / cell_) - 1.0;
        const double fx1 = std::floor((center.x() + r - x0_) / cell_) + 1.0;
        const double fy0 = std::floor((center.y() - r - y0_) / cell_) - 1.0;
        const double fy1 = std::floor((center.y() + r - y0_) / cell_) + 1.0;
        if (!(fx1 >= 0.0 && fy1 >= 0.0 && fx0 <= static_cast<double>(nx_ - 1) && fy0 <= static_cast<double>(ny_ - 1)))
            return true;  // the disk misses the agents' bounding box
        const auto cx0 = static_cast<std::int64_t>(clampf(fx0, 0.0, static_cast<double>(nx_ - 1)));
        const auto cx1 = static_cast<std::int64_t>(clampf(fx1, 0.0, static_cast<double>(nx_ - 1)));
        const auto gy0 = static_cast<std::int64_t>(clampf(fy0, 0.0, static_cast<double>(ny_ - 1)));
        const auto gy1 = static_cast<std::int64_t>(clampf(fy1, 0.0, static_cast<double>(ny_ - 1)));
        if (cx1 - cx0 + 1 > n) {
            for (std::size_t s = 0; s < order_.size(); ++s)
                if (!fn(Vec2(xs_[s], ys_[s]), order_[s])) return false;
            return true;
        }
        for (std::int64_t cx = cx0; cx <= cx1; ++cx) {
            // The disk's extent over this column's x-interval [xa, xb].
            const double xa = x0_ + static_cast<double>(cx) * cell_, xb = xa + cell_;
            const double dx = center.x() < xa ? xa - center.x() : (center.x() > xb ? center.x() - xb : 0.0);
            if (dx > r) continue;
            const double half = std::sqrt(std::max(0.0, r * r - dx * dx)) * (1.0 + 1e-12);
            const double ly = std::floor((center.y() - half - y0_) / cell_) - 1.0;
            const double hy = std::floor((center.y() + half - y0_) / cell_) + 1.0;
            if (hy < static_cast<double>(gy0) || ly > static_cast<double>(gy1)) continue;
            const auto cy0 = static_cast<std::int64_t>(clampf(ly, static_cast<double>(gy0), static_cast<double>(gy1)));
            const auto cy1 = static_cast<std::int64_t>(clampf(hy, static_cast<double>(gy0), static_cast<double>(gy1)));
            std::size_t lo, hi;
            column_run(cx, cy0, cy1, lo, hi);
            for (std::size_t s = lo; s < hi; ++s)
                if (!fn(Vec2(xs_[s], ys_[s]), order_[s])) return false;
        }
        return true;
    }

private:
    static constexpr double kUnitRoundoff = 1.1102230246251565e-16;

    /// The key of v - d (key_lo) or v + d (key_hi) on an axis from v0 with nmax cells, rounded
    /// outwards and clamped to the grid: a bound on the keys of agents within d of v.
    std::int64_t key_lo(double v, double v0, double d, std::int64_t nmax) const {
        const double m = d + 8.0 * kUnitRoundoff * (std::fabs(v) + d);
        const double f = std::floor((v - m - v0) / cell_);
        return static_cast<std::int64_t>(std::min(std::max(f, 0.0), static_cast<double>(nmax - 1)));
    }
    std::int64_t key_hi(double v, double v0, double d, std::int64_t nmax) const {
        const double m = d + 8.0 * kUnitRoundoff * (std::fabs(v) + d);
        const double f = std::floor((v + m - v0) / cell_);
        return static_cast<std::int64_t>(std::min(std::max(f, 0.0), static_cast<double>(nmax - 1)));
    }

    /// Positions [lo, hi) of grid_order() in cells (cx, cy0..cy1).
    void column_run(std::int64_t cx, std::int64_t cy0, std::int64_t cy1, std::size_t& lo, std::size_t& hi) const {
        if (dense_) {
            lo = static_cast<std::size_t>(start_[static_cast<std::size_t>(cx * ny_ + cy0)]);
            hi = static_cast<std::size_t>(start_[static_cast<std::size_t>(cx * ny_ + cy1 + 1)]);
        } else {
            const auto cmp = [](const Key& a, const Key& b) { return a.cx != b.cx ? a.cx < b.cx : a.cy < b.cy; };
            lo = static_cast<std::size_t>(std::lower_bound(sorted_keys_.begin(), sorted_keys_.end(), Key{cx, cy0}, cmp) - sorted_keys_.begin());
            hi = static_cast<std::size_t>(std::upper_bound(sorted_keys_.begin(), sorted_keys_.end(), Key{cx, cy1}, cmp) - sorted_keys_.begin());
        }
    }

    struct Key {
        std::int64_t cx, cy;
    };
    Key key_at(double x, double y) const {
        return {static_cast<std::int64_t>(std::floor((x - x0_) / cell_)),
                static_cast<std::int64_t>(std::floor((y - y0_) / cell_))};
    }
    Key key_of(Index i) const { return key_inside(pts_(i, 0), pts_(i, 1)); }
    /// key_at for a point inside the grid's box: the quotients are not negative, so truncation is floor.
    Key key_inside(double x, double y) const {
        return {static_cast<std::int64_t>((x - x0_) / cell_), static_cast<std::int64_t>((y - y0_) / cell_)};
    }

    void within_impl(double x, double y, Key k, std::size_t self, double radius,
                     std::vector<detail::Candidate>& out) const {
        out.clear();
        visit_within(x, y, k, self, radius,
                     [&](const double* xs, const double* ys, const Index* ids, const std::uint32_t* sel, std::size_t count) {
                         for (std::size_t t = 0; t < count; ++t)
                             out.push_back({Vec2(xs[sel[t]], ys[sel[t]]), ids[sel[t]]});
                     });
    }

    /// No agent: the position to leave out of a query around a point that is not an agent.
    static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

    /// Hands every agent strictly within 2*radius of (x, y) (exact), except the one at grid position
    /// `self` (kNone: none), to batch(xs, ys, ids, sel, count) (see for_each_batch_within_at), in
    /// the index's deterministic traversal order.
    template <class Batch>
    void visit_within(double x, double y, Key k, std::size_t self, double radius, Batch&& batch) const {
        if (pts_.rows() == 0) return;
        const Vec2 c(x, y);
        constexpr std::size_t kChunk = 64;
        std::uint32_t keep[kChunk];
        // Every agent of [lo, hi) that `take` accepts, in batches of up to kChunk.
        const auto every = [&](std::size_t lo, std::size_t hi, auto&& take) {
            for (std::size_t s0 = lo; s0 < hi; s0 += kChunk) {
                const std::size_t s1 = std::min(hi, s0 + kChunk);
                std::size_t kept = 0;
                for (std::size_t s = s0; s < s1; ++s)
                    if (take(s)) keep[kept++] = static_cast<std::uint32_t>(s - s0);
                if (kept > 0) batch(xs_.data() + s0, ys_.data() + s0, order_.data() + s0, keep, kept);
            }
        };
        if (!(radius < std::numeric_limits<double>::infinity())) {
            every(0, order_.size(), [&](std::size_t s) { return s != self; });
            return;
        }
        // Cells to scan on each side: one within the indexed range (its margin covers the rounding
        // of the cell coordinates), else enough for 2*radius plus a margin for that rounding.
        const double span = 2.0 * radius / cell_;
        const std::int64_t reach =
            span <= 1.0 ? 1 : static_cast<std::int64_t>(std::min(std::ceil(span + 1e-5), 1e15));
        const double wide = static_cast<double>(std::min(2 * reach + 1, nx_)) *
                            static_cast<double>(std::min(2 * reach + 1, ny_));
        if (reach > 1 && wide > static_cast<double>(order_.size())) {
            // More cells than agents to visit: test every agent instead.
            every(0, order_.size(), [&](std::size_t s) {
                return s != self && pred::within_2r(c, Vec2(xs_[s], ys_[s]), radius) > 0;
            });
            return;
        }
        // The agents of a column run, in chunks: one branch-free pass keeps those clearly inside (a
        // branch there mispredicts often) and notes any within rounding of the circle; only a
        // chunk with such an agent (rare) is redone with the exact test for those.
        const double r2 = 4.0 * radius * radius, r2hi = r2 * (1.0 + 1e-9), r2lo = r2 * (1.0 - 1e-9);
        const auto scan = [&](std::int64_t cx, std::int64_t cy0, std::int64_t cy1) {
            std::size_t lo, hi;
            column_run(cx, cy0, cy1, lo, hi);
            for (std::size_t s0 = lo; s0 < hi; s0 += kChunk) {
                const std::size_t s1 = std::min(hi, s0 + kChunk);
                std::size_t kept = 0;
                bool unclear = false;
                for (std::size_t s = s0; s < s1; ++s) {
                    const double dx = xs_[s] - c.x(), dy = ys_[s] - c.y(), d2 = dx * dx + dy * dy;
                    keep[kept] = static_cast<std::uint32_t>(s - s0);
                    kept += (d2 < r2lo) & (s != self);
                    unclear |= (d2 >= r2lo) & (d2 <= r2hi);
                }
                if (unclear) {
                    kept = 0;
                    for (std::size_t s = s0; s < s1; ++s) {
                        const double dx = xs_[s] - c.x(), dy = ys_[s] - c.y(), d2 = dx * dx + dy * dy;
                        if (s != self && d2 <= r2hi && (d2 < r2lo || pred::within_2r(c, Vec2(xs_[s], ys_[s]), radius) > 0))
                            keep[kept++] = static_cast<std::uint32_t>(s - s0);
                    }
                }
                if (kept > 0) batch(xs_.data() + s0, ys_.data() + s0, order_.data() + s0, keep, kept);
            }
        };
        if (reach == 1) {  // 3 x 3 cells
            for (std::int64_t cx = std::max<std::int64_t>(0, k.cx - 1); cx <= std::min<std::int64_t>(nx_ - 1, k.cx + 1); ++cx)
                scan(cx, std::max<std::int64_t>(0, k.cy - 1), std::min<std::int64_t>(ny_ - 1, k.cy + 1));
            return;
        }
        // Cells finer than 2R: per column, only the rows the disk can reach. Keys are a monotone
        // function of the coordinate (floor of rounded (v - v0) / cell), so a bound on the agents'
        // coordinates, itself rounded outwards, bounds their keys: no margin of whole cells.
        constexpr double u = kUnitRoundoff;
        const double rr = 2.0 * radius * (1.0 + 1e-9);
        const std::int64_t cx0 = key_lo(x, x0_, rr, nx_), cx1 = key_hi(x, x0_, rr, nx_);
        for (std::int64_t cx = cx0; cx <= cx1; ++cx) {
            // Agents keyed in column cx lie in [xa, xb] up to the rounding of their keys (slack).
            const double xa = x0_ + static_cast<double>(cx) * cell_, xb = xa + cell_;
            const double slack = 8.0 * u * (std::fabs(x0_) + std::fabs(x) + std::fabs(xb)) + 1e-9 * cell_;
            const double dx = std::max({0.0, xa - x, x - xb}) - slack;
            const double half = dx <= 0.0 ? rr : std::sqrt(std::max(0.0, rr * rr - dx * dx)) * (1.0 + 1e-12);
            if (dx >= rr) continue;
            scan(cx, key_lo(y, y0_, half, ny_), key_hi(y, y0_, half, ny_));
        }
    }


    const Points& pts_;
    double x0_ = 0.0, y0_ = 0.0, x1_ = 0.0, y1_ = 0.0, cell_ = 1.0;
    std::int64_t nx_ = 0, ny_ = 0;
    bool dense_ = true;
    std::vector<Index> order_;
    std::vector<Index> start_;
    std::vector<Key> sorted_keys_;
    std::vector<double> xs_, ys_;
};

}  // namespace dvoronoi
