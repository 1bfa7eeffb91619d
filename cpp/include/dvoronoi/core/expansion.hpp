// Exact arithmetic on doubles for the predicates: Shewchuk's floating-point expansions, and a
// forward-error-bounded double (ErrDouble) used as the fast filter in front of them.
//
// Why hand-written: the library is header-only on Eigen (no GMP at run time), and predicates of
// degree <= 6 on double inputs are exactly what expansions handle well. Exactness holds as long as no
// intermediate product underflows or overflows: nonzero coordinate differences between about 1e-45
// and 1e45 for the degree-6 predicates (far outside any robot or sensor deployment).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

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

    int sign() const { return c_.empty() ? 0 : (c_.back() > 0.0 ? 1 : -1); }

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

/// Evaluates a predicate expression `f(tag)` (a generic lambda taking a type tag) with the filter
/// first and exact expansions when the filter cannot decide; returns its sign.
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
    return f(Tag<Expansion>{}).sign();
}

}  // namespace dvoronoi::detail
