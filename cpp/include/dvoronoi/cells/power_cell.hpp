// One agent's cell of a heterogeneous team (docs/spec.md, heterogeneous teams):
// W_i = {q in B(p_i, R_i) : |q - p_i|^2 - R_i^2 <= |q - p_j|^2 - R_j^2 for all j}, the power cell with
// weights R^2 clipped to the agent's own disk.
//
// The exact clipping route (Method::Auto's exact fallback; the generalised Boundary Scan and RCVC are
// cells/power_boundary_scan.hpp and cells/power_rcvc.hpp). Clipping needs no point of the cell known
// in advance, so it handles a cell that does not contain its agent in one pass:
//   1. classify each agent j with an exact test on (s_j, C4_j) (cells/power_chords.hpp): its
//      radical axis misses the disk on the far side (irrelevant), cuts it (a chord), or leaves the
//      disk outside the open half-plane (the cell is empty: zero area, at most a tangent point);
//   2. clip the box |x|,|y| <= 2R_i (which holds the disk) by the half-planes of the chords:
//      Sutherland-Hodgman on a cyclic list of lines, every vertex the meeting of two consecutive lines,
//      its side of a new line an exact degree-4 sign; a clip that leaves no vertex strictly inside
//      means zero area (empty cell);
//   3. intersect each edge of the polygon with the open disk by exact comparisons of positions along
//      its line (degree 8); edges of positive length inside the disk are the cell's edges, and the
//      arcs of the circle join them (emit_power_cell, cells/power_chords.hpp).
// All decisions are exact, so neighbours, empty flags and the order of pieces are the exact ones.
// Cost: O(m k) for m chords and k polygon vertices (k is small: about six in a swarm).
// Constructions: vertices in double-double from the exact differences (from exact expansions where
// a denominator or C4 loses more than 40 bits), then rounded to double: each coordinate within a few
// units in the last place of max(|vertex|, R_i) of the exact vertex; measures are summed in double
// from those vertices (Green's theorem, arcs exact).
#pragma once

#include "dvoronoi/cells/power_boundary_scan.hpp"  // for power_limited_cell's methods
#include "dvoronoi/cells/power_chords.hpp"
#include "dvoronoi/cells/power_rcvc.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace dvoronoi {

namespace detail {

/// Scratch of power_cell, reused across agents.
struct PowerWorkspace {
    std::vector<pred::power::WLine> lines;  ///< 0..3 the box, then the chords
    std::vector<pred::power::FastLine> fast;  ///< the same, rounded (the predicates' fast path)
    std::vector<Index> ids;                 ///< caller's index of each line (-1 for the box)
    std::vector<int> poly, next;            ///< the polygon: cyclic list of lines
    std::vector<int> sides;
    std::vector<pred::power::FastVertex> verts, next_verts;  ///< vertex k: poly[k-1] meets poly[k]
    std::vector<int> origin;                                  ///< during a clip: old edge of next[t], -1 = the new line
    struct Kept {
        std::size_t k;     // polygon edge
        bool from_vertex;  // starts at polygon vertex k (else at the chord's entry end)
        bool to_vertex;    // ends at polygon vertex k + 1 (else at the chord's exit end)
    };
    std::vector<Kept> kept;
    std::vector<int> cycle;
    std::vector<char> meets;
    std::vector<Vec2> rel;
    std::vector<char> is_arc;
    std::vector<double> span;
};

/// The cell of c (radius r) among candidate agents cand with radii cand_r (any agents: the exact
/// classification ignores those whose radical axis misses the disk). Writes `out`; an empty cell has
/// no pieces, area 0 and its centroid at c.
/// \throws CoincidentError when a candidate lies at c with the same radius (index `self` names c).
inline void power_cell(const Vec2& c, double r, const std::vector<Candidate>& cand, const std::vector<double>& cand_r,
                       LimitedCell& out, PowerWorkspace& ws, Index self = -1) {
    using namespace pred::power;
    const Frame f{c, r};
    power_empty_cell(c, r, static_cast<Index>(cand.size()), out);
    ws.lines.clear();
    ws.fast.clear();
    ws.ids.clear();
    for (int b = 0; b < 4; ++b) {
        WLine l;
        l.box = b;
        ws.lines.push_back(l);
        ws.fast.push_back(fast_line(f, l));
        ws.ids.push_back(-1);
    }
    bool center_inside = true;  // c strictly inside every chord's half-plane
    if (!collect_chords(f, cand, cand_r, self, ws.lines, ws.fast, ws.ids, center_inside)) return;

    // 2. Clip the box by the chords' half-planes.
    auto& poly = ws.poly;
    auto& next = ws.next;
    auto& sides = ws.sides;
    poly.assign({0, 1, 2, 3});
    const auto& L = ws.lines;
    const auto& F = ws.fast;
    auto& verts = ws.verts;
    auto& origin = ws.origin;
    const auto vertex_of = [&](int j, int k) { return fast_vertex(F[static_cast<std::size_t>(j)], F[static_cast<std::size_t>(k)]); };
    verts.clear();
    for (std::size_t k = 0; k < 4; ++k) verts.push_back(vertex_of(poly[(k + 3) % 4], poly[k]));
    for (int l = 4; l < static_cast<int>(L.size()); ++l) {
        const std::size_t n = poly.size();
        const auto ll = static_cast<std::size_t>(l);
        sides.resize(n);
        bool any_in = false, any_out = false;
        for (std::size_t k = 0; k < n; ++k) {  // vertex k starts edge k: poly[k-1] meets poly[k]
            const auto j = static_cast<std::size_t>(poly[(k + n - 1) % n]), q = static_cast<std::size_t>(poly[k]);
            sides[k] = side_of_vertex(f, L[ll], L[j], L[q], F[ll], verts[k]);
            any_in |= sides[k] < 0;
            any_out |= sides[k] > 0;
        }
        if (!any_in) return;  // nothing strictly inside: zero area
        if (!any_out) {
            // Unchanged; an edge with both ends on L_l lies on it (coaxal disks): the farther agent
            // holds the far side, so it is the neighbour across that edge.
            for (std::size_t k = 0; k < n; ++k)
                if (sides[k] == 0 && sides[(k + 1) % n] == 0 && farther(f, L[ll], L[static_cast<std::size_t>(poly[k])]) > 0) {
                    poly[k] = l;
                    verts[k] = vertex_of(poly[(k + n - 1) % n], l);
                    verts[(k + 1) % n] = vertex_of(l, poly[(k + 1) % n]);
                }
            continue;
        }
        next.clear();
        origin.clear();
        for (std::size_t k = 0; k < n; ++k) {
            const int s0 = sides[k], s1 = sides[(k + 1) % n];
            if (std::min(s0, s1) < 0) {
                next.push_back(poly[k]);
                origin.push_back(static_cast<int>(k));
            }
            if (s0 < 0 && s1 >= 0) {  // the exit edge: L_l follows it
                next.push_back(l);
                origin.push_back(-1);
            }
        }
        // A vertex between two old consecutive edges is an old vertex; the two at L_l are new.
        auto& nv = ws.next_verts;
        nv.clear();
        const std::size_t m = next.size();
        for (std::size_t t = 0; t < m; ++t) {
            const int o = origin[t], op = origin[(t + m - 1) % m];
            if (o >= 0 && op >= 0 && static_cast<std::size_t>(op) == (static_cast<std::size_t>(o) + n - 1) % n)
                nv.push_back(verts[static_cast<std::size_t>(o)]);
            else
                nv.push_back(vertex_of(next[(t + m - 1) % m], next[t]));
        }
        poly.swap(next);
        verts.swap(nv);
    }

    // 3. The polygon's edges inside the open disk, and the arcs between them.
    const std::size_t n = poly.size();
    using Kept = PowerWorkspace::Kept;
    auto& kept = ws.kept;
    kept.clear();
    for (std::size_t k = 0; k < n; ++k) {
        const int t = poly[k];
        if (t < 4) continue;  // box sides never meet the disk
        const auto it = static_cast<std::size_t>(t), ip = static_cast<std::size_t>(poly[(k + n - 1) % n]),
                   in = static_cast<std::size_t>(poly[(k + 1) % n]);
        const WLine &Lt = L[it], &Lp = L[ip], &Ln = L[in];
        const FastLine &Ft = F[it], &Fp = F[ip], &Fn = F[in];
        // Positive length inside the open disk: starts before the exit end, ends after the entry end.
        if (position_vs_chord_end(f, Lt, Lp, Lt, +1, Ft, Fp, Ft) >= 0) continue;
        if (position_vs_chord_end(f, Lt, Lt, Ln, -1, Ft, Ft, Fn) <= 0) continue;
        kept.push_back({k, position_vs_chord_end(f, Lt, Lp, Lt, -1, Ft, Fp, Ft) >= 0,
                        position_vs_chord_end(f, Lt, Lt, Ln, +1, Ft, Ft, Fn) <= 0});
    }
    if (kept.empty()) {
        if (center_inside) power_full_disk(c, r, out);  // else the polygon misses the open disk: zero area
        return;
    }
    // The kept edges are the cycle; consecutive ones meet at the polygon vertex between them (inside
    // the disk or on the circle), else an arc joins them.
    ws.cycle.clear();
    ws.meets.clear();
    for (std::size_t q = 0; q < kept.size(); ++q) {
        const Kept& e = kept[q];
        const Kept& g = kept[(q + 1) % kept.size()];
        ws.cycle.push_back(poly[e.k]);
        ws.meets.push_back(kept.size() > 1 && e.to_vertex && g.from_vertex && g.k == (e.k + 1) % n);
    }
    emit_power_cell(f, L, ws.ids, ws.cycle, ws.meets, out, ws.rel, ws.is_arc, ws.span);
}

}  // namespace detail

/// The cell W of the agent at `center` with radius `radius` among `others` with radii `other_radii`
/// (docs/spec.md, heterogeneous teams): the power cell (weights R^2) clipped to B(center, radius).
/// Edge pieces name their neighbour by its row in `others`. An empty cell (zero area) has no pieces.
/// With every other radius equal to `radius` this is limited_cell(center, others, radius, method).
///
/// Methods: Auto is the exact clipping (power_cell), Scan the generalised Boundary Scan
/// (cells/power_boundary_scan.hpp), Chords the generalised RCVC (cells/power_rcvc.hpp); the same cell.
///
/// \throws InputError for a bad radius, radii of the wrong length, non-finite coordinates;
///         CoincidentError for an agent of `others` at `center` with the same radius; RangeError for
///         Chords with more than kMaxChordsCandidates radical axes cutting the disk.
/// \note Thread-safe (pure function). O(m k) for Auto (m agents within radius + R_j, k vertices of the
///       cell), O(m log m) for Scan when the agent lies in its cell (else a few restarts), O(m^2) for Chords.
inline LimitedCell power_limited_cell(const Vec2& center, PointsRef others, double radius,
                                      const std::vector<double>& other_radii, Method method = Method::Auto) {
    detail::require_finite_radius(radius);
    detail::require_finite_point(center, "center");
    detail::require_finite_points(others, "others");
    if (static_cast<Index>(other_radii.size()) != others.rows())
        throw InputError("other_radii must have one radius per row of others: " + std::to_string(other_radii.size()) +
                         " radii for " + std::to_string(others.rows()) + " agents");
    bool equal = true;
    for (double R : other_radii) {
        detail::require_finite_radius(R, "other_radii");
        equal &= R == radius;
    }
    if (equal) return limited_cell(center, others, radius, method);
    std::vector<detail::Candidate> cand;
    std::vector<double> rs;
    for (Index j = 0; j < others.rows(); ++j) {
        cand.push_back({others.row(j).transpose(), j});
        rs.push_back(other_radii[static_cast<std::size_t>(j)]);
    }
    LimitedCell cell;
    if (method == Method::Auto) {
        detail::PowerWorkspace ws;
        detail::power_cell(center, radius, cand, rs, cell, ws);
    } else {
        detail::PowerChordWorkspace ws;
        if (method == Method::Scan)
            detail::power_boundary_scan(center, radius, cand, rs, cell, ws);
        else
            detail::power_rcvc(center, radius, cand, rs, cell, ws);
    }
    return cell;
}

}  // namespace dvoronoi
