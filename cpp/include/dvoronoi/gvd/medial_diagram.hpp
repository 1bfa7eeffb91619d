// The medial diagram of an occupancy grid (SPEC "Grid diagram on occupancy grids", diagram="medial"):
// the pixels where the nearest occupied point jumps from one side of a passage to the other, so a
// corridor between two parts of the same wall gets its centreline.
//
// Definition (pixel units; a, b, p, q as points, exact integers in doubled units):
//  - F(p): the nearest point of the occupied set (closed occupied squares and the outside of the
//    map) to free pixel p's centre; ties to the smallest x, then the smallest y (feature_transform.hpp).
//  - A pair of 4-adjacent free pixels p, q with a = F(p), b = F(q) *separates* when
//      1. |a - b| > min_separation (default 1.5: unit steps along a wall and 45-degree staircases,
//         whose nearest points move by 1 or sqrt(2), never separate; a 2-pixel corridor does), and
//      2. a and b are not joined by the walls near them: unless |a - b| > prune_length (default 8),
//         the occupied squares that meet the closed box spanned by a and b, grown by one pixel, must
//         not connect a's square to b's square (8-connected, inside the grown box). This drops the
//         spurs of pixel staircases (a step's two corners are joined by the step), of bumps, of room
//         corners (the two walls meet in the corner) and the tips of acute wedges, and keeps every
//         passage: the two sides of an open corridor are not joined across it.
//  - Of a separating pair, the pixel nearer the bisector of a and b is on the diagram (both on a tie):
//    p when |p-b|^2 - |p-a|^2 <= |q-a|^2 - |q-b|^2.
// A pixel is on the diagram when one of its (up to four) pairs puts it there. The rule reads only
// F of the pair and the occupancy inside a box of side <= prune_length, so a pixel's membership is a
// function of its neighbourhood: rows can be split over threads, and an update only needs the pixels
// whose nearest points or nearby walls changed.
#pragma once

#include "dvoronoi/gvd/feature_transform.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace dvoronoi::gvd {

struct MedialOptions {
    double min_separation = 1.5;  ///< pixels: nearest points of a pair must be farther apart than this
    double prune_length = 8.0;    ///< pixels: pairs whose nearest points are at most this far apart and joined by walls are dropped
    int workers = 1;
};

inline void check_medial_options(const MedialOptions& o) {
    // at most 32768: no two points of a map (sides <= 16383) lie farther apart, and 4 s^2 stays an integer
    if (!(o.min_separation >= 1.0 && o.min_separation <= 32768.0))
        throw InputError("min_separation must be a number in [1, 32768] (pixels)");
    if (!std::isfinite(o.prune_length) || o.prune_length < 0.0 || o.prune_length > 256.0)
        throw InputError("prune_length must be a finite number in [0, 256] (pixels)");
    if (o.workers < 1) throw InputError("workers must be at least 1, got " + std::to_string(o.workers));
}

namespace detail {

/// Are the occupied squares containing a and b joined by occupied squares that meet the closed box
/// spanned by a and b grown by one pixel (8-connected)? Squares outside the map count as occupied.
/// a, b in doubled units. One BoxJoin answers for one state of the map: it remembers answers.
class BoxJoin {
public:
    BoxJoin() = default;
    /// With the map's bits (kept by MedialDiagram), box rows are read a word at a time.
    explicit BoxJoin(const OccupancyBits* bits) : bits_(bits) {}

    bool operator()(const OccupancyGrid& g, std::int32_t ax, std::int32_t ay, std::int32_t bx, std::int32_t by) {
        // Along a spur or a rough wall, neighbouring pairs ask about the same two nearest points
        // (three calls in four on a cave map), so answers are kept in a direct-mapped table. Its
        // 4096 slots (36 KB, in L2) keep 96 % of a cave map's answers; 256 slots kept 74 %.
        // The question is symmetric; nearest points lie in [0, 2 cols] x [0, 2 rows] (sides <= 16383),
        // so each coordinate fits 16 bits of the key.
        auto point_key = [](std::int32_t x, std::int32_t y) {
            return std::uint64_t{static_cast<std::uint16_t>(x)} << 16 | static_cast<std::uint16_t>(y);
        };
        std::uint64_t ka = point_key(ax, ay), kb = point_key(bx, by);
        if (ka > kb) std::swap(ka, kb);
        const std::uint64_t key = (ka << 32 | kb) + 1;  // 0 marks an empty slot
        const std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - kMemoBits));
        if (memo_key_[slot] == key) return memo_joined_[slot] != 0;
        const bool joined = search(g, ax, ay, bx, by);
        memo_key_[slot] = key;
        memo_joined_[slot] = joined ? 1 : 0;
        return joined;
    }

private:
    static constexpr int kMemoBits = 12;

    bool search(const OccupancyGrid& g, std::int32_t ax, std::int32_t ay, std::int32_t bx, std::int32_t by) {
        // the box spanned by a and b, grown by one pixel (two doubled units) on every side
        const std::int32_t xlo = std::min(ax, bx) - 2, xhi = std::max(ax, bx) + 2;
        const std::int32_t ylo = std::min(ay, by) - 2, yhi = std::max(ay, by) + 2;
        // square column c covers [2c, 2c+2]; it meets [xlo, xhi] when 2c <= xhi and 2c + 2 >= xlo
        c0_ = std::max<std::int32_t>(-1, ceil_half(xlo - 2));
        c1_ = std::min<std::int32_t>(g.cols, xhi >> 1);
        j0_ = std::max<std::int32_t>(-1, ceil_half(ylo - 2));  // j: square row counted from the bottom
        j1_ = std::min<std::int32_t>(g.rows, yhi >> 1);
        // Most calls come from spurs whose two points lie on one square or on touching squares.
        std::array<std::int32_t, 8> sa{}, sb{};
        const int na = squares_at(g, ax, ay, sa), nb = squares_at(g, bx, by, sb);
        for (int i = 0; i < na; i += 2)
            for (int k = 0; k < nb; k += 2)
                if (std::abs(sa[i] - sb[k]) <= 1 && std::abs(sa[i + 1] - sb[k + 1]) <= 1) return true;
        const std::int32_t nw = c1_ - c0_ + 1, nh = j1_ - j0_ + 1;
        if (nw > 64) return flood_fill(g, sa, na, sb, nb);
        // Bit-parallel flood fill: one 64-bit word per square row of the box, grown through the 3 x 3
        // neighbourhood and masked by the occupied squares until it stops growing.
        if (occ_.size() < static_cast<std::size_t>(nh)) { occ_.resize(static_cast<std::size_t>(nh)); reach_.resize(static_cast<std::size_t>(nh)); }
        std::fill(reach_.begin(), reach_.begin() + nh, std::uint64_t{0});
        for (std::int32_t j = j0_; j <= j1_; ++j) {
            if (bits_) {
                occ_[static_cast<std::size_t>(j - j0_)] = bits_->row(j, c0_, nw);
                continue;
            }
            const std::int32_t r = g.rows - 1 - j;
            std::uint64_t bits = 0;
            if (r < 0 || r >= g.rows) {
                bits = nw == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << nw) - 1);
            } else {
                const std::uint8_t* row = &g.occupied[g.at(r, 0)];
                for (std::int32_t c = c0_; c <= c1_; ++c)
                    if (c < 0 || c >= g.cols || row[c]) bits |= std::uint64_t{1} << (c - c0_);
            }
            occ_[static_cast<std::size_t>(j - j0_)] = bits;
        }
        for (int i = 0; i < na; i += 2) reach_[static_cast<std::size_t>(sa[i + 1] - j0_)] |= std::uint64_t{1} << (sa[i] - c0_);
        auto reached = [&] {
            for (int k = 0; k < nb; k += 2)
                if (reach_[static_cast<std::size_t>(sb[k + 1] - j0_)] >> (sb[k] - c0_) & 1) return true;
            return false;
        };
        for (bool grew = true; grew;) {
            grew = false;
            for (int pass = 0; pass < 2; ++pass)  // downward, then upward: a path is found in few rounds
                for (std::int32_t t = 0; t < nh; ++t) {
                    const std::size_t j = static_cast<std::size_t>(pass == 0 ? t : nh - 1 - t);
                    std::uint64_t x = reach_[j];
                    if (j > 0) x |= reach_[j - 1];
                    if (j + 1 < static_cast<std::size_t>(nh)) x |= reach_[j + 1];
                    x = (x | (x << 1) | (x >> 1)) & occ_[j];
                    // along the row: spread through runs of occupied squares
                    for (std::uint64_t y = x; (y = (x | (x << 1) | (x >> 1)) & occ_[j]) != x;) x = y;
                    if ((x & ~reach_[j]) != 0) {
                        reach_[j] |= x;
                        grew = true;
                    }
                }
            if (reached()) return true;  // most joins are found in the first round
        }
        return false;
    }

    static std::int32_t ceil_half(std::int32_t v) { return v >= 0 ? (v + 1) / 2 : -((-v) / 2); }

    /// The occupied squares (c, j pairs, flattened) whose closed extent holds the point (x, y).
    int squares_at(const OccupancyGrid& g, std::int32_t x, std::int32_t y, std::array<std::int32_t, 8>& out) const {
        const SquaresHolding h(x, y);
        const std::int32_t cs[2] = {h.c0, h.c1}, js[2] = {h.j0, h.j1};
        int n = 0;
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                if ((a == 1 && cs[1] == cs[0]) || (b == 1 && js[1] == js[0])) continue;
                const std::int32_t c = cs[a], j = js[b];
                if (c < c0_ || c > c1_ || j < j0_ || j > j1_) continue;
                // the bits when the diagram keeps them: the bytes of a box far away are out of cache
                if (!(bits_ ? bits_->test(j, c) : g.blocked(g.rows - 1 - j, c))) continue;
                out[static_cast<std::size_t>(n++)] = c;
                out[static_cast<std::size_t>(n++)] = j;
            }
        return n;
    }

    /// The same search square by square, for boxes wider than 64 squares (prune_length > ~30).
    bool flood_fill(const OccupancyGrid& g, const std::array<std::int32_t, 8>& sa, int na,
                    const std::array<std::int32_t, 8>& sb, int nb) {
        const std::int32_t nw = c1_ - c0_ + 1, nh = j1_ - j0_ + 1;
        auto idx = [&](std::int32_t c, std::int32_t j) { return static_cast<std::size_t>((j - j0_) * nw + (c - c0_)); };
        cell_.assign(static_cast<std::size_t>(nw * nh), 0);  // 0 free, 1 occupied, 2 reached
        for (std::int32_t j = j0_; j <= j1_; ++j)
            for (std::int32_t c = c0_; c <= c1_; ++c) cell_[idx(c, j)] = g.blocked(g.rows - 1 - j, c) ? 1 : 0;
        stack_.clear();
        for (int i = 0; i < na; i += 2) {
            cell_[idx(sa[i], sa[i + 1])] = 2;
            stack_.push_back({sa[i], sa[i + 1]});
        }
        while (!stack_.empty()) {
            const auto [c, j] = stack_.back();
            stack_.pop_back();
            for (std::int32_t dj = -1; dj <= 1; ++dj)
                for (std::int32_t dc = -1; dc <= 1; ++dc) {
                    const std::int32_t cc = c + dc, jj = j + dj;
                    if (cc < c0_ || cc > c1_ || jj < j0_ || jj > j1_) continue;
                    auto& v = cell_[idx(cc, jj)];
                    if (v == 1) { v = 2; stack_.push_back({cc, jj}); }
                }
        }
        for (int k = 0; k < nb; k += 2)
            if (cell_[idx(sb[k], sb[k + 1])] == 2) return true;
        return false;
    }

    const OccupancyBits* bits_ = nullptr;
    std::array<std::uint64_t, std::size_t{1} << kMemoBits> memo_key_{};
    std::array<std::uint8_t, std::size_t{1} << kMemoBits> memo_joined_{};
    std::int32_t c0_ = 0, c1_ = 0, j0_ = 0, j1_ = 0;
    std::vector<std::uint64_t> occ_, reach_;
    std::vector<std::uint8_t> cell_;
    std::vector<std::array<std::int32_t, 2>> stack_;
};

/// Bit c of out (64-bit words) = |a_c - b_c|^2 > sep2, for n pixels given by their nearest points'
/// x and y; bits from n up to the word's end are 0. Differences of nearest points fit in 16 bits and
/// their squared norms in 31 (sides <= 16383), so SSE2's pmaddwd computes dx^2 + dy^2 for eight
/// pixels at once. Bits, not bytes: the few separated pairs are then found without a branch a pixel.
inline void separated(const std::int16_t* ax, const std::int16_t* ay, const std::int16_t* bx, const std::int16_t* by,
                      std::int32_t n, std::int32_t sep2, std::uint64_t* out) {
    std::fill(out, out + (n + 63) / 64, std::uint64_t{0});
    std::int32_t c = 0;
#if defined(__SSE2__)
    const __m128i limit = _mm_set1_epi32(sep2);
    for (; c + 8 <= n; c += 8) {
        auto load = [c](const std::int16_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + c)); };
        const __m128i dx = _mm_sub_epi16(load(ax), load(bx)), dy = _mm_sub_epi16(load(ay), load(by));
        const __m128i lo = _mm_unpacklo_epi16(dx, dy), hi = _mm_unpackhi_epi16(dx, dy);
        const __m128i d2lo = _mm_madd_epi16(lo, lo), d2hi = _mm_madd_epi16(hi, hi);  // dx^2 + dy^2, int32
        const __m128i flags = _mm_packs_epi32(_mm_cmpgt_epi32(d2lo, limit), _mm_cmpgt_epi32(d2hi, limit));
        const auto bits = static_cast<std::uint64_t>(_mm_movemask_epi8(_mm_packs_epi16(flags, flags)) & 0xff);
        out[c / 64] |= bits << (c % 64);  // c % 8 == 0: the eight bits lie in one word
    }
#endif
    for (; c < n; ++c) {
        const std::int32_t dx = ax[c] - bx[c], dy = ay[c] - by[c];
        out[c / 64] |= static_cast<std::uint64_t>(dx * dx + dy * dy > sep2) << (c % 64);
    }
}

/// Squared thresholds in doubled units.
struct PairRule {
    std::int64_t sep2, prune2;
    explicit PairRule(const MedialOptions& o)
        : sep2(static_cast<std::int64_t>(std::floor(4.0 * o.min_separation * o.min_separation))),
          prune2(static_cast<std::int64_t>(std::floor(4.0 * o.prune_length * o.prune_length))) {}
};

}  // namespace detail

/// The medial diagram of an occupancy grid with its nearest-point transform.
struct MedialDiagram {
    OccupancyGrid grid;
    FeatureMap features;
    PixelMask mask;                  ///< the diagram's pixels (bits)
    /// Pixels with a pair that the box rule judges (separated, nearest points at most prune_length
    /// apart): the only pixels whose membership a change of occupancy can alter without changing
    /// their nearest points or their neighbours' (an update rechecks these near the change).
    PixelMask boxed;
    MedialOptions options;
    /// Per block of kBlock x kBlock pixels (row-major): an upper bound of its pixels' squared
    /// clearance (doubled units), kept by updates; empty until an update needs it.
    std::vector<std::int32_t> block_sq;
    static constexpr std::int32_t kBlock = 32;
    OccupancyBits bits;              ///< the occupancy as bits, for the box rule

    /// Clearance of pixel (r, c)'s centre in map units (0 for occupied pixels).
    double clearance(std::int32_t r, std::int32_t c) const {
        return 0.5 * std::sqrt(static_cast<double>(features.sq(r, c))) * grid.resolution;
    }
    std::size_t count() const { return mask.count(); }
};

namespace detail {

/// Marks rows [r0, r1) of `m.mask`, pair by pair: a pair is judged once and marks one or both of
/// its pixels (the rule seen from both ends). Most pairs fail the separation test: it runs first over
/// whole rows (branch-free, vectorised), and only separated pairs get the full rule. The vertical
/// pairs across the band's edges are judged by both bands, each marking its own row only, so threads
/// never write the same row. An update re-marks a few row segments (mark_segment) the same way.
class RowMarker {
public:
    explicit RowMarker(MedialDiagram& m)
        : m_(m), rule_(m.options), join_(&m.bits), flag_(static_cast<std::size_t>(m.grid.cols) / 64 + 1, 0),
          sep2_(static_cast<std::int32_t>(std::min<std::int64_t>(rule_.sep2, INT32_MAX))) {}

    /// Marks rows [r0, r1): reads the nearest points of rows r0-1 .. r1.
    void mark(std::int32_t r0, std::int32_t r1) {
        const std::int32_t W = m_.grid.cols;
        m_.mask.clear_rows(r0, r1);
        m_.boxed.clear_rows(r0, r1);
        for (std::int32_t r = std::max(0, r0 - 1); r < r1; ++r) {
            if (r + 1 < m_.grid.rows)  // vertical pairs (r, c), (r + 1, c)
                judge_flagged(r, r + 1, 0, W, [&](std::int32_t c, int v) {
                    if (r >= r0) put(r, c, v & (kMarkP | kBoxed));
                    if (r + 1 < r1) put(r + 1, c, (v & kMarkQ ? kMarkP : 0) | (v & kBoxed));
                });
            if (r < r0) continue;
            judge_flagged(r, r, 0, W - 1, [&](std::int32_t c, int v) {  // horizontal pairs (r, c), (r, c + 1)
                put(r, c, v & (kMarkP | kBoxed));
                put(r, c + 1, (v & kMarkQ ? kMarkP : 0) | (v & kBoxed));
            });
        }
    }

    /// Recomputes the pixels (r, a .. b) of `m.mask` (and `m.boxed`) from every pair they belong to.
    void mark_segment(std::int32_t r, std::int32_t a, std::int32_t b) {
        const std::int32_t H = m_.grid.rows, W = m_.grid.cols;
        m_.mask.clear(r, a, b);
        m_.boxed.clear(r, a, b);
        auto in = [&](std::int32_t c) { return c >= a && c <= b; };
        if (r > 0)
            judge_flagged(r - 1, r, a, b + 1, [&](std::int32_t c, int v) { put(r, c, (v & kMarkQ ? kMarkP : 0) | (v & kBoxed)); });
        if (r + 1 < H)
            judge_flagged(r, r + 1, a, b + 1, [&](std::int32_t c, int v) { put(r, c, v & (kMarkP | kBoxed)); });
        judge_flagged(r, r, std::max(0, a - 1), std::min(W - 1, b + 1), [&](std::int32_t c, int v) {
            if (in(c)) put(r, c, v & (kMarkP | kBoxed));
            if (in(c + 1)) put(r, c + 1, (v & kMarkQ ? kMarkP : 0) | (v & kBoxed));
        });
    }

private:
    // judge's answer: bits of the pair (p, q)
    static constexpr int kMarkP = 1, kMarkQ = 2, kBoxed = 4;

    /// Sets pixel (r, c)'s bits from a pair's answer seen from the pixel (kMarkP: on the diagram).
    void put(std::int32_t r, std::int32_t c, int v) {
        if (v & kMarkP) m_.mask.set(r, c, true);
        if (v & kBoxed) m_.boxed.set(r, c, true);
    }

    /// Runs the separation test over the pairs (r, c), (q, c + (q == r)) for c in [c0, c1) and calls
    /// fn(c, judge(...)) for the separated ones.
    template <class Fn>
    void judge_flagged(std::int32_t r, std::int32_t q, std::int32_t c0, std::int32_t c1, Fn&& fn) {
        if (c1 <= c0) return;
        const FeatureMap& f = m_.features;
        const std::int32_t dc = q == r ? 1 : 0, n = c1 - c0;
        std::uint64_t* flag = flag_.data();
        separated(&f.fx[f.at(r, c0)], &f.fy[f.at(r, c0)], &f.fx[f.at(q, c0 + dc)], &f.fy[f.at(q, c0 + dc)], n, sep2_, flag);
        for (std::int32_t k = 0; k < n; k += 64)
            for (std::uint64_t w = flag[k / 64]; w != 0; w &= w - 1) {
                const std::int32_t d = k + lowest_bit(w);
                const int v = judge(r, c0 + d, q, c0 + d + dc);
                if (v != 0) fn(c0 + d, v);
            }
    }

    /// The pair (p, q) of 4-adjacent pixels: kMarkP marks p, kMarkQ marks q (both on a tie), 0: the
    /// pair does not separate; kBoxed is added when the box rule judged it (whatever its answer). p marks when it is no farther from the bisector of the nearest points a, b
    /// than q (|p-b|^2 - |p-a|^2 <= |q-a|^2 - |q-b|^2). `sep2` is floor(4 s^2): for integers,
    /// |a-b|^2 > 4 s^2 <=> |a-b|^2 > floor(4 s^2).
    int judge(std::int32_t pr, std::int32_t pc, std::int32_t qr, std::int32_t qc) {
        const OccupancyGrid& g = m_.grid;
        const FeatureMap& f = m_.features;
        const std::size_t i = f.at(pr, pc), j = f.at(qr, qc);
        const std::int32_t ax = f.fx[i], ay = f.fy[i], bx = f.fx[j], by = f.fy[j];
        const std::int64_t px = 2 * pc + 1, py = 2 * (g.rows - 1 - pr) + 1, qx = 2 * qc + 1, qy = 2 * (g.rows - 1 - qr) + 1;
        // an occupied pixel is its own nearest point, a free one never is (the occupancy bytes are
        // not read: an update's pairs lie on rows out of cache)
        if ((ax == px && ay == py) || (bx == qx && by == qy)) return 0;
        const std::int64_t dx = ax - bx, dy = ay - by, d2 = dx * dx + dy * dy;
        if (d2 <= rule_.sep2) return 0;
        auto sq = [](std::int64_t x, std::int64_t y, std::int64_t u, std::int64_t v) { return (x - u) * (x - u) + (y - v) * (y - v); };
        const std::int64_t sp = sq(px, py, bx, by) - sq(px, py, ax, ay), sq_ = sq(qx, qy, ax, ay) - sq(qx, qy, bx, by);
        const int boxed = d2 <= rule_.prune2 ? kBoxed : 0;
        if (boxed && join_(g, ax, ay, bx, by)) return boxed;
        return boxed | (sp <= sq_ ? kMarkP : 0) | (sq_ <= sp ? kMarkQ : 0);
    }

    MedialDiagram& m_;
    PairRule rule_;
    BoxJoin join_;
    std::vector<std::uint64_t> flag_;  // separated pairs of a row, as bits
    std::int32_t sep2_;
};

}  // namespace detail

/// The medial diagram of `grid` (copied into the result) with options.workers threads; the same
/// pixels for every worker count.
/// \throws InputError for a bad grid or options.
/// \note O(rows x cols) plus a box search (<= (prune_length + 2)^2) for the few pairs that separate.
inline MedialDiagram medial_diagram(OccupancyGrid grid, const MedialOptions& options = {}) {
    check_grid(grid);
    check_medial_options(options);
    MedialDiagram m;
    // the bits of each band's rows while the feature passes have them in cache (square row j = H-1-r)
    m.bits = OccupancyBits(grid.rows, grid.cols);
    m.features = feature_transform(grid, options.workers, [&m, &grid](std::int32_t r0, std::int32_t r1) {
        m.bits.fill_rows(grid, grid.rows - r1, grid.rows - r0);
    });
    m.grid = std::move(grid);
    m.options = options;
    m.mask = PixelMask(m.grid.rows, m.grid.cols);
    m.boxed = PixelMask(m.grid.rows, m.grid.cols);
    // (Marking each row while pass 2 still has its neighbours in cache was measured: no faster, as
    // the bands' vertical pairs are then judged twice.)
    // Chunks of 64 rows: each chunk judges the vertical pairs above its first row again.
    const int k_rows = std::max(1, std::min(options.workers, m.grid.rows));
    run_chunks(k_rows, m.grid.rows, 64, [&m] { return detail::RowMarker(m); },
               [](detail::RowMarker& marker, std::int32_t r0, std::int32_t r1) { marker.mark(r0, r1); });
    return m;
}

}  // namespace dvoronoi::gvd
