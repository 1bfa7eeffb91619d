// Incremental updates of the medial diagram (SPEC: "after any sequence of updates" the diagram is
// exactly what a full build on the new map gives): pixels become occupied or free, and only what the
// change can affect is recomputed.
//
// An update runs in two exact steps, removals first, then additions:
//  1. Columns: the vertical nearest squares (pass 1) change only between the nearest pixels of the
//     column that stay occupied: after removals they are recomputed there (closed form: every pixel
//     between is free); after additions a walk out of each run of new pixels stops at the first
//     pixel that keeps its offset. The rows where a column's value changed are recorded.
//  2. Nearest points. A pixel's nearest point comes from its row's pass-1 squares, so only rows with
//     a changed column can change, and in them:
//     - removals: a pixel needs a new nearest point only if its old one lies on no occupied square any
//       more; that square was its column's pass-1 square, so the point's x lies in the changed columns'
//       span, and nearest points' x only grows along a row: the candidates are one interval, found by
//       a search from the column. They are recomputed in a window of columns (bounded by their own
//       vertical distances and by their neighbours' nearest points) or by pass 2 over their free run.
//     - additions: squares only come closer; a pixel takes a changed column's square when it beats (or
//       ties with a smaller x) the one it has. Scanning outward from a run of changed columns stops at
//       the first pixel that keeps a nearest point lying beyond the run: parabolas of translates
//       differ by a linear function, so beyond that pixel the run never wins again.
//  3. Diagram: the pair rule reads a pixel's and its neighbours' nearest points and the occupancy in
//     a box spanned by two nearest points at most prune_length apart (grown by one pixel). Rechecked:
//     pixels whose nearest point or occupancy changed, their neighbours, and pixels of box-judged
//     pairs (MedialDiagram::boxed) whose nearest point lies within prune_length + 3 pixels of a
//     changed pixel (searched in the blocks of pixels whose largest clearance reaches that far,
//     MedialDiagram::block_sq; skipped where no unchanged wall is that near). They are re-marked in
//     row segments, vectorised as a build marks rows.
// Steps 2 and 3 work row by row, so a large update splits its rows over the diagram's workers.
// What an update touches is kept as row-sparse bit masks (SparseRowMask): its cost follows the
// change, not the map. Its rows lie far apart in memory, out of the hardware prefetcher's sight:
// the column walks and the row pass fetch ahead.
// Thread safety: as for the standard containers, concurrent reads of a MedialDiagram are safe, and an
// update needs it to itself (no other update or read meanwhile); its own workers are its business.
// Python's OccupancyVoronoi takes a lock per call.
#pragma once

#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/core/parallel.hpp"
#include "dvoronoi/gvd/medial_diagram.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace dvoronoi::gvd {

/// What an update touched.
struct UpdateStats {
    std::uint64_t changed_pixels = 0;     ///< pixels whose occupancy flipped
    std::uint64_t column_cells = 0;       ///< pass-1 values recomputed
    /// pixels whose nearest point was rewritten, each once (a pixel of update_occupancy that a removal
    /// moves and the additions move back counts too)
    std::uint64_t feature_changes = 0;
    std::uint64_t mask_checks = 0;        ///< pixels whose diagram membership was rechecked
};

namespace detail {

inline constexpr std::int32_t kBlock = MedialDiagram::kBlock;

/// The largest squared clearance (doubled units) of each kBlock x kBlock block of pixels, blocks in
/// row-major order. Offsets from a pixel's centre to its nearest point fit 16 bits (sides <= 16383),
/// so SSE2's pmaddwd gives dx^2 + dy^2 for eight pixels at once (< 2^31).
inline std::vector<std::int32_t> block_clearances(const FeatureMap& f) {
    const std::int32_t bw = (f.cols + kBlock - 1) / kBlock;
    std::vector<std::int32_t> out(static_cast<std::size_t>(bw) * static_cast<std::size_t>((f.rows + kBlock - 1) / kBlock), 0);
    for (std::int32_t r = 0; r < f.rows; ++r) {
        const std::int16_t* x = &f.fx[f.at(r, 0)];
        const std::int16_t* y = &f.fy[f.at(r, 0)];
        const std::int32_t Y = 2 * (f.rows - 1 - r) + 1;
        std::int32_t* o = &out[static_cast<std::size_t>(r / kBlock * bw)];
        for (std::int32_t c0 = 0; c0 < f.cols; c0 += kBlock) {
            const std::int32_t end = std::min(f.cols, c0 + kBlock);
            std::int32_t best = 0, c = c0;
#if defined(__SSE2__)
            __m128i most = _mm_setzero_si128();
            const __m128i cy = _mm_set1_epi16(static_cast<std::int16_t>(Y));
            for (; c + 8 <= end; c += 8) {
                const __m128i cx = _mm_add_epi16(_mm_set1_epi16(static_cast<std::int16_t>(2 * c + 1)), _mm_setr_epi16(0, 2, 4, 6, 8, 10, 12, 14));
                const __m128i dx = _mm_sub_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x + c)), cx);
                const __m128i dy = _mm_sub_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(y + c)), cy);
                const __m128i lo = _mm_unpacklo_epi16(dx, dy), hi = _mm_unpackhi_epi16(dx, dy);
                for (const __m128i d2 : {_mm_madd_epi16(lo, lo), _mm_madd_epi16(hi, hi)}) {
                    const __m128i gt = _mm_cmpgt_epi32(d2, most);  // SSE2 has no pmaxsd
                    most = _mm_or_si128(_mm_and_si128(gt, d2), _mm_andnot_si128(gt, most));
                }
            }
            alignas(16) std::int32_t lanes[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(lanes), most);
            best = std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
#endif
            for (; c < end; ++c) {
                const std::int32_t dx = x[c] - (2 * c + 1), dy = y[c] - Y;
                best = std::max(best, dx * dx + dy * dy);
            }
            o[c0 / kBlock] = std::max(o[c0 / kBlock], best);
        }
    }
    return out;
}

/// Changed cells bucketed by row: row rows[k] has the ascending columns cols[start[k] .. start[k+1]).
struct RowCells {
    std::vector<std::int32_t> rows, cols;
    std::vector<std::size_t> start{0};
};

/// Pixels as bits whose rows are zeroed when first set: an update touches a few rows of a large map,
/// and zeroing or scanning every row would cost more than a small update itself.
class SparseRowMask {
public:
    SparseRowMask(std::int32_t rows, std::int32_t cols)
        : cols_(cols), stride_((static_cast<std::size_t>(cols) + 63) / 64),
          words_(stride_ * static_cast<std::size_t>(rows)), live_(static_cast<std::size_t>(rows), 0) {}

    void set(std::int32_t r, std::int32_t c) { row_for_writing(r)[c / 64] |= std::uint64_t{1} << (c % 64); }
    /// Sets the pixels c + k of row r for the bits k of `bits` (< 256), eight pixels at once.
    void set_eight(std::int32_t r, std::int32_t c, std::uint64_t bits) {
        std::uint64_t* w = row_for_writing(r);
        w[c / 64] |= bits << (c % 64);
        if (c % 64 > 56) w[c / 64 + 1] |= bits >> (64 - c % 64);
    }
    /// Row r's words, zeroed if the row had none set yet.
    std::uint64_t* row_for_writing(std::int32_t r) {
        std::uint64_t* w = words_.data() + static_cast<std::size_t>(r) * stride_;
        if (!live_[static_cast<std::size_t>(r)]) {
            live_[static_cast<std::size_t>(r)] = 1;
            std::fill_n(w, stride_, std::uint64_t{0});
            rows_.push_back(r);
        }
        return w;
    }
    /// Row r's words, or nullptr when none is set.
    const std::uint64_t* row(std::int32_t r) const {
        return live_[static_cast<std::size_t>(r)] ? words_.data() + static_cast<std::size_t>(r) * stride_ : nullptr;
    }
    /// Bits of columns c0 .. c0 + n - 1 of row r (n <= 64); columns outside the map read as unset.
    std::uint64_t bits(std::int32_t r, std::int32_t c0, std::int32_t n) const {
        const std::uint64_t* w = row(r);
        std::uint64_t v = 0;
        if (w == nullptr) return v;
        for (std::int32_t k = std::max(0, -c0); k < n && c0 + k < cols_;) {
            const std::int32_t c = c0 + k, m = std::min(n - k, 64 - c % 64);
            const std::uint64_t part = w[c / 64] >> (c % 64);
            v |= (m == 64 ? part : part & ((std::uint64_t{1} << m) - 1)) << k;
            k += m;
        }
        return v;
    }
    /// The rows with a set pixel, ascending.
    std::vector<std::int32_t> rows() const {
        std::vector<std::int32_t> out = rows_;
        std::sort(out.begin(), out.end());
        return out;
    }
    std::size_t words_per_row() const { return stride_; }
    /// The pixels set.
    std::uint64_t count() const {
        std::uint64_t n = 0;
        for (const std::int32_t r : rows_)
            for (std::size_t k = 0; k < stride_; ++k)
                if (row(r)[k] != 0) n += static_cast<std::uint64_t>(popcount(row(r)[k]));  // most words are empty
        return n;
    }

    /// The mask grown by each pixel's four neighbours (inside the map), whole words at a time.
    SparseRowMask dilated4() const {
        const auto H = static_cast<std::int32_t>(live_.size());
        SparseRowMask out(H, cols_);
        const std::size_t n = stride_;
        const std::uint64_t last = cols_ % 64 == 0 ? ~std::uint64_t{0} : (std::uint64_t{1} << (cols_ % 64)) - 1;
        for (const std::int32_t r : rows_) {
            const std::uint64_t* w = row(r);
            for (std::int32_t q = std::max(0, r - 1); q <= std::min(H - 1, r + 1); ++q) {
                std::uint64_t* o = out.row_for_writing(q);
                if (q != r) {  // the row above or below: the same columns
                    for (std::size_t k = 0; k < n; ++k) o[k] |= w[k];
                    continue;
                }
                for (std::size_t k = 0; k < n; ++k) {  // left and right, across word edges
                    std::uint64_t v = w[k] | w[k] << 1 | w[k] >> 1;
                    if (k > 0) v |= w[k - 1] >> 63;
                    if (k + 1 < n) v |= w[k + 1] << 63;
                    o[k] |= k + 1 == n ? v & last : v;
                }
            }
        }
        return out;
    }

    /// The first column >= c of row r (a set row) whose bit is v, or cols.
    std::int32_t find(std::int32_t r, std::int32_t c, bool v) const { return find_in_row(row(r), cols_, c, v, cols_); }

private:
    std::int32_t cols_;
    std::size_t stride_;
    ::dvoronoi::detail::UninitVector<std::uint64_t> words_;  // rows not live hold garbage
    std::vector<std::uint8_t> live_;
    std::vector<std::int32_t> rows_;  // the live rows, in the order they were first set
};

/// Step 2 of an update, row by row: a row's nearest points depend on its own pass-1 values only, so
/// rows are independent and may run on several threads. Writes row r's nearest points, its touched
/// bits (its row of `touched` must be set up already) and the clearance bounds of r's block row.
class RowPass {
public:
    // A column costs about three times as much in RowEnvelope::build as in build_run (measured in
    // instructions on three 2048 x 2048 maps); fill_run then reads only the pixels asked for.
    static constexpr std::int32_t kWindowCost = 3, kRunCost = 1;

    RowPass(MedialDiagram& m, SparseRowMask& touched)
        : m_(m), g_(m.grid), f_(m.features), touched_(touched), run_x_(static_cast<std::size_t>(m.grid.cols)),
          run_y_(static_cast<std::size_t>(m.grid.cols)) {}

    /// Removals in row r with changed columns `cols` (n, ascending; all free now). A pixel needs a
    /// new nearest point only if its old one lies on no occupied square any more: on a changed
    /// column's old pass-1 square, so its x lies in a run of changed columns' span, and nearest x only
    /// grows along a row: one interval of pixels a run, found by a search out from the run, inside
    /// the free run [s, t] that holds the changed columns. The interval's new points are found among
    /// the columns of a window, or, when the window is not much smaller than the run, by pass 2 over
    /// the whole run as a build runs it (a column costs less there). Two bounds make the window:
    ///  - the pixels' own squares are at most 2k - 1 away (doubled units) and a column d pixels away
    ///    is at least 2d - 1 away, so columns more than k away cannot win (ties included); nor can
    ///    columns beyond an occupied pixel of the row (its edge is at distance 0 in the row);
    ///  - nearest x grows along the row, so the new points' x lies between the final points of the
    ///    pixels just left and right of the interval: only the columns whose squares reach that span
    ///    can hold them (the pixel on the right is final unless a later run of the row recomputes it).
    void remove_row(std::int32_t r, const std::int32_t* cols, std::size_t n) {
        const std::int32_t W = g_.cols, j = g_.rows - 1 - r;
        const std::size_t base = f_.at(r, 0);
        const std::int16_t* fx = &f_.fx[base];
        const std::int16_t* fy = &f_.fy[base];
        const std::int16_t* vg = &f_.vgap[base];
        // clearances grow only here (additions bring points closer): the blocks' bounds follow
        std::int32_t* bound = m_.block_sq.empty() ? nullptr : &m_.block_sq[static_cast<std::size_t>(r / kBlock * ((W + kBlock - 1) / kBlock))];
        auto take_if_new = [&](std::int32_t x, const Candidate2& nc) {
            if (nc.x != fx[x] || nc.y != fy[x]) take(r, x, nc, bound);
        };
        std::int32_t from = 0, built = -1;  // built: the first column of the run build_run holds
        for (std::size_t a = 0; a < n;) {
            std::size_t b = a;
            while (b + 1 < n && cols[b + 1] == cols[b] + 1) ++b;
            const std::int32_t c = cols[a], xhi = 2 * cols[b] + 2;
            a = b + 1;
            const std::int32_t x1 = first_at_least(fx, from, W, 2 * c, c);
            std::int32_t k = 0;  // the largest vertical offset of pixels x1 .. x2 - 1
            const std::int32_t x2 = interval_end(fx, vg, x1, W, xhi, k);
            from = x2;
            if (x1 == x2) continue;
            const auto [s, t] = m_.bits.free_run(j, c);
            const std::int32_t R = std::max(k, 1) + 1;
            const std::int32_t lo = x1 > 0 ? fx[x1 - 1] : 0;  // the new points' x lies in [lo, hi]
            const std::int32_t hi = x2 < W && (a == n || fx[x2] < 2 * cols[a]) ? fx[x2] : 2 * W;
            // columns whose squares [2e, 2e + 2] meet [lo, hi]
            const std::int32_t ca = std::max({s - 1, x1 - R, (lo + 1) / 2 - 1}), cb = std::min({t + 1, x2 - 1 + R, hi / 2});
            const bool window = built != s && kWindowCost * (cb - ca + 1) < kRunCost * (t - s + 1);
            if (window) {
                env_.build(g_, f_, r, ca, cb);
                built = -1;
            } else if (built != s) {
                env_.build_run(g_, f_, r, s, t);
                built = s;
            }
            // pixels among the envelope's own columns segment by segment, any others one by one
            const std::int32_t fa = window ? std::max(x1, ca) : x1, fb = window ? std::min(x2 - 1, cb) : x2 - 1;
            for (std::int32_t x = x1; x < std::min(fa, x2); ++x) take_if_new(x, env_.query(x));
            if (fa <= fb) {
                env_.fill_run(fa, fb, run_x_.data(), run_y_.data());
                take_filled(r, fa, fb, bound);
            }
            for (std::int32_t x = std::max(fb + 1, x1); x < x2; ++x) take_if_new(x, env_.query(x));
        }
    }

    /// Additions in row r with changed columns `cols` (n, ascending).
    void add_row(std::int32_t r, const std::int32_t* cols, std::size_t n) {
        const std::int32_t W = g_.cols, Y = 2 * (g_.rows - 1 - r) + 1;
        const std::size_t base = f_.at(r, 0);
        const std::int16_t* vg = &f_.vgap[base];  // 0: occupied (the occupancy row is not read)
        for (std::size_t k = 0; k < n; ++k)  // newly occupied pixels: their own centres
            if (vg[cols[k]] == 0) set_feature(r, cols[k], 2 * cols[k] + 1, Y);
        std::size_t a = 0;
        while (a < n) {
            std::size_t b = a;
            while (b + 1 < n && cols[b + 1] == cols[b] + 1) ++b;
            const std::int32_t ca = cols[a], cb = cols[b];
            a = b + 1;
            if (std::all_of(vg + ca + 1, vg + cb + 1, [&](std::int16_t v) { return v == vg[ca]; })) {
                // The common run (a blob's columns above or below it): one offset, so the envelope
                // is its two end edges (build() drops the flat ones between) and each pixel of the run
                // takes its own column's square, strictly nearer than either edge.
                const std::int32_t y = feature_y(Y, vg[ca]);
                if (ca > 0) offer_segment<false>(r, ca - 1, 0, 2 * ca, y, 2 * ca);
                if (vg[ca] != 0) offer_filled<true>(r, ca, cb, y);  // else all newly occupied
                if (cb + 1 < W) offer_segment<true>(r, cb + 1, W - 1, 2 * cb + 2, y, 2 * cb + 2);
                continue;
            }
            env_.build(g_, f_, r, ca, cb);
            // Outside [ca, cb] a pixel's candidate is the edge whose segment holds it: the segments
            // are walked along with the scan, each offered to its pixels at once.
            std::size_t k = env_.segments() - 1;
            std::int64_t begin = k > 0 ? env_.segment_end(k - 1) : std::numeric_limits<std::int64_t>::min();
            for (std::int32_t x = ca - 1; x >= 0;) {  // leftwards: segment k holds pixels begin .. x
                while (x < begin) begin = --k > 0 ? env_.segment_end(k - 1) : std::numeric_limits<std::int64_t>::min();
                const Candidate2 e = env_.on_edge(k, x);
                const auto lo = static_cast<std::int32_t>(std::max<std::int64_t>(begin, 0));
                if (offer_segment<false>(r, x, lo, e.x, e.y, 2 * ca) >= lo) break;
                x = lo - 1;
            }
            // inside [ca, cb], the run's pixels segment by segment as a build fills them
            env_.fill_run(ca, cb, run_x_.data(), run_y_.data());
            offer_filled<false>(r, ca, cb);
            k = 0;
            std::int64_t end = env_.segment_end(0);
            for (std::int32_t x = cb + 1; x < W;) {  // rightwards: segment k holds pixels x .. end - 1
                while (x >= end) end = env_.segment_end(++k);
                const Candidate2 e = env_.on_edge(k, x);
                const auto hi = static_cast<std::int32_t>(std::min<std::int64_t>(end, W) - 1);
                if (offer_segment<true>(r, x, hi, e.x, e.y, 2 * cb + 2) <= hi) break;
                x = hi + 1;
            }
        }
    }

private:
    /// Removals: pixel (r, x) takes the nearest point n, and its block's clearance bound grows to it.
    void take(std::int32_t r, std::int32_t x, const Candidate2& n, std::int32_t* bound) {
        store(r, x, n);
        if (bound) bound[x / kBlock] = std::max(bound[x / kBlock], static_cast<std::int32_t>(n.sq));  // < 2^31: sides <= 16383
    }

    void set_feature(std::int32_t r, std::int32_t x, std::int32_t fx, std::int32_t fy) {
        const std::size_t i = f_.at(r, x);
        if (f_.fx[i] == fx && f_.fy[i] == fy) return;
        const std::int64_t dx = fx - (2 * x + 1), dy = fy - (2 * (g_.rows - 1 - r) + 1);
        store(r, x, {dx * dx + dy * dy, fx, fy});
    }

    /// Pixel (r, x) takes the nearest point n (a different one), n.sq away.
    void store(std::int32_t r, std::int32_t x, const Candidate2& n) {
        const std::size_t i = f_.at(r, x);
        f_.fx[i] = static_cast<std::int16_t>(n.x);
        f_.fy[i] = static_cast<std::int16_t>(n.y);
        touched_.set(r, x);
    }

    /// The first x in [from, W) with fx[x] >= v (fx non-decreasing), searched outward from `guess`:
    /// the answer is usually near it, and a binary search over the whole row reads a cache line a step.
    static std::int32_t first_at_least(const std::int16_t* fx, std::int32_t from, std::int32_t W, std::int32_t v, std::int32_t guess) {
        if (from >= W) return W;
        std::int32_t lo = std::max(from, std::min(guess, W - 1)), hi = lo;  // the answer lies in (lo, hi]
        if (fx[lo] >= v) {
            for (std::int32_t step = 1; lo > from && fx[lo - 1] >= v; step *= 2) {
                hi = lo;
                lo = std::max(from, lo - step);
                if (fx[lo] < v) break;
            }
            if (fx[lo] >= v) return lo;
        } else {
            for (std::int32_t step = 1; fx[hi] < v; step *= 2) {
                lo = hi;
                if (hi == W - 1) return W;
                hi = std::min(W - 1, hi + step);
            }
        }
        return static_cast<std::int32_t>(std::lower_bound(fx + lo + 1, fx + hi, v) - fx);
    }

    /// Removals: the first x >= x0 with fx[x] > xhi (fx non-decreasing), or W; k becomes the largest
    /// |vg| over the pixels before it. Eight pixels at a time with SSE2 (the intervals run for
    /// dozens of pixels in open space).
    static std::int32_t interval_end(const std::int16_t* fx, const std::int16_t* vg, std::int32_t x0, std::int32_t W, std::int32_t xhi,
                                     std::int32_t& k) {
        std::int32_t x = x0;
#if defined(__SSE2__)
        const __m128i lim = _mm_set1_epi16(static_cast<std::int16_t>(xhi)), zero = _mm_setzero_si128();
        __m128i most = zero;
        for (; x + 8 <= W; x += 8) {
            if (_mm_movemask_epi8(_mm_cmpgt_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(fx + x)), lim)) != 0) break;
            const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(vg + x));
            most = _mm_max_epi16(most, _mm_max_epi16(v, _mm_sub_epi16(zero, v)));  // |v| <= 16383
        }
        alignas(16) std::int16_t lanes[8];
        _mm_store_si128(reinterpret_cast<__m128i*>(lanes), most);
        for (const std::int16_t l : lanes) k = std::max<std::int32_t>(k, l);
#endif
        for (; x < W && fx[x] <= xhi; ++x) k = std::max<std::int32_t>(k, std::abs(static_cast<std::int32_t>(vg[x])));
        return x;
    }

    /// Removals: pixels x0 .. x1 of row r take the nearest points fill_run put in run_x_ / run_y_
    /// where they differ (and raise their blocks' clearance bounds), eight at a time with SSE2.
    void take_filled(std::int32_t r, std::int32_t x0, std::int32_t x1, std::int32_t* bound) {
        const std::size_t base = f_.at(r, 0);
        std::int16_t* fx = &f_.fx[base];
        std::int16_t* fy = &f_.fy[base];
        const std::int16_t* nx = run_x_.data();
        const std::int16_t* ny = run_y_.data();
        const std::int32_t Y = 2 * (g_.rows - 1 - r) + 1;
        std::int32_t x = x0;
#if defined(__SSE2__)
        const __m128i lane2 = _mm_setr_epi16(0, 2, 4, 6, 8, 10, 12, 14), YV = _mm_set1_epi16(static_cast<std::int16_t>(Y));
        for (; x + 8 <= x1 + 1; x += 8) {
            const __m128i vx = _mm_loadu_si128(reinterpret_cast<const __m128i*>(nx + x)), vy = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ny + x));
            const __m128i same = _mm_and_si128(_mm_cmpeq_epi16(vx, _mm_loadu_si128(reinterpret_cast<const __m128i*>(fx + x))),
                                               _mm_cmpeq_epi16(vy, _mm_loadu_si128(reinterpret_cast<const __m128i*>(fy + x))));
            const auto differ = static_cast<std::uint64_t>(~_mm_movemask_epi8(_mm_packs_epi16(same, same)) & 0xff);
            if (differ == 0) continue;
            _mm_storeu_si128(reinterpret_cast<__m128i*>(fx + x), vx);  // the same where they agree
            _mm_storeu_si128(reinterpret_cast<__m128i*>(fy + x), vy);
            touched_.set_eight(r, x, differ);
            if (bound == nullptr) continue;
            // the eight squares (pmaddwd, < 2^31); unchanged pixels are within their block's bound already
            const __m128i dx = _mm_sub_epi16(vx, _mm_add_epi16(_mm_set1_epi16(static_cast<std::int16_t>(2 * x + 1)), lane2));
            const __m128i dy = _mm_sub_epi16(vy, YV);
            const __m128i lo = _mm_madd_epi16(_mm_unpacklo_epi16(dx, dy), _mm_unpacklo_epi16(dx, dy));
            const __m128i hi = _mm_madd_epi16(_mm_unpackhi_epi16(dx, dy), _mm_unpackhi_epi16(dx, dy));
            alignas(16) std::int32_t sq[8];
            _mm_store_si128(reinterpret_cast<__m128i*>(sq), lo);
            _mm_store_si128(reinterpret_cast<__m128i*>(sq + 4), hi);
            for (int k = 0; k < 8; ++k) bound[(x + k) / kBlock] = std::max(bound[(x + k) / kBlock], sq[k]);
        }
#endif
        for (; x <= x1; ++x) {
            if (nx[x] == fx[x] && ny[x] == fy[x]) continue;
            const std::int64_t dx = nx[x] - (2 * x + 1), dy = ny[x] - Y;
            take(r, x, {dx * dx + dy * dy, nx[x], ny[x]}, bound);
        }
    }

    /// Additions: pixels `from` .. `to` of row r (rightwards when kRight, else leftwards) lie on one
    /// segment of the changed columns' envelope, whose nearest point is (cx, cy). Each free pixel takes
    /// it when it beats the pixel's own (ties: the smaller x, then y). Returns the first pixel that
    /// keeps a point beyond the run (right: x beyond `lim`; left: below it), where the scan ends, or
    /// the pixel past `to`. Eight pixels at a time with SSE2: offsets fit 16 bits and two squares sum
    /// below 2^31 (sides <= 16383), as in a build's fill_run.
    template <bool kRight>
    std::int32_t offer_segment(std::int32_t r, std::int32_t from, std::int32_t to, std::int32_t cx, std::int32_t cy, std::int32_t lim) {
        const std::size_t base = f_.at(r, 0);
        std::int16_t* fx = &f_.fx[base];
        std::int16_t* fy = &f_.fy[base];
        const std::int16_t* vg = &f_.vgap[base];
        const std::int32_t Y = 2 * (g_.rows - 1 - r) + 1, step = kRight ? 1 : -1;
        std::int32_t x = from;
#if defined(__SSE2__)
        const __m128i CX = _mm_set1_epi16(static_cast<std::int16_t>(cx)), CY = _mm_set1_epi16(static_cast<std::int16_t>(cy));
        const __m128i YV = _mm_set1_epi16(static_cast<std::int16_t>(Y)), LIM = _mm_set1_epi16(static_cast<std::int16_t>(lim));
        const __m128i lane = _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7), zero = _mm_setzero_si128();
        for (; kRight ? x + 7 <= to : x - 7 >= to; x += 8 * step) {
            const std::int32_t x0 = kRight ? x : x - 7;  // the eight pixels x0 .. x0 + 7
            const __m128i vfx = _mm_loadu_si128(reinterpret_cast<const __m128i*>(fx + x0));
            const __m128i vfy = _mm_loadu_si128(reinterpret_cast<const __m128i*>(fy + x0));
            const __m128i vvg = _mm_loadu_si128(reinterpret_cast<const __m128i*>(vg + x0));
            __m128i take = beats(vfx, vfy, vvg, x0, YV, CX, CY);
            const __m128i beyond = kRight ? _mm_cmpgt_epi16(vfx, LIM) : _mm_cmplt_epi16(vfx, LIM);
            const int stops = _mm_movemask_epi8(_mm_packs_epi16(_mm_andnot_si128(take, beyond), zero));
            std::int32_t stop = -1;  // the lane where the scan ends
            if (stops != 0) {
                stop = kRight ? lowest_bit(static_cast<std::uint64_t>(stops)) : highest_bit(static_cast<std::uint64_t>(stops));
                // only the lanes the scan reaches before it
                take = _mm_and_si128(take, kRight ? _mm_cmplt_epi16(lane, _mm_set1_epi16(static_cast<std::int16_t>(stop)))
                                                  : _mm_cmpgt_epi16(lane, _mm_set1_epi16(static_cast<std::int16_t>(stop))));
            }
            store_taken(r, x0, take, CX, CY, vfx, vfy);
            if (stop >= 0) return x0 + stop;
        }
#endif
        for (; kRight ? x <= to : x >= to; x += step) {
            const std::int64_t ndx = cx - (2 * x + 1), ndy = cy - Y;
            const bool took = vg[x] != 0 && offer(r, x, {ndx * ndx + ndy * ndy, cx, cy});
            if (!took && (kRight ? fx[x] > lim : fx[x] < lim)) return x;
        }
        return x;
    }

#if defined(__SSE2__)
    /// Additions, eight pixels x0 .. x0 + 7 of a row (pixel centres' y YV) with nearest points
    /// (vfx, vfy) and pass-1 offsets vvg: the lanes where the candidates (CX, CY) beat the pixel's
    /// point (ties: the smaller x, then y) and the pixel is free. Offsets fit 16 bits and two squares
    /// sum below 2^31 (sides <= 16383): pmaddwd squares, as in a build's fill_run.
    static __m128i beats(__m128i vfx, __m128i vfy, __m128i vvg, std::int32_t x0, __m128i YV, __m128i CX, __m128i CY) {
        const __m128i X = _mm_add_epi16(_mm_set1_epi16(static_cast<std::int16_t>(2 * x0 + 1)), _mm_setr_epi16(0, 2, 4, 6, 8, 10, 12, 14));
        const __m128i odx = _mm_sub_epi16(vfx, X), ody = _mm_sub_epi16(vfy, YV);
        const __m128i ndx = _mm_sub_epi16(CX, X), ndy = _mm_sub_epi16(CY, YV);
        const __m128i olo = _mm_unpacklo_epi16(odx, ody), ohi = _mm_unpackhi_epi16(odx, ody);
        const __m128i nlo = _mm_unpacklo_epi16(ndx, ndy), nhi = _mm_unpackhi_epi16(ndx, ndy);
        const __m128i o0 = _mm_madd_epi16(olo, olo), o1 = _mm_madd_epi16(ohi, ohi);
        const __m128i n0 = _mm_madd_epi16(nlo, nlo), n1 = _mm_madd_epi16(nhi, nhi);
        const __m128i lt = _mm_packs_epi32(_mm_cmplt_epi32(n0, o0), _mm_cmplt_epi32(n1, o1));
        const __m128i eq = _mm_packs_epi32(_mm_cmpeq_epi32(n0, o0), _mm_cmpeq_epi32(n1, o1));
        const __m128i tie = _mm_or_si128(_mm_cmplt_epi16(CX, vfx), _mm_and_si128(_mm_cmpeq_epi16(CX, vfx), _mm_cmplt_epi16(CY, vfy)));
        return _mm_andnot_si128(_mm_cmpeq_epi16(vvg, _mm_setzero_si128()), _mm_or_si128(lt, _mm_and_si128(eq, tie)));
    }

    /// Additions: the lanes `take` of pixels x0 .. x0 + 7 of row r take the points (nx, ny), the others
    /// keep (vfx, vfy); the changed pixels are recorded.
    void store_taken(std::int32_t r, std::int32_t x0, __m128i take, __m128i nx, __m128i ny, __m128i vfx, __m128i vfy) {
        const auto took = static_cast<std::uint64_t>(_mm_movemask_epi8(_mm_packs_epi16(take, _mm_setzero_si128())));
        if (took == 0) return;
        const std::size_t i = f_.at(r, x0);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(&f_.fx[i]), _mm_or_si128(_mm_and_si128(take, nx), _mm_andnot_si128(take, vfx)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(&f_.fy[i]), _mm_or_si128(_mm_and_si128(take, ny), _mm_andnot_si128(take, vfy)));
        touched_.set_eight(r, x0, took);
    }
#endif

    /// Additions: pixels x0 .. x1 of row r take the nearest points fill_run put in run_x_ / run_y_
    /// (kOwn: the points (2x + 1, y) of their own columns) where those beat their own (free pixels
    /// only), eight at a time with SSE2.
    template <bool kOwn>
    void offer_filled(std::int32_t r, std::int32_t x0, std::int32_t x1, std::int32_t y = 0) {
        const std::size_t base = f_.at(r, 0);
        std::int16_t* fx = &f_.fx[base];
        std::int16_t* fy = &f_.fy[base];
        const std::int16_t* vg = &f_.vgap[base];
        const std::int32_t Y = 2 * (g_.rows - 1 - r) + 1;
        std::int32_t x = x0;
#if defined(__SSE2__)
        const __m128i YV = _mm_set1_epi16(static_cast<std::int16_t>(Y));
        for (; x + 8 <= x1 + 1; x += 8) {
            const __m128i vfx = _mm_loadu_si128(reinterpret_cast<const __m128i*>(fx + x));
            const __m128i vfy = _mm_loadu_si128(reinterpret_cast<const __m128i*>(fy + x));
            const __m128i nx = kOwn ? _mm_add_epi16(_mm_set1_epi16(static_cast<std::int16_t>(2 * x + 1)), _mm_setr_epi16(0, 2, 4, 6, 8, 10, 12, 14))
                                    : _mm_loadu_si128(reinterpret_cast<const __m128i*>(run_x_.data() + x));
            const __m128i ny = kOwn ? _mm_set1_epi16(static_cast<std::int16_t>(y)) : _mm_loadu_si128(reinterpret_cast<const __m128i*>(run_y_.data() + x));
            store_taken(r, x, beats(vfx, vfy, _mm_loadu_si128(reinterpret_cast<const __m128i*>(vg + x)), x, YV, nx, ny), nx, ny, vfx, vfy);
        }
#endif
        for (; x <= x1; ++x) {
            if (vg[x] == 0) continue;
            const std::int32_t nx = kOwn ? 2 * x + 1 : run_x_[static_cast<std::size_t>(x)], ny = kOwn ? y : run_y_[static_cast<std::size_t>(x)];
            const std::int64_t dx = nx - (2 * x + 1), dy = ny - Y;
            offer(r, x, {dx * dx + dy * dy, nx, ny});
        }
    }

    /// Additions: pixel (r, x) takes the candidate nc when it beats the pixel's nearest point (ties:
    /// the smaller x, then y); true when it did.
    bool offer(std::int32_t r, std::int32_t x, const Candidate2& nc) {
        const std::size_t i = f_.at(r, x);
        const std::int64_t dx = f_.fx[i] - (2 * x + 1), dy = f_.fy[i] - (2 * (g_.rows - 1 - r) + 1);
        if (!(nc < Candidate2{dx * dx + dy * dy, f_.fx[i], f_.fy[i]})) return false;
        store(r, x, nc);
        return true;
    }

    MedialDiagram& m_;
    OccupancyGrid& g_;
    FeatureMap& f_;
    SparseRowMask& touched_;
    RowEnvelope env_;
    std::vector<std::int16_t> run_x_, run_y_;  // nearest points fill_run gives, by column
};

class Updater {
public:
    static constexpr std::size_t kAhead = 2;  // rows fetched ahead of the row pass
    // pixels beyond a row's changed columns fetched too: most scans and windows end within them
    // (on three 2048 x 2048 maps, with other work between updates: 64-160 save 5-10 % of an update)
    static constexpr std::int32_t kAheadMargin = 128;
    static constexpr std::int32_t kWalkAhead = 8;  // rows a column walk fetches ahead (measured: 4-16 save 10 % of an addition)
    static constexpr std::size_t kCellsPerWorker = 4096;  // changed pass-1 values below which one thread works
    static constexpr std::size_t kRowsPerWorker = 64;     // rows to re-mark below which one thread works

    explicit Updater(MedialDiagram& m) : m_(m), g_(m.grid), f_(m.features), touched_(m.grid.rows, m.grid.cols) {}

    /// Sets the listed pixels (linear indices) to `occupied`; pixels already so are skipped.
    void apply(const std::vector<std::size_t>& pixels, bool occupied) {
        const auto W = static_cast<std::uint32_t>(g_.cols);
        std::vector<std::pair<std::int32_t, std::int32_t>> rc;  // (row, column) of the changes, as given
        for (std::size_t i : pixels) {
            if ((g_.occupied[i] != 0) == occupied) continue;  // already so, or listed twice
            g_.occupied[i] = occupied ? 1 : 0;
            const auto k = static_cast<std::uint32_t>(i);  // < 2^28: 32-bit division
            const auto r = static_cast<std::int32_t>(k / W), c = static_cast<std::int32_t>(k % W);
            m_.bits.put(g_.rows - 1 - r, c, occupied);
            touched_.set(r, c);
            rc.push_back({r, c});
        }
        if (rc.empty()) return;
        stats.changed_pixels += rc.size();
        // (column, row) order for the column pass, by two stable bucketings (a sort of the list costs
        // more than the column pass)
        std::vector<std::pair<std::int32_t, std::int32_t>> by_c = bucketed(bucketed(rc, 0, g_.rows), 1, g_.cols);
        for (auto& p : by_c) std::swap(p.first, p.second);
        for (const auto& [r, c] : rc) changed_.push_back(g_.at(r, c));
        const RowCells cells = by_row(occupied ? add_columns(by_c) : remove_columns(by_c));
        // Rows go to the workers in groups of whole block rows (kBlock rows share clearance bounds);
        // their touched rows are set up first, so the workers write only their own rows.
        std::vector<std::size_t> groups;  // indices into cells.rows where a block row starts
        for (std::size_t k = 0; k < cells.rows.size(); ++k) {
            touched_.row_for_writing(cells.rows[k]);
            if (k == 0 || cells.rows[k] / kBlock != cells.rows[k - 1] / kBlock) groups.push_back(k);
        }
        groups.push_back(cells.rows.size());
        const auto n_groups = static_cast<std::int32_t>(groups.size() - 1);
        // a few rows are not worth a thread's wake-up
        const int workers = cells.cols.size() < kCellsPerWorker ? 1 : std::min(m_.options.workers, n_groups);
        run_chunks(workers, n_groups, 1, [this] { return RowPass(m_, touched_); }, [&](RowPass& pass, std::int32_t g0, std::int32_t g1) {
            const std::size_t end = groups[static_cast<std::size_t>(g1)];
            for (std::size_t k = groups[static_cast<std::size_t>(g0)]; k < end; ++k) {
                if (k + kAhead < end) fetch_cells_row(cells, k + kAhead, occupied);
                const std::int32_t* cols = cells.cols.data() + cells.start[k];
                const std::size_t n = cells.start[k + 1] - cells.start[k];
                if (occupied) pass.add_row(cells.rows[k], cols, n);
                else pass.remove_row(cells.rows[k], cols, n);
            }
        });
    }

    /// Rechecks the diagram where the changes can reach it. A pixel's membership is a function of
    /// the final nearest points, so the pixels found are collected, then re-marked row segment by
    /// row segment as a build marks them.
    void refresh_mask() {
        if (changed_.empty()) return;
        stats.feature_changes = touched_.count();  // each pixel once: its occupancy or nearest point changed
        SparseRowMask redo = touched_.dilated4();  // touched pixels and their 4-neighbours (they share a pair)
        find_boxed(redo);
        const std::vector<std::int32_t> rows = redo.rows();  // a row's marks are its own: rows go to the workers
        std::atomic<std::uint64_t> checks{0};
        const int workers = rows.size() < kRowsPerWorker ? 1 : m_.options.workers;
        run_chunks(workers, static_cast<std::int32_t>(rows.size()), 16, [this] { return RowMarker(m_); },
                   [&](RowMarker& marker, std::int32_t k0, std::int32_t k1) {
                       std::uint64_t n = 0;
                       for (std::int32_t k = k0; k < k1; ++k) {
                           const std::int32_t r = rows[static_cast<std::size_t>(k)];
                           for (std::int32_t a = redo.find(r, 0, true); a < g_.cols; a = redo.find(r, a, true)) {  // runs of set bits
                               const std::int32_t b = redo.find(r, a, false);
                               n += static_cast<std::uint64_t>(b - a);
                               marker.mark_segment(r, a, b - 1);
                               a = b;
                           }
                       }
                       checks += n;
                   });
        stats.mask_checks += checks.load();
    }

    UpdateStats stats;

private:
    /// Adds to `redo` the pixels of box-judged pairs (m.boxed: the only pixels whose membership a
    /// change of occupancy can alter without a touched neighbour) whose nearest point lies near a
    /// change: changed pixels grouped in blocks, each block's box grown by the margin below (a zone).
    /// A pixel is no farther from its nearest point than its clearance, so only the blocks no farther
    /// from a zone than their largest clearance (MedialDiagram::block_sq) are searched, and a pixel's
    /// nearest point is looked up in a coarse grid of cells holding the zones (a cell over a zone's
    /// edge adds pixels to recheck, never drops one).
    void find_boxed(SparseRowMask& redo) {
        const std::int32_t H = g_.rows, W = g_.cols;
        // a grown box lies within prune_length + sqrt(2) + 1 pixels of either nearest point
        const std::int32_t margin = static_cast<std::int32_t>(std::ceil(m_.options.prune_length)) + 3;
        constexpr std::int32_t kCell = 3;  // cells of 8 x 8 pixels
        const std::int32_t bw = (W + kBlock - 1) / kBlock, bh = (H + kBlock - 1) / kBlock;
        std::vector<std::uint8_t> has_change(static_cast<std::size_t>(bw) * static_cast<std::size_t>(bh), 0);
        for (std::size_t i : changed_) {
            const auto r = static_cast<std::int32_t>(i / static_cast<std::size_t>(W));
            const auto c = static_cast<std::int32_t>(i % static_cast<std::size_t>(W));
            has_change[static_cast<std::size_t>(r / kBlock * bw + c / kBlock)] = 1;
        }
        // nearest points' pixel coordinates (x, y) = (fx / 2, fy / 2) lie in [0, W] x [0, H]
        const std::int32_t zw = (W >> kCell) + 1;
        std::vector<std::uint8_t> zone, search;
        std::int64_t reach = 0;  // pixels: the largest clearance of the map, and the margin
        for (std::int32_t t = 0; t < bw * bh; ++t) {
            if (!has_change[static_cast<std::size_t>(t)]) continue;
            const std::int32_t r0 = t / bw * kBlock, c0 = t % bw * kBlock;
            const std::int32_t r1 = std::min(H, r0 + kBlock) - 1, c1 = std::min(W, c0 + kBlock) - 1;
            // nearest points (doubled) in [xlo, xhi] x [ylo, yhi]
            const std::int32_t xlo = 2 * (c0 - margin), xhi = 2 * (c1 + 1 + margin);
            const std::int32_t ylo = 2 * (H - 1 - r1 - margin), yhi = 2 * (H - r0 + margin);
            if (!unchanged_walls_meet(xlo, xhi, ylo, yhi)) continue;
            if (zone.empty()) {
                const std::int32_t most = *std::max_element(block_sq().begin(), block_sq().end());
                reach = static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(most)) / 2.0)) + margin + 1;
                zone.assign(static_cast<std::size_t>(zw) * static_cast<std::size_t>((H >> kCell) + 1), 0);
                search.assign(has_change.size(), 0);
            }
            const std::int32_t x0 = std::max(0, xlo / 2) >> kCell, x1 = std::min(W, xhi / 2) >> kCell;
            const std::int32_t y0 = std::max(0, ylo / 2) >> kCell, y1 = std::min(H, yhi / 2) >> kCell;
            for (std::int32_t y = y0; y <= y1; ++y)
                std::fill_n(&zone[static_cast<std::size_t>(y) * static_cast<std::size_t>(zw) + static_cast<std::size_t>(x0)], x1 - x0 + 1, std::uint8_t{1});
            // blocks within the map's largest clearance, then each by its own
            const auto i0 = static_cast<std::int32_t>(std::max<std::int64_t>(0, r0 - reach) / kBlock);
            const auto i1 = static_cast<std::int32_t>(std::min<std::int64_t>(H - 1, r1 + reach) / kBlock);
            const auto j0 = static_cast<std::int32_t>(std::max<std::int64_t>(0, c0 - reach) / kBlock);
            const auto j1 = static_cast<std::int32_t>(std::min<std::int64_t>(W - 1, c1 + reach) / kBlock);
            for (std::int32_t bi = i0; bi <= i1; ++bi)
                for (std::int32_t bj = j0; bj <= j1; ++bj) {
                    // the block's pixel centres span [bx0, bx1] x [by0, by1] (doubled)
                    const std::int64_t bx0 = 2 * bj * kBlock + 1, bx1 = 2 * (std::min(W, (bj + 1) * kBlock) - 1) + 1;
                    const std::int64_t by1 = 2 * (H - 1 - bi * kBlock) + 1, by0 = 2 * (H - std::min(H, (bi + 1) * kBlock)) + 1;
                    const std::int64_t dx = std::max<std::int64_t>({0, xlo - bx1, bx0 - xhi}), dy = std::max<std::int64_t>({0, ylo - by1, by0 - yhi});
                    const std::size_t b = static_cast<std::size_t>(bi * bw + bj);
                    if (dx * dx + dy * dy <= block_sq()[b]) search[b] = 1;
                }
        }
        if (zone.empty()) return;
        for (std::int32_t bi = 0; bi < bh; ++bi)
            for (std::int32_t bj = 0; bj < bw;) {  // runs of blocks to search in a row of blocks
                if (!search[static_cast<std::size_t>(bi * bw + bj)]) { ++bj; continue; }
                std::int32_t bk = bj + 1;
                while (bk < bw && search[static_cast<std::size_t>(bi * bw + bk)]) ++bk;
                const std::int32_t ca = bj * kBlock, cb = std::min(W, bk * kBlock) - 1;
                for (std::int32_t r = bi * kBlock; r < std::min(H, (bi + 1) * kBlock); ++r) {
                    const std::size_t base = f_.at(r, 0);
                    for (std::int32_t x = m_.boxed.find(r, ca, true, cb + 1); x <= cb; x = m_.boxed.find(r, x + 1, true, cb + 1)) {
                        const std::size_t i = base + static_cast<std::size_t>(x);
                        const std::size_t cell = static_cast<std::size_t>(f_.fy[i] >> (kCell + 1)) * static_cast<std::size_t>(zw) +
                                                 static_cast<std::size_t>(f_.fx[i] >> (kCell + 1));
                        if (zone[cell]) redo.set(r, x);
                    }
                }
                bj = bk;
            }
    }

    /// Does an occupied square that is not a changed pixel (or the outside) meet the zone
    /// [xlo, xhi] x [ylo, yhi] (doubled units)? If not, a pixel whose nearest point lies in the zone
    /// has it on a changed square only, so the update gave it that point (or took it away): the pixel
    /// was touched and is rechecked anyway. A blob put into open space (the common update) skips the
    /// search for pixels whose nearest point lies near it. An occupied pixel is touched only when it
    /// was changed (its nearest point is its own centre), so the unchanged walls are the occupied
    /// bits less the touched ones, a word at a time.
    bool unchanged_walls_meet(std::int32_t xlo, std::int32_t xhi, std::int32_t ylo, std::int32_t yhi) const {
        const std::int32_t H = g_.rows, W = g_.cols;
        // square column c covers [2c, 2c + 2]: it meets [xlo, xhi] (even bounds) for xlo/2 - 1 <= c <= xhi/2;
        // columns and rows -1 and cols / rows are the outside (occupied in the bits)
        const std::int32_t c0 = std::max(-1, xlo / 2 - 1), c1 = std::min(W, xhi / 2);
        const std::int32_t j0 = std::max(-1, ylo / 2 - 1), j1 = std::min(H, yhi / 2);
        if (j0 < 0 || j1 >= H) return true;
        for (std::int32_t j = j0; j <= j1; ++j)
            for (std::int32_t c = c0; c <= c1; c += 64) {
                const std::int32_t n = std::min(64, c1 - c + 1);
                if ((m_.bits.row(j, c, n) & ~touched_.bits(H - 1 - j, c, n)) != 0) return true;
            }
        return false;
    }

    /// The diagram's bounds of each block's clearance; the first update that needs them computes them.
    const std::vector<std::int32_t>& block_sq() {
        if (m_.block_sq.empty()) m_.block_sq = block_clearances(f_);
        return m_.block_sq;
    }

    /// Pass 1 after removals: between the nearest pixels lo and hi of a column that stay occupied (or
    /// the outside) every pixel is free, so its offsets to both are known without a pass. Those pixels
    /// are found by jumping along the old offsets: a free pixel's offset says how far its column was
    /// free (and a pixel with none was occupied: it stays so or was freed). Only the pixels whose old
    /// nearest pixel was freed change: from the middle between lo and the first freed pixel a to the
    /// middle between the last one b and hi (ties went below, as in a build's pass 1).
    SparseRowMask remove_columns(const std::vector<std::pair<std::int32_t, std::int32_t>>& cr) {
        const std::int32_t H = g_.rows;
        SparseRowMask cells(H, g_.cols);  // the pixels whose pass-1 value changed
        for (std::size_t k = 0; k < cr.size();) {
            const std::int32_t c = cr[k].first, a = cr[k].second;
            auto v = [&](std::int32_t r) -> std::int32_t { return f_.vgap[f_.at(r, c)]; };
            std::int32_t lo = a - 1, hi = a + 1;
            // above: offset k > 0 (below nearer or as near) leaves rows r-1 .. r-k+1 free; k < 0 points
            // at the occupied pixel above
            while (lo >= 0 && !g_.occ(lo, c)) lo -= v(lo) > 0 ? v(lo) : (v(lo) < 0 ? -v(lo) : 1);
            // below: k > 0 points at the occupied pixel below; k < 0 (above strictly nearer) leaves
            // rows r+1 .. r-k free
            while (hi < H && !g_.occ(hi, c)) hi += v(hi) > 0 ? v(hi) : (v(hi) < 0 ? 1 - v(hi) : 1);
            std::int32_t b = a;
            for (; k < cr.size() && cr[k].first == c && cr[k].second < hi; ++k) b = cr[k].second;
            // rows r with a - r <= r - lo, to rows r with r - b < hi - r
            const std::int32_t first = (a + lo + 1) >> 1, last = (hi + b - 1) >> 1;  // lo + a >= -1
            for (std::int32_t r = first; r <= last; ++r) {
                const std::int32_t up = r - lo, down = hi - r;  // ties: below, as in a build's pass 1
                const auto nv = static_cast<std::int16_t>(down <= up ? down : -up);
                std::int16_t& cur = f_.vgap[f_.at(r, c)];
                if (cur != nv) {
                    cur = nv;
                    cells.set(r, c);
                }
            }
            stats.column_cells += static_cast<std::uint64_t>(last - first + 1);
        }
        return cells;
    }

    /// Pass 1 after additions: offsets only shrink, so from each run of new pixels of a column the
    /// walk goes outward while the run is nearer than the offset a pixel has (ties: below). It stops
    /// at the first pixel that keeps its offset: the run's distance grows by one a row and the kept
    /// side's shrinks by one, so no pixel beyond changes either. New pixels get offset 0 first, so the
    /// walks read the offsets only (0: occupied). A walk reads and writes its own column only, and a
    /// column's runs walk in ascending order. Neighbouring columns with the same run (a blob's) walk
    /// together row by row: a row's offsets share a cache line, a column's lie a row apart.
    SparseRowMask add_columns(const std::vector<std::pair<std::int32_t, std::int32_t>>& cr) {
        const std::int32_t H = g_.rows;
        SparseRowMask cells(H, g_.cols);  // the pixels whose pass-1 value changed
        auto put = [&](std::int32_t r, std::int32_t c, std::int32_t v) {
            std::int16_t& cur = f_.vgap[f_.at(r, c)];
            if (cur == v) return;
            cur = static_cast<std::int16_t>(v);
            cells.set(r, c);
        };
        struct Run { std::int32_t a, b, c; };  // new pixels a .. b of column c
        std::vector<Run> runs;
        for (std::size_t k = 0; k < cr.size();) {
            std::size_t e = k + 1;
            while (e < cr.size() && cr[e].first == cr[k].first && cr[e].second == cr[e - 1].second + 1) ++e;
            runs.push_back({cr[k].second, cr[e - 1].second, cr[k].first});
            for (std::size_t q = k; q < e; ++q) put(cr[q].second, cr[q].first, 0);
            k = e;
        }
        // bands: the same run in consecutive columns; ascending a keeps each column's runs in order
        std::sort(runs.begin(), runs.end(), [](const Run& x, const Run& y) {
            return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.c < y.c);
        });
        std::vector<std::int32_t> active, stop(static_cast<std::size_t>(g_.cols));
        for (std::size_t k = 0; k < runs.size();) {
            std::size_t e = k + 1;
            while (e < runs.size() && runs[e].a == runs[k].a && runs[e].b == runs[k].b && runs[e].c == runs[e - 1].c + 1) ++e;
            const std::int32_t a = runs[k].a, b = runs[k].b, c0 = runs[k].c, c1 = runs[e - 1].c;
            k = e;
            // above the run: the run is below, at a - r; a column stops at its first kept offset
            active.clear();
            for (std::int32_t c = c0; c <= c1; ++c) active.push_back(c);
            for (std::int32_t r = a - 1; !active.empty(); --r) {
                if (r - kWalkAhead >= 0) fetch_row(r - kWalkAhead, c0, c1);
                std::size_t keep = 0;
                for (const std::int32_t c : active) {
                    const std::int32_t v = r < 0 ? 0 : f_.vgap[f_.at(r, c)];
                    if (v == 0 || (v < 0 && -v < a - r)) {
                        stop[static_cast<std::size_t>(c)] = r;
                        continue;
                    }
                    put(r, c, a - r);
                    active[keep++] = c;
                }
                active.resize(keep);
            }
            // below the run: the run is above, at s - b
            for (std::int32_t c = c0; c <= c1; ++c) active.push_back(c);
            for (std::int32_t s = b + 1; !active.empty(); ++s) {
                if (s + kWalkAhead < H) fetch_row(s + kWalkAhead, c0, c1);
                std::size_t keep = 0;
                for (const std::int32_t c : active) {
                    const std::int32_t v = s >= H ? 0 : f_.vgap[f_.at(s, c)];
                    if (v == 0 || (v > 0 && v <= s - b)) {
                        stats.column_cells += static_cast<std::uint64_t>(s - stop[static_cast<std::size_t>(c)] - 1);
                        continue;
                    }
                    put(s, c, b - s);
                    active[keep++] = c;
                }
                active.resize(keep);
            }
        }
        return cells;
    }

    /// Fetches what the row pass reads of cells row q: its rows lie 2 W bytes apart, out of the
    /// hardware prefetcher's sight.
    void fetch_cells_row(const RowCells& cells, std::size_t q, bool occupied) const {
        const std::int32_t c0 = std::max(0, cells.cols[cells.start[q]] - kAheadMargin);
        const std::int32_t c1 = std::min(g_.cols - 1, cells.cols[cells.start[q + 1] - 1] + kAheadMargin);
        for (std::int32_t c = c0; c <= c1; c += 32) {  // a cache line of each array
            const std::size_t i = f_.at(cells.rows[q], c);
            ::dvoronoi::detail::prefetch(&f_.vgap[i]);
            ::dvoronoi::detail::prefetch(&f_.fx[i]);
            ::dvoronoi::detail::prefetch(&f_.fy[i]);
        }
        if (!occupied) {  // removals look for the free run in the bits (512 columns a line)
            const std::uint64_t* w = m_.bits.row_words(g_.rows - 1 - cells.rows[q]);
            for (std::int32_t c = c0 + 1; c <= c1 + 1 + 511; c += 512) ::dvoronoi::detail::prefetch(w + c / 64);
        }
    }

    /// Fetches the pass-1 values of columns c0 .. c1 of row r (a walk's rows lie 2 W bytes apart,
    /// out of the hardware prefetcher's sight).
    void fetch_row(std::int32_t r, std::int32_t c0, std::int32_t c1) const {
        ::dvoronoi::detail::prefetch(&f_.vgap[f_.at(r, c0)]);
        ::dvoronoi::detail::prefetch(&f_.vgap[f_.at(r, c1)]);
    }

    /// `items` (pairs) stably bucketed by their `key`-th member, which lies in [0, n).
    static std::vector<std::pair<std::int32_t, std::int32_t>> bucketed(const std::vector<std::pair<std::int32_t, std::int32_t>>& items,
                                                                       int key, std::int32_t n) {
        auto k = [key](const std::pair<std::int32_t, std::int32_t>& p) { return static_cast<std::size_t>(key == 0 ? p.first : p.second); };
        std::vector<std::size_t> at(static_cast<std::size_t>(n) + 1, 0);
        for (const auto& p : items) ++at[k(p) + 1];
        for (std::size_t b = 1; b < at.size(); ++b) at[b] += at[b - 1];
        std::vector<std::pair<std::int32_t, std::int32_t>> out(items.size());
        for (const auto& p : items) out[at[k(p)]++] = p;
        return out;
    }

    /// The cells of a mask as rows with ascending columns, rows ascending.
    static RowCells by_row(const SparseRowMask& cells) {
        RowCells out;
        out.rows = cells.rows();
        for (const std::int32_t r : out.rows) {
            const std::uint64_t* w = cells.row(r);
            for (std::size_t k = 0; k < cells.words_per_row(); ++k)
                for (std::uint64_t word = w[k]; word != 0; word &= word - 1)
                    out.cols.push_back(static_cast<std::int32_t>(k * 64) + lowest_bit(word));
            out.start.push_back(out.cols.size());
        }
        return out;
    }

    MedialDiagram& m_;
    OccupancyGrid& g_;
    FeatureMap& f_;
    std::vector<std::size_t> changed_;         // pixels whose occupancy flipped
    SparseRowMask touched_;                    // pixels whose occupancy or nearest point changed
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
/// nonzero; b == nullptr: all zero). A change touches few pixels: 64 bytes are compared at a time
/// (SSE2), and only a block that differs is looked at byte by byte.
template <class Fn>
void for_each_difference(const std::uint8_t* a, const std::uint8_t* b, std::size_t n, Fn&& fn) {
    auto at = [b](std::size_t k) { return b != nullptr && b[k] != 0; };
    std::size_t i = 0;
#if defined(__SSE2__)
    for (; i + 64 <= n; i += 64) {
        __m128i same = _mm_set1_epi8(-1);
        for (std::size_t k = 0; k < 64; k += 16) {
            const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + i + k));
            const __m128i y = b != nullptr ? _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + i + k)) : _mm_setzero_si128();
            same = _mm_and_si128(same, _mm_cmpeq_epi8(x, y));
        }
        if (_mm_movemask_epi8(same) == 0xffff) continue;
        for (std::size_t k = i; k < i + 64; ++k)
            if ((a[k] != 0) != at(k)) fn(k);
    }
#endif
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
