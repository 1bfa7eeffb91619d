// Boundary Scan (He, Feng & Ren, Sensors 2018): the limited cell by a Graham-like stack scan of the
// bisectors sorted counter-clockwise from the nearest neighbour's. O(m log m) for m agents within 2R.
//
// The paper's three steps:
//   1. the sorted bisector set (cells/bisectors.hpp; the nearest neighbour's bisector first, Lemma 1);
//   2. the scan: the bisector on top of the stack (b_j) against the scanned one (b_k), five cases —
//      (1) they intersect, b_k after b_j: b_j ends and b_k starts at x_jk, push b_k;
//      (2) they intersect in reverse order (theta_k - theta_j > pi): push b_k, settled after looping back;
//      (3) b_k lies outside the half-plane of b_j within the disk: skip b_k;
//      (4) b_j's remaining part lies outside the half-plane of b_k: pop b_j, compare again;
//      (5) neither cuts the other inside the disk: push b_k (an arc joins them);
//   3. the labelled vertex set: consecutive boundaries meeting at a vertex ('line') or joined by an
//      arc ('arc').
// What we add for exactness in every configuration: the case analysis is one exact test, "does b_j
// keep a part of positive length between its stack neighbours", decided by comparing the points that
// bound b_j (chord ends and vertices with its neighbours) with exact predicates (core/predicates.hpp);
// the scan loops back once to the first bisector (which is never popped, Lemma 1) so case (2) is
// settled; concurrent bisectors through one vertex and vertices exactly on the circle give no
// zero-length edges or arcs.
#pragma once

#include "dvoronoi/cells/bisectors.hpp"

namespace dvoronoi {
namespace detail {

/// Is the chord bound that line k puts on line j (o = orient(j, k)) compatible with j keeping a part
/// of positive length? k bounds L_j from above (o > 0: the part before their vertex survives), from
/// below (o < 0) or not at all (antiparallel, o = 0); the bound must leave part of the chord.
inline bool chord_bound_ok(const LineGeometry& g, int j, int k, int o) {
    if (o > 0) return g.after_chord_start(j, k, 1);
    if (o < 0) return g.before_chord_end(j, k, -1);
    return true;
}

/// Step 2, the scan, on m lines in sorted order (at(t): the t-th line's index; at(0) bounds the
/// cell, Lemma 1), with the geometry `g` (LineGeometry here, PowerGeometry for radical axes:
/// orient, vertex_before, and chord_bound_ok(g, j, k, o)). Leaves the boundary lines on `st`.
/// b_j on top keeps a part of positive length between its neighbours b_i (below) and b_k when both
/// chord bounds leave part of the chord and, if one bounds from below and the other from above, the
/// lower vertex comes first; otherwise it is cut away (case 4). The scan loops back to at(0) to close
/// the loop (it only pops), so case (2) is settled.
template <class Geometry, class At>
void scan_stack(const Geometry& g, int m, const At& at, std::vector<ScanEntry>& st) {
    st.clear();
    if (m > 0) st.push_back({at(0), 0, true});
    for (int step = 1; step <= m && m > 1; ++step) {
        const int k = at(step % m);
        int tested = -1, o_tested = 0;
        if (step != m) {
            tested = st.back().line;
            o_tested = g.orient(k, tested);
            if (!chord_bound_ok(g, k, tested, o_tested)) continue;  // case (3): b_k outside b_j's half-plane
        }
        while (st.size() >= 2) {
            const ScanEntry& e = st.back();
            const int j = e.line, i = st[st.size() - 2].line;
            const int o = g.orient(j, k);
            bool keep = e.ok_prev && chord_bound_ok(g, j, k, o);
            if (keep && e.o_prev != 0 && o != 0 && (e.o_prev > 0) != (o > 0))
                keep = e.o_prev < 0 ? g.vertex_before(j, i, k) : g.vertex_before(j, k, i);
            if (keep) break;  // cases (1), (2), (5): b_j stays
            st.pop_back();    // case (4): b_j is cut away
        }
        if (step != m) {
            const int top = st.back().line;
            const int o = top == tested ? o_tested : g.orient(k, top);
            st.push_back({k, o, top == tested || chord_bound_ok(g, k, top, o)});
        }
    }
}

/// Boundary Scan on candidates already known to lie strictly within 2R of c.
inline void boundary_scan(const Vec2& c, const std::vector<Candidate>& cand, double radius,
                          LimitedCell& out, CellWorkspace& ws) {
    sorted_bisectors(c, cand, ws);  // Step 1
    out.candidates = static_cast<Index>(cand.size());
    out.chords_after_check = -1;
    const auto& L = ws.lines;
    const int m = static_cast<int>(L.size());
    const LineGeometry g{c, L, radius};
    auto& st = ws.scan;
    scan_stack(g, m, [](int t) { return t; }, st);  // Step 2
    auto& cycle = ws.stack;
    cycle.clear();
    for (const ScanEntry& e : st) cycle.push_back(e.line);
    // Step 3: label the joints: a vertex when consecutive boundaries meet inside the closed disk.
    const std::size_t s = cycle.size();
    std::vector<char>& meets = ws.start_is_vertex;
    meets.assign(s, 0);
    if (s >= 2)
        for (std::size_t t = 0; t < s; ++t) {
            const int j = cycle[t], k = cycle[(t + 1) % s];
            meets[t] = g.orient(j, k) > 0 && g.vertex_in_closed_disk(j, k);
        }
    emit_cell(c, radius, L, cycle, meets, out);
}

}  // namespace detail

/// Boundary Scan limited cell of `center` among `others` (see limited_cell for the contract).
inline LimitedCell boundary_scan_cell(const Vec2& center, PointsRef others, double radius) {
    const std::vector<detail::Candidate> cand = detail::candidates_within_2r(center, others, radius);
    LimitedCell cell;
    detail::CellWorkspace ws;
    detail::boundary_scan(center, cand, radius, cell, ws);
    return cell;
}

}  // namespace dvoronoi
