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
// every chord's half-plane. Otherwise the scan starts again from another chord until
// power_cycle_is_cell accepts the cycle; a chord that bounds the cell is a right start (the scan from
// it is the paper's), and no scan ever drops one, so the next start is taken among the chords that
// every cycle so far kept, and the cell is empty when none is left. Crescents usually take one or
// two starts, empty cells a few.
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
    const auto& order = ws.order;
    const std::size_t m = order.size();
    // Which chords may still bound the cell. A chord that bounds a nonempty cell keeps a part of
    // positive length between any two others, so no scan pops or skips it, whatever its start:
    // every scan's cycle holds all of them. So the next start is taken among the chords of every
    // cycle so far, and when none is left the cell is empty.
    auto& maybe = ws.removed;  // scratch
    maybe.assign(ws.lines.size(), 1);
    std::size_t start = 0;
    for (;;) {
        ws.from_start.assign(order.begin() + static_cast<std::ptrdiff_t>(start), order.end());
        ws.from_start.insert(ws.from_start.end(), order.begin(), order.begin() + static_cast<std::ptrdiff_t>(start));
        power_scan(g, ws.from_start, ws);
        if (inside || power_cycle_is_cell(g, order, ws.cycle, ws.meets, ws.in_cycle)) {
            emit_power_cell(f, ws.lines, ws.ids, ws.cycle, ws.meets, out, ws.rel, ws.is_arc, ws.span);
            return;
        }
        // in_cycle: the cycle's chords (power_cycle_is_cell marks them before it can fail on another).
        ws.in_cycle.assign(ws.lines.size(), 0);
        for (const int j : ws.cycle) ws.in_cycle[static_cast<std::size_t>(j)] = 1;
        for (std::size_t t = 0; t < ws.lines.size(); ++t) maybe[t] = maybe[t] && ws.in_cycle[t];
        maybe[static_cast<std::size_t>(order[start])] = 0;  // tried
        std::size_t next = m;
        for (std::size_t d = 1; d < m && next == m; ++d)
            if (maybe[static_cast<std::size_t>(order[(start + d) % m])]) next = (start + d) % m;
        if (next == m) return;  // no chord can bound the cell: it is empty
        start = next;
    }
}

}  // namespace detail
}  // namespace dvoronoi
