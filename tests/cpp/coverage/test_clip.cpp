// coverage/clip.hpp and coverage/cell_moments.hpp: clipped limited cells against an independent
// polygon clip of the densified cell (Sutherland-Hodgman), closed forms for a disk cut by a line, and
// the quadrature rule against the exact uniform moments.
#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/coverage/cell_moments.hpp"
#include "dvoronoi/coverage/clip.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace dvoronoi;

namespace {

const double kPi = 3.14159265358979323846;

std::vector<Piece> local_pieces(const LimitedCell& c) {
    std::vector<Piece> out = c.pieces;
    for (Piece& p : out) p.start -= c.center;
    return out;
}

/// The cell as a polygon: arcs replaced by `k` chords per radian (inscribed, so area is slightly low).
std::vector<Vec2> densify(const std::vector<Piece>& cell, double R, int per_radian) {
    std::vector<Vec2> poly;
    for (const Piece& p : cell) {
        poly.push_back(p.start);
        if (p.neighbor != kArc) continue;
        const double a0 = std::atan2(p.start.y(), p.start.x());
        const int m = std::max(1, static_cast<int>(std::ceil(p.arc_span * per_radian)));
        for (int j = 1; j < m; ++j) {
            const double a = a0 + p.arc_span * j / m;
            poly.push_back(Vec2(R * std::cos(a), R * std::sin(a)));
        }
    }
    return poly;
}

/// Sutherland-Hodgman clip of a polygon by {x : n.x <= h}.
std::vector<Vec2> clip_polygon(const std::vector<Vec2>& poly, const Vec2& n, double h) {
    std::vector<Vec2> out;
    for (std::size_t k = 0; k < poly.size(); ++k) {
        const Vec2& a = poly[k];
        const Vec2& b = poly[(k + 1) % poly.size()];
        const double sa = n.dot(a) - h, sb = n.dot(b) - h;
        if (sa <= 0) out.push_back(a);
        if ((sa <= 0) != (sb <= 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
    }
    return out;
}

double polygon_area(const std::vector<Vec2>& p, Vec2* centroid = nullptr) {
    double a = 0, cx = 0, cy = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
        const Vec2& u = p[k];
        const Vec2& v = p[(k + 1) % p.size()];
        const double c = u.x() * v.y() - u.y() * v.x();
        a += c / 2;
        cx += (u.x() + v.x()) * c / 6;
        cy += (u.y() + v.y()) * c / 6;
    }
    if (centroid) *centroid = a != 0 ? Vec2(cx / a, cy / a) : Vec2::Zero();
    return a;
}

}  // namespace

TEST_CASE("a full disk cut by one line: circular segment closed form") {
    const double R = 2.0;
    for (double h : {0.0, 0.3, 1.0, 1.7, 1.999}) {
        for (double theta : {0.0, 0.7, kPi / 2, 2.5, -1.0}) {
            const std::vector<Piece> disk{Piece{kArc, Vec2(R, 0), 2 * kPi}};
            std::vector<Piece> out;
            const Vec2 n(std::cos(theta), std::sin(theta));
            detail::clip_to_halfplane(disk, R, n, h, out);
            const Moments m = uniform_moments(out, R);
            const double alpha = std::acos(h / R);
            const double cut = R * R * (alpha - std::sin(alpha) * std::cos(alpha));  // removed segment
            CHECK(m.mass == doctest::Approx(kPi * R * R - cut).epsilon(1e-13));
            // The first moment of the removed segment is 2/3 (R sin alpha)^3 along n.
            const double seg_first = 2.0 / 3.0 * std::pow(R * std::sin(alpha), 3);
            CHECK((m.first + seg_first * n).norm() < 1e-12 * R * R * R);
            CHECK(out.size() == 2);
            int walls = 0;
            for (const Piece& p : out) walls += p.neighbor == kWall;
            CHECK(walls == 1);
        }
    }
}

TEST_CASE("clipped random cells equal a polygon clip of the densified cell") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0), ang(-kPi, kPi), hd(0.0, 1.2);
    const double R = 1.0;
    int cut = 0;
    for (int trial = 0; trial < 400; ++trial) {
        Points others(1 + static_cast<int>(rng() % 7), 2);
        for (Eigen::Index j = 0; j < others.rows(); ++j) others.row(j) << 2.2 * u(rng), 2.2 * u(rng);
        const LimitedCell cell = limited_cell(Vec2::Zero(), others, R);
        std::vector<Piece> pieces = local_pieces(cell), out, scratch;
        std::vector<Vec2> poly = densify(pieces, R, 20000);
        // Up to three random half-planes through or near the disk (the agent stays inside: h >= 0).
        const int lines = 1 + static_cast<int>(rng() % 3);
        for (int l = 0; l < lines; ++l) {
            const double t = ang(rng), h = hd(rng);
            const Vec2 n(std::cos(t), std::sin(t));
            detail::clip_to_halfplane(pieces, R, n, h, out);
            pieces.swap(out);
            poly = clip_polygon(poly, n, h);
        }
        Vec2 pc;
        const double pa = polygon_area(poly, &pc);
        const Moments m = uniform_moments(pieces, R);
        // Densification with 20000 chords per radian loses at most ~ arc length * R / (8 * 20000^2).
        CHECK(m.mass == doctest::Approx(pa).epsilon(1e-7));
        if (pa > 1e-6) CHECK((m.centroid(Vec2::Zero()) - pc).norm() < 1e-7);
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            if (pieces[k].neighbor == kArc) {
                CHECK(std::fabs(pieces[k].start.norm() - R) < 1e-12);
                CHECK(pieces[k].arc_span > 0.0);
            }
        }
        cut += pieces.size() != cell.pieces.size();
    }
    CHECK(cut > 100);  // the lines really cut most cells
}

TEST_CASE("clip_cell skips environment edges farther than R and keeps the cell") {
    const ConvexPolygon box = ConvexPolygon::box(-10, -10, 10, 10);
    Points others(2, 2);
    others << 1.0, 0.2, -0.5, 1.1;
    const LimitedCell cell = limited_cell(Vec2::Zero(), others, 1.0);
    std::vector<Piece> out, scratch;
    clip_cell(local_pieces(cell), Vec2::Zero(), 1.0, box, out, scratch);
    CHECK(out.size() == cell.pieces.size());
    CHECK(uniform_moments(out, 1.0).mass == doctest::Approx(cell.measures().area).epsilon(1e-14));
}

TEST_CASE("uniform moments agree with limited_cell's own measures") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int trial = 0; trial < 200; ++trial) {
        Points others(1 + static_cast<int>(rng() % 9), 2);
        for (Eigen::Index j = 0; j < others.rows(); ++j) others.row(j) << u(rng), u(rng);
        const LimitedCell cell = limited_cell(Vec2::Zero(), others, 1.0);
        const Moments m = uniform_moments(local_pieces(cell), 1.0);
        CHECK(m.mass == doctest::Approx(cell.measures().area).epsilon(1e-13));
        CHECK((m.centroid(Vec2::Zero()) - cell.measures().centroid).norm() < 1e-13);
        CHECK(m.perimeter == doctest::Approx(cell.measures().perimeter).epsilon(1e-13));
    }
}

TEST_CASE("quadrature reproduces the exact moments and integrates polynomials exactly") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-2.0, 2.0), ang(-kPi, kPi), hd(0.0, 0.9);
    for (int order : {3, 6, 9}) {
        const GaussRule g(order);
        for (int trial = 0; trial < 100; ++trial) {
            Points others(1 + static_cast<int>(rng() % 8), 2);
            for (Eigen::Index j = 0; j < others.rows(); ++j) others.row(j) << u(rng), u(rng);
            const LimitedCell cell = limited_cell(Vec2::Zero(), others, 1.0);
            std::vector<Piece> pieces = local_pieces(cell), out;
            const double t = ang(rng);
            detail::clip_to_halfplane(pieces, 1.0, Vec2(std::cos(t), std::sin(t)), hd(rng), out);
            const Moments m = uniform_moments(out, 1.0);
            double mass = 0, polar = 0;
            Vec2 first = Vec2::Zero();
            std::size_t count = 0;
            quadrature_nodes(out, 1.0, g, [&](const Vec2& q, double w) {
                mass += w;
                first += w * q;
                polar += w * q.squaredNorm();
                ++count;
            });
            CHECK(count == quadrature_size(out, g));
            // Mass and polar moment are constant in the angle and polynomial in the radius: exact.
            CHECK(mass == doctest::Approx(m.mass).epsilon(1e-12));
            // The first moment is cos/sin in the angle: Gauss-Legendre error ~ (pi/8)^(2n+1) / (2n)!.
            CHECK((first - m.first).norm() < (order >= 6 ? 1e-12 : 1e-6));
            CHECK(polar == doctest::Approx(m.polar).epsilon(1e-12));
        }
    }
}

TEST_CASE("bad environments are named errors") {
    CHECK_THROWS_AS(ConvexPolygon::box(1, 0, 0, 1), InputError);
    CHECK_THROWS_AS(ConvexPolygon({Vec2(0, 0), Vec2(1, 0)}), InputError);
    // A straight-on vertex is dropped (the same reading as the exact cells' bounds); going back along
    // an edge is a spike, three collinear vertices are no polygon.
    CHECK(ConvexPolygon({Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(0, 1)}).vertices() ==
          ConvexPolygon({Vec2(0, 0), Vec2(2, 0), Vec2(0, 1)}).vertices());
    CHECK_THROWS_WITH_AS(ConvexPolygon({Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(0, 1)}),
                         doctest::Contains("turns back on itself at vertex 1"), InputError);
    CHECK_THROWS_AS(ConvexPolygon({Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)}), InputError);
    CHECK_THROWS_AS(ConvexPolygon({Vec2(0, 0), Vec2(2, 0), Vec2(1, 0.2), Vec2(2, 2), Vec2(0, 2)}),
                    InputError);
    const ConvexPolygon cw({Vec2(0, 0), Vec2(0, 1), Vec2(1, 1), Vec2(1, 0)});  // clockwise: reversed
    CHECK(cw.area() == doctest::Approx(1.0));
    CHECK(cw.contains(Vec2(0.5, 0.5)));
    CHECK(cw.contains(Vec2(1.0, 0.5)));
    CHECK_FALSE(cw.contains(Vec2(1.0 + 1e-16 * 4, 0.5)));
    // A closed ring is the open polygon (the repeated last vertex is dropped).
    const ConvexPolygon ring({Vec2(0, 0), Vec2(2, 0), Vec2(2, 1), Vec2(0, 1), Vec2(0, 0)});
    CHECK(ring.size() == 4);
    CHECK(ring.area() == doctest::Approx(2.0));
}

TEST_CASE("an agent on a wall keeps a half disk, in a corner a quarter disk (cuts through the arc's start)") {
    const double R = 0.3;
    const std::vector<Piece> disk{Piece{kArc, Vec2(R, 0), 2 * kPi}};
    std::vector<Piece> out, scratch;
    // Walls through the agent in every direction, including through the arc's start point (R, 0).
    for (double theta : {-kPi / 2, 0.0, kPi / 2, kPi, 0.3, -2.0}) {
        const Vec2 n(std::cos(theta), std::sin(theta));
        detail::clip_to_halfplane(disk, R, n, 0.0, out);
        const Moments m = uniform_moments(out, R);
        CHECK(m.mass == doctest::Approx(kPi * R * R / 2).epsilon(1e-14));
        CHECK((m.first + 2.0 / 3.0 * R * R * R * n).norm() < 1e-15);
    }
    const ConvexPolygon box = ConvexPolygon::box(0, 0, 1, 1);
    for (const Vec2& corner : {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}) {
        clip_cell(disk, corner, R, box, out, scratch);
        const Moments m = uniform_moments(out, R);
        CHECK(m.mass == doctest::Approx(kPi * R * R / 4).epsilon(1e-14));
        const Vec2 inward = (Vec2(0.5, 0.5) - corner) * 2.0;  // (+-1, +-1)
        CHECK((m.centroid(corner) - corner - 4 * R / (3 * kPi) * inward).norm() < 1e-15);
        CHECK(out.size() == 3);
    }
}
