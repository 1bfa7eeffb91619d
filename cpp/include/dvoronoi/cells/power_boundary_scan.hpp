// Boundary Scan (He, Feng & Ren, Sensors 2018) generalised to a heterogeneous team: agent c's cell
// W = power cell (weights R^2) ∩ B(c, r) by the paper's stack scan of its chords, which are chords of
// c's own circle cut by the radical axes (docs/spec.md, heterogeneous teams). O(m log m) for m agents
// within r + R_j when c lies in its cell.
//
// The paper's three steps, on radical axes (cells/power_chords.hpp says what changes and why):
//   1. the chord set, sorted counter-clockwise by the axes' normals from the nearest radical axis;
//   2. the scan: the chord on top of the stack (b_j) against the scanned one (b_k), the paper's five
//      cases decided by one exact test, "does b_j keep a part of positive length between its stack
//      neighbours" (PowerGeometry::keeps), then a loop back to the first chord;
//   3. the labelled vertex set: consecutive chords meeting at a vertex or joined by an arc.
// Lemma 1 (the first chord bounds the cell, so it is never popped) holds when c lies strictly inside
// every chord's half-plane. Otherwise the scan starts from each chord in turn, nearest axis first,
// until power_cycle_is_cell accepts the cycle; a chord that bounds the cell is a right start (the
// scan from it is the paper's), so when none is accepted the cell is empty. Crescents away from c
// usually take one or two starts.
#pragma once

#include "dvoronoi/cells/boundary_scan.hpp"
#include "dvoronoi/cells/power_chords.hpp"

namespace dvoronoi {
namespace detail {

/// Steps 2 and 3 on the chords `seq` (sorted, seq[0] the start): Boundary Scan's stack scan
/// (cells/boundary_scan.hpp, scan_stack) on the radical axes, then the labels: a vertex where
/// consecutive chords meet in the closed disk, else an arc. The cycle in ws.cycle, ws.meets.
inline void power_scan(const PowerGeometry& g, const std::vector<int>& seq, PowerChordWorkspace& ws) {
    scan_stack(g, static_cast<int>(seq.size()), [&](int t) { return seq[static_cast<std::size_t>(t)]; }, ws.scan);
    ws.cycle.clear();
    for (const ScanEntry& e : ws.scan) ws.cycle.push_back(e.line);
    const std::size_t s = ws.cycle.size();
    ws.meets.assign(s, 0);
    for (std::size_t t = 0; t < s && s >= 2; ++t) ws.meets[t] = g.meets(ws.cycle[t], ws.cycle[(t + 1) % s]);
}

/// The cell of c (radius r) among candidate agents cand with radii cand_r (any agents: those whose
/// radical axis misses the disk are dropped) by the generalised Boundary Scan. Writes `out` as
/// power_cell does (an empty cell has no pieces, area 0, centroid c).
/// \throws CoincidentError when a candidate lies at c with the same radius (`self` names c).
inline void power_boundary_scan(const Vec2& c, double r, const std::vector<Candidate>& cand,
                                const std::vector<double>& cand_r, LimitedCell& out, PowerChordWorkspace& ws,
                                Index self = -1) {
    const pred::power::Frame f{c, r};
    bool inside = true;
    if (!start_chords(f, cand, cand_r, self, out, ws, inside)) return;  // step 1 decided the cell
    const PowerGeometry g{f, ws.lines, ws.fast};
    first_accepted_cycle(g, ws.order, inside, ws, out, [&](const std::vector<int>& seq) { power_scan(g, seq, ws); });
}

}  // namespace detail
}  // namespace dvoronoi
