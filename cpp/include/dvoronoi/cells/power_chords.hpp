// The step both generalised chord algorithms (cells/power_boundary_scan.hpp, cells/power_rcvc.hpp)
// share with the power-cell clipping (cells/power_cell.hpp), for one agent c with radius r of a
// heterogeneous team (docs/spec.md, heterogeneous teams): the chords of c's circle cut by the radical
// axes, their order by the direction of the axes' normals, the exact tests the scan and the walk make
// on them, the check that a cycle of chords is the cell, and the assembly of a cell from that cycle.
//
// What changes from the equal-radius bisectors (cells/bisectors.hpp): c need not lie in its own cell.
// The half-plane of agent j is H_j = {2 a_j.x <= s_j} (core/power_predicates.hpp); its outward normal
// is a_j whatever the sign of s_j, so the cell's edges still come in the counter-clockwise order of
// the directions a_j, and the chords are still chords of c's own circle. But "c's side" of a chord is
// no longer the cell's side (s_j < 0: j's disk covers c), so
//   - the sort starts from the nearest radical axis (smallest s_j / |a_j|, signed), which bounds the
//     cell when c is strictly inside every H_j (its foot lies in the cell: Boundary Scan's Lemma 1);
//   - of parallel axes with the same normal the nearer one bounds (not the nearer agent); an
//     antiparallel axis bounds nothing or leaves nothing;
//   - a chord that another cuts away may mean an empty cell rather than a redundant chord;
//   - when c is not strictly inside its cell no chord is known to bound it in advance: the algorithms
//     start again from other chords until power_cycle_is_cell accepts the result (exact), and report
//     the cell empty when no start is left (RCVC tries every kept chord; Boundary Scan only those
//     that every scan so far kept, cells/power_boundary_scan.hpp).
#pragma once

#include "dvoronoi/cells/bisectors.hpp"  // ScanEntry
#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/core/accurate.hpp"
#include "dvoronoi/core/cell.hpp"
#include "dvoronoi/core/power_predicates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace dvoronoi::detail {

inline constexpr double kPowerPi = 3.14159265358979323846;

/// A line in double-double: a = p - c exactly (two_sum), s rounded once per operation (about 2^-104
/// of its terms' sizes `ps`).
struct DDLine {
    DD ax, ay, s;
    double ps;
};

inline DDLine dd_line(const pred::power::Frame& f, const pred::power::WLine& l) {
    const DD r = dd(f.r);
    if (l.box >= 0) {
        const DD zero = dd(0.0);
        const DD s = r * r * 4.0;
        const double ps = 4.0 * f.r * f.r;
        switch (l.box) {
            case 0: return {r, zero, s, ps};
            case 1: return {zero, r, s, ps};
            case 2: return {-r, zero, s, ps};
            default: return {zero, -r, s, ps};
        }
    }
    DD ax, ay;
    two_sum(l.p.x(), -f.c.x(), ax.hi, ax.lo);
    two_sum(l.p.y(), -f.c.y(), ay.hi, ay.lo);
    const DD n2 = ax * ax + ay * ay, R2 = dd(l.R) * dd(l.R);
    return {ax, ay, n2 + r * r - R2, n2.hi + f.r * f.r + l.R * l.R};
}

/// The point x_jk (relative to c) as double-double. From double-double line data when the
/// denominator D_jk keeps 40 of its bits (then each coordinate is within about 2^-60 R of the exact
/// one: |M| / |D| <= 2^40 R-sized terms carry 2^-100 relative errors), else from exact expansions
/// of M_jk and D_jk rounded once.
inline DDPoint power_vertex(const pred::power::Frame& f, const pred::power::WLine& j, const pred::power::WLine& k) {
    using pred::power::line;
    const DDLine A = dd_line(f, j), B = dd_line(f, k);
    const DD D = A.ax * B.ay - A.ay * B.ax;
    const double pD = std::fabs(A.ax.hi * B.ay.hi) + std::fabs(A.ay.hi * B.ax.hi);
    if (std::fabs(D.hi) >= 0x1p-40 * pD && pD > 1e-250 && pD < 1e250) {
        const DD d2 = D * 2.0;
        return {(A.s * B.ay - B.s * A.ay) / d2, (B.s * A.ax - A.s * B.ax) / d2};
    }
    const auto Ae = line<Expansion>(f, j), Be = line<Expansion>(f, k);
    const Expansion mx = Ae.s * Be.ay - Be.s * Ae.ay, my = Be.s * Ae.ax - Ae.s * Be.ax;
    const Expansion De = Ae.ax * Be.ay - Ae.ay * Be.ax;
    const DD d2 = to_dd(De) * 2.0;
    return {to_dd(mx) / d2, to_dd(my) / d2};
}

/// The chord end e_j^sigma (relative to c): (s a + sigma perp(a) sqrt(C4)) / (2 |a|^2). In
/// double-double when C4 keeps 40 of its bits, else with C4 from exact expansions.
inline DDPoint power_chord_end(const pred::power::Frame& f, const pred::power::WLine& j, int sigma) {
    using pred::power::line;
    const DDLine A = dd_line(f, j);
    const DD n2 = A.ax * A.ax + A.ay * A.ay;
    DD c4 = dd(f.r) * dd(f.r) * n2 * 4.0 - A.s * A.s;
    const double pc4 = 4.0 * f.r * f.r * n2.hi + A.ps * A.ps;
    if (!(c4.hi >= 0x1p-40 * pc4) || !(pc4 > 1e-250 && pc4 < 1e250)) {
        const auto Ae = line<Expansion>(f, j);
        const Expansion r = Expansion(f.r);
        c4 = to_dd(Expansion(4.0) * r * r * (Ae.ax * Ae.ax + Ae.ay * Ae.ay) - Ae.s * Ae.s);
    }
    const DD root = sqrt(c4), den = n2 * 2.0, sg = dd(static_cast<double>(sigma));
    return {(A.s * A.ax - sg * A.ay * root) / den, (A.s * A.ay + sg * A.ax * root) / den};
}

/// Area, centroid (relative to c) and perimeter of a closed cycle of pieces given relative to c, by
/// Green's theorem: segments exactly, arcs of radius r through the closed forms of x^2 dy and y^2 dx.
inline CellMeasures power_measures(const std::vector<Vec2>& v, const std::vector<char>& arc,
                                   const std::vector<double>& span, double r) {
    double a2 = 0.0, mx = 0.0, my = 0.0, per = 0.0;
    const std::size_t n = v.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& u = v[k];
        const Vec2& w = v[(k + 1) % n];
        if (arc[k]) {
            a2 += r * r * span[k];
            mx += (r * r * w.y() - w.y() * w.y() * w.y() / 3.0) - (r * r * u.y() - u.y() * u.y() * u.y() / 3.0);
            my += (-r * r * w.x() + w.x() * w.x() * w.x() / 3.0) - (-r * r * u.x() + u.x() * u.x() * u.x() / 3.0);
            per += r * span[k];
        } else {
            a2 += u.x() * w.y() - u.y() * w.x();
            mx += (w.y() - u.y()) * (u.x() * u.x() + u.x() * w.x() + w.x() * w.x()) / 3.0;
            my -= (w.x() - u.x()) * (u.y() * u.y() + u.y() * w.y() + w.y() * w.y()) / 3.0;
            per += (w - u).norm();
        }
    }
    CellMeasures m;
    m.area = 0.5 * a2;
    m.perimeter = per;
    // The moments above are twice the integrals of x and y.
    if (m.area > 0.0) m.centroid = Vec2(0.5 * mx / m.area, 0.5 * my / m.area);
    return m;
}


/// Step 1, exact: appends to (lines, fast, ids) the agents whose radical axis cuts the open disk
/// B(c, r) (a chord); drops those whose axis misses it on the far side. Returns false when the cell
/// is empty: an agent at c with a larger radius, or a closed disk outside an open half-plane.
/// `inside`: c lies strictly inside every chord's half-plane (then it lies in its cell).
/// \throws CoincidentError when a candidate lies at c with the same radius (index `self` names c).
inline bool collect_chords(const pred::power::Frame& f, const std::vector<Candidate>& cand, const std::vector<double>& cand_r,
                           Index self, std::vector<pred::power::WLine>& lines, std::vector<pred::power::FastLine>& fast,
                           std::vector<Index>& ids, bool& inside) {
    using namespace pred::power;
    bool empty = false;
    inside = true;
    for (std::size_t t = 0; t < cand.size(); ++t) {
        const Vec2& p = cand[t].p;
        const double R = cand_r[t];
        if (p == f.c) {
            if (R == f.r) {
                const Index j = cand[t].id;
                char at[64];
                std::snprintf(at, sizeof at, "(%.17g, %.17g)", f.c.x(), f.c.y());
                const std::string who = self >= 0 ? "points[" + std::to_string(self) + "]" : std::string("center");
                throw CoincidentError(who + " and points[" + std::to_string(j) + "] coincide at " + at +
                                          " with the same radius; their cells are undefined",
                                      self, j);
            }
            if (R > f.r) empty = true;  // the larger disk at the same place holds the cell
            continue;
        }
        WLine l;
        l.p = p;
        l.R = R;
        const FastLine fl = fast_line(f, l);
        const int c4 = chord_sign(f, l, fl);
        if (c4 > 0) {
            lines.push_back(l);
            fast.push_back(fl);
            ids.push_back(cand[t].id);
            if (inside && s_sign(f, l, fl) <= 0) inside = false;
        } else if (s_sign(f, l, fl) <= 0) {
            empty = true;  // the closed disk lies outside the open half-plane: zero area
        }
    }
    return !empty;
}

/// The exact tests on chords (indices into L) that the scan and the walk make, each with the fast
/// path of core/power_predicates.hpp first. Positions along L_j run in the direction perp(a_j) (the
/// counter-clockwise direction of the cell's boundary on it); L_k bounds L_j from above when
/// cross(a_j, a_k) > 0 (the part before x_jk is in H_k), from below when < 0.
struct PowerGeometry {
    const pred::power::Frame& f;
    const std::vector<pred::power::WLine>& L;
    const std::vector<pred::power::FastLine>& F;

    const pred::power::WLine& l(int j) const { return L[static_cast<std::size_t>(j)]; }
    const pred::power::FastLine& fl(int j) const { return F[static_cast<std::size_t>(j)]; }

    /// sign(cross(a_j, a_k)).
    int orient(int j, int k) const {
        const int s = pred::power::fast_cross_sign(fl(j), fl(k));
        return s != 2 ? s : pred::power::cross_sign(f, l(j), l(k));
    }
    /// Position of x_jk along L_j against the chord end e_j^sigma; requires orient(j, k) != 0.
    int vertex_vs_end(int j, int k, int sigma) const {
        return pred::power::position_vs_chord_end(f, l(j), l(j), l(k), sigma, fl(j), fl(j), fl(k));
    }
    /// Does L_j keep a part of positive length of its chord inside H_k? o = orient(j, k).
    bool chord_bound_ok(int j, int k, int o) const {
        if (o > 0) return vertex_vs_end(j, k, -1) > 0;
        if (o < 0) return vertex_vs_end(j, k, +1) < 0;
        return pred::power::foot_side(f, l(j), l(k)) < 0;  // parallel: all of L_j strictly inside, or none
    }
    /// Is x_ji strictly before x_jk along L_j (x_ji strictly inside H_k)? Requires orient(j, i) < 0
    /// and orient(j, k) > 0.
    bool vertex_before(int j, int i, int k) const {
        return pred::power::side_of_vertex(f, l(k), l(j), l(i), fl(k), fl(j), fl(i)) < 0;
    }
    /// Does L_j keep a part of positive length inside the open disk, H_i and H_k?
    bool keeps(int j, int i, int k) const {
        const int oi = orient(j, i), ok = orient(j, k);
        if (!chord_bound_ok(j, i, oi) || !chord_bound_ok(j, k, ok)) return false;
        if (oi != 0 && ok != 0 && (oi > 0) != (ok > 0)) return oi < 0 ? vertex_before(j, i, k) : vertex_before(j, k, i);
        return true;
    }
    /// Consecutive boundary chords j, k meet at x_jk in the closed disk (else an arc joins them).
    bool meets(int j, int k) const { return orient(j, k) > 0 && vertex_vs_end(j, k, +1) <= 0; }
    /// Side of the chord end e_m^sigma w.r.t. L_j (-1 strictly inside H_j).
    int endpoint_side(int m, int sigma, int j) const { return pred::power::chord_end_side(f, l(m), sigma, l(j)); }
    /// Is x_jk strictly after the chord start e_j^- along L_j? Requires orient(j, k) != 0.
    bool after_chord_start(int j, int k) const { return vertex_vs_end(j, k, -1) > 0; }
};

/// The chord bound of Boundary Scan's step 2 (cells/boundary_scan.hpp, scan_stack) on radical axes.
inline bool chord_bound_ok(const PowerGeometry& g, int j, int k, int o) { return g.chord_bound_ok(j, k, o); }

/// Step 2: the chords lines[first..) in the counter-clockwise order of their normals a_j, starting
/// from the nearest radical axis (smallest signed s_j / |a_j|). Of axes with the same normal only the
/// nearest is kept (on one line, coaxal disks: the farther agent, which holds the far side).
inline void sort_chords(const PowerGeometry& g, std::size_t first, std::vector<int>& order, std::vector<char>& half) {
    using namespace pred::power;
    order.clear();
    const int m = static_cast<int>(g.L.size());
    if (static_cast<int>(first) >= m) return;
    int s = static_cast<int>(first);
    for (int j = s + 1; j < m; ++j)
        if (axis_distance_cmp(g.f, g.l(j), g.l(s)) < 0) s = j;
    half.assign(static_cast<std::size_t>(m), 0);
    for (int j = static_cast<int>(first); j < m; ++j) {
        order.push_back(j);
        if (j == s) continue;
        const int o = g.orient(s, j);
        half[static_cast<std::size_t>(j)] = o < 0 || (o == 0 && dot_sign(g.f, g.l(s), g.l(j)) < 0);
    }
    const auto before = [&](int x, int y) {
        const char hx = half[static_cast<std::size_t>(x)], hy = half[static_cast<std::size_t>(y)];
        if (hx != hy) return hx < hy;
        return g.orient(x, y) > 0;
    };
    std::sort(order.begin(), order.end(), before);
    std::size_t w = 0;
    for (std::size_t t = 0; t < order.size(); ++t) {
        const int x = order[t];
        if (w > 0 && !before(order[w - 1], x)) {  // the same normal direction as the last kept
            const int y = order[w - 1];
            int keep_x = -foot_side(g.f, g.l(x), g.l(y));  // x's axis nearer: its foot strictly inside H_y
            if (keep_x == 0) keep_x = farther(g.f, g.l(x), g.l(y));
            if (keep_x > 0) order[w - 1] = x;
            continue;
        }
        order[w++] = x;
    }
    order.resize(w);
}

/// Is the cycle (chords in normal order, `meets` as PowerGeometry::meets) the cell, given that every
/// chord of `all` not in it was discarded by the scan or the walk? Exact: every cycle chord keeps a
/// part between its neighbours (so the cycle bounds a region R of positive area, the intersection of
/// the disk and its half-planes), and R lies in the closed half-plane of every other chord: R's
/// joints do, and no arc of R holds the middle of the cap the chord cuts off (cap_middle_side).
inline bool power_cycle_is_cell(const PowerGeometry& g, const std::vector<int>& all, const std::vector<int>& cycle,
                                const std::vector<char>& meets, std::vector<char>& in_cycle) {
    using namespace pred::power;
    const std::size_t s = cycle.size();
    if (s == 0) return false;
    for (std::size_t t = 0; t < s && s >= 2; ++t)
        if (!g.keeps(cycle[t], cycle[(t + s - 1) % s], cycle[(t + 1) % s])) return false;
    in_cycle.assign(g.L.size(), 0);
    bool arcs = false;
    for (std::size_t t = 0; t < s; ++t) {
        in_cycle[static_cast<std::size_t>(cycle[t])] = 1;
        arcs |= !meets[t];
    }
    for (const int j : all) {
        if (in_cycle[static_cast<std::size_t>(j)]) continue;
        for (std::size_t t = 0; t < s; ++t) {
            const int a = cycle[t], b = cycle[(t + 1) % s];
            if (meets[t]) {
                if (side_of_vertex(g.f, g.l(j), g.l(a), g.l(b), g.fl(j), g.fl(a), g.fl(b)) > 0) return false;
            } else if (g.endpoint_side(a, +1, j) > 0 || g.endpoint_side(b, -1, j) > 0) {
                return false;
            }
        }
        if (!arcs) continue;
        bool cap_outside = false;
        for (std::size_t t = 0; t < s && !cap_outside; ++t) cap_outside = cap_middle_side(g.f, g.l(j), g.l(cycle[t])) > 0;
        if (!cap_outside) return false;
    }
    return true;
}

/// Scratch of the chord algorithms, reused across agents.
struct PowerChordWorkspace {
    std::vector<pred::power::WLine> lines;
    std::vector<pred::power::FastLine> fast;
    std::vector<Index> ids;
    std::vector<int> order, from_start, cycle, kept;
    std::vector<char> half, meets, in_cycle, removed, line_start;
    std::vector<ScanEntry> scan;  // Boundary Scan's stack
    std::vector<Vec2> rel;
    std::vector<char> is_arc;
    std::vector<double> span;
};

/// Resets `out` to the empty cell of c (no pieces, area 0, centroid at c).
inline void power_empty_cell(const Vec2& c, double r, Index candidates, LimitedCell& out) {
    out.center = c;
    out.radius = r;
    out.pieces.clear();
    out.candidates = candidates;
    out.chords_after_check = -1;
    out.measures_ = CellMeasures{};
    out.measures_.centroid = c;
}

/// The whole disk: one arc.
inline void power_full_disk(const Vec2& c, double r, LimitedCell& out) {
    Piece p;
    p.start = c + Vec2(r, 0.0);
    p.arc_span = 2.0 * kPowerPi;
    out.pieces.assign(1, p);
    out.measures_.area = kPowerPi * r * r;
    out.measures_.centroid = c;
    out.measures_.perimeter = 2.0 * kPowerPi * r;
}

/// Step 3: the cell from its boundary chords in counter-clockwise order (`cycle`, indices into L)
/// and, for each t, whether chord cycle[t] meets cycle[t+1] at their vertex (else an arc of the
/// circle joins the exit end of one to the entry end of the other). Vertices and chord ends as
/// power_vertex and power_chord_end state; measures by power_measures.
inline void emit_power_cell(const pred::power::Frame& f, const std::vector<pred::power::WLine>& L,
                            const std::vector<Index>& ids, const std::vector<int>& cycle, const std::vector<char>& meets,
                            LimitedCell& out, std::vector<Vec2>& rel, std::vector<char>& is_arc, std::vector<double>& span) {
    const std::size_t s = cycle.size();
    // The constructions have terms of degree 4 in the radii (the half chord's 4 r^2 |a|^2 - s^2):
    // at radii beyond 2^+-200 they would overflow or underflow, so the frame is then scaled by a power
    // of two near the largest radius (exact) and the results scaled back.
    double big = f.r;
    for (std::size_t t = 0; t < s; ++t) big = std::max(big, L[static_cast<std::size_t>(cycle[t])].R);
    int k = std::abs(std::ilogb(big)) > 200 ? std::ilogb(big) : 0;
    auto down = [&k](const Vec2& v) { return Vec2(std::ldexp(v.x(), -k), std::ldexp(v.y(), -k)); };
    if (k != 0 && !down(f.c).allFinite()) k = 0;  // a frame beyond doubles' range: as it is
    const pred::power::Frame fs{down(f.c), std::ldexp(f.r, -k)};
    const auto line = [&](std::size_t t) {
        pred::power::WLine l = L[static_cast<std::size_t>(cycle[t % s])];
        if (k != 0 && l.box < 0) l.p = down(l.p), l.R = std::ldexp(l.R, -k);
        return l;
    };
    const auto start_of = [&](std::size_t t) {
        const std::size_t tp = (t + s - 1) % s;
        return meets[tp] ? power_vertex(fs, line(tp), line(t)) : power_chord_end(fs, line(t), -1);
    };
    auto up = [k](const Vec2& v) { return Vec2(std::ldexp(v.x(), k), std::ldexp(v.y(), k)); };
    out.pieces.clear();
    rel.clear();  // relative to c, in the scaled frame
    is_arc.clear();
    span.clear();
    for (std::size_t t = 0; t < s; ++t) {
        const Vec2 st = start_of(t).value();
        Piece edge;
        edge.neighbor = ids[static_cast<std::size_t>(cycle[t])];
        edge.start = f.c + up(st);
        out.pieces.push_back(edge);
        rel.push_back(st);
        is_arc.push_back(0);
        span.push_back(0.0);
        if (meets[t]) continue;
        const DDPoint ud = power_chord_end(fs, line(t), +1), wd = start_of(t + 1);
        const Vec2 u = ud.value();
        // The span from the double-double ends (before rounding), so that only an arc shorter than
        // about 2^-100 radians could be mistaken for a full turn; the exact combinatorics already
        // know it has positive length, and counter-clockwise means a in (0, 2 pi].
        const DD cr = ud.x * wd.y - ud.y * wd.x, dt = ud.x * wd.x + ud.y * wd.y;
        double a = std::atan2(cr.hi + cr.lo, dt.hi + dt.lo);
        if (a <= 0.0) a += 2.0 * kPowerPi;
        Piece arc;
        arc.start = f.c + up(u);
        arc.arc_span = a;
        out.pieces.push_back(arc);
        rel.push_back(u);
        is_arc.push_back(1);
        span.push_back(a);
    }
    CellMeasures m = power_measures(rel, is_arc, span, fs.r);
    m.area = std::ldexp(m.area, 2 * k);
    m.perimeter = std::ldexp(m.perimeter, k);
    m.centroid = f.c + up(m.centroid);
    out.measures_ = m;
}

/// Step 1 and the sort of the chord algorithms: ws.lines, ws.fast, ws.ids and ws.order (sorted, the
/// nearest radical axis first). False when that already decides the cell (empty, or the whole disk:
/// `out` holds it). `inside`: c lies strictly inside every chord's half-plane.
inline bool start_chords(const pred::power::Frame& f, const std::vector<Candidate>& cand, const std::vector<double>& cand_r,
                         Index self, LimitedCell& out, PowerChordWorkspace& ws, bool& inside) {
    power_empty_cell(f.c, f.r, static_cast<Index>(cand.size()), out);
    ws.lines.clear();
    ws.fast.clear();
    ws.ids.clear();
    if (!collect_chords(f, cand, cand_r, self, ws.lines, ws.fast, ws.ids, inside)) return false;
    if (ws.lines.empty()) {
        power_full_disk(f.c, f.r, out);
        return false;
    }
    sort_chords(PowerGeometry{f, ws.lines, ws.fast}, 0, ws.order, ws.half);
    return true;
}

/// Runs cycle_from(seq) (RCVC's walk, writing ws.cycle and ws.meets) on `chords` rotated to start at
/// each chord in turn, until the cycle is the cell, and emits it: at once when `inside`
/// (Lemma 1: the first chord bounds the cell), else when power_cycle_is_cell accepts it. When no
/// start is accepted the cell is empty (`out` stays as start_chords left it).
template <class CycleFrom>
void first_accepted_cycle(const PowerGeometry& g, const std::vector<int>& chords, bool inside, PowerChordWorkspace& ws,
                          LimitedCell& out, CycleFrom&& cycle_from) {
    for (std::size_t start = 0; start < chords.size(); ++start) {
        ws.from_start.assign(chords.begin() + static_cast<std::ptrdiff_t>(start), chords.end());
        ws.from_start.insert(ws.from_start.end(), chords.begin(), chords.begin() + static_cast<std::ptrdiff_t>(start));
        cycle_from(ws.from_start);
        if (inside || power_cycle_is_cell(g, chords, ws.cycle, ws.meets, ws.in_cycle)) {
            emit_power_cell(g.f, ws.lines, ws.ids, ws.cycle, ws.meets, out, ws.rel, ws.is_arc, ws.span);
            return;
        }
    }
}

}  // namespace dvoronoi::detail
