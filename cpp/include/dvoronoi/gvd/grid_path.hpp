// Paths for a disk robot on an occupancy grid (docs/spec.md, "paths"): no path when start and goal are
// disconnected in {x : d(x, occupied) > r}; a path whenever they are connected in
// {x : d(x, occupied) > r + 1 pixel}; every segment keeps a distance > r from every occupied pixel.
//
// The search runs over pixel centres whose clearance exceeds r, between 4-neighbours. A segment
// between 4-neighbouring centres is as clear as its nearer end (for an axis-parallel unit segment
// and axis-parallel squares, the nearest point of the segment to any square is an end or lies on
// a perpendicular from the square, which an end's own column or row already sees), so clear
// centres make clear steps. A free path with clearance > r + sqrt(2)/2 crosses pixels whose centres
// are within sqrt(2)/2 of it, hence clear, and 4-adjacent (a crossing exactly through a corner is
// replaced by a detour through one of the two other pixels, also within sqrt(2)/2): the search
// finds a path whenever docs/spec.md promises one.
// Costs keep the path on the diagram where it serves: a step onto a diagram pixel costs its length,
// a step elsewhere `off_diagram_cost` times that. The pixel path is then straightened where a
// straight segment is exactly clear (segment_clear below), runs of diagram pixels only among
// themselves, so the path still follows the diagram. Segment tests are conservative: squared
// distances in doubles are compared with a relative margin of 1e-12 toward "not clear", so a
// returned segment is never within r, at the price of refusing one that clears r by less.
#pragma once

#include "dvoronoi/gvd/medial_diagram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <string>
#include <vector>

namespace dvoronoi::gvd {

struct GridPath {
    std::vector<Vec2> points;  ///< map coordinates: start, turning points, goal; empty: no path
    double length = 0.0;       ///< map units
    std::size_t expanded = 0;  ///< pixels the search settled
    bool found() const { return !points.empty(); }
};

namespace detail {

/// Clear by more than r: squared distances compared with a relative margin of 1e-12 toward
/// "not clear", so a rounded comparison never calls a touching segment clear (conservative).
inline bool clearer_than(double sq_px, double r_px) { return sq_px > r_px * r_px * (1.0 + 1e-12); }

/// Squared distance (pixel units) from segment pq to the axis-parallel box [x0, x1] x [y0, y1]
/// (0 when they meet).
inline double sq_segment_box(const Vec2& p, const Vec2& q, double x0, double x1, double y0, double y1) {
    auto inside = [&](const Vec2& v) { return v.x() >= x0 && v.x() <= x1 && v.y() >= y0 && v.y() <= y1; };
    if (inside(p) || inside(q)) return 0.0;
    const Vec2 c[4] = {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
    // crossing a box edge?
    auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
    auto seg_meet = [&](const Vec2& a, const Vec2& b, const Vec2& u, const Vec2& v) {
        const double d1 = cross(b - a, u - a), d2 = cross(b - a, v - a), d3 = cross(v - u, a - u), d4 = cross(v - u, b - u);
        return ((d1 > 0) != (d2 > 0) || d1 == 0 || d2 == 0) && ((d3 > 0) != (d4 > 0) || d3 == 0 || d4 == 0) &&
               std::min(a.x(), b.x()) <= std::max(u.x(), v.x()) && std::min(u.x(), v.x()) <= std::max(a.x(), b.x()) &&
               std::min(a.y(), b.y()) <= std::max(u.y(), v.y()) && std::min(u.y(), v.y()) <= std::max(a.y(), b.y());
    };
    for (int k = 0; k < 4; ++k)
        if (seg_meet(p, q, c[k], c[(k + 1) % 4])) return 0.0;
    auto pt_box = [&](const Vec2& v) {
        const double dx = std::max({x0 - v.x(), 0.0, v.x() - x1}), dy = std::max({y0 - v.y(), 0.0, v.y() - y1});
        return dx * dx + dy * dy;
    };
    auto pt_seg = [&](const Vec2& v) {
        const Vec2 d = q - p;
        const double l2 = d.squaredNorm();
        const double t = l2 > 0 ? std::clamp((v - p).dot(d) / l2, 0.0, 1.0) : 0.0;
        return (p + t * d - v).squaredNorm();
    };
    double best = std::min(pt_box(p), pt_box(q));
    for (const Vec2& v : c) best = std::min(best, pt_seg(v));
    return best;
}

}  // namespace detail

/// Is every point of segment pq (pixel units: x right, y up from the map's lower-left corner)
/// farther than r_px from every occupied pixel and from the outside of the map?
inline bool segment_clear(const OccupancyGrid& g, const Vec2& p, const Vec2& q, double r_px) {
    const double W = g.cols, H = g.rows;
    // the outside: the segment's extreme coordinates against the map's edges
    const double xmin = std::min(p.x(), q.x()), xmax = std::max(p.x(), q.x());
    const double ymin = std::min(p.y(), q.y()), ymax = std::max(p.y(), q.y());
    for (double gap : {xmin, W - xmax, ymin, H - ymax})
        if (!(gap > 0.0) || !detail::clearer_than(gap * gap, r_px)) return false;
    const auto reach = static_cast<std::int32_t>(std::ceil(r_px)) + 1;
    const std::int32_t c0 = std::max(0, static_cast<std::int32_t>(std::floor(xmin)) - reach);
    const std::int32_t c1 = std::min(g.cols - 1, static_cast<std::int32_t>(std::floor(xmax)) + reach);
    const std::int32_t j0 = std::max(0, static_cast<std::int32_t>(std::floor(ymin)) - reach);
    const std::int32_t j1 = std::min(g.rows - 1, static_cast<std::int32_t>(std::floor(ymax)) + reach);
    for (std::int32_t j = j0; j <= j1; ++j)
        for (std::int32_t c = c0; c <= c1; ++c)
            if (g.occ(g.rows - 1 - j, c) &&
                !detail::clearer_than(detail::sq_segment_box(p, q, c, c + 1.0, j, j + 1.0), r_px))
                return false;
    return true;
}

/// Distance (pixel units) from a point to the occupied pixels and the outside of the map.
inline double point_clearance(const MedialDiagram& m, const Vec2& p) {
    const OccupancyGrid& g = m.grid;
    if (!(p.x() > 0 && p.y() > 0 && p.x() < g.cols && p.y() < g.rows)) return 0.0;
    const auto c = std::clamp(static_cast<std::int32_t>(std::floor(p.x())), 0, g.cols - 1);
    const auto j = std::clamp(static_cast<std::int32_t>(std::floor(p.y())), 0, g.rows - 1);
    const std::int32_t r = g.rows - 1 - j;
    if (g.occ(r, c)) return 0.0;
    // the point is within sqrt(2)/2 of its pixel's centre: squares farther than the centre's
    // clearance + 1 cannot be the nearest
    const double bound = 0.5 * std::sqrt(static_cast<double>(m.features.sq(r, c))) + 1.0;
    double best = std::min({p.x(), g.cols - p.x(), p.y(), g.rows - p.y()});
    best *= best;
    const auto reach = static_cast<std::int32_t>(std::ceil(bound)) + 1;
    // the occupied squares of each row of the box, 64 at a time from the occupancy bits (in open
    // space a box of thousands of squares holds few occupied ones); rows farther than the best are skipped
    const std::int32_t c_lo = std::max(0, c - reach), c_hi = std::min(g.cols - 1, c + reach);
    for (std::int32_t jj = std::max(0, j - reach); jj <= std::min(g.rows - 1, j + reach); ++jj) {
        const double dy = std::max({jj - p.y(), 0.0, p.y() - (jj + 1.0)});
        if (dy * dy >= best) continue;
        for (std::int32_t c0 = c_lo; c0 <= c_hi; c0 += 64)
            for (std::uint64_t w = m.bits.row(jj, c0, std::min(64, c_hi - c0 + 1)); w != 0; w &= w - 1) {
                const std::int32_t cc = c0 + lowest_bit(w);
                const double dx = std::max({cc - p.x(), 0.0, p.x() - (cc + 1.0)});
                best = std::min(best, dx * dx + dy * dy);
            }
    }
    return std::sqrt(best);
}

/// A path for a disk robot of radius `robot_radius` (map units) from `start` to `goal` (map
/// coordinates).
/// \throws InputError naming `start` or `goal` when it is outside the map or not farther than the
/// robot radius from every occupied pixel; `robot_radius` when negative or not finite.
/// \note O(P log P) for the P pixels the search settles; 5 bytes per pixel of the map while it runs.
inline GridPath find_grid_path(const MedialDiagram& m, const Vec2& start, const Vec2& goal, double robot_radius,
                               double off_diagram_cost = 3.0) {
    const OccupancyGrid& g = m.grid;
    if (!std::isfinite(robot_radius) || robot_radius < 0.0)
        throw InputError("robot_radius must be a finite number >= 0");
    // at most 1e6: the search sums step costs in float (5 bytes a pixel), and a sum of 2^28 steps of
    // that cost stays far below float's range
    if (!(off_diagram_cost >= 1.0 && off_diagram_cost <= 1e6))
        throw InputError("off_diagram_cost must be a number in [1, 1e6], got " + ::dvoronoi::detail::shortest_text(off_diagram_cost));
    // The tests run in pixel units on rounded pixel coordinates (to_pixels), and the path returns in
    // map coordinates rounded again (origin + resolution * p): each is off by a few ulps of the
    // larger of |origin| / resolution and the map's side. Clearances must beat r by that too, or a
    // segment cleared in pixels could touch a corner in map units (r = 0) or come nearer than r far
    // from (0, 0).
    const double span = std::max(std::abs(g.origin.x()), std::abs(g.origin.y())) / g.resolution + std::max(g.cols, g.rows) + 1.0;
    const double r_px = robot_radius / g.resolution + 8.0 * std::numeric_limits<double>::epsilon() * span;
    auto show = [](const Vec2& p) {
        return "(" + ::dvoronoi::detail::shortest_text(p.x()) + ", " + ::dvoronoi::detail::shortest_text(p.y()) + ")";
    };
    const Vec2 sp = g.to_pixels(start), gp = g.to_pixels(goal);
    for (auto [p, name, orig] : {std::tuple<Vec2, const char*, Vec2>{sp, "start", start}, {gp, "goal", goal}}) {
        if (!std::isfinite(p.x()) || !std::isfinite(p.y())) throw InputError(std::string(name) + " has a non-finite coordinate");
        if (!(p.x() > 0 && p.y() > 0 && p.x() < g.cols && p.y() < g.rows))
            throw InputError(std::string(name) + " " + show(orig) + " is outside the map");
        const double cl = point_clearance(m, p);
        if (!detail::clearer_than(cl * cl, r_px))
            throw InputError(std::string(name) + " " + show(orig) + " is blocked: its clearance " +
                             ::dvoronoi::detail::shortest_text(cl * g.resolution) +
                             " is not greater than the robot radius " + ::dvoronoi::detail::shortest_text(robot_radius) +
                             " by more than rounding");
    }
    GridPath out;
    if (start == goal) {  // already there (and clear)
        out.points = {start, goal};
        return out;
    }
    const std::int32_t H = g.rows, W = g.cols;
    auto node_ok = [&](std::size_t i) {
        return !g.occupied[i] && detail::clearer_than(0.25 * static_cast<double>(m.features.sq(static_cast<std::int32_t>(i / static_cast<std::size_t>(W)), static_cast<std::int32_t>(i % static_cast<std::size_t>(W)))), r_px);
    };
    auto pixel_of = [&](const Vec2& p) {
        const auto c = std::clamp(static_cast<std::int32_t>(std::floor(p.x())), 0, W - 1);
        const auto j = std::clamp(static_cast<std::int32_t>(std::floor(p.y())), 0, H - 1);
        return g.at(H - 1 - j, c);
    };
    auto centre = [&](std::size_t i) {
        return Vec2(static_cast<double>(i % static_cast<std::size_t>(W)) + 0.5,
                    static_cast<double>(H - 1 - static_cast<std::int32_t>(i / static_cast<std::size_t>(W))) + 0.5);
    };
    // Entry pixels: a clear pixel among the point's own and its 8 neighbours, joined by a clear segment.
    auto entries = [&](const Vec2& p) {
        std::vector<std::size_t> e;
        const std::size_t i = pixel_of(p);
        const auto r = static_cast<std::int32_t>(i / static_cast<std::size_t>(W)), c = static_cast<std::int32_t>(i % static_cast<std::size_t>(W));
        for (std::int32_t dr = -1; dr <= 1; ++dr)
            for (std::int32_t dc = -1; dc <= 1; ++dc) {
                const std::int32_t rr = r + dr, cc = c + dc;
                if (rr < 0 || cc < 0 || rr >= H || cc >= W) continue;
                const std::size_t k = g.at(rr, cc);
                if (node_ok(k) && segment_clear(g, p, centre(k), r_px)) e.push_back(k);
            }
        return e;
    };
    const auto from = entries(sp), to = entries(gp);
    if (from.empty() || to.empty()) return out;
    std::vector<float> dist(g.size(), std::numeric_limits<float>::infinity());
    std::vector<std::uint8_t> state(g.size(), 0);  // bit 0: settled, bits 1-3: step into the pixel (1..4), 5: goal
    for (std::size_t k : to) state[k] |= 32;
    using Item = std::pair<float, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    auto h = [&](std::size_t i) { return static_cast<float>((centre(i) - gp).norm()); };
    for (std::size_t k : from) {
        const float d = static_cast<float>((centre(k) - sp).norm());
        if (d < dist[k]) { dist[k] = d; open.push({d + h(k), k}); }
    }
    const std::int64_t step[4] = {-1, 1, -static_cast<std::int64_t>(W), static_cast<std::int64_t>(W)};
    std::size_t reached = g.size();
    while (!open.empty()) {
        const auto [f, u] = open.top();
        open.pop();
        if (state[u] & 1) continue;
        state[u] |= 1;
        ++out.expanded;
        if (state[u] & 32) { reached = u; break; }
        const auto r = static_cast<std::int32_t>(u / static_cast<std::size_t>(W)), c = static_cast<std::int32_t>(u % static_cast<std::size_t>(W));
        for (int k = 0; k < 4; ++k) {
            if ((k == 0 && c == 0) || (k == 1 && c == W - 1) || (k == 2 && r == 0) || (k == 3 && r == H - 1)) continue;
            const auto v = static_cast<std::size_t>(static_cast<std::int64_t>(u) + step[k]);
            if ((state[v] & 1) || !node_ok(v)) continue;
            const float d = dist[u] + (m.mask[v] ? 1.0f : static_cast<float>(off_diagram_cost));
            if (d < dist[v]) {
                dist[v] = d;
                state[v] = static_cast<std::uint8_t>((state[v] & ~std::uint8_t(14)) | ((k + 1) << 1));
                open.push({d + h(v), v});
            }
        }
    }
    if (reached == g.size()) return out;
    // back along the steps
    std::vector<std::size_t> pix;
    for (std::size_t u = reached;;) {
        pix.push_back(u);
        const int k = ((state[u] >> 1) & 7) - 1;
        if (k < 0) break;
        u = static_cast<std::size_t>(static_cast<std::int64_t>(u) - step[k]);
    }
    std::reverse(pix.begin(), pix.end());
    // Straighten: from each kept pixel, jump to the farthest later pixel of the same kind (along the
    // diagram or not) that a clear segment reaches, looking at most 64 pixels ahead. A diagonal stretch
    // of the diagram is 8-connected and the search 4-connected: the pixel path alternates diagram
    // pixels and single pixels beside them, which count as along the diagram too.
    std::vector<std::uint8_t> along(pix.size());
    for (std::size_t k = 0; k < pix.size(); ++k)
        along[k] = m.mask[pix[k]] || (k > 0 && k + 1 < pix.size() && m.mask[pix[k - 1]] && m.mask[pix[k + 1]]);
    std::vector<Vec2> pts{sp};
    std::size_t a = 0;
    pts.push_back(centre(pix[0]));
    while (a + 1 < pix.size()) {
        std::size_t best = a + 1;
        for (std::size_t b = a + 2; b < pix.size() && b <= a + 64; ++b) {
            if (along[b] != along[a + 1]) break;
            if (segment_clear(g, centre(pix[a]), centre(pix[b]), r_px)) best = b;
        }
        pts.push_back(centre(pix[best]));
        a = best;
    }
    pts.push_back(gp);
    for (const Vec2& p : pts) out.points.push_back(g.origin + g.resolution * p);
    for (std::size_t k = 0; k + 1 < out.points.size(); ++k) out.length += (out.points[k + 1] - out.points[k]).norm();
    return out;
}

}  // namespace dvoronoi::gvd
