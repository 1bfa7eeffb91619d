// RCVC, the Range-Constrained Voronoi Cell algorithm (Guruprasad & Dasgupta, IROS 2012), as
// published: constructChords, checkChords, constructVor with its self-intersection refinement.
//
//   constructChords: the chord L_j of every bisector in the disk, sorted by the angle of its agent
//     starting from the nearest (shared with Boundary Scan, cells/bisectors.hpp).
//   checkChords: remove every chord whose two endpoints both lie in the arc another chord cuts off
//     (the half-plane of L_j not containing the agent). Quadratic in the worst case, as the Boundary
//     Scan paper points out (the RCVC paper claims linear); we keep it quadratic, as published.
//   constructVor: walk consecutive chords once around; consecutive chords that intersect in the disk
//     give a 'line' vertex, otherwise two 'circ' vertices joined by an arc; a new vertex that does not
//     lie after the previous vertex on the same chord (the self-intersecting polygon of the paper's
//     Fig. 6b) removes that chord.
// Exactness: the paper compares polar angles of chord endpoints (Theta) and of vertices (Delta theta);
// we decide the same questions with exact predicates on the agents' coordinates ("this endpoint lies
// beyond that chord", "this vertex lies after that one on the chord"), so the answers are exact.
// Completing the published walk: after a removal the walk steps back to the previous chord (its last
// vertex is withdrawn), and the walk closes on the first chord, which is never removed.
#pragma once

#include "dvoronoi/cells/bisectors.hpp"

#include <cstdio>
#include <string>

namespace dvoronoi {

/// The most agents within 2R that RCVC (Method::Chords) accepts per cell. Its checkChords is
/// quadratic in them: 1024 take a few milliseconds per cell, 2,000 agents all within 2R of each other
/// took 110 s. Boundary Scan (Method::Scan) gives the same cells in O(m log m) without a bound.
inline constexpr std::size_t kMaxChordsCandidates = 1024;

namespace detail {

/// constructVor on mk kept chords in sorted order (at(t): the t-th one's index; at(0) bounds the
/// cell and is never removed), with the geometry `g` (LineGeometry here, PowerGeometry for radical
/// axes: endpoint_side, vertex_before, after_chord_start). `st` holds the chords of the boundary so
/// far; line_start[t] says whether chord st[t] starts at a 'line' vertex with st[t-1] (else at its
/// 'circ' endpoint s_j).
template <class Geometry, class At>
void construct_vor(const Geometry& g, int mk, const At& at, std::vector<int>& st, std::vector<char>& line_start) {
    st.clear();
    line_start.clear();
    if (mk > 0) {
        st.push_back(at(0));
        line_start.push_back(0);
    }
    for (int step = 1; step <= mk && mk > 1; ++step) {
        const int k = at(step % mk);
        for (;;) {
            const int j = st.back();
            // Consecutive chords intersect in the disk when L_k's first endpoint lies on or beyond
            // L_j (after checkChords, the only way one endpoint of L_k is beyond L_j).
            const bool intersect = k != j && g.endpoint_side(k, -1, j) >= 0;
            if (!intersect) {
                if (step % mk != 0) {
                    st.push_back(k);
                    line_start.push_back(0);
                } else {
                    line_start[0] = 0;
                }
                break;
            }
            // Self-intersection test: the new vertex x_jk must lie after the vertex where L_j starts.
            bool accepted;
            if (st.size() >= 2 && line_start.back())
                accepted = g.vertex_before(j, st[st.size() - 2], k);
            else
                accepted = g.after_chord_start(j, k);
            if (accepted || st.size() == 1) {
                if (step % mk != 0) {
                    st.push_back(k);
                    line_start.push_back(1);
                } else {
                    line_start[0] = 1;
                }
                break;
            }
            st.pop_back();  // remove L_j and its vertex; retry with the previous chord
            line_start.pop_back();
        }
    }
}

/// RCVC on candidates already known to lie strictly within 2R of c.
/// \throws RangeError when there are more than kMaxChordsCandidates of them.
inline void rcvc(const Vec2& c, const std::vector<Candidate>& cand, double radius, LimitedCell& out,
                 CellWorkspace& ws) {
    if (cand.size() > kMaxChordsCandidates) {
        char r[32];
        std::snprintf(r, sizeof r, "%.17g", radius);
        throw RangeError("method \"chords\" (RCVC, quadratic in the agents within 2R) accepts at most " +
                         std::to_string(kMaxChordsCandidates) + " agents within 2R of an agent; this one has " +
                         std::to_string(cand.size()) + " within 2R = 2 x " + r +
                         ": use method \"scan\" (the same cells in O(m log m)) or a smaller radius");
    }
    sorted_bisectors(c, cand, ws);  // constructChords
    out.candidates = static_cast<Index>(cand.size());
    const auto& L = ws.lines;
    const int m = static_cast<int>(L.size());
    const LineGeometry g{c, L, radius};

    // checkChords: chord q is redundant when both its endpoints lie in the closed arc cut off by
    // another chord j (both on or beyond L_j).
    auto& removed = ws.removed;
    removed.assign(static_cast<std::size_t>(m), 0);
    for (int j = 0; j < m; ++j)
        for (int q = 0; q < m; ++q) {
            if (q == j || removed[static_cast<std::size_t>(q)]) continue;
            if (g.endpoint_side(q, -1, j) >= 0 && g.endpoint_side(q, +1, j) >= 0)
                removed[static_cast<std::size_t>(q)] = 1;
        }
    auto& kept = ws.bound;
    kept.clear();
    for (int j = 0; j < m; ++j)
        if (!removed[static_cast<std::size_t>(j)]) kept.push_back(j);
    out.chords_after_check = static_cast<Index>(kept.size());

    // constructVor.
    auto& st = ws.stack;
    auto& line_start = ws.start_is_vertex;
    construct_vor(g, static_cast<int>(kept.size()), [&](int t) { return kept[static_cast<std::size_t>(t)]; }, st, line_start);
    // Labelled vertex set: joint t (between st[t] and st[t+1]) is a 'line' vertex when st[t+1] starts
    // at one.
    const std::size_t s = st.size();
    std::vector<char> meets(s, 0);
    for (std::size_t t = 0; t < s && s >= 2; ++t) meets[t] = line_start[(t + 1) % s];
    emit_cell(c, radius, L, st, meets, out);
}

}  // namespace detail

/// RCVC limited cell of `center` among `others` (see limited_cell for the contract).
inline LimitedCell rcvc_cell(const Vec2& center, PointsRef others, double radius) {
    const std::vector<detail::Candidate> cand = detail::candidates_within_2r(center, others, radius);
    LimitedCell cell;
    detail::CellWorkspace ws;
    detail::rcvc(center, cand, radius, cell, ws);
    return cell;
}

}  // namespace dvoronoi
