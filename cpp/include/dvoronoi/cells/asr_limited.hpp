// The range-limited cell by the two other routes the Boundary Scan paper times against Boundary Scan
// itself (Section 4.1, Table 3 and Figure 8):
//   - EVT: the exact Voronoi tessellation of the agent and its agents within 2R (our exact incremental
//     Delaunay triangulation, cells/delaunay.hpp), the agent's cell extracted and intersected with the
//     disk of radius R;
//   - ASR (with BS or EVT as its inner step), "trivially generalized to the range-limited cell": the
//     radius doubles from the nearest-neighbour distance; a cell certified exact at a radius below R
//     (a polygon with every vertex strictly inside that radius) is already the limited cell, else the
//     last step computes the limited cell at R itself.
// All routes give the same cell as boundary_scan (same pieces, same exact decisions); the paper's
// point, reproduced in tools/reproduce/, is what each costs.
#pragma once

#include "dvoronoi/cells/boundary_scan.hpp"
#include "dvoronoi/cells/delaunay.hpp"

#include <cmath>
#include <vector>

namespace dvoronoi {

namespace detail {

/// EVT: the limited cell of c among `cand` (every agent strictly within 2R) from the Delaunay star.
/// An edge on the bisector with neighbour j survives when its open chord meets the Voronoi edge
/// between the neighbours before (i) and after (k): the chord's end lies strictly on c's side of
/// L_i and its start strictly on c's side of L_k. Consecutive surviving edges meet at their Voronoi
/// vertex when they are adjacent in the Voronoi cycle and that vertex lies in the closed disk.
inline void evt_limited_cell(const Vec2& c, const std::vector<Candidate>& cand, double radius, LimitedCell& out,
                             CellWorkspace& ws, DelaunayWorkspace& dws) {
    DelaunayCell dc;
    delaunay_star(c, cand, dc, dws);
    // Lines for the Voronoi neighbours, in the cycle's order (emit_cell measures from them).
    auto& L = ws.lines;
    L.clear();
    for (Index id : dc.neighbors)
        for (const Candidate& q : cand)
            if (q.id == id) {
                const Vec2 a = q.p - c;
                L.push_back(Line{q.p, a, a.squaredNorm(), id, 0.0, 0});
                break;
            }
    const std::size_t s = L.size();
    const auto P = [&](std::size_t t) -> const Vec2& { return L[t].p; };
    auto& keep = ws.stack;
    keep.clear();
    for (std::size_t t = 0; t < s; ++t) {
        if (pred::within_2r(c, P(t), radius) <= 0) continue;
        const bool has_prev = !(dc.on_hull && t == 0) && s > 1;
        const bool has_next = !(dc.on_hull && t + 1 == s) && s > 1;
        if (has_prev && pred::endpoint_side(c, P(t), +1, P((t + s - 1) % s), radius) >= 0) continue;
        if (has_next && pred::endpoint_side(c, P(t), -1, P((t + 1) % s), radius) >= 0) continue;
        keep.push_back(static_cast<int>(t));
    }
    auto& meets = ws.start_is_vertex;
    meets.assign(keep.size(), 0);
    for (std::size_t t = 0; t < keep.size() && keep.size() >= 2; ++t) {
        const auto j = static_cast<std::size_t>(keep[t]), k = static_cast<std::size_t>(keep[(t + 1) % keep.size()]);
        const bool adjacent = (j + 1) % s == k && !(dc.on_hull && j + 1 == s);
        meets[t] = adjacent && pred::vertex_in_disk(c, P(j), P(k), radius) <= 0;
    }
    out.candidates = static_cast<Index>(cand.size());
    out.chords_after_check = -1;
    emit_cell(c, radius, L, keep, meets, out);
}

}  // namespace detail

/// The inner step of asr_limited_cell.
enum class LimitedInner { Scan, Evt };

/// The range-limited cell V ∩ B(center, radius) by Adjust-Sensing-Radius (see the top of this file):
/// the same cell as limited_cell, reached through a radius schedule that stops early when the cell
/// is small. `steps` (optional) receives the number of radius steps.
inline LimitedCell asr_limited_cell(const Vec2& center, PointsRef others, double radius,
                                    LimitedInner inner = LimitedInner::Scan, int* steps = nullptr) {
    detail::require_finite_point(center, "center");
    detail::require_finite_points(others, "others");
    detail::require_finite_radius(radius);
    std::vector<detail::Candidate> cand;
    detail::CellWorkspace ws;
    detail::DelaunayWorkspace dws;
    LimitedCell out;
    double nearest2 = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < others.rows(); ++j)
        nearest2 = std::min(nearest2, (Vec2(others.row(j).transpose()) - center).squaredNorm());
    const auto step = [&](double r) {
        cand = detail::candidates_within_2r(center, others, r);
        if (inner == LimitedInner::Evt)
            detail::evt_limited_cell(center, cand, r, out, ws, dws);
        else
            detail::boundary_scan(center, cand, r, out, ws);
    };
    int k = 0;
    for (double r = std::sqrt(nearest2); r < radius; r *= 2.0) {
        step(r);
        ++k;
        // Certified: a polygon (no arc) whose vertices lie strictly inside the disk of radius r.
        bool certified = out.pieces.size() >= 3;
        for (std::size_t t = 0; certified && t < out.pieces.size(); ++t) {
            const Piece& p = out.pieces[t];
            const Piece& q = out.pieces[(t + 1) % out.pieces.size()];
            certified = !p.is_arc() && !q.is_arc() &&
                        pred::vertex_in_disk(center, others.row(p.neighbor).transpose(),
                                             others.row(q.neighbor).transpose(), r) < 0;
        }
        if (certified) {
            out.radius = radius;  // the same polygon is the cell limited to R
            if (steps) *steps = k;
            return out;
        }
    }
    step(radius);
    if (steps) *steps = k + 1;
    return out;
}

}  // namespace dvoronoi
