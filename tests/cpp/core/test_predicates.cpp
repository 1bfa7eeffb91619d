// The exact predicates against integer arithmetic (__int128) on small integer inputs, where ties
// (zero signs) are frequent, and on exactly scaled and translated copies of the same inputs.
#include "dvoronoi/core/predicates.hpp"

#include <doctest/doctest.h>

#include <cfenv>
#include <cmath>
#include <random>
#include <string>

using dvoronoi::Vec2;
namespace pred = dvoronoi::pred;
__extension__ typedef __int128 I;  // exact reference arithmetic (GCC/Clang)

namespace {

int sgn(I v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

struct IP {
    I x, y;
};
I cross(IP a, IP b) { return a.x * b.y - a.y * b.x; }
I dot(IP a, IP b) { return a.x * b.x + a.y * b.y; }
I n2(IP a) { return dot(a, a); }

struct Case {
    IP c, j, k, l;
    I r;  // radius (integer)
};

// Reference signs from the defining polynomials, evaluated exactly in 128-bit integers.
int ref_orient(const Case& t) { return sgn(cross({t.j.x - t.c.x, t.j.y - t.c.y}, {t.k.x - t.c.x, t.k.y - t.c.y})); }

}  // namespace

TEST_CASE("predicates agree with exact integer evaluation, on integer and transformed inputs") {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> coord(-6, 6), rad(1, 6);
    // Exact transforms: scale by 2^-30 then translate by 2^20 (fits in 53 bits for |x| <= 6).
    const double scale = std::ldexp(1.0, -30), shift = std::ldexp(1.0, 20);
    int zeros[6] = {0, 0, 0, 0, 0, 0};
    for (int it = 0; it < 20000; ++it) {
        Case t{{coord(rng), coord(rng)}, {coord(rng), coord(rng)}, {coord(rng), coord(rng)},
               {coord(rng), coord(rng)}, rad(rng)};
        const IP aj{t.j.x - t.c.x, t.j.y - t.c.y}, ak{t.k.x - t.c.x, t.k.y - t.c.y},
            al{t.l.x - t.c.x, t.l.y - t.c.y};
        if (n2(aj) == 0 || n2(ak) == 0 || n2(al) == 0) continue;
        const I d = cross(aj, ak);
        for (int variant = 0; variant < 2; ++variant) {
            auto tr = [&](IP p) {
                const double x = static_cast<double>(p.x), y = static_cast<double>(p.y);
                return variant == 0 ? Vec2(x, y) : Vec2(x * scale + shift, y * scale - shift);
            };
            const double R = variant == 0 ? static_cast<double>(t.r) : static_cast<double>(t.r) * scale;
            const Vec2 c = tr(t.c), pj = tr(t.j), pk = tr(t.k), pl = tr(t.l);
            CHECK(pred::orient(c, pj, pk) == ref_orient(t));
            CHECK(pred::dot_sign(c, pj, pk) == sgn(dot(aj, ak)));
            CHECK(pred::compare_distance(c, pj, pk) == sgn(n2(aj) - n2(ak)));
            CHECK(pred::within_2r(c, pj, R) == sgn(4 * t.r * t.r - n2(aj)));
            if (d == 0) continue;
            const I inc = n2(aj) * cross(ak, al) - n2(ak) * cross(aj, al) + n2(al) * cross(aj, ak);
            CHECK(pred::vertex_side(c, pj, pk, pl) == -sgn(inc) * sgn(d));
            const IP jk{t.j.x - t.k.x, t.j.y - t.k.y};
            const int disk = sgn(n2(aj) * n2(ak) * n2(jk) - 4 * t.r * t.r * d * d);
            CHECK(pred::vertex_in_disk(c, pj, pk, R) == disk);
            CHECK(pred::vertex_position(c, pj, pk) == sgn(n2(ak) - dot(aj, ak)) * sgn(d));
            if (variant == 0) {
                zeros[0] += inc == 0;
                zeros[1] += disk == 0;
            }
        }
    }
    // The integer inputs must actually exercise the degenerate (zero) branches.
    CHECK(zeros[0] > 100);
    CHECK(zeros[1] > 10);
}

TEST_CASE("vertex predicates match the constructed vertex on generic inputs") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int it = 0; it < 5000; ++it) {
        const Vec2 c(u(rng), u(rng)), pj(u(rng), u(rng)), pk(u(rng), u(rng)), pl(u(rng), u(rng));
        const double R = 0.1 + std::fabs(u(rng));
        const Vec2 aj = pj - c, ak = pk - c, al = pl - c;
        const double d = aj.x() * ak.y() - aj.y() * ak.x();
        if (std::fabs(d) < 1e-3) continue;
        const Vec2 v((0.5 * aj.squaredNorm() * ak.y() - 0.5 * ak.squaredNorm() * aj.y()) / d,
                     (0.5 * aj.x() * ak.squaredNorm() - 0.5 * ak.x() * aj.squaredNorm()) / d);
        const double side = v.dot(al) - 0.5 * al.squaredNorm();
        if (std::fabs(side) > 1e-6) CHECK(pred::vertex_side(c, pj, pk, pl) == (side > 0 ? 1 : -1));
        const double rr = v.squaredNorm() - R * R;
        if (std::fabs(rr) > 1e-6) CHECK(pred::vertex_in_disk(c, pj, pk, R) == (rr > 0 ? 1 : -1));
        const double t = v.dot(Vec2(-aj.y(), aj.x()));
        if (std::fabs(t) > 1e-6) CHECK(pred::vertex_position(c, pj, pk) == (t > 0 ? 1 : -1));
        // Chord endpoints of L_j against L_k.
        if (aj.norm() < 2 * R) {
            for (int sigma : {-1, 1}) {
                const double h = 0.5 * aj.norm();
                const double w = std::sqrt(R * R - h * h) / aj.norm();
                const Vec2 q = 0.5 * aj + sigma * w * Vec2(-aj.y(), aj.x());
                const double s = q.dot(ak) - 0.5 * ak.squaredNorm();
                if (std::fabs(s) > 1e-6) CHECK(pred::endpoint_side(c, pj, sigma, pk, R) == (s > 0 ? 1 : -1));
            }
        }
    }
}

TEST_CASE("endpoint_side is exact when a chord endpoint lies on another bisector") {
    // c = 0, R = 5: the chord of p_j = (6, 0) (line x = 3) ends at (3, +-4); p_k = (0, 8) has the
    // bisector y = 4 through (3, 4) exactly, so the last endpoint is on L_k and the first inside.
    const Vec2 c(0, 0), pj(6, 0), pk(0, 8);
    CHECK(pred::endpoint_side(c, pj, +1, pk, 5.0) == 0);
    CHECK(pred::endpoint_side(c, pj, -1, pk, 5.0) == -1);
    CHECK(pred::endpoint_side(c, pj, +1, Vec2(0, 7.999999999999999), 5.0) == 1);
    // The vertex (3, 4) of L_j and L_k is exactly on the circle.
    CHECK(pred::vertex_in_disk(c, pj, pk, 5.0) == 0);
    CHECK(pred::vertex_in_disk(c, pj, pk, 5.000000000000001) == -1);
}

TEST_CASE("exact far from 1: inputs scaled by 2^k for |k| up to 540 give the unscaled signs") {
    // orient(0, a, b) = s^2 2^-51 > 0 for a = s (1, 1), b = s (2, 2 + 2^-51): the filter cannot
    // decide it (the value is at the size of its error bound), so the exact stage runs. Scaled by
    // s = 2^-k, the product's low bit falls below the smallest subnormal step from k = 512 on, and
    // scaled by 2^k the products overflow from k = 512 on. Before: the sign came out 0 (or from
    // inf - inf). Now the exact stage sees the lost bits and evaluates again on rescaled inputs.
    const Vec2 o(0.0, 0.0);
    for (int k = 0; k <= 540; ++k)
        for (int dir : {-1, 1}) {
            const double s = std::ldexp(1.0, dir * k);
            const Vec2 a = s * Vec2(1.0, 1.0), b = s * Vec2(2.0, 2.0 + std::ldexp(1.0, -51));
            CHECK(pred::orient(o, a, b) == 1);
            CHECK(pred::orient(o, b, a) == -1);
            // Degree 4 and 6: a cocircular lattice square, and its vertex on the disk of radius
            // sqrt(2)/2 exactly (0 signs stay 0 at every scale).
            CHECK(pred::incircle(s * Vec2(0, 0), s * Vec2(1, 0), s * Vec2(1, 1), s * Vec2(0, 1)) == 0);
            CHECK(pred::vertex_in_disk(s * Vec2(0, 0), s * Vec2(1, 0), s * Vec2(0, 1), s * 0.5) == 1);
            CHECK(pred::vertex_in_disk(s * Vec2(0, 0), s * Vec2(2, 0), s * Vec2(0, 2), s * 2.0) == -1);
        }
}

TEST_CASE("inputs spanning more than doubles hold within one test: RangeError, not a guess") {
    // orient(0, a, b) = -2^-1074 2^-1000 < 0 for a = (1, 2^-1074), b = (2^-1000, 0): no scale holds
    // both 1 and that product. Before: 0 (the product underflowed).
    const Vec2 o(0.0, 0.0), a(1.0, std::ldexp(1.0, -1074)), b(std::ldexp(1.0, -1000), 0.0);
    CHECK_THROWS_WITH_AS(pred::orient(o, a, b), doctest::Contains("out of the exact range: an exact test underflowed"),
                         dvoronoi::RangeError);
    // A flag the caller had raised is still raised afterwards, and none is added.
    std::feclearexcept(FE_ALL_EXCEPT);
    std::feraiseexcept(FE_OVERFLOW);
    CHECK_THROWS_AS(pred::orient(o, a, b), dvoronoi::RangeError);
    CHECK(std::fetestexcept(FE_OVERFLOW) != 0);
    std::feclearexcept(FE_ALL_EXCEPT);
    CHECK(pred::orient(o, Vec2(1, 1), Vec2(2, 2 + std::ldexp(1.0, -51))) == 1);
    CHECK(std::fetestexcept(FE_UNDERFLOW | FE_OVERFLOW) == 0);
}
