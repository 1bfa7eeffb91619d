// Occupancy grids (SPEC "Grid diagram on occupancy grids"): an H x W array of occupied / free pixels,
// row 0 at the top as in the image, with the map's resolution (map units per pixel) and origin (the
// lower-left corner of pixel (H-1, 0), as ROS map_server writes it).
//
// Pixel (r, c) covers [c, c+1] x [H-1-r, H-r] in pixel units. Occupied pixels are closed squares;
// everything outside the map counts as occupied (a map's edge is a wall: what lies beyond is unknown).
//
// Exact integer geometry: the diagram code works in *doubled* pixel units, where every pixel centre,
// square corner and nearest point of an occupied square has integer coordinates: pixel (r, c) has its
// centre at (2c+1, 2(H-1-r)+1) and covers [2c, 2c+2] x [2(H-1-r), 2(H-r)]. Squared distances are then
// exact integers (4 x the squared distance in pixel units).
#pragma once

#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/core/types.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <string>
#include <utility>
#include <vector>

namespace dvoronoi::gvd {

/// The largest map side: doubled coordinates must fit in 16 bits (features are stored as int16).
inline constexpr std::int32_t kMaxMapSide = 16383;

struct OccupancyGrid {
    std::int32_t rows = 0, cols = 0;
    /// rows x cols, row-major, row 0 at the top; nonzero = occupied (updates write 1). UninitVector: a large map's bytes start
    /// on a 2 MB boundary for huge pages, and a copy into it needs no zero-fill first.
    ::dvoronoi::detail::UninitVector<std::uint8_t> occupied;
    double resolution = 1.0;             ///< map units per pixel
    Vec2 origin = Vec2(0.0, 0.0);        ///< map coordinates of the lower-left corner of pixel (rows-1, 0)

    OccupancyGrid() = default;
    OccupancyGrid(std::int32_t h, std::int32_t w, double res = 1.0, Vec2 org = Vec2(0.0, 0.0))
        : rows(h), cols(w), occupied(static_cast<std::size_t>(h) * static_cast<std::size_t>(w), 0),
          resolution(res), origin(org) {}

    std::size_t size() const { return occupied.size(); }
    std::size_t at(std::int32_t r, std::int32_t c) const {
        return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c);
    }
    bool occ(std::int32_t r, std::int32_t c) const { return occupied[at(r, c)] != 0; }
    /// Occupied, or outside the map.
    bool blocked(std::int32_t r, std::int32_t c) const {
        return r < 0 || c < 0 || r >= rows || c >= cols || occupied[at(r, c)] != 0;
    }

    /// Map coordinates of pixel (r, c)'s centre.
    Vec2 center(std::int32_t r, std::int32_t c) const {
        return origin + resolution * Vec2(c + 0.5, (rows - 1 - r) + 0.5);
    }
    /// Map coordinates of a point given in doubled pixel units.
    Vec2 from_doubled(double x2, double y2) const { return origin + resolution * Vec2(0.5 * x2, 0.5 * y2); }
    /// Pixel units (not doubled) of a map point: x right, y up from the lower-left corner.
    Vec2 to_pixels(const Vec2& p) const { return (p - origin) / resolution; }
};

/// The index of the lowest set bit of w (w != 0).
inline std::int32_t lowest_bit(std::uint64_t w) {
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctzll(w);
#else
    std::int32_t k = 0;
    for (; (w & 1) == 0; w >>= 1) ++k;
    return k;
#endif
}

/// The index of the highest set bit of w (w != 0).
inline std::int32_t highest_bit(std::uint64_t w) {
#if defined(__GNUC__) || defined(__clang__)
    return 63 - __builtin_clzll(w);
#else
    std::int32_t k = 63;
    for (; (w >> k) == 0; --k) {}
    return k;
#endif
}

/// The number of set bits of w. Without the POPCNT instruction (the baseline x86-64 of a portable
/// wheel) the builtin is a call into libgcc, a few percent of an update; the bit-parallel sum inline
/// is a dozen instructions.
inline std::int32_t popcount(std::uint64_t w) {
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__POPCNT__) || !defined(__x86_64__))
    return __builtin_popcountll(w);
#else
    w -= (w >> 1) & 0x5555555555555555ULL;
    w = (w & 0x3333333333333333ULL) + ((w >> 2) & 0x3333333333333333ULL);
    w = (w + (w >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
    return static_cast<std::int32_t>((w * 0x0101010101010101ULL) >> 56);
#endif
}

/// The first column in [c, stop) of a row of bits `w` (`cols` bits, stop <= cols) whose bit is v,
/// a word at a time; when there is none, a column >= stop (cols at most).
inline std::int32_t find_in_row(const std::uint64_t* w, std::int32_t cols, std::int32_t c, bool v, std::int32_t stop) {
    while (c < stop) {
        const std::uint64_t word = (v ? w[c / 64] : ~w[c / 64]) >> (c % 64);
        if (word != 0) return std::min(cols, c + lowest_bit(word));
        c = (c / 64 + 1) * 64;
    }
    return std::min(cols, std::max(c, stop));
}

/// The squares whose closed extent holds a point (x, y) given in doubled units: columns c0 .. c1 and
/// square rows j0 .. j1 (counted from the bottom); one of each when the coordinate is odd (inside a
/// square), two when it is even (on the line between two).
struct SquaresHolding {
    std::int32_t c0, c1, j0, j1;
    SquaresHolding(std::int32_t x, std::int32_t y)
        : c0((x >> 1) - ((x & 1) ? 0 : 1)), c1(x >> 1), j0((y >> 1) - ((y & 1) ? 0 : 1)), j1(y >> 1) {}
};

/// The occupancy as bits, with the outside: square row j (counted from the bottom, -1 .. rows) and
/// column c (-1 .. cols) at bit c + 1 of row j + 1. The medial diagram's box rule reads a box's rows
/// as words instead of byte by byte.
class OccupancyBits {
public:
    OccupancyBits() = default;
    /// Bits for a rows x cols map with only the outside set; fill_rows sets the map's.
    OccupancyBits(std::int32_t rows, std::int32_t cols)
        : rows_(rows), cols_(cols), stride_((static_cast<std::size_t>(cols) + 2 + 63) / 64 + 1),
          w_(stride_ * (static_cast<std::size_t>(rows) + 2), 0) {
        for (std::size_t k = 0; k < stride_; ++k) {  // the outside rows
            w_[k] = ~std::uint64_t{0};
            w_[(static_cast<std::size_t>(rows_) + 1) * stride_ + k] = ~std::uint64_t{0};
        }
    }
    /// The bits of `g`, its rows split over `workers` threads (rows never share a word).
    explicit OccupancyBits(const OccupancyGrid& g, int workers = 1) : OccupancyBits(g.rows, g.cols) {
        const int team = std::max(1, std::min({workers, rows_, ::dvoronoi::detail::max_team()}));
        run_team(team, [&](int t) {
            fill_rows(g, static_cast<std::int32_t>(static_cast<std::int64_t>(rows_) * t / team),
                      static_cast<std::int32_t>(static_cast<std::int64_t>(rows_) * (t + 1) / team));
        });
    }
    void put(std::int32_t j, std::int32_t c, bool v) {
        const std::size_t bit = static_cast<std::size_t>(c + 1);
        std::uint64_t& word = w_[static_cast<std::size_t>(j + 1) * stride_ + bit / 64];
        const std::uint64_t m = std::uint64_t{1} << (bit % 64);
        word = v ? (word | m) : (word & ~m);
    }
    /// Is square (j, c) occupied or outside (-1 <= j <= rows, -1 <= c <= cols)?
    bool test(std::int32_t j, std::int32_t c) const {
        const std::size_t bit = static_cast<std::size_t>(c + 1);
        return (w_[static_cast<std::size_t>(j + 1) * stride_ + bit / 64] >> (bit % 64) & 1) != 0;
    }
    /// Square row j's words (column c is bit c + 1).
    const std::uint64_t* row_words(std::int32_t j) const { return &w_[static_cast<std::size_t>(j + 1) * stride_]; }
    /// Bits of columns c0 .. c0 + n - 1 (n <= 64, -1 <= c0, c0 + n - 1 <= cols) of square row j.
    std::uint64_t row(std::int32_t j, std::int32_t c0, std::int32_t n) const {
        const std::size_t bit = static_cast<std::size_t>(c0 + 1), k = bit / 64, sh = bit % 64;
        const std::uint64_t* p = &w_[static_cast<std::size_t>(j + 1) * stride_ + k];
        std::uint64_t v = p[0] >> sh;
        if (sh != 0) v |= p[1] << (64 - sh);  // the spare word per row keeps p[1] in range
        return n == 64 ? v : v & ((std::uint64_t{1} << n) - 1);
    }
    bool empty() const { return w_.empty(); }
    /// The free columns s .. t of square row j around free column c (0 <= c < cols): bounded by
    /// occupied squares or the outside, found a word at a time.
    std::pair<std::int32_t, std::int32_t> free_run(std::int32_t j, std::int32_t c) const {
        std::int32_t s = c;  // columns s .. c are free
        for (;;) {
            const std::int32_t n = std::min(64, s + 1);  // columns s - n .. s - 1 (column -1 is set)
            const std::uint64_t w = row(j, s - n, n);
            if (w != 0) {
                s = s - n + highest_bit(w) + 1;
                break;
            }
            s -= n;
        }
        std::int32_t t = c;  // columns c .. t are free
        for (;;) {
            const std::int32_t n = std::min(64, cols_ - t);  // columns t + 1 .. t + n (column cols is set)
            const std::uint64_t w = row(j, t + 1, n);
            if (w != 0) {
                t += lowest_bit(w);
                break;
            }
            t += n;
        }
        return {s, t};
    }
    /// Is the point (x, y) (doubled units, 0 <= x <= 2 cols, 0 <= y <= 2 rows) on an occupied square
    /// or on the outside?
    bool holds_point(std::int32_t x, std::int32_t y) const {
        const SquaresHolding s(x, y);
        const std::int32_t n = s.c1 - s.c0 + 1;
        return row(s.j0, s.c0, n) != 0 || row(s.j1, s.c0, n) != 0;
    }

    /// Square rows j in [j0, j1) from the occupancy bytes (threads may fill different rows at once).
    void fill_rows(const OccupancyGrid& g, std::int32_t j0, std::int32_t j1) {
        for (std::int32_t j = j0; j < j1; ++j) {
            const std::uint8_t* o = &g.occupied[g.at(rows_ - 1 - j, 0)];
            std::uint64_t* w = &w_[static_cast<std::size_t>(j + 1) * stride_];
            for (std::int32_t c0 = 0; c0 < cols_; c0 += 64) {  // 64 bytes to one word, then into place
                const std::int32_t n = std::min(64, cols_ - c0);
                std::uint64_t m = 0;
                std::int32_t k = 0;
#if defined(__SSE2__)
                // sixteen bytes at a time: compare with zero, gather the sign bits (pmovmskb)
                for (; k + 16 <= n; k += 16) {
                    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(o + c0 + k));
                    const auto zero = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128())));
                    m |= static_cast<std::uint64_t>(~zero & 0xffffu) << k;
                }
#endif
                for (; k < n; ++k) m |= static_cast<std::uint64_t>(o[c0 + k] != 0) << k;
                const std::size_t bit = static_cast<std::size_t>(c0) + 1;
                w[bit / 64] |= m << (bit % 64);
                if (bit % 64 != 0) w[bit / 64 + 1] |= m >> (64 - bit % 64);
            }
            put(j, -1, true);
            put(j, cols_, true);
        }
    }

private:
    std::int32_t rows_ = 0, cols_ = 0;
    std::size_t stride_ = 0;
    std::vector<std::uint64_t> w_;
};

/// A set of pixels as bits (a diagram: 1/8 byte a pixel). Every row starts a new 64-bit word, so
/// threads that write different rows never share a word.
class PixelMask {
public:
    PixelMask() = default;
    PixelMask(std::int32_t rows, std::int32_t cols)
        : rows_(rows), cols_(cols), stride_((static_cast<std::size_t>(cols) + 63) / 64),
          w_(stride_ * static_cast<std::size_t>(rows), 0) {}

    bool operator()(std::int32_t r, std::int32_t c) const {
        return (w_[static_cast<std::size_t>(r) * stride_ + static_cast<std::size_t>(c) / 64] >> (c % 64)) & 1;
    }
    /// By row-major pixel index r * cols + c.
    bool operator[](std::size_t i) const {
        return (*this)(static_cast<std::int32_t>(i / static_cast<std::size_t>(cols_)), static_cast<std::int32_t>(i % static_cast<std::size_t>(cols_)));
    }
    void set(std::int32_t r, std::int32_t c, bool v) {
        std::uint64_t& w = w_[static_cast<std::size_t>(r) * stride_ + static_cast<std::size_t>(c) / 64];
        const std::uint64_t m = std::uint64_t{1} << (c % 64);
        w = v ? (w | m) : (w & ~m);
    }
    void set(std::size_t i, bool v) {
        set(static_cast<std::int32_t>(i / static_cast<std::size_t>(cols_)), static_cast<std::int32_t>(i % static_cast<std::size_t>(cols_)), v);
    }
    /// The first column >= c of row r whose bit is v (cols when there is none); the search stops
    /// at column `end` (default: the row's end) and then returns a column >= end.
    std::int32_t find(std::int32_t r, std::int32_t c, bool v, std::int32_t end = -1) const {
        return find_in_row(row_words(r), cols_, c, v, end < 0 ? cols_ : std::min(end, cols_));
    }
    /// Pixels (r, a .. b) emptied.
    void clear(std::int32_t r, std::int32_t a, std::int32_t b) {
        std::uint64_t* w = row_words(r);
        for (std::int32_t c = a; c <= b;) {
            const std::int32_t n = std::min(b - c + 1, 64 - c % 64);
            const std::uint64_t m = (n == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << n) - 1)) << (c % 64);
            w[c / 64] &= ~m;
            c += n;
        }
    }
    /// Rows [r0, r1) emptied.
    void clear_rows(std::int32_t r0, std::int32_t r1) {
        std::fill(w_.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(r0) * stride_),
                  w_.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(r1) * stride_), std::uint64_t{0});
    }
    std::size_t count() const {
        std::size_t n = 0;
        for (std::uint64_t w : w_) n += static_cast<std::size_t>(popcount(w));
        return n;
    }
    /// Row-major 0/1 bytes into `out` (rows x cols), eight pixels at a time, rows split over
    /// `workers` threads (a large map's output is mostly fresh pages to fault in).
    void to_bytes(std::uint8_t* out, int workers = 1) const {
        run_chunks(std::min(workers, rows_ / 64 + 1), rows_, 64, [] { return 0; },
                   [&](int&, std::int32_t r0, std::int32_t r1) { to_bytes(out, r0, r1); });
    }
    /// Rows [r0, r1) of to_bytes.
    void to_bytes(std::uint8_t* out, std::int32_t r0, std::int32_t r1) const {
        for (std::int32_t r = r0; r < r1; ++r) {
            const std::uint64_t* w = row_words(r);
            std::uint8_t* o = out + static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_);
            std::int32_t c = 0;
            for (; c + 8 <= cols_; c += 8) {  // c % 8 == 0: the 8 bits lie in one word
                const std::uint64_t spread = spread_table()[(w[c / 64] >> (c % 64)) & 0xff];
                std::memcpy(o + c, &spread, 8);
            }
            for (; c < cols_; ++c) o[c] = (*this)(r, c);
        }
    }
    std::vector<std::uint8_t> bytes() const {
        std::vector<std::uint8_t> out(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_));
        to_bytes(out.data());
        return out;
    }
    /// The words of rows [r0, r1) (for sending whole rows, e.g. MPI).
    std::uint64_t* row_words(std::int32_t r) { return w_.data() + static_cast<std::size_t>(r) * stride_; }
    const std::uint64_t* row_words(std::int32_t r) const { return w_.data() + static_cast<std::size_t>(r) * stride_; }
    std::size_t words_per_row() const { return stride_; }
    std::int32_t rows() const { return rows_; }
    std::int32_t cols() const { return cols_; }
    bool operator==(const PixelMask& o) const { return rows_ == o.rows_ && cols_ == o.cols_ && w_ == o.w_; }
    bool operator!=(const PixelMask& o) const { return !(*this == o); }

private:
    /// Byte k of entry b is bit k of b: eight pixels' bits to eight 0/1 bytes (little-endian memory order).
    static const std::uint64_t* spread_table() {
        static const auto table = [] {
            std::vector<std::uint64_t> t(256);
            for (unsigned b = 0; b < 256; ++b) {
                std::uint8_t bytes[8];
                for (unsigned k = 0; k < 8; ++k) bytes[k] = static_cast<std::uint8_t>((b >> k) & 1);
                std::memcpy(&t[b], bytes, 8);
            }
            return t;
        }();
        return table.data();
    }

    std::int32_t rows_ = 0, cols_ = 0;
    std::size_t stride_ = 0;
    std::vector<std::uint64_t> w_;
};

/// check_grid's range of resolutions: map coordinates stay finite 2^40 pixels from (0, 0).
inline bool resolution_in_range(double r) {
    return r >= std::numeric_limits<double>::min() && r <= std::numeric_limits<double>::max() / (4.0 * 1099511627776.0);
}

/// "[2.2250738585072014e-308, 4.0874809539271057e+295]": the ends exactly, so that both are accepted
/// (a rounded 2.2e-308 would be refused).
inline std::string resolution_range() {
    return "[" + ::dvoronoi::detail::shortest_text(std::numeric_limits<double>::min()) + ", " +
           ::dvoronoi::detail::shortest_text(std::numeric_limits<double>::max() / (4.0 * 1099511627776.0)) + "]";
}

/// Checks sizes, resolution and origin; names the argument.
inline void check_grid(const OccupancyGrid& g) {
    if (g.rows < 1 || g.cols < 1)
        throw InputError("occupancy grid must have at least one row and one column, got " + std::to_string(g.rows) +
                         " x " + std::to_string(g.cols));
    if (g.rows > kMaxMapSide || g.cols > kMaxMapSide)
        throw InputError("occupancy grid of " + std::to_string(g.rows) + " x " + std::to_string(g.cols) +
                         " pixels: each side must be at most " + std::to_string(kMaxMapSide) + " pixels");
    if (g.occupied.size() != static_cast<std::size_t>(g.rows) * static_cast<std::size_t>(g.cols))
        throw InputError("occupancy grid data has " + std::to_string(g.occupied.size()) + " values for " +
                         std::to_string(g.rows) + " x " + std::to_string(g.cols) + " pixels");
    if (!std::isfinite(g.resolution) || g.resolution <= 0.0)
        throw InputError("resolution must be a positive finite number (map units per pixel)");
    if (!std::isfinite(g.origin.x()) || !std::isfinite(g.origin.y()))
        throw InputError("origin must be finite");
    // Map coordinates are origin + resolution x pixel units. Within 2^40 pixels of (0, 0) they stay
    // finite and keep 12 bits below a pixel (doubles carry 52); farther, pixel centres round together
    // and clearances and paths lose their meaning.
    constexpr double kReach = 1099511627776.0;  // 2^40 pixels
    using ::dvoronoi::detail::shortest_text;
    if (!resolution_in_range(g.resolution))
        throw InputError("resolution " + shortest_text(g.resolution) + " is out of range: map units per pixel must lie in " +
                         resolution_range() + " so that map coordinates stay finite");
    const double reach = std::max(std::abs(g.origin.x()) / g.resolution + g.cols, std::abs(g.origin.y()) / g.resolution + g.rows);
    if (!(reach <= kReach))
        throw InputError("origin (" + shortest_text(g.origin.x()) + ", " + shortest_text(g.origin.y()) +
                         ") lies more than 2^40 pixels (of this resolution) from (0, 0): map coordinates could not tell "
                         "pixels apart; shift the origin nearer");
}

}  // namespace dvoronoi::gvd
