// Exact arithmetic on doubles for the predicates: Shewchuk's floating-point expansions, and a
// forward-error-bounded double (ErrDouble) used as the fast filter in front of them.
//
// Why hand-written: the library is header-only on Eigen (no GMP at run time), and predicates of
// degree <= 6 on double inputs are exactly what expansions handle well. Exactness holds as long as no
// intermediate product underflows or overflows: nonzero coordinate differences between about 1e-45
// and 1e45 for the degree-6 predicates (far outside any robot or sensor deployment). Outside that
// range a decision is still exact or refused, never wrong: the filter's bound covers underflow and
// gives up on overflow, and the exact stage is checked (filtered_sign): where it lost bits it runs
// again on rescaled inputs, and what even that cannot decide throws dvoronoi::RangeError.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <cfenv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <xmmintrin.h>
#endif

namespace dvoronoi::detail {

inline void two_sum(double a, double b, double& x, double& y) {
    x = a + b;
    const double bv = x - a;
    const double av = x - bv;
    y = (a - av) + (b - bv);
}

inline void fast_two_sum(double a, double b, double& x, double& y) {  // requires |a| >= |b|
    x = a + b;
    y = b - (x - a);
}

inline void two_product(double a, double b, double& x, double& y) {
    x = a * b;
    y = std::fma(a, b, -x);
}

/// A nonoverlapping expansion: the exact value is the sum of the components, stored in increasing
/// magnitude, zeros eliminated. Only the operations the predicates need.
class Expansion {
public:
    Expansion() = default;
    explicit Expansion(double v) {
        if (v != 0.0) c_.push_back(v);
    }
    /// Exact a - b.
    static Expansion diff(double a, double b) {
        double x, y;
        two_sum(a, -b, x, y);
        Expansion e;
        if (y != 0.0) e.c_.push_back(y);
        if (x != 0.0) e.c_.push_back(x);
        return e;
    }
    static Expansion from(double v) { return Expansion(v); }
    static Expansion constant(double v) { return Expansion(v); }

    int sign() const { return c_.empty() ? 0 : (c_.back() > 0.0 ? 1 : -1); }
    /// The components, increasing in magnitude.
    const std::vector<double>& components() const { return c_; }
    /// This times b, exactly (barring underflow).
    Expansion times(double b) const { return scaled(b); }
    std::size_t size() const { return c_.size(); }
    /// The value rounded (the components summed from the smallest: within a few ulps).
    double estimate() const {
        double sum = 0.0;
        for (double v : c_) sum += v;
        return sum;
    }
    /// A lower bound on |value|: the largest component less the others (nonoverlapping, so the
    /// largest dominates); rounded down.
    double magnitude_below() const {
        if (c_.empty()) return 0.0;
        double rest = 0.0;
        for (std::size_t i = 0; i + 1 < c_.size(); ++i) rest += std::fabs(c_[i]);
        return (std::fabs(c_.back()) - rest * (1.0 + 1e-10)) * (1.0 - 1e-10);
    }
    /// An upper bound on |value|: the sum of the components' magnitudes, rounded up.
    double magnitude_above() const {
        double sum = 0.0;
        for (double v : c_) sum += std::fabs(v);
        return sum * (1.0 + 1e-10);
    }

    friend Expansion operator+(const Expansion& a, const Expansion& b) {
        // Shewchuk's linear expansion sum (merge by magnitude, then one two_sum per component,
        // zeros eliminated): one allocation per result.
        if (a.c_.empty()) return b;
        if (b.c_.empty()) return a;
        const std::vector<double>& e = a.c_;
        const std::vector<double>& f = b.c_;
        std::size_t ei = 0, fi = 0;
        const auto take = [&]() {
            if (fi >= f.size() || (ei < e.size() && std::fabs(e[ei]) < std::fabs(f[fi]))) return e[ei++];
            return f[fi++];
        };
        Expansion r;
        r.c_.reserve(e.size() + f.size());
        double q = take();
        while (ei < e.size() || fi < f.size()) {
            double qn, hh;
            two_sum(q, take(), qn, hh);
            q = qn;
            if (hh != 0.0) r.c_.push_back(hh);
        }
        if (q != 0.0) r.c_.push_back(q);
        return r;
    }
    friend Expansion operator-(const Expansion& a) {
        Expansion r = a;
        for (double& v : r.c_) v = -v;
        return r;
    }
    friend Expansion operator-(const Expansion& a, const Expansion& b) { return a + (-b); }
    friend Expansion operator*(const Expansion& a, const Expansion& b) {
        Expansion r;
        const Expansion& big = a.c_.size() >= b.c_.size() ? a : b;
        const Expansion& small = a.c_.size() >= b.c_.size() ? b : a;
        for (double v : small.c_) r = r + big.scaled(v);
        return r;
    }

private:
    Expansion scaled(double b) const {  // scale_expansion_zeroelim
        Expansion r;
        if (c_.empty() || b == 0.0) return r;
        r.c_.reserve(2 * c_.size());
        double q, hh;
        two_product(c_[0], b, q, hh);
        if (hh != 0.0) r.c_.push_back(hh);
        for (std::size_t i = 1; i < c_.size(); ++i) {
            double p1, p0, sum, t;
            two_product(c_[i], b, p1, p0);
            two_sum(q, p0, sum, hh);
            if (hh != 0.0) r.c_.push_back(hh);
            fast_two_sum(p1, sum, q, hh);
            if (hh != 0.0) r.c_.push_back(hh);
            (void)t;
        }
        if (q != 0.0) r.c_.push_back(q);
        return r;
    }

    std::vector<double> c_;
};

/// A double with a rigorous bound on its absolute error (round-to-nearest, no FMA contraction
/// assumed): the floating-point filter. sign() returns 2 when the bound does not decide the sign.
struct ErrDouble {
    double v = 0.0;
    double e = 0.0;

    static constexpr double kU = std::numeric_limits<double>::epsilon() * 0.5;  // unit roundoff
    static constexpr double kTiny = std::numeric_limits<double>::denorm_min();   // underflow slack

    static ErrDouble diff(double a, double b) {
        const double d = a - b;
        return {d, kU * std::fabs(d) + kTiny};
    }
    static ErrDouble from(double a) { return {a, 0.0}; }
    static ErrDouble constant(double a) { return {a, 0.0}; }

    friend ErrDouble operator+(const ErrDouble& a, const ErrDouble& b) {
        const double s = a.v + b.v;
        return {s, a.e + b.e + kU * std::fabs(s) + kTiny};
    }
    friend ErrDouble operator-(const ErrDouble& a, const ErrDouble& b) {
        const double s = a.v - b.v;
        return {s, a.e + b.e + kU * std::fabs(s) + kTiny};
    }
    friend ErrDouble operator-(const ErrDouble& a) { return {-a.v, a.e}; }
    friend ErrDouble operator*(const ErrDouble& a, const ErrDouble& b) {
        const double p = a.v * b.v;
        return {p, std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e + kU * std::fabs(p) + kTiny};
    }

    /// -1, 0 (only when exactly zero with no error), +1, or 2 = undecided.
    int sign() const {
        // The bound itself was computed with rounding; a relative slack of 1e-10 covers it.
        const double bound = e * (1.0 + 1e-10);
        if (!(std::fabs(v) <= std::numeric_limits<double>::max()) || !(bound <= 1e300)) return 2;
        if (v > bound) return 1;
        if (-v > bound) return -1;
        if (e == 0.0) return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0);
        return 2;
    }
};

/// The scale 2^k of the Rescaled evaluation running on this thread (set by filtered_sign).
inline thread_local int rescale_k = 0;

/// The exact stage again, where it lost bits, on inputs scaled by 2^k: a predicate is a homogeneous
/// polynomial in its inputs (coordinate differences, radii, distances; its constant coefficients
/// come from T::constant and are not scaled), so its sign is the same, while products that fell below
/// the smallest subnormal step (or past the largest double) at the inputs' own scale may fit at
/// another. With `Bounded`, `e` bounds what is still lost: additions of expansions stay exact (a sum
/// of two doubles is a double down to the smallest subnormal); a scaled input that falls into the
/// subnormal range is off by less than 2^-1075, a two_product whose result underflows loses at most
/// 2^-1075, and a product of expansions adds those of its own two_products to the losses it carries,
/// scaled by the other factor. sign() is 2 when the loss could change the sign.
template <bool Bounded>
struct Rescaled {
    Expansion v;
    double e = 0.0;  ///< |exact value x 2^(k degree) - value of v| <= e (Bounded only)

    static constexpr double kTiny = std::numeric_limits<double>::denorm_min();  // 2^-1074

    static Rescaled input(double a) {
        const double s = std::ldexp(a, rescale_k);
        return {Expansion(s), Bounded && std::ldexp(s, -rescale_k) != a ? kTiny : 0.0};
    }
    static Rescaled diff(double a, double b) {
        const Rescaled x = input(a), y = input(b);
        return {x.v - y.v, x.e + y.e};
    }
    static Rescaled from(double a) { return input(a); }
    static Rescaled constant(double a) { return {Expansion(a), 0.0}; }
    friend Rescaled operator+(const Rescaled& a, const Rescaled& b) {
        return {a.v + b.v, Bounded ? (a.e + b.e) * (1.0 + 1e-10) : 0.0};
    }
    friend Rescaled operator-(const Rescaled& a, const Rescaled& b) {
        return {a.v - b.v, Bounded ? (a.e + b.e) * (1.0 + 1e-10) : 0.0};
    }
    friend Rescaled operator-(const Rescaled& a) { return {-a.v, a.e}; }
    friend Rescaled operator*(const Rescaled& a, const Rescaled& b) {
        if (!Bounded) return {a.v * b.v, 0.0};
        const double ma = a.v.magnitude_above(), mb = b.v.magnitude_above();
        const double products = static_cast<double>(a.v.size() * b.v.size());
        // Each term below is rounded up by the slack and by one kTiny (its own possible underflow).
        const double e = (ma * b.e + mb * a.e + a.e * b.e) * (1.0 + 1e-10) + (products + 3.0) * kTiny;
        return {a.v * b.v, e};
    }
    /// The sign; Bounded: 2 when the loss could change it (or the value overflowed even so).
    int sign() const {
        if (!Bounded) return v.sign();
        if (!(e <= 1e300) || !(v.magnitude_above() <= 1e300)) return 2;
        return v.magnitude_below() > e ? v.sign() : 2;
    }
};

/// The largest input an expression reads (for the scale of Rescaled); constants do not count.
struct InputMagnitude {
    double m = 0.0;
    static InputMagnitude diff(double a, double b) { return {std::max(std::fabs(a), std::fabs(b))}; }
    static InputMagnitude from(double a) { return {std::fabs(a)}; }
    static InputMagnitude constant(double) { return {0.0}; }
    friend InputMagnitude operator+(const InputMagnitude& a, const InputMagnitude& b) { return {std::max(a.m, b.m)}; }
    friend InputMagnitude operator-(const InputMagnitude& a, const InputMagnitude& b) { return {std::max(a.m, b.m)}; }
    friend InputMagnitude operator-(const InputMagnitude& a) { return a; }
    friend InputMagnitude operator*(const InputMagnitude& a, const InputMagnitude& b) { return {std::max(a.m, b.m)}; }
};

/// The IEEE underflow and overflow flags, read and written around the exact stage. On x86 (SSE2,
/// where doubles are computed) straight from MXCSR; the <cfenv> calls go through the x87 status
/// word and environment as well.
namespace fpflags {
#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
using Flags = unsigned;
inline constexpr Flags kLost = 0x18;  // MXCSR: OE (overflow) | UE (underflow)
inline Flags test() { return _mm_getcsr() & kLost; }
inline bool overflow(Flags f) { return (f & 0x08) != 0; }
/// Sets the two flags to `f` (only flags: no exception is raised by writing them).
inline void set(Flags f) {
    const unsigned csr = _mm_getcsr();
    const unsigned want = (csr & ~kLost) | f;
    if (want != csr) _mm_setcsr(want);
}
#else
using Flags = int;
inline constexpr Flags kLost = FE_UNDERFLOW | FE_OVERFLOW;
inline Flags test() { return std::fetestexcept(kLost); }
inline bool overflow(Flags f) { return (f & FE_OVERFLOW) != 0; }
inline void set(Flags f) {
    std::feclearexcept(kLost & ~f);
    if (f) std::feraiseexcept(f);  // only flags that were raised before, so no new trap
}
#endif
}  // namespace fpflags

/// The message of a decision the exact stage cannot vouch for.
inline RangeError out_of_exact_range(bool overflowed) {
    return RangeError(std::string("out of the exact range: an exact test ") + (overflowed ? "overflowed" : "underflowed") +
                      " even on rescaled inputs (the values of one test span more than doubles hold at once; "
                      "decisions are exact for nonzero coordinate differences between about 1e-45 and 1e45, "
                      "and beyond while no single test spans that much)");
}

/// Evaluates a predicate expression `f(tag)` (a generic lambda taking a type tag) with the filter
/// first and exact expansions when the filter cannot decide; returns its sign.
///
/// The exact stage is checked: an evaluation that raised the IEEE overflow flag, or the underflow
/// flag (a product rounded below the smallest subnormal step: exact results in the subnormal range
/// raise none), is no longer exact. It is then evaluated again on inputs scaled so that the largest
/// is about 2^125 (room for degree 8): exact if that raises no flag, else once more with a bound on
/// what underflow still loses (Rescaled<true>), which decides unless the inputs of one test span
/// more than doubles can hold at once (about 2^1000 / degree), and then RangeError. So a common
/// scale far from 1 (spacings of 1e-200, coordinates of 1e200) is exact; a coordinate a few
/// subnormal steps from 0 beside others 1e-9 apart may not be. The flags are touched around the
/// exact stage only (the filter decides nearly every test), and the caller's flags are left as
/// they were.
/// \throws RangeError when the sign stays unknown.
template <class T>
struct Tag {
    using type = T;
};

template <class F>
int filtered_sign(F&& f) {
    const int s = f(Tag<ErrDouble>{}).sign();
    if (s != 2) return s;
#ifdef DV_DEBUG_EXACT
    DV_DEBUG_EXACT(f(Tag<ErrDouble>{}));
#endif
    const fpflags::Flags before = fpflags::test();  // e.g. from the filter: errors of exact zeros
    if (before) fpflags::set(0);
    // volatile: the evaluation is complete before the flags are read.
    volatile int sign = f(Tag<Expansion>{}).sign();
    const fpflags::Flags lost = fpflags::test();
    if (lost != before) fpflags::set(before);
    if (!lost) return sign;
    const double m = f(Tag<InputMagnitude>{}).m;
    const int saved = rescale_k;
    rescale_k = m > 0.0 ? 125 - std::ilogb(m) : 0;
    fpflags::set(0);
    volatile int rescaled = f(Tag<Rescaled<false>>{}).sign();
    const bool exact = !fpflags::test();
    const int bounded = exact ? rescaled : f(Tag<Rescaled<true>>{}).sign();
    rescale_k = saved;
    fpflags::set(before);
    if (bounded == 2) throw out_of_exact_range(fpflags::overflow(lost));
    return bounded;
}

}  // namespace dvoronoi::detail
