// A limited cell clipped to a convex environment: V_i ∩ B(p_i, R) ∩ Q (or a heterogeneous team's power
// cell ∩ B(p_i, R_i) ∩ Q: the same convex cycle of edges and arcs of the agent's circle, which need not
// contain the agent; nothing below assumes it does).
//
// The cell is a convex cycle of edges and arcs given relative to its agent; each half-plane of Q that
// reaches into the disk (distance from the agent below R) cuts it. A convex region meets a line in
// at most one chord, so each cut keeps one connected run of the boundary and closes it with one
// straight "wall" piece along the environment's edge. Arcs are cut where the circle meets the line
// (angle theta_n ± acos(h / R)), so arcs stay exact arcs and the measures stay exact.
//
// Accuracy: the cut points are constructed in floating point (one division or one acos per cut);
// which vertices lie inside a half-plane is decided once per vertex from the same rounded values, so
// the cycle is always consistent. Pieces shorter than 1e-13 R left by cuts through a vertex are
// dropped. Points on the circle carry ~1e-16 R of rounding, so when the disk holds all of Q (R may be
// a billion times Q's size) the cell is not cut: clip_environment cuts Q by the cell's bisectors.
#pragma once

#include "dvoronoi/core/cell.hpp"
#include "dvoronoi/coverage/environment.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dvoronoi {

/// Piece::neighbor of a straight piece on the environment's boundary (a "wall"). Walls have
/// arc_span 0, so code that tells arcs by `arc_span > 0` (plots, SVG) draws them as straight edges;
/// Piece::is_arc() must not be used on clipped cells.
inline constexpr Index kWall = -2;

namespace detail {

inline constexpr double kTwoPiC = 6.283185307179586476925286766559;

inline double wrap_angle(double a) {
    a = std::fmod(a, kTwoPiC);
    return a < 0.0 ? a + kTwoPiC : a;
}

/// `in` (pieces relative to the agent, circle radius R) ∩ {x : n.x <= h}, n a unit vector, into `out`.
inline void clip_to_halfplane(const std::vector<Piece>& in, double R, const Vec2& n, double h,
                              std::vector<Piece>& out) {
    out.clear();
    const std::size_t m = in.size();
    if (m == 0) return;
    const double alpha = std::acos(std::clamp(h / R, -1.0, 1.0));
    const double theta_n = std::atan2(n.y(), n.x());
    const auto side = [&](const Vec2& p) { return n.dot(p) - h; };
    const auto circle = [&](double a) { return Vec2(R * std::cos(a), R * std::sin(a)); };
    bool have_exit = false;
    Vec2 exit_pt = Vec2::Zero();
    const auto emit = [&](Index nb, const Vec2& s, double span) { out.push_back(Piece{nb, s, span}); };
    const auto exit_at = [&](const Vec2& x) {
        exit_pt = x;
        have_exit = true;
    };
    const auto enter_at = [&]() {
        if (have_exit) emit(kWall, exit_pt, 0.0);
        have_exit = false;
    };
    // One inside/outside decision per vertex, shared by the two pieces that meet there.
    std::vector<double> s(m);
    for (std::size_t k = 0; k < m; ++k) s[k] = side(in[k].start);

    for (std::size_t k = 0; k < m; ++k) {
        const Piece& p = in[k];
        const Vec2& u = p.start;
        const Vec2& v = in[(k + 1) % m].start;
        const double su = s[k], sv = s[(k + 1) % m];
        const bool in_u = su <= 0.0, in_v = sv <= 0.0;
        if (p.neighbor != kArc) {  // edge or wall: a segment
            if (in_u) {
                emit(p.neighbor, u, 0.0);
                if (!in_v) exit_at(u + (v - u) * (su / (su - sv)));
            } else if (in_v) {
                const Vec2 y = u + (v - u) * (su / (su - sv));
                enter_at();
                emit(p.neighbor, y, 0.0);
            }
            continue;
        }
        // An arc from angle a0 sweeping phi; the circle is outside on (theta_n - alpha, theta_n + alpha).
        const double phi = p.arc_span;
        const double a0 = std::atan2(u.y(), u.x());
        // Offsets from u, counter-clockwise. The vertex decisions above are authoritative: from an
        // inside u the next crossing is an exit, from an outside u an entry; the other crossing
        // follows it after the outside (2 alpha) or inside (2 pi - 2 alpha) run, unwrapped, so a
        // crossing exactly at u lands at the end of a full turn, not at its start.
        const double eps = 1e-12;
        double d_exit, d_entry;
        if (in_u) {
            d_exit = wrap_angle(theta_n - alpha - a0);
            if (d_exit > kTwoPiC - eps) d_exit = 0.0;
            d_entry = d_exit + 2.0 * alpha;
        } else {
            d_entry = wrap_angle(theta_n + alpha - a0);
            if (d_entry > kTwoPiC - eps) d_entry = 0.0;
            d_exit = d_entry + (kTwoPiC - 2.0 * alpha);
        }
        // A single crossing must lie on the arc; rounding may put it a hair beyond its end.
        const auto on_arc = [&](double d) { return std::min(d, phi); };
        const auto at = [&](double d) { return d <= 0.0 ? u : (d >= phi ? v : circle(a0 + d)); };
        if (in_u && in_v) {
            if (alpha > 0.0 && d_entry <= phi + eps) {  // dips out and back in
                d_entry = std::min(d_entry, phi);
                d_exit = std::min(d_exit, d_entry);
                emit(kArc, u, d_exit);
                exit_at(at(d_exit));
                const Vec2 y = at(d_entry);
                enter_at();
                emit(kArc, y, phi - d_entry);
            } else {
                emit(kArc, u, phi);
            }
        } else if (in_u) {
            const double t = on_arc(d_exit);
            emit(kArc, u, t);
            exit_at(at(t));
        } else if (in_v) {
            const double t = on_arc(d_entry);
            const Vec2 y = at(t);
            enter_at();
            emit(kArc, y, phi - t);
        } else if (alpha > 0.0 && d_exit <= phi + eps) {  // comes in and goes out again
            d_exit = std::min(d_exit, phi);
            const Vec2 y = at(d_entry);
            enter_at();
            emit(kArc, y, d_exit - d_entry);
            exit_at(at(d_exit));
        }
    }
    // An exit with no entry after it: the entry was before the first emitted piece, which starts there.
    if (have_exit && !out.empty()) emit(kWall, exit_pt, 0.0);
    if (have_exit && out.empty()) out.clear();

    // Drop the zero-length pieces that cuts through a vertex leave.
    const double tol = 1e-13 * R;
    for (bool changed = true; changed && out.size() > 1;) {
        changed = false;
        for (std::size_t k = 0; k < out.size() && out.size() > 1; ++k) {
            const Vec2& a = out[k].start;
            const Vec2& b = out[(k + 1) % out.size()].start;
            const bool tiny = out[k].neighbor == kArc ? out[k].arc_span <= 1e-13 : (b - a).norm() <= tol;
            if (tiny && (b - a).norm() <= tol) {
                out.erase(out.begin() + static_cast<std::ptrdiff_t>(k));
                changed = true;
            }
        }
    }
    // Consecutive arcs (a cut that removed everything between them) are one arc.
    for (std::size_t k = 0; out.size() > 1 && k < out.size();) {
        const std::size_t nx = (k + 1) % out.size();
        if (out[k].neighbor == kArc && out[nx].neighbor == kArc) {
            out[k].arc_span = std::min(out[k].arc_span + out[nx].arc_span, kTwoPiC);
            out.erase(out.begin() + static_cast<std::ptrdiff_t>(nx));
            if (nx < k) --k;
        } else {
            ++k;
        }
    }
    if (out.size() == 1 && out[0].neighbor != kArc) out.clear();  // a degenerate sliver
}

}  // namespace detail

/// Does the disk B(center, R) hold all of `env`? Decided with a margin of 1e-12 R^2: a disk that
/// nearly touches a corner counts as not holding it (clip_cell then cuts its arcs, accurate there).
inline bool disk_holds(const ConvexPolygon& env, const Vec2& center, double R) {
    const double r2 = R * R * (1.0 - 1e-12);
    for (const Vec2& v : env.vertices())
        if (!((v - center).squaredNorm() < r2)) return false;
    return true;
}

/// V_i ∩ Q for a disk that holds all of `env` (see disk_holds): `env` (relative to `center`) cut by
/// the bisector of every neighbour in `neighbors` (positions relative to `center`; pass the cell's edge
/// neighbours), into `out`. Pieces are walls (kWall) and edges named by the neighbour whose bisector
/// cut them (Sutherland-Hodgman, one decision per vertex; a side leaving a vertex that lies exactly on
/// the bisector runs along it). Nothing here is farther than Q's extent from the agent, whereas the
/// cell's arcs at radius R >> |Q| would carry a rounding error of ~1e-16 R into every cut. Pieces
/// shorter than 1e-13 of the cell's extent are dropped, as clip_cell drops them.
/// With `shift` (one per neighbour, R^2 - R_j^2: heterogeneous teams) the cuts are the radical axes
/// q.a <= (|a|^2 + shift_j) / 2 of the power cell instead of the bisectors.
/// \note Thread-safe.
inline void clip_environment(const ConvexPolygon& env, const Vec2& center, const std::vector<detail::Candidate>& neighbors,
                             std::vector<Piece>& out, std::vector<Piece>& scratch,
                             const std::vector<double>* shift = nullptr) {
    out.clear();
    for (const Vec2& v : env.vertices()) out.push_back(Piece{kWall, v - center, 0.0});
    for (std::size_t t = 0; t < neighbors.size(); ++t) {
        const detail::Candidate& q = neighbors[t];
        const Vec2& a = q.p;
        const double h = shift ? 0.5 * (a.squaredNorm() + (*shift)[t]) : 0.5 * a.squaredNorm();
        scratch.clear();
        const std::size_t m = out.size();
        for (std::size_t k = 0; k < m; ++k) {
            const Vec2& u = out[k].start;
            const Vec2& v = out[(k + 1) % m].start;
            const double fu = u.dot(a) - h, fv = v.dot(a) - h;
            if (fu <= 0.0) scratch.push_back(Piece{fu == 0.0 && fv > 0.0 ? q.id : out[k].neighbor, u, 0.0});
            if ((fu < 0.0 && fv > 0.0) || (fu > 0.0 && fv < 0.0))  // leaving: along the bisector
                scratch.push_back(Piece{fu < 0.0 ? q.id : out[k].neighbor, u + (v - u) * (fu / (fu - fv)), 0.0});
        }
        out.swap(scratch);
        if (out.size() < 3) {
            out.clear();
            return;
        }
    }
    double extent = 0.0;
    for (const Piece& p : out) extent = std::max(extent, p.start.norm());
    const double tol = 1e-13 * extent;
    for (std::size_t k = 0; k < out.size() && out.size() > 1;) {
        if ((out[(k + 1) % out.size()].start - out[k].start).norm() <= tol)
            out.erase(out.begin() + static_cast<std::ptrdiff_t>(k));
        else
            ++k;
    }
    if (out.size() < 3) out.clear();
}

/// The cell `local` (pieces relative to `center`, circle radius R) clipped to `env`, into `out`
/// (relative to `center` too). Walls carry neighbor kWall. `scratch` is reused between calls.
/// Edges of `env` at distance >= R from the center cannot cut the disk and are skipped, so a cell far
/// from the boundary costs one distance test per environment edge.
/// \note The center must lie in `env` (the Lloyd driver keeps agents there); thread-safe.
inline void clip_cell(const std::vector<Piece>& local, const Vec2& center, double R,
                      const ConvexPolygon& env, std::vector<Piece>& out, std::vector<Piece>& scratch) {
    out = local;
    const std::size_t n = env.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& nrm = env.normal(k);
        const double h = nrm.dot(env.vertices()[k] - center);
        if (h >= R) continue;
        detail::clip_to_halfplane(out, R, nrm, h, scratch);
        out.swap(scratch);
        if (out.empty()) return;
    }
}

}  // namespace dvoronoi
