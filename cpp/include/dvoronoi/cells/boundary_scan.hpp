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

/// Does line j keep a boundary part of positive length inside the disk and the half-planes of the
/// lines in `nb` (its stack neighbours)? Each neighbour bounds L_j from below (D < 0: the part after
/// their vertex survives), from above (D > 0) or not at all (antiparallel, D = 0).
inline bool keeps_positive_part(const LineGeometry& g, int j, const int* nb, int count) {
    int lower[2], upper[2], nl = 0, nu = 0;
    for (int t = 0; t < count; ++t) {
        const int o = g.orient(j, nb[t]);
        if (o > 0) upper[nu++] = nb[t];
        else if (o < 0) lower[nl++] = nb[t];
    }
    // Every lower bound must lie strictly before every upper bound (chord ends included).
    for (int u = 0; u < nu; ++u)
        if (!g.after_chord_start(j, upper[u], 1)) return false;
    for (int l = 0; l < nl; ++l)
        if (!g.before_chord_end(j, lower[l], -1)) return false;
    for (int l = 0; l < nl; ++l)
        for (int u = 0; u < nu; ++u)
            if (lower[l] != upper[u] && !g.vertex_before(j, lower[l], upper[u])) return false;
    return true;
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
    auto& st = ws.stack;
    st.clear();
    if (m > 0) st.push_back(0);
    // Step 2: scan b_1 .. b_{m-1}, then b_0 again to close the loop (it only pops).
    for (int step = 1; step <= m && m > 1; ++step) {
        const int k = step % m;
        if (k != 0) {
            const int top = st.back();
            if (!keeps_positive_part(g, k, &top, 1)) continue;  // case (3): b_k outside b_j's half-plane
        }
        while (st.size() >= 2) {
            const int nb[2] = {st[st.size() - 2], k};
            if (keeps_positive_part(g, st.back(), nb, 2)) break;  // cases (1), (2), (5): b_j stays
            st.pop_back();                                         // case (4): b_j is cut away
        }
        if (k != 0) st.push_back(k);
    }
    // Step 3: label the joints: a vertex when consecutive boundaries meet inside the closed disk.
    const std::size_t s = st.size();
    std::vector<char>& meets = ws.start_is_vertex;
    meets.assign(s, 0);
    if (s >= 2)
        for (std::size_t t = 0; t < s; ++t) {
            const int j = st[t], k = st[(t + 1) % s];
            meets[t] = g.orient(j, k) > 0 && g.vertex_in_closed_disk(j, k);
        }
    emit_cell(c, radius, L, st, meets, out);
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
