// Geodesic cells of a heterogeneous team (a geodesic range R_i per agent; docs/geodesic_coverage.md):
// the geodesic analogue of the power cells clipped to the disks (docs/spec.md, heterogeneous teams),
//   W_i = { free pixels q : d_i(q) <= R_i and d_i(q)^2 - R_i^2 <= d_j(q)^2 - R_j^2 for every j with d_j(q) <= R_j },
// d_i the geodesic distance from agent i; ties go to the lower index. An agent need not lie in its own
// cell, and cells need not be connected, so one multi-source wavefront (each pixel keeps only its
// nearest agent, and a wave stops where another agent's begins) cannot compute them:
//   1. each agent's own wavefront, range-limited to R_i (geodesic_distance.hpp). A path of length at
//      most R_i stays within R_i of the agent, so the wavefront runs on that window of the map (its
//      bounding box plus a margin of two pixels; outside the map counts as occupied, as everywhere);
//   2. the pixels of every window are merged in agent order, keeping the smallest d_i^2 - R_i^2
//      (strictly: ties stay with the lower index).
// Each wavefront is a pure function of the map and one agent, so the cells do not depend on the worker
// count. Work O(Σ_i R_i^2) pixels (against O(map) for the one wavefront of equal ranges).
#pragma once

#include "dvoronoi/coverage/geodesic_path.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace dvoronoi::coverage {

//! One agent's wavefront on its window of the map: pixel (r, c) of the window is pixel (r0 + r, c0 + c)
//! of the map.
struct AgentWave {
    std::int32_t r0 = 0, c0 = 0;
    std::vector<std::uint8_t> occ;
    GeodesicField field;  //!< one source (the agent), in window pixel units
};

/*! The cells above: `merged` gets, per map pixel, the owner (label), the owner's geodesic distance and
    no anchors (-1: paths come from the owner's wave); `waves[i]` agent i's wavefront. `ranges` in pixel
    units, one per agent (finite, > 0); agents must lie in free pixels (the caller checks them). */
inline void geodesic_team_field(const std::uint8_t* occ, std::int32_t rows, std::int32_t cols,
                                const std::vector<PixelPoint>& agents, const std::vector<double>& ranges, int workers,
                                GeodesicField& merged, std::vector<AgentWave>& waves) {
    const auto n = static_cast<std::int32_t>(agents.size());
    waves.resize(static_cast<std::size_t>(n));
    std::atomic<std::int32_t> next{0};
    run_team(std::max(1, std::min({workers, n, ::dvoronoi::detail::max_team()})), [&](int) {
        for (std::int32_t i; (i = next++) < n;) {
            AgentWave& w = waves[static_cast<std::size_t>(i)];
            const PixelPoint& a = agents[static_cast<std::size_t>(i)];
            const double R = ranges[static_cast<std::size_t>(i)];
            const auto clampr = [&](double v, std::int32_t hi) {
                return static_cast<std::int32_t>(std::clamp(v, 0.0, static_cast<double>(hi)));
            };
            w.r0 = clampr(std::floor(a.w - R) - 2, rows);
            w.c0 = clampr(std::floor(a.u - R) - 2, cols);
            const std::int32_t r1 = clampr(std::floor(a.w + R) + 3, rows), c1 = clampr(std::floor(a.u + R) + 3, cols);
            const std::int32_t wr = r1 - w.r0, wc = c1 - w.c0;
            w.occ.resize(std::size_t(wr) * wc);
            for (std::int32_t r = 0; r < wr; ++r)
                std::copy_n(occ + std::int64_t(w.r0 + r) * cols + w.c0, wc, w.occ.begin() + std::int64_t(r) * wc);
            GeodesicWorkspace ws(w.occ.data(), wr, wc);
            geodesic_field(w.occ.data(), wr, wc, {PixelPoint{a.u - w.c0, a.w - w.r0}}, R, w.field, ws);
        }
    });
    constexpr double inf = std::numeric_limits<double>::infinity();
    const std::size_t P = std::size_t(rows) * cols;
    merged.rows = rows;
    merged.cols = cols;
    merged.sources = n;
    merged.points = agents;
    merged.distance.assign(P, inf);
    merged.label.assign(P, -1);
    merged.anchor.assign(P, -1);
    merged.vertex_distance.clear();
    merged.vertex_parent.clear();
    std::vector<double> best(P, inf);  // d_i^2 - R_i^2 of the pixel's owner
    for (std::int32_t i = 0; i < n; ++i) {
        const AgentWave& w = waves[static_cast<std::size_t>(i)];
        const double R2 = ranges[static_cast<std::size_t>(i)] * ranges[static_cast<std::size_t>(i)];
        for (std::int32_t r = 0; r < w.field.rows; ++r)
            for (std::int32_t c = 0; c < w.field.cols; ++c) {
                const double d = w.field.distance[std::size_t(r) * w.field.cols + c];
                if (!(d < inf)) continue;
                const std::size_t q = std::size_t(w.r0 + r) * cols + (w.c0 + c);
                const double power = d * d - R2;
                if (power < best[q]) {
                    best[q] = power;
                    merged.label[q] = i;
                    merged.distance[q] = d;
                }
            }
    }
}

/*! Agent i's path to point `t` (map pixel units) in map pixel q, from its own wave (geodesic_path on
    the window, shifted to the map). Empty when the wave does not reach q. */
inline std::vector<PixelPoint> team_path(const AgentWave& w, std::int32_t cols, std::int64_t q, PixelPoint t) {
    const std::int64_t r = q / cols - w.r0, c = q % cols - w.c0;
    if (r < 0 || c < 0 || r >= w.field.rows || c >= w.field.cols) return {};
    const OccupancyView g{w.occ.data(), w.field.rows, w.field.cols};
    std::vector<PixelPoint> path = geodesic_path(w.field, g, r * w.field.cols + c, PixelPoint{t.u - w.c0, t.w - w.r0});
    for (PixelPoint& p : path) {
        p.u += w.c0;
        p.w += w.r0;
    }
    return path;
}

}  // namespace dvoronoi::coverage
