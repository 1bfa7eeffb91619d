// Canonical types and the error policy of dvoronoi.
//
// Error policy (decided once, for every header): misuse of the API (bad shapes, NaN/inf coordinates,
// a non-positive radius, coinciding agents) throws dvoronoi::Error (or its subclass InputError) with a
// message that names the argument. Geometric degeneracy (cocircular, collinear, lattice inputs) is never
// an error: it is decided exactly. Input outside the range where exact answers are possible (a radius
// outside kMinRadius..kMaxRadius, an exact test that would over- or underflow: see core/expansion.hpp)
// throws RangeError, never a silently wrong answer.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace dvoronoi {

/// Agent indices: 0-based, input order, 64-bit (scipy's CSR layout uses int64 too).
using Index = std::int64_t;

/// A point of the plane.
using Vec2 = Eigen::Vector2d;

/// `n x 2` row-major array of agent positions: the layout numpy hands over without a copy.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

/// Read-only view of an `n x 2` array of any stride (a numpy slice binds without a copy when its rows
/// are contiguous).
using PointsRef = Eigen::Ref<const Points, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

/// The library's exception type: every misuse of the API throws it.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Bad input data (shape, non-finite values, coinciding agents, malformed files).
class InputError : public Error {
public:
    using Error::Error;
};

/// Input outside the documented range, where the answer could not be exact (an exact test that over-
/// or underflows, a radius whose square or disk area is not a normal double) or would take
/// unbounded time (RCVC with more candidates than it accepts). The message names the argument.
class RangeError : public InputError {
public:
    using InputError::InputError;
};

/// Coinciding agents: their cells are undefined. Carries the first pair of indices found.
class CoincidentError : public InputError {
public:
    CoincidentError(const std::string& what, Index first, Index second)
        : InputError(what), first_(first), second_(second) {}
    Index first() const noexcept { return first_; }
    Index second() const noexcept { return second_; }

private:
    Index first_, second_;
};

namespace detail {

/// The shortest decimal that reads back as `v`, for messages that quote the caller's numbers.
inline std::string shortest_text(double v) {
    char buf[40];
    for (int digits = 6; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (!std::isfinite(v) || std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

/// An agent seen by another: its position and its index in the caller's numbering.
struct Candidate {
    Vec2 p;
    Index id;
};

}  // namespace detail

/// The range of a radius (a cell radius, a communication range): its square and the area of its
/// disk are normal doubles, and the index's floating-point screens keep their error bounds.
inline constexpr double kMinRadius = 1e-150;
inline constexpr double kMaxRadius = 1e150;

namespace detail {

/// \throws RangeError naming `name` unless lo <= radius <= hi; `why` says what needs the range.
inline void require_radius_range(double radius, double lo, double hi, const char* name, const char* why) {
    if (radius >= lo && radius <= hi) return;
    const auto show = [](double v) {  // "1e150", not printf's "1e+150"
        char b[32];
        std::snprintf(b, sizeof b, "%g", v);
        std::string t(b);
        const std::size_t plus = t.find("e+");
        if (plus != std::string::npos) t.erase(plus + 1, 1);
        return t;
    };
    char got[32];
    std::snprintf(got, sizeof got, "%.17g", radius);
    throw RangeError(name + std::string(" must lie between ") + show(lo) + " and " + show(hi) + " (" + why +
                     "), got " + got);
}

/// \throws InputError naming `name` unless radius is positive and finite; RangeError unless it lies
///         in [kMinRadius, kMaxRadius].
inline void require_finite_radius(double radius, const char* name = "radius") {
    if (!std::isfinite(radius) || !(radius > 0.0)) {
        char got[32];
        std::snprintf(got, sizeof got, "%.17g", radius);
        throw InputError(std::string(name) + " must be a positive finite number, got " + got);
    }
    require_radius_range(radius, kMinRadius, kMaxRadius, name,
                         "its square and its disk's area must be normal doubles");
}

/// require_finite_radius for each entry of a radius per agent, naming `name[i]`.
inline void require_finite_radii(const std::vector<double>& radii, const char* name = "radius") {
    for (std::size_t i = 0; i < radii.size(); ++i)
        require_finite_radius(radii[i], (name + ("[" + std::to_string(i) + "]")).c_str());
}

/// Drops the last vertex of a closed ring (one that repeats the first), so a polygon given as a
/// closed ring and as an open one are the same.
template <class Vertices>
void open_ring(Vertices& v) {
    if (v.size() > 1 && v.front() == v.back()) v.pop_back();
}

inline void require_finite_point(const Vec2& p, const std::string& name) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
        throw InputError(name + " has a non-finite coordinate (NaN or inf)");
}

template <class Derived>
void require_finite_points(const Eigen::MatrixBase<Derived>& pts, const char* name) {
    for (Eigen::Index i = 0; i < pts.rows(); ++i)
        for (int d = 0; d < 2; ++d)
            if (!std::isfinite(pts(i, d)))
                throw InputError(std::string(name) + "[" + std::to_string(i) + ", " +
                                 std::to_string(d) + "] is not finite (NaN or inf)");
}

/// A hint to load the cache line at p (no effect on results).
inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}

/// A hint to fetch the cache line at p for writing (no effect on results).
inline void prefetch_for_write(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 1);
#else
    (void)p;
#endif
}

}  // namespace detail
}  // namespace dvoronoi
