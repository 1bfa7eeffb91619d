// The boundary of the convex hull of all agents, with the agents that lie on hull edges (not only the
// corners): exactly the agents whose Voronoi cells are unbounded. Andrew's monotone chain on exact
// orientation tests, O(n log n).
//
// What the exact-cell driver needs from it (partition/voronoi_partition.hpp): for an agent c on the
// boundary, its predecessor and successor along the boundary generate, from c, the cone that holds
// every agent (with one agent off the line when c lies inside a hull edge) — so the recession cone
// of a candidate cell can be certified with three orientation tests.
#pragma once

#include "dvoronoi/core/predicates.hpp"
#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace dvoronoi {

class ConvexHull {
public:
    /// The hull of `pts` (agents must be distinct; not checked here).
    explicit ConvexHull(const Points& pts) {
        const Index n = pts.rows();
        prev_.assign(static_cast<std::size_t>(n), -1);
        next_.assign(static_cast<std::size_t>(n), -1);
        if (n == 0) return;
        const auto P = [&](Index i) { return Vec2(pts(i, 0), pts(i, 1)); };
        std::vector<Index> s = candidates(pts);
        std::sort(s.begin(), s.end(), [&](Index a, Index b) {
            return pts(a, 0) != pts(b, 0) ? pts(a, 0) < pts(b, 0) : pts(a, 1) < pts(b, 1);
        });
        if (n == 1) {
            boundary_ = corners_ = {s[0]};
            return;
        }
        // Strict corners of the lower and upper chains, as positions in the sorted order.
        std::vector<std::size_t> lower, upper;
        const auto chain = [&](std::vector<std::size_t>& h, std::size_t k) {
            while (h.size() >= 2 && pred::orient(P(s[h[h.size() - 2]]), P(s[h.back()]), P(s[k])) <= 0) h.pop_back();
            h.push_back(k);
        };
        for (std::size_t k = 0; k < s.size(); ++k) chain(lower, k);
        for (std::size_t k = s.size(); k-- > 0;) chain(upper, k);
        if (lower.size() == 2 && upper.size() == 2) {
            // Every agent on one line: the boundary is the sorted order, walked both ways.
            collinear_ = true;
            boundary_ = s;
            corners_ = {s.front(), s.back()};
            for (std::size_t k = 0; k < s.size(); ++k) {
                const auto i = static_cast<std::size_t>(s[k]);
                prev_[i] = s[k > 0 ? k - 1 : k + 1];
                next_[i] = s[k + 1 < s.size() ? k + 1 : k - 1];
            }
            return;
        }
        // Walk the corners counter-clockwise, inserting the agents that lie on each hull edge: on the
        // lower chain they sit between the edge's ends in the sorted order, on the upper chain too
        // (walked backwards).
        const auto walk = [&](const std::vector<std::size_t>& h, bool forward) {
            for (std::size_t e = 0; e + 1 < h.size(); ++e) {
                const std::size_t a = h[e], b = h[e + 1];
                boundary_.push_back(s[a]);
                if (forward) {
                    for (std::size_t k = a + 1; k < b; ++k)
                        if (pred::orient(P(s[a]), P(s[b]), P(s[k])) == 0) boundary_.push_back(s[k]);
                } else {
                    for (std::size_t k = a; k-- > b + 1;)
                        if (pred::orient(P(s[a]), P(s[b]), P(s[k])) == 0) boundary_.push_back(s[k]);
                }
            }
        };
        walk(lower, true);
        walk(upper, false);
        const std::size_t m = boundary_.size();
        for (std::size_t k = 0; k < m; ++k) {
            const auto i = static_cast<std::size_t>(boundary_[k]);
            prev_[i] = boundary_[(k + m - 1) % m];
            next_[i] = boundary_[(k + 1) % m];
        }
        // Three corners that are not collinear: one of them lies off any line through a hull edge.
        for (std::size_t k = 0; k + 1 < lower.size(); ++k) corners_.push_back(s[lower[k]]);
        for (std::size_t k = 0; k + 1 < upper.size(); ++k) corners_.push_back(s[upper[k]]);
        witnesses_.assign(corners_.begin(), corners_.begin() + 3);
        // Outward normal angle of each corner's outgoing edge; they increase around the hull.
        const std::size_t h = corners_.size();
        for (std::size_t k = 0; k < h; ++k) {
            const Vec2 e = P(corners_[(k + 1) % h]) - P(corners_[k]);
            normal_angle_.push_back(std::atan2(-e.x(), e.y()));
        }
        const auto first = std::min_element(normal_angle_.begin(), normal_angle_.end()) - normal_angle_.begin();
        std::rotate(normal_angle_.begin(), normal_angle_.begin() + first, normal_angle_.end());
        std::rotate(corners_.begin(), corners_.begin() + first, corners_.end());
    }

    /// The agent lies on the hull boundary (its Voronoi cell is unbounded).
    bool on_boundary(Index i) const { return next_[static_cast<std::size_t>(i)] >= 0; }
    /// Neighbours along the boundary, counter-clockwise (collinear input: along the sorted line; an
    /// end of the line has the same agent as both). Only for agents on the boundary.
    Index prev(Index i) const { return prev_[static_cast<std::size_t>(i)]; }
    Index next(Index i) const { return next_[static_cast<std::size_t>(i)]; }
    /// Every agent lies on one line.
    bool collinear() const noexcept { return collinear_; }
    /// The boundary, counter-clockwise from the lexicographically smallest agent.
    const std::vector<Index>& boundary() const noexcept { return boundary_; }
    /// The corners, counter-clockwise (collinear input: the two ends of the line); the agent
    /// farthest from any point is one of them.
    const std::vector<Index>& corners() const noexcept { return corners_; }
    /// Agents that together span the plane (empty for a collinear input): for any line, one of them
    /// lies off it.
    const std::vector<Index>& witnesses() const noexcept { return witnesses_; }

    /// A hull corner that maximises d . p (up to rounding of the edge angles: a hint for where to
    /// look, not an exact answer), in O(log h). Collinear input: the end of the line in direction d.
    Index extreme(const Vec2& d, const Points& pts) const {
        if (boundary_.empty()) return -1;
        if (collinear_) {
            const Index a = boundary_.front(), b = boundary_.back();
            return d.dot(Vec2(pts(b, 0) - pts(a, 0), pts(b, 1) - pts(a, 1))) >= 0.0 ? b : a;
        }
        // The corner whose incoming edge normal comes before d's angle and outgoing one after it.
        const double phi = std::atan2(d.y(), d.x());
        const std::size_t h = corners_.size();
        const auto k = static_cast<std::size_t>(
            std::upper_bound(normal_angle_.begin(), normal_angle_.end(), phi) - normal_angle_.begin());
        return corners_[k % h];
    }

private:
    /// Akl-Toussaint: the agents that are not strictly inside the polygon of the extreme agents in
    /// eight directions. Those strictly inside lie strictly inside the hull, so neither corners nor
    /// on its edges; dropping them (exact orientation tests) leaves O(sqrt n) agents of a uniform
    /// swarm to sort instead of n. A degenerate polygon (collinear input) drops nothing.
    static std::vector<Index> candidates(const Points& pts) {
        const Index n = pts.rows();
        const auto P = [&](Index i) { return Vec2(pts(i, 0), pts(i, 1)); };
        // Directions in counter-clockwise order: their extreme agents go round the hull that way.
        constexpr double dir[8][2] = {{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}};
        Index ext[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        double best[8];
        for (int d = 0; d < 8; ++d) best[d] = dir[d][0] * pts(0, 0) + dir[d][1] * pts(0, 1);
        for (Index i = 1; i < n; ++i)
            for (int d = 0; d < 8; ++d) {
                const double v = dir[d][0] * pts(i, 0) + dir[d][1] * pts(i, 1);
                if (v > best[d]) best[d] = v, ext[d] = i;
            }
        // An extreme agent of a diagonal is only approximately extreme (the sum rounds), which is
        // harmless: an agent strictly left of every (non-degenerate) edge of any closed polygon of
        // agents has the polygon winding around it with only left turns, so it lies strictly inside
        // the polygon's hull, hence strictly inside the agents' hull.
        Vec2 q[8];
        for (int d = 0; d < 8; ++d) q[d] = P(ext[d]);
        bool any_edge = false, same[8];
        for (int t = 0; t < 8; ++t) {
            same[t] = q[t] == q[(t + 1) & 7];
            any_edge = any_edge || !same[t];
        }
        // p clearly left of edge t, or the edge is a point (the orient2d filter's error bound,
        // generously widened).
        const auto clearly_left = [&](int t, const Vec2& p) {
            const Vec2& a = q[t];
            const Vec2& b = q[(t + 1) & 7];
            const double l = (a.x() - p.x()) * (b.y() - p.y()), r = (a.y() - p.y()) * (b.x() - p.x());
            return same[t] | (l - r > 1e-15 * (std::fabs(l) + std::fabs(r)));
        };
        std::vector<Index> out;
        out.reserve(static_cast<std::size_t>(n));
        for (Index i = 0; i < n; ++i) {
            const Vec2 p = P(i);
            // All eight edges tested without branches (most agents are clearly inside: the branchy
            // test and its modulo were most of the hull's time); else edge by edge, exactly where
            // unclear.
            bool clear = any_edge;
            for (int t = 0; t < 8; ++t) clear &= clearly_left(t, p);
            bool inside = any_edge;
            for (int t = 0; !clear && inside && t < 8; ++t)
                inside = clearly_left(t, p) || pred::orient(q[t], q[(t + 1) & 7], p) > 0;
            if (!inside) out.push_back(i);
        }
        return out;
    }

    std::vector<Index> prev_, next_, boundary_, witnesses_, corners_;
    std::vector<double> normal_angle_;
    bool collinear_ = false;
};

}  // namespace dvoronoi
