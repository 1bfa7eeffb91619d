// RCVC (Guruprasad & Dasgupta, IROS 2012) generalised to a heterogeneous team: agent c's cell
// W = power cell (weights R^2) ∩ B(c, r) by the paper's constructChords, checkChords and constructVor
// on the chords of c's own circle cut by the radical axes (docs/spec.md, heterogeneous teams).
// Quadratic in the chords, as published (at most kMaxChordsCandidates of them, as for equal radii).
//
//   constructChords: the chords sorted counter-clockwise by the axes' normals from the nearest
//     radical axis (cells/power_chords.hpp).
//   checkChords: chord q with both ends on or beyond L_j lies outside j's side of the disk. The paper
//     removes it ("keep c's side"); here c's side need not be the cell's, so j's chord ends decide:
//     j's side lies in H_q (q is redundant: removed) or outside it (the cell is empty).
//   constructVor: the walk over consecutive chords with the self-intersection refinement, as for
//     equal radii (cells/rcvc.hpp), closing on the first chord.
// The first chord must bound the cell (the walk never removes it): true for the nearest axis when c
// lies strictly inside every chord's half-plane; otherwise the walk starts from each kept chord in
// turn until power_cycle_is_cell accepts the cycle, and the cell is empty when none does.
#pragma once

#include "dvoronoi/cells/power_chords.hpp"
#include "dvoronoi/cells/rcvc.hpp"

namespace dvoronoi {
namespace detail {

/// constructVor (cells/rcvc.hpp, construct_vor) on the kept chords `seq` (sorted, seq[0] the start)
/// on the radical axes: ws.cycle, and ws.meets[t] when cycle[t] meets cycle[t+1] at a vertex.
inline void power_walk(const PowerGeometry& g, const std::vector<int>& seq, PowerChordWorkspace& ws) {
    auto& st = ws.cycle;
    auto& line_start = ws.line_start;  // st[t] starts at a 'line' vertex with st[t-1]
    construct_vor(g, static_cast<int>(seq.size()), [&](int t) { return seq[static_cast<std::size_t>(t)]; }, st, line_start);
    const std::size_t s = st.size();
    ws.meets.assign(s, 0);
    for (std::size_t t = 0; t < s && s >= 2; ++t) ws.meets[t] = line_start[(t + 1) % s];
}

/// The cell of c (radius r) among cand with radii cand_r by the generalised RCVC; as
/// power_boundary_scan otherwise.
/// \throws RangeError for more than kMaxChordsCandidates chords; CoincidentError as
///         power_boundary_scan.
inline void power_rcvc(const Vec2& c, double r, const std::vector<Candidate>& cand, const std::vector<double>& cand_r,
                       LimitedCell& out, PowerChordWorkspace& ws, Index self = -1) {
    const pred::power::Frame f{c, r};
    bool inside = true;
    if (!start_chords(f, cand, cand_r, self, out, ws, inside)) return;  // constructChords decided the cell
    if (ws.lines.size() > kMaxChordsCandidates) {  // the agents whose radical axes cut the disk
        char rs[32];
        std::snprintf(rs, sizeof rs, "%.17g", r);
        throw RangeError("method \"chords\" (RCVC, quadratic in the chords) accepts at most " +
                         std::to_string(kMaxChordsCandidates) + " agents whose radical axis cuts an agent's disk; this one (radius " +
                         rs + ") has " + std::to_string(ws.lines.size()) +
                         ": use method \"scan\" (the same cells in O(m log m))");
    }
    const PowerGeometry g{f, ws.lines, ws.fast};
    const int m = static_cast<int>(ws.order.size());

    // checkChords.
    auto& removed = ws.removed;
    removed.assign(static_cast<std::size_t>(m), 0);
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) {
            if (a == b || removed[static_cast<std::size_t>(b)]) continue;
            const int j = ws.order[static_cast<std::size_t>(a)], q = ws.order[static_cast<std::size_t>(b)];
            if (g.endpoint_side(q, -1, j) < 0 || g.endpoint_side(q, +1, j) < 0) continue;
            // Chord q misses j's open side of the disk: that side lies on one side of L_q, the side
            // of j's chord ends (both on L_q only when the axes coincide, opposite: no area).
            int side = g.endpoint_side(j, -1, q);
            if (side == 0) side = g.endpoint_side(j, +1, q);
            if (side >= 0) return;  // j's side of the disk is outside H_q: the cell is empty
            removed[static_cast<std::size_t>(b)] = 1;
        }
    auto& kept = ws.kept;
    kept.clear();
    for (int a = 0; a < m; ++a)
        if (!removed[static_cast<std::size_t>(a)]) kept.push_back(ws.order[static_cast<std::size_t>(a)]);
    out.chords_after_check = static_cast<Index>(kept.size());

    // constructVor, from each kept chord in turn when the first need not bound the cell.
    first_accepted_cycle(g, kept, inside, ws, out, [&](const std::vector<int>& seq) { power_walk(g, seq, ws); });
}

}  // namespace detail
}  // namespace dvoronoi
