// ASR's own numbers per agent — the radius steps and the agents in range that one robot running
// Adjust-Sensing-Radius alone needs (cells/asr.hpp: asr_cell) — derived from its exact cell, for the
// all-agents driver (partition/voronoi_partition.hpp), whose certificates (the one-shot clip, empty
// vertex circles) reach the same cell by other means. So the reported numbers are the paper's
// quantity, the same whichever way the driver computed the cell and whichever inner step ran.
//
// With radii R_k = d1 2^(k-1) (d1 the nearest-neighbour distance), ASR stops at the first k where
//   - its limited cell certifies itself: exactly when the exact cell is bounded and every vertex lies
//     strictly inside B(c, R_k) (then the limited cell is the cell; otherwise it has an arc or a
//     vertex outside), or
//   - every other agent is strictly within 2 R_k, or 4 R_k overflows: then it uses them all.
// Both conditions are monotone in k, so the first k is found by a short search from an estimate.
// It reports k and the agents strictly within 2 R_k when it certified there, else all others.
#pragma once

#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/core/convex_hull.hpp"
#include "dvoronoi/core/grid_index.hpp"
#include "dvoronoi/core/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace dvoronoi::detail {

/// R_k = d1 * 2^(k-1), the schedule's radius: the same value as std::ldexp(d1, k - 1) (scaling by
/// a power of two is exact, and overflows to infinity alike), without its library call for the
/// usual small k (it is called for every agent and step).
inline double schedule_radius(double d1, int k) {
    if (k >= 1 && k <= 64) return d1 * static_cast<double>(std::uint64_t{1} << (k - 1));
    return std::ldexp(d1, k - 1);
}

class AsrSchedule {
public:
    /// `hull` and `index` (which counts the agents in range) of the same points.
    AsrSchedule(const Points& pts, const GridIndex& index, const ConvexHull& hull)
        : pts_(pts), index_(index), hull_(hull) {
        const Index n = pts.rows();
        for (int d = 0; d < 4 && n > 0; ++d) {  // the agents of least/greatest x and y
            Index best = 0;
            for (Index i = 1; i < n; ++i) {
                const double a = pts(i, d / 2), b = pts(best, d / 2);
                if (d % 2 == 0 ? a < b : a > b) best = i;
            }
            extreme_[d] = best;
        }
    }

    /// Where ASR stops for the agent at c with nearest-neighbour distance d1: `steps`, and whether
    /// it certified its cell there (else it used every agent). `inside(R)`: every vertex of the exact
    /// cell lies strictly inside B(c, R) (exact; false for an unbounded cell); `reach`: about the
    /// farthest vertex's distance (a hint for the search; infinite for an unbounded cell).
    template <class Inside>
    std::pair<int, bool> stop(const Vec2& c, double d1, double reach, Inside&& inside) const {
        require_schedule_start(d1);
        const double far = far_lower(c);
        const auto all_in = [&](int k) {
            const double r = schedule_radius(d1, k);
            return !std::isfinite(4.0 * r) || all_within(c, r, far);
        };
        const auto done = [&](int k) { return all_in(k) || inside(schedule_radius(d1, k)); };
        // Estimates: R_k just beyond the farthest vertex, 2 R_k just beyond the farthest agent.
        const auto step_beyond = [&](double dist) {
            int e = 0;
            const double q = dist / d1;
            if (!(q < std::numeric_limits<double>::max())) return 1100;  // overflow: the search corrects it
            std::frexp(q, &e);  // q < 2^e
            return std::max(1, e + 1);
        };
        int k = step_beyond(far * 0.5);
        if (std::isfinite(reach)) k = std::min(k, step_beyond(reach));
        if (done(k)) {
            while (k > 1 && done(k - 1)) --k;
        } else {
            do ++k;
            while (!done(k));
        }
        const double r = schedule_radius(d1, k);
        return {k, std::isfinite(4.0 * r) && inside(r)};
    }

    /// The same for a cell as cells/asr.hpp returns it (edges counter-clockwise; a vertex between
    /// consecutive edges).
    std::pair<int, bool> stop(const Vec2& c, double d1, const VoronoiCell& cell) const {
        const std::size_t s = cell.edges.size();
        const bool bounded = !cell.on_hull && s >= 3;
        double reach = std::numeric_limits<double>::infinity();
        if (bounded) {
            reach = 0.0;
            for (const VoronoiEdge& e : cell.edges) reach = std::max(reach, (e.start - c).norm());
        }
        const auto at = [&](Index j) { return Vec2(pts_(j, 0), pts_(j, 1)); };
        return stop(c, d1, reach, [&](double radius) {
            for (std::size_t t = 0; bounded && t < s; ++t)
                if (pred::vertex_in_disk(c, at(cell.edges[t == 0 ? s - 1 : t - 1].neighbor), at(cell.edges[t].neighbor),
                                         radius) >= 0)
                    return false;
            return bounded;
        });
    }

    /// The agents strictly within 2R of the agent at c (all others when the radius did not certify
    /// the cell).
    Index used(const Vec2& c, double radius, bool certified) const {
        return certified ? index_.count_around(c, radius) - 1 : static_cast<Index>(pts_.rows()) - 1;
    }

private:
    /// A lower bound on the distance from c to the farthest agent (an axis-extreme agent's).
    double far_lower(const Vec2& c) const {
        double f = 0.0;
        for (Index e : extreme_) f = std::max(f, (Vec2(pts_(e, 0), pts_(e, 1)) - c).norm());
        return f;
    }

    /// Every agent strictly within 2R of c: the farthest agent is a hull corner, so the corners
    /// decide (exactly), after a cheap rejection by `far` (far_lower(c)).
    bool all_within(const Vec2& c, double radius, double far) const {
        if (2.0 * radius * (1.0 + 1e-12) < far * (1.0 - 1e-12)) return false;
        for (Index q : hull_.corners()) {
            const Vec2 p(pts_(q, 0), pts_(q, 1));
            if (p != c && pred::within_2r(c, p, radius) <= 0) return false;
        }
        return true;
    }

    const Points& pts_;
    const GridIndex& index_;
    const ConvexHull& hull_;
    Index extreme_[4] = {0, 0, 0, 0};
};

}  // namespace dvoronoi::detail
