// The exact nearest-point transform of an occupancy grid: for every free pixel, the point of the
// occupied set (closed squares, and everything outside the map) nearest to the pixel's centre, in
// doubled pixel units (occupancy_grid.hpp), so squared distances are exact integers.
//
// Ties: among nearest points, the one with the smallest x, then the smallest y. The rule is part of
// the medial diagram's definition (medial_diagram.hpp), and the brute-force oracle applies it too.
//
// Two separable passes (Meijster, Roerdink & Hesselink 2000, adapted to squares):
//  1. per column: the signed row offset to the nearest occupied pixel of the column (ties: below).
//  2. per row, per free run between occupied pixels: with V(c) = (2|k|-1)^2 the vertical part of
//     column c and 0 for an occupied pixel, the nearest point of column c's square seen from pixel x
//     != c lies on the square's left or right edge, at x = 2c or 2c+2. So each *edge* e between
//     columns e-1 and e carries one parabola (X - 2e)^2 + min(V(e-1), V(e)), the distance from pixel
//     x is min(V(x), min_e (2x+1-2e)^2 + O(e)), and a lower envelope of parabolas answers a whole run
//     in linear time. Edges outside the run cannot win (the run's end edges have offset 0 and are
//     nearer). The envelope is built with exact integer cross-multiplications (no division).
// Both passes run band by band (bands of 32 rows): a band's pass 1 starts from the nearest occupied
// rows above and below it (BandEdges, one read of the map), and its pass 2 reads the band while it is
// still in cache. Pass 1 over whole columns streamed the map twice and the offsets back and forth:
// memory-bound, it did not speed up with a second worker. Bands go to the worker threads as they
// become free; the result is identical for any count.
#pragma once

#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/gvd/occupancy_grid.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace dvoronoi::gvd {

/// Nearest points of every pixel: fx, fy in doubled pixel units (an occupied pixel's own centre).
struct FeatureMap {
    std::int32_t rows = 0, cols = 0;
    // Not zero-filled when sized: the column and row passes write every element, in parallel.
    ::dvoronoi::detail::UninitVector<std::int16_t> vgap;  ///< signed row offset to the nearest occupied pixel of the column (0: occupied)
    ::dvoronoi::detail::UninitVector<std::int16_t> fx, fy;

    std::size_t at(std::int32_t r, std::int32_t c) const {
        return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c);
    }
    /// Squared distance (doubled units, so 4x pixel units) from pixel (r, c)'s centre to its nearest point.
    std::int64_t sq(std::int32_t r, std::int32_t c) const {
        const std::size_t i = at(r, c);
        const std::int64_t dx = fx[i] - (2 * c + 1), dy = fy[i] - (2 * (rows - 1 - r) + 1);
        return dx * dx + dy * dy;
    }
};

namespace detail {

/// Lexicographic order of candidates (squared distance, x, y): the tie rule.
struct Candidate2 {
    std::int64_t sq;
    std::int32_t x, y;
    bool operator<(const Candidate2& o) const {
        if (sq != o.sq) return sq < o.sq;
        if (x != o.x) return x < o.x;
        return y < o.y;
    }
};

/// The nearest point's y (doubled) in column c's square at vertical offset k, from pixel centre Y.
inline std::int32_t feature_y(std::int32_t Y, std::int32_t k) {
    return k > 0 ? Y + 1 - 2 * k : (k < 0 ? Y - 1 - 2 * k : Y);
}

/// Pass 2's lower envelope for one row over the squares of a range of columns [ca, cb] (their
/// vertical nearest squares in this row; columns -1 and cols are the outside, distance 0 in the row).
/// A full row's run uses the run's columns and the occupied ones around it; an update uses only the
/// changed columns, or a window around the pixels it recomputes.
class RowEnvelope {
public:
    /// Builds the envelope of row r over columns [ca, cb] (ca <= cb; -1 <= ca, cb <= cols).
    void build(const OccupancyGrid& g, const FeatureMap& f, std::int32_t r, std::int32_t ca, std::int32_t cb) {
        W_ = g.cols;
        Y_ = 2 * (g.rows - 1 - r) + 1;
        vg_ = &f.vgap[f.at(r, 0)];
        ca_ = ca;
        cb_ = cb;
        // edges ca .. cb+1; edge e lies between columns e-1 and e
        const std::size_t m = static_cast<std::size_t>(cb - ca + 2);
        if (hA_.size() < m) { hA_.resize(m); he_.resize(m); hy_.resize(m); cv_.resize(m); }
        std::int32_t* cv = cv_.data();  // V of columns ca .. cb at index c - ca, computed once
        for (std::int32_t c = ca; c <= cb; ++c) cv[c - ca] = static_cast<std::int32_t>(V(c));
        std::size_t top = 0;
        push_edge(top, ca, cv[0], yv(ca));  // the first edge sees column ca only
        for (std::int32_t e = ca + 1; e <= cb; ++e) {
            const std::int32_t a = cv[e - 1 - ca], b = cv[e - ca];
            if (a == b) continue;  // never the nearest: see flat_edge
            const bool left = a < b;  // the nearer column's square
            push_edge(top, e, left ? a : b, yv(left ? e - 1 : e));
        }
        push_edge(top, cb + 1, cv[cb - ca], yv(cb));  // the last edge sees column cb only
        top_ = top;
        k_ = 0;
        cv_from_ = ca;
    }

    /// build() for a whole free run [s, t] (columns s-1 and t+1 occupied or outside, offset 0 in the
    /// row): no range checks, and each column's V and y computed once for the build and the queries.
    void build_run(const OccupancyGrid& g, const FeatureMap& f, std::int32_t r, std::int32_t s, std::int32_t t) {
        W_ = g.cols;
        Y_ = 2 * (g.rows - 1 - r) + 1;
        vg_ = &f.vgap[f.at(r, 0)];
        ca_ = s - 1;
        cb_ = t + 1;
        const std::size_t m = static_cast<std::size_t>(t - s + 3);  // edges s .. t+1, one spare
        if (hA_.size() < m) { hA_.resize(m); he_.resize(m); hy_.resize(m); cv_.resize(m); }
        std::int32_t* cv = cv_.data();  // V of columns s .. t at index x - s (< 2^31: sides <= 16383)
        const std::int16_t* vg = vg_ + s;
        for (std::int32_t i = 0; i <= t - s; ++i) {
            const std::int32_t k = vg[i], a = k < 0 ? -k : k;
            cv[i] = (2 * a - 1) * (2 * a - 1);
        }
        std::size_t top = 0;
        push_edge(top, s, 0, Y_);  // the occupied (or outside) pixel left of the run, in this row
        for (std::int32_t e = s + 1; e <= t; ++e) {
            const std::int32_t a = cv[e - 1 - s], b = cv[e - s];
            if (a == b) continue;  // never the nearest: see flat_edge
            const bool left = a < b;  // the nearer column's square
            push_edge(top, e, left ? a : b, feature_y(Y_, left ? vg[e - 1 - s] : vg[e - s]));
        }
        push_edge(top, t + 1, 0, Y_);
        top_ = top;
        k_ = 0;
        cv_from_ = s;
    }

    /// After build_run: the nearest points of the run's pixels s .. t into fx[x], fy[x], segment by
    /// segment of the envelope. Edge k+1 beats edge k from the first pixel where its value is strictly
    /// smaller (ties stay with the smaller edge); the values differ by a linear function of X, so that
    /// pixel is found by one division, and the pixels between two such starts take edge k without a
    /// comparison along the envelope. Each pixel's own column (dx = 0) wins ties against edges to its
    /// right only, as in query(). The same answers as walking the envelope pixel by pixel. After
    /// build(), for free pixels s .. t inside [ca, cb], the same answers as query().
    void fill_run(std::int32_t s, std::int32_t t, std::int16_t* fx, std::int16_t* fy) const {
        std::int32_t x = s;
        // the segment holding s: edge k + 1 takes s when its value there is strictly smaller (a
        // product, not first_beaten's division: an update fills a few pixels of a wide envelope)
        const std::int64_t X4 = 4 * (2 * std::int64_t{s} + 1);
        std::size_t k0 = 0;
        while (k0 + 1 < top_ && hA_[k0 + 1] - X4 * he_[k0 + 1] < hA_[k0] - X4 * he_[k0]) ++k0;
        for (std::size_t k = k0; k < top_ && x <= t; ++k) {
            std::int32_t end = t + 1;  // the first pixel that edge k + 1 takes
            if (k + 1 < top_) end = std::min<std::int64_t>(end, first_beaten(k));
            const std::int64_t e2 = 2 * std::int64_t{he_[k]}, off = hA_[k] - e2 * e2;
            const std::int32_t ey = hy_[k];
#if defined(__SSE2__)
            x = fill_eight_at_a_time(x, end, static_cast<std::int32_t>(e2), static_cast<std::int32_t>(off), ey, fx, fy);
#endif
            for (; x < end; ++x) {
                const std::int64_t X = 2 * x + 1, sq = (X - e2) * (X - e2) + off;
                const std::int64_t own = cv_[static_cast<std::size_t>(x - cv_from_)];
                const bool mine = own < sq || (own == sq && e2 > X);
                fx[x] = static_cast<std::int16_t>(mine ? X : e2);
                fy[x] = static_cast<std::int16_t>(mine ? feature_y(Y_, vg_[x]) : ey);
            }
        }
    }

    /// The envelope as segments along the row, for a scan outward from an update's columns: edge k
    /// is the nearest of the envelope's squares for the pixels x with segment_end(k - 1) <= x <
    /// segment_end(k) (fill_run's rule: the edge query() finds too, for pixels outside [ca, cb]).
    std::size_t segments() const { return top_; }
    std::int64_t segment_end(std::size_t k) const {
        return k + 1 < top_ ? first_beaten(k) : std::numeric_limits<std::int64_t>::max();
    }
    /// Edge k's square seen from pixel x.
    Candidate2 on_edge(std::size_t k, std::int32_t x) const {
        const std::int64_t X = 2 * x + 1;
        return {hA_[k] - 4 * X * he_[k] + X * X, 2 * he_[k], hy_[k]};
    }

    /// The nearest candidate of pixel x among the envelope's squares. Fastest when queries come in
    /// ascending x (the minimising edge only moves right), correct in any order: along the envelope
    /// the values at one x fall, then rise, and the first minimiser is the smallest edge (tie rule).
    Candidate2 query(std::int32_t x) {
        const std::int64_t X = 2 * x + 1, X4 = 4 * X;
        std::size_t k = k_;
        std::int64_t best = hA_[k] - X4 * he_[k];
        while (k + 1 < top_) {
            const std::int64_t nxt = hA_[k + 1] - X4 * he_[k + 1];
            if (nxt < best) { best = nxt; ++k; }
            else break;
        }
        while (k > 0) {
            const std::int64_t prv = hA_[k - 1] - X4 * he_[k - 1];
            if (prv <= best) { best = prv; --k; }
            else break;
        }
        k_ = k;
        const std::int64_t e = he_[k];
        Candidate2 c{best + X * X, static_cast<std::int32_t>(2 * e), hy_[k]};
        if (x >= ca_ && x <= cb_) {
            // the pixel's own column (dx = 0) wins ties against edges to its right only
            const std::int64_t own = V(x);
            if (own < c.sq || (own == c.sq && 2 * e > X)) c = {own, static_cast<std::int32_t>(X), yv(x)};
        }
        return c;
    }
private:
#if defined(__SSE2__)
    /// fill_run's loop over pixels [x, end) that edge e2 / 2 (offset off, nearest y ey) takes unless
    /// their own column is nearer, eight pixels at a time; returns where it stopped (fewer than eight
    /// left). Everything fits 16-bit lanes but the squares: X, e2 <= 2 cols <= 32766, and the squares
    /// (X - e2)^2 and V are below 2^30 (sides <= 16383), so their sum fits 32 bits; pmaddwd squares.
    std::int32_t fill_eight_at_a_time(std::int32_t x, std::int32_t end, std::int32_t e2, std::int32_t off, std::int32_t ey,
                                      std::int16_t* fx, std::int16_t* fy) const {
        const __m128i zero = _mm_setzero_si128(), ramp = _mm_setr_epi16(1, 3, 5, 7, 9, 11, 13, 15);
        const __m128i e2v = _mm_set1_epi16(static_cast<short>(e2)), offv = _mm_set1_epi32(off);
        const __m128i eyv = _mm_set1_epi16(static_cast<short>(ey)), Yv = _mm_set1_epi16(static_cast<short>(Y_));
        for (; x + 8 <= end; x += 8) {
            const __m128i X = _mm_add_epi16(_mm_set1_epi16(static_cast<short>(2 * x)), ramp);
            const __m128i d = _mm_sub_epi16(X, e2v);
            const __m128i dlo = _mm_unpacklo_epi16(d, zero), dhi = _mm_unpackhi_epi16(d, zero);
            const __m128i sqlo = _mm_add_epi32(_mm_madd_epi16(dlo, dlo), offv), sqhi = _mm_add_epi32(_mm_madd_epi16(dhi, dhi), offv);
            const __m128i* own = reinterpret_cast<const __m128i*>(&cv_[static_cast<std::size_t>(x - cv_from_)]);
            const __m128i ownlo = _mm_loadu_si128(own), ownhi = _mm_loadu_si128(own + 1);
            // the own column wins when nearer, or as near with the edge to the right (e2 > X)
            const __m128i right = _mm_cmpgt_epi16(e2v, X);
            const __m128i minelo = _mm_or_si128(_mm_cmplt_epi32(ownlo, sqlo),
                                                _mm_and_si128(_mm_cmpeq_epi32(ownlo, sqlo), _mm_unpacklo_epi16(right, right)));
            const __m128i minehi = _mm_or_si128(_mm_cmplt_epi32(ownhi, sqhi),
                                                _mm_and_si128(_mm_cmpeq_epi32(ownhi, sqhi), _mm_unpackhi_epi16(right, right)));
            const __m128i mine = _mm_packs_epi32(minelo, minehi);
            // feature_y of the own column: Y - 2k + sign(k)
            const __m128i k = _mm_loadu_si128(reinterpret_cast<const __m128i*>(vg_ + x));
            const __m128i sign = _mm_sub_epi16(_mm_cmpgt_epi16(zero, k), _mm_cmpgt_epi16(k, zero));
            const __m128i own_y = _mm_add_epi16(_mm_sub_epi16(Yv, _mm_add_epi16(k, k)), sign);
            auto pick = [&mine](__m128i a, __m128i b) { return _mm_or_si128(_mm_and_si128(mine, a), _mm_andnot_si128(mine, b)); };
            _mm_storeu_si128(reinterpret_cast<__m128i*>(fx + x), pick(X, e2v));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(fy + x), pick(own_y, eyv));
        }
        return x;
    }
#endif

    /// The first pixel x where edge k + 1 is strictly nearer than edge k: with A = off + 4e^2 the
    /// values at X = 2x + 1 are A - 4Xe (+ X^2 for both), so X (e_{k+1} - e_k) 4 > A_{k+1} - A_k;
    /// X is the smallest odd integer above that quotient.
    std::int64_t first_beaten(std::size_t k) const {
        const std::int64_t num = hA_[k + 1] - hA_[k], den = 4 * (std::int64_t{he_[k + 1]} - he_[k]);  // den > 0
        const std::int64_t q = num / den - ((num % den != 0 && num < 0) ? 1 : 0);  // floor(num / den)
        const std::int64_t X = (q + 1) % 2 != 0 ? q + 1 : q + 2;  // the smallest odd integer > num / den
        return (X - 1) / 2;
    }

    // flat_edge: an edge between two columns with the same V is never the nearest candidate, so it is
    // left out of the envelope (in a room with a flat floor, most edges). With V(e-1) = V(e) = C its
    // offset is C; at pixels e-1 and e the own columns give C < C + 1; left of e-1 edge e-1 is nearer
    // with an offset <= C, right of e edge e+1 likewise: strictly smaller everywhere, ties included.

    /// Adds edge e's parabola (X - 2e)^2 + off to the lower envelope (edges come in ascending order).
    /// Edge q is dropped when the new edge u overtakes it no later than q overtakes its predecessor p
    /// (crossings at X = (A_q - A_p) / (4 (e_q - e_p)), A = off + 4e^2): exact integer
    /// cross-multiplication, no division.
    void push_edge(std::size_t& top, std::int32_t e, std::int64_t off, std::int32_t y) {
        std::int64_t* hA = hA_.data();
        std::int32_t* he = he_.data();
        const std::int64_t Au = off + 4 * std::int64_t{e} * e;
        while (top >= 2) {
            const std::int64_t Aq = hA[top - 1], Ap = hA[top - 2];
            const std::int64_t eq = he[top - 1], ep = he[top - 2];
            if ((Au - Aq) * (eq - ep) <= (Aq - Ap) * (e - eq)) --top;
            else break;
        }
        hA[top] = Au;
        he[top] = e;
        hy_[top] = y;
        ++top;
    }

    std::int64_t V(std::int32_t c) const {
        if (c < 0 || c >= W_) return 0;
        const std::int64_t k = std::abs(static_cast<std::int32_t>(vg_[c]));
        return k == 0 ? 0 : (2 * k - 1) * (2 * k - 1);
    }
    std::int32_t yv(std::int32_t c) const { return c < 0 || c >= W_ ? Y_ : feature_y(Y_, vg_[c]); }

    std::int32_t W_ = 0, Y_ = 0, ca_ = 0, cb_ = 0;
    const std::int16_t* vg_ = nullptr;
    std::vector<std::int64_t> hA_;  // envelope: A = offset + 4e^2, edge e, nearest point's y
    std::vector<std::int32_t> he_, hy_;
    std::vector<std::int32_t> cv_;  // the columns' V (build: from ca, build_run: from s)
    std::size_t top_ = 0, k_ = 0;
    std::int32_t cv_from_ = 0;  // the column whose V is cv_[0]
};

/// The first occupied (nonzero) byte of o[c .. W), or W. Sixteen bytes at a time with SSE2 (memchr
/// finds one value only, and any nonzero byte is occupied).
inline std::int32_t next_occupied(const std::uint8_t* o, std::int32_t c, std::int32_t W) {
#if defined(__SSE2__)
    for (; c + 16 <= W; c += 16) {
        const auto zero = static_cast<unsigned>(
            _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(o + c)), _mm_setzero_si128())));
        if (zero != 0xffffu) return c + lowest_bit(~zero & 0xffffu);
    }
#endif
    while (c < W && o[c] == 0) ++c;
    return c;
}

/// Pass 2 over row r: each free run [s, t] against the squares of columns s-1 .. t+1 (the
/// run's ends are occupied or outside: squares beyond them are farther than the ends' edges).
inline void row_pass(const OccupancyGrid& g, FeatureMap& f, std::int32_t r, RowEnvelope& env) {
    const std::int32_t W = g.cols;
    const std::uint8_t* o = &g.occupied[g.at(r, 0)];
    std::int16_t* fx = &f.fx[f.at(r, 0)];
    std::int16_t* fy = &f.fy[f.at(r, 0)];
    const std::int32_t Y = 2 * (g.rows - 1 - r) + 1;
    std::int32_t c = 0;
    while (c < W) {
        if (o[c]) {  // occupied pixels are their own nearest points (distance 0), a run at a time
            std::int32_t e = c + 1;
            for (std::uint64_t w; e + 8 <= W; e += 8) {  // eight occupied bytes (1s, as maps hold) at a time
                std::memcpy(&w, o + e, 8);
                if (w != 0x0101010101010101ull) break;
            }
            while (e < W && o[e]) ++e;
            for (std::int32_t x = c; x < e; ++x) {  // vectorised: a ramp and a constant
                fx[x] = static_cast<std::int16_t>(2 * x + 1);
                fy[x] = static_cast<std::int16_t>(Y);
            }
            c = e;
            continue;
        }
        const std::int32_t t = next_occupied(o, c, W) - 1;  // the run ends before the next occupied pixel
        env.build_run(g, f, r, c, t);
        env.fill_run(c, t, fx, fy);
        c = t + 1;
    }
}

/// Pass 1's state at the edges of bands of kRows rows: for band b and column c, the last occupied row
/// above the band (-1: the frame) and the first occupied row below it (rows: the frame).
struct BandEdges {
    static constexpr std::int32_t kRows = 32;  // a band's rows and their offsets stay in L2; < 255 (bytes below)
    std::int32_t bands = 0, cols = 0;
    std::vector<std::int16_t> above, below;  // bands x cols

    BandEdges(const OccupancyGrid& g, int workers) : bands((g.rows + kRows - 1) / kRows), cols(g.cols) {
        const std::size_t W = static_cast<std::size_t>(cols), n = static_cast<std::size_t>(bands) * W;
        // each band's own last and first occupied rows, as 1 + the row's index in the band (0: none
        // for last, 255: none for first): bytes, so sixteen columns go in one vector operation
        std::vector<std::uint8_t> last(n, 0), first(n, 255);
        run_chunks(workers, bands, 4, [] { return 0; }, [&](int&, std::int32_t b0, std::int32_t b1) {
            for (std::int32_t b = b0; b < b1; ++b) {
                std::uint8_t* lb = &last[static_cast<std::size_t>(b) * W];
                std::uint8_t* fb = &first[static_cast<std::size_t>(b) * W];
                for (std::int32_t r = b * kRows; r < std::min(g.rows, (b + 1) * kRows); ++r)
                    note_row(&g.occupied[g.at(r, 0)], static_cast<std::uint8_t>(r - b * kRows + 1), W, lb, fb);
            }
        });
        // then, per band, the nearest of the earlier bands' last rows and of the later bands' first rows
        above.resize(n);
        below.resize(n);
        std::vector<std::int16_t> run(W, -1);
        for (std::int32_t b = 0; b < bands; ++b) {
            const std::size_t at = static_cast<std::size_t>(b) * W;
            const auto r0 = static_cast<std::int16_t>(b * kRows - 1);
            for (std::size_t k = 0; k < W; ++k) {
                above[at + k] = run[k];
                run[k] = last[at + k] != 0 ? static_cast<std::int16_t>(r0 + last[at + k]) : run[k];
            }
        }
        std::fill(run.begin(), run.end(), static_cast<std::int16_t>(g.rows));
        for (std::int32_t b = bands - 1; b >= 0; --b) {
            const std::size_t at = static_cast<std::size_t>(b) * W;
            const auto r0 = static_cast<std::int16_t>(b * kRows - 1);
            for (std::size_t k = 0; k < W; ++k) {
                below[at + k] = run[k];
                run[k] = first[at + k] != 255 ? static_cast<std::int16_t>(r0 + first[at + k]) : run[k];
            }
        }
    }

private:
    /// Row `idx` (1-based in its band) of a band: into last / first where its pixels are occupied.
    static void note_row(const std::uint8_t* o, std::uint8_t idx, std::size_t n, std::uint8_t* last, std::uint8_t* first) {
        std::size_t k = 0;
#if defined(__SSE2__)
        // sixteen columns at a time (GCC leaves the byte loop scalar: byte pointers may alias anything)
        const __m128i zero = _mm_setzero_si128(), at = _mm_set1_epi8(static_cast<char>(idx));
        for (; k + 16 <= n; k += 16) {
            const __m128i free = _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(o + k)), zero);
            __m128i* l = reinterpret_cast<__m128i*>(last + k);
            __m128i* f = reinterpret_cast<__m128i*>(first + k);
            _mm_storeu_si128(l, _mm_max_epu8(_mm_loadu_si128(l), _mm_andnot_si128(free, at)));  // occupied: idx, else 0
            _mm_storeu_si128(f, _mm_min_epu8(_mm_loadu_si128(f), _mm_or_si128(free, at)));      // occupied: idx, else 255
        }
#endif
        for (; k < n; ++k)
            if (o[k] != 0) {
                last[k] = std::max(last[k], idx);
                first[k] = std::min(first[k], idx);
            }
    }
};

/// Pass 1 over the rows [r0, r1) of band b: two sweeps, started from the band's edges.
inline void band_column_pass(const OccupancyGrid& g, FeatureMap& f, const BandEdges& e, std::int32_t b,
                             std::int32_t r0, std::int32_t r1, std::vector<std::int16_t>& run) {
    const std::size_t W = static_cast<std::size_t>(g.cols);
    const std::int16_t* above = &e.above[static_cast<std::size_t>(b) * W];
    const std::int16_t* below = &e.below[static_cast<std::size_t>(b) * W];
    run.resize(W);
    // top to bottom: rows since the nearest occupied pixel above (in row r0 - 1: r0 - 1 - above)
    for (std::size_t k = 0; k < W; ++k) run[k] = static_cast<std::int16_t>(r0 - 1 - above[k]);
    for (std::int32_t r = r0; r < r1; ++r) {
        const std::uint8_t* o = &g.occupied[g.at(r, 0)];
        std::int16_t* v = &f.vgap[f.at(r, 0)];
        for (std::size_t k = 0; k < W; ++k) {
            run[k] = o[k] ? std::int16_t(0) : static_cast<std::int16_t>(run[k] + 1);
            v[k] = run[k];
        }
    }
    // bottom to top: rows to the nearest occupied pixel below; keep the nearer side (ties: below)
    for (std::size_t k = 0; k < W; ++k) run[k] = static_cast<std::int16_t>(below[k] - r1);
    for (std::int32_t r = r1 - 1; r >= r0; --r) {
        const std::uint8_t* o = &g.occupied[g.at(r, 0)];
        std::int16_t* v = &f.vgap[f.at(r, 0)];
        for (std::size_t k = 0; k < W; ++k) {
            run[k] = o[k] ? std::int16_t(0) : static_cast<std::int16_t>(run[k] + 1);
            const std::int16_t up = v[k];
            v[k] = run[k] <= up ? run[k] : static_cast<std::int16_t>(-up);
        }
    }
}

/// Both passes over the rows [r0, r1) of one band (r0 its first row): pass 1 leaves the band's
/// offsets in cache for pass 2.
struct BandWorker {
    RowEnvelope env;
    std::vector<std::int16_t> run;
    void operator()(const OccupancyGrid& g, FeatureMap& f, const BandEdges& e, std::int32_t r0, std::int32_t r1) {
        const std::int32_t b = r0 / BandEdges::kRows;
        band_column_pass(g, f, e, b, r0, r1, run);
        for (std::int32_t r = r0; r < r1; ++r) row_pass(g, f, r, env);
    }
};

}  // namespace detail

/// A map of g's size whose values the passes are still to write: not filled (UninitVector; a serial
/// fill would cap the passes' speed-up), its pages faulted in by the passes that write them, as huge
/// pages where the system gives them.
inline FeatureMap feature_map_for(const OccupancyGrid& g) {
    FeatureMap f;
    f.rows = g.rows;
    f.cols = g.cols;
    f.vgap.resize(g.size());
    f.fx.resize(g.size());
    f.fy.resize(g.size());
    // Fresh memory for a large map is 6 bytes a pixel of page faults (6,500 4 KB faults at 2048^2,
    // most of a build's time on a VM); 2 MB pages take a few hundred.
    for (const void* p : {static_cast<const void*>(f.vgap.data()), static_cast<const void*>(f.fx.data()),
                          static_cast<const void*>(f.fy.data())})
        ::dvoronoi::detail::advise_huge_pages(p, g.size() * sizeof(std::int16_t));
    return f;
}

/// The nearest-point transform of `g` with `workers` threads (same result for any count); after each
/// band's passes, its thread calls after_band(r0, r1) for the band's rows [r0, r1) (while they are in
/// cache).
/// \throws InputError for a grid check_grid rejects.
/// \note O(rows x cols); 6 bytes per pixel.
template <class AfterBand>
FeatureMap feature_transform(const OccupancyGrid& g, int workers, AfterBand&& after_band) {
    check_grid(g);
    FeatureMap f = feature_map_for(g);
    const int k = std::max(1, std::min(workers, (g.rows + detail::BandEdges::kRows - 1) / detail::BandEdges::kRows));
    const detail::BandEdges edges(g, k);
    run_chunks(k, g.rows, detail::BandEdges::kRows, [] { return detail::BandWorker(); },
               [&](detail::BandWorker& w, std::int32_t r0, std::int32_t r1) {
                   w(g, f, edges, r0, r1);
                   after_band(r0, r1);
               });
    return f;
}

/// The nearest-point transform of `g` with `workers` threads (same result for any count).
inline FeatureMap feature_transform(const OccupancyGrid& g, int workers = 1) {
    return feature_transform(g, workers, [](std::int32_t, std::int32_t) {});
}

}  // namespace dvoronoi::gvd
