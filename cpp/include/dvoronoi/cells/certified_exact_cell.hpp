// The exact (unlimited) Voronoi cell of an agent by certified clipping, for the all-agents driver of
// exact cells (partition/voronoi_partition.hpp): the square of half-side R around the agent is
// clipped by the bisector half-planes of the agents strictly within 2R (nearest first, every
// decision certified by a forward error bound, cells/certified_clip.hpp). When the result has no
// side of the square left and every vertex lies certainly strictly inside the disk of radius R, it
// is the agent's exact Voronoi cell: the same certificate as Adjust-Sensing-Radius (an agent not
// closer than 2R has its bisector at distance >= R, so it cannot cut a polygon inside the open disk).
// Otherwise (ties, a far vertex, an unbounded cell) it gives up and the caller finishes the cell by
// other means. certified_candidate_cell is the same clipping from any square, for candidate sets
// known to hold every neighbour.
//
// Why a square and not the disk: the exact cell has no arcs, so starting from a polygon spares the
// chord ends (square roots) and the arc bookkeeping of the limited cell; why one radius for every
// agent instead of ASR's schedule: the schedule computes two or three limited cells per agent, each
// with its own grid query, where one query at a radius chosen from the density certifies ~97% of a
// uniform swarm's cells at once. The schedule's own numbers (radius steps, agents in range) follow
// exactly from the certified cell (vertices_inside, below; partition/asr_schedule.hpp).
#pragma once

#include "dvoronoi/cells/certified_clip.hpp"

#include <cmath>
#include <vector>

namespace dvoronoi::detail {

/// A certified exact cell: its sides (workspace candidate indices), counter-clockwise, and the
/// vertex where each side starts (relative to c, with its error bound).
struct ExactClip {
    std::vector<int> side;
    std::vector<clip::CellVertex> vertex;
};

/// The cell of w.c among the loaded candidates (pairwise distinct and distinct from c, at any
/// distance) when it lies within the square of half-side `half` around c: clipped from that square,
/// every decision certified; false when a side of the square is left or a decision is uncertain
/// (`out` unspecified).
inline bool certified_candidate_cell(double half, ExactClip& out, ClipWorkspace& w) {
    using namespace clip;
    w.summarize();
    const std::size_t m = w.m;
    if (m < 3) return false;
    // Products of up to three squared lengths must neither underflow nor overflow.
    if (!(w.lo > 1e-90 && w.hi < 1e90 && half * half > 1e-90 && half * half < 1e90)) return false;
    w.add_square(half);
    Clipper clipper(w, half, m);
    clipper.start_square();
    if (!clipper.cut_loaded()) return false;
    const std::size_t s = clipper.size();
    out.side.resize(s);
    out.vertex.resize(s);
    for (std::size_t t = 0; t < s; ++t) {
        const CellVertex& v = clipper.vertex(t);
        if (v.side < 0 || static_cast<std::size_t>(v.side) >= m || !(v.e < kInf)) return false;
        out.side[t] = v.side;
        out.vertex[t] = v;
    }
    return true;
}

/// The exact cell of w.c among the loaded candidates (every agent strictly within 2R of c, pairwise
/// distinct and distinct from c), certified as above; false when it gives up (`out` unspecified).
inline bool certified_exact_cell(double radius, ExactClip& out, ClipWorkspace& w) {
    using namespace clip;
    if (!certified_candidate_cell(radius, out, w)) return false;
    for (const CellVertex& v : out.vertex) {
        const double r = std::sqrt(v.x * v.x + v.y * v.y) * (1.0 + 4.0 * kU) + v.e;
        if (!(r < radius * (1.0 - 4.0 * kU))) return false;
    }
    return true;
}

/// Every vertex of the certified cell lies strictly inside B(c, radius) (what ASR's certificate
/// asks of its limited cell at that radius): decided per vertex by its error bound, else by the
/// exact predicate.
inline bool vertices_inside(const ExactClip& cell, const ClipWorkspace& w, double radius) {
    using namespace clip;
    const std::size_t s = cell.side.size();
    for (std::size_t t = 0; t < s; ++t) {
        const CellVertex& v = cell.vertex[t];
        const double r = std::sqrt(v.x * v.x + v.y * v.y);
        if (r * (1.0 + 4.0 * kU) + v.e < radius * (1.0 - 4.0 * kU)) continue;
        if (r * (1.0 - 4.0 * kU) - v.e > radius * (1.0 + 4.0 * kU)) return false;
        const auto j = static_cast<std::size_t>(cell.side[t == 0 ? s - 1 : t - 1]);
        const auto i = static_cast<std::size_t>(cell.side[t]);
        if (pred::vertex_in_disk(w.c, Vec2(w.px[j], w.py[j]), Vec2(w.px[i], w.py[i]), radius) >= 0) return false;
    }
    return true;
}

/// Area and centroid of a certified cell (its vertices within the square of half-side `half`), to
/// core/accurate.hpp's accuracy: from the clip's bounded vertices, in units of 2^e ~ half (an exact
/// scaling), each redone from exact expansions where its bound is too large.
inline ClippedCell certified_cell_measures(const ExactClip& cell, const ClipWorkspace& w, double half) {
    thread_local Boundary b;
    b.clear();
    const int e = std::ilogb(half);
    const double unit = std::ldexp(1.0, -e), back = std::ldexp(1.0, e);
    const std::size_t s = cell.side.size();
    for (const clip::CellVertex& v : cell.vertex) b.push({v.x * unit, v.y * unit, v.e * unit}, false, 0.0);
    const auto at = [&](int k) { return Vec2(w.px[static_cast<std::size_t>(k)], w.py[static_cast<std::size_t>(k)]); };
    b.summarize();
    const LocalMeasures lm = accurate_measures(b, 0.0, [&](std::size_t t) {
        return exact_vertex(w.c, at(cell.side[(t + s - 1) % s]), at(cell.side[t]), unit);
    });
    ClippedCell m;
    m.area = lm.area * back * back;
    m.centroid = w.c + back * Vec2(lm.cx, lm.cy);
    return m;
}

/// About the distance from c of the cell's farthest vertex.
inline double farthest_vertex(const ExactClip& cell) {
    double r2 = 0.0;
    for (const clip::CellVertex& v : cell.vertex) r2 = std::max(r2, v.x * v.x + v.y * v.y);
    return std::sqrt(r2);
}

}  // namespace dvoronoi::detail
