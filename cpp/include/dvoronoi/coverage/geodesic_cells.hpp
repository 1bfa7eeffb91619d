// Geodesic cells on an occupancy grid: the map frame (map units <-> pixel units), the agents' check,
// and the cells' moments and coverage cost from a geodesic field (geodesic_distance.hpp).
//
// Cell W_i = the free pixels whose centre is geodesically nearest to agent i (ties to the lower index),
// within the range if one is given. Integrals over a cell are sums over its pixels' centres:
//   M_i = sum phi(q),  centroid_i = sum phi(q) q / M_i,
//   H   = sum over reached pixels phi(q) d(q)^2  +  sum over reachable, unreached pixels phi(q) R^2,
// (times the pixel area) — the coverage cost of docs/spec.md with the range's R^2 for what no agent
// covers, as for limited cells. "Reachable" = connected through free space to some agent.
// A heterogeneous team (a range R_i per agent, geodesic_team.hpp) pays, as the limited power cost of
// coverage/lloyd.hpp with R̄ = max R_i, d_i(q)^2 + R̄^2 - R_i^2 at a pixel of W_i and R̄^2 at a reachable,
// unreached one: H = Σ_q φ(q) (min(min_i (d_i(q)^2 - R_i^2), 0) + R̄^2); equal ranges give the cost above.
#pragma once

#include "dvoronoi/coverage/geodesic_distance.hpp"
#include "dvoronoi/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace dvoronoi::coverage {

//! An occupancy grid's frame as in gvd/occupancy_grid.hpp: pixel (r, c) covers [c, c+1] x [H-1-r, H-r]
//! in pixel units, scaled by `resolution` and shifted by `origin` (the lower-left corner of pixel (H-1, 0)).
struct MapFrame {
    std::int32_t rows = 0, cols = 0;
    double resolution = 1.0, ox = 0.0, oy = 0.0;

    PixelPoint to_pixel(double x, double y) const { return {(x - ox) / resolution, rows - (y - oy) / resolution}; }
    void to_map(const PixelPoint& p, double& x, double& y) const {
        x = ox + p.u * resolution;
        y = oy + (rows - p.w) * resolution;
    }
};

namespace detail {
inline std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", v);
    return buf;
}
}  // namespace detail

/*! Agents in pixel units; throws std::invalid_argument naming `points[i]` when an agent is not finite,
    outside the map, or in an occupied pixel (the pixel containing it; a point on a pixel edge belongs to
    the pixel right of / below it in the image, as floor() says). */
inline std::vector<PixelPoint> agents_on_map(const std::uint8_t* occ, const MapFrame& frame, const double* xy,
                                             std::int64_t n) {
    std::vector<PixelPoint> out(static_cast<std::size_t>(n));
    const OccupancyView g{occ, frame.rows, frame.cols};
    for (std::int64_t i = 0; i < n; ++i) {
        const double x = xy[2 * i], y = xy[2 * i + 1];
        const std::string name = "points[" + std::to_string(i) + "] = (" + detail::number(x) + ", " + detail::number(y) + ")";
        if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument(name + " is not finite");
        const PixelPoint p = frame.to_pixel(x, y);
        const double c = std::floor(p.u), r = std::floor(p.w);
        if (c < 0 || r < 0 || c >= frame.cols || r >= frame.rows)
            throw std::invalid_argument(name + " is outside the map");
        if (g.blocked(static_cast<std::int64_t>(r), static_cast<std::int64_t>(c)))
            throw std::invalid_argument(name + " is in an occupied pixel (row " + std::to_string(std::int64_t(r)) +
                                        ", col " + std::to_string(std::int64_t(c)) + ")");
        out[static_cast<std::size_t>(i)] = p;
    }
    return out;
}

//! Free pixels connected (through free space: 4-adjacency) to a pixel holding an agent.
inline std::vector<std::uint8_t> reachable_pixels(const std::uint8_t* occ, std::int32_t rows, std::int32_t cols,
                                                  const std::vector<PixelPoint>& agents) {
    const OccupancyView g{occ, rows, cols};
    std::vector<std::uint8_t> seen(std::size_t(rows) * cols, 0);
    std::vector<std::int64_t> stack;
    for (const auto& a : agents) {
        const auto r = static_cast<std::int64_t>(std::floor(a.w)), c = static_cast<std::int64_t>(std::floor(a.u));
        if (g.blocked(r, c) || seen[r * cols + c]) continue;
        seen[r * cols + c] = 1;
        stack.push_back(r * cols + c);
        while (!stack.empty()) {
            const std::int64_t p = stack.back();
            stack.pop_back();
            const std::int64_t pr = p / cols, pc = p % cols;
            const std::int64_t nr[4] = {pr - 1, pr + 1, pr, pr}, nc[4] = {pc, pc, pc - 1, pc + 1};
            for (int k = 0; k < 4; ++k) {
                if (g.blocked(nr[k], nc[k]) || seen[nr[k] * cols + nc[k]]) continue;
                seen[nr[k] * cols + nc[k]] = 1;
                stack.push_back(nr[k] * cols + nc[k]);
            }
        }
    }
    return seen;
}

//! Per-agent mass, first moments (pixel units) and pixel count, and the cost H (pixel units, unit weight
//! per pixel times phi).
struct GeodesicMoments {
    std::vector<double> mass, mu, mw;
    std::vector<std::int64_t> pixels;
    double cost = 0.0;
};

/*! Moments and cost of the cells of field `f`. `weight` (per pixel, may be null = 1) is phi at the pixel
    centres; `reachable` (may be null) marks the pixels that pay R^2 = limit^2 when unreached (only when
    `limit` is finite). `ranges` (may be null): a heterogeneous team's R_i, `limit` then being R̄ = max R_i.
    Blocks of rows are summed by `workers` threads and combined in a fixed order, so the sums do not
    depend on the worker count. */
inline GeodesicMoments geodesic_moments(const GeodesicField& f, const double* weight, const std::uint8_t* reachable,
                                        double limit, int workers, const std::vector<double>* ranges = nullptr) {
    const std::int32_t n = f.sources, rows = f.rows, cols = f.cols;
    constexpr std::int32_t BLOCK = 32;
    const std::int32_t blocks = (rows + BLOCK - 1) / BLOCK;
    std::vector<GeodesicMoments> part(static_cast<std::size_t>(blocks));
    std::atomic<std::int32_t> next{0};
    const double r2 = std::isfinite(limit) ? limit * limit : 0.0;
    std::vector<double> extra(static_cast<std::size_t>(n), 0.0);  // R̄^2 - R_i^2
    if (ranges)
        for (std::size_t i = 0; i < extra.size(); ++i) extra[i] = r2 - (*ranges)[i] * (*ranges)[i];
    run_team(std::max(1, std::min({workers, blocks, ::dvoronoi::detail::max_team()})), [&](int) {
        for (std::int32_t b; (b = next++) < blocks;) {
            GeodesicMoments& m = part[static_cast<std::size_t>(b)];
            m.mass.assign(static_cast<std::size_t>(n), 0.0);
            m.mu.assign(static_cast<std::size_t>(n), 0.0);
            m.mw.assign(static_cast<std::size_t>(n), 0.0);
            m.pixels.assign(static_cast<std::size_t>(n), 0);
            for (std::int64_t r = std::int64_t(b) * BLOCK; r < std::min<std::int64_t>(rows, (b + 1) * BLOCK); ++r)
                for (std::int64_t c = 0; c < cols; ++c) {
                    const std::int64_t p = r * cols + c;
                    const std::int32_t l = f.label[static_cast<std::size_t>(p)];
                    const double phi = weight ? weight[p] : 1.0;
                    if (l < 0) {
                        if (reachable && reachable[p]) m.cost += phi * r2;
                        continue;
                    }
                    const double d = f.distance[static_cast<std::size_t>(p)];
                    m.mass[l] += phi;
                    m.mu[l] += phi * (c + 0.5);
                    m.mw[l] += phi * (r + 0.5);
                    m.pixels[l] += 1;
                    m.cost += ranges ? phi * (d * d + extra[static_cast<std::size_t>(l)]) : phi * d * d;
                }
        }
    });
    GeodesicMoments out;
    out.mass.assign(static_cast<std::size_t>(n), 0.0);
    out.mu.assign(static_cast<std::size_t>(n), 0.0);
    out.mw.assign(static_cast<std::size_t>(n), 0.0);
    out.pixels.assign(static_cast<std::size_t>(n), 0);
    for (const auto& m : part) {
        for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
            out.mass[i] += m.mass[i];
            out.mu[i] += m.mu[i];
            out.mw[i] += m.mw[i];
            out.pixels[i] += m.pixels[i];
        }
        out.cost += m.cost;
    }
    return out;
}

/*! Each cell's pixel whose centre is nearest (Euclidean) to `target[i]` (ties to the lower pixel
    index), -1 for an empty cell: the cell point that minimises sum phi |q - x|^2 over the cell's
    pixels is the centroid, and over the cell's pixel centres the nearest one to it. */
inline std::vector<std::int64_t> nearest_cell_pixels(const GeodesicField& f, const std::vector<PixelPoint>& target,
                                                     int workers) {
    const std::int32_t n = f.sources, rows = f.rows, cols = f.cols;
    constexpr std::int32_t BLOCK = 32;
    const std::int32_t blocks = (rows + BLOCK - 1) / BLOCK;
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::vector<double> best(std::size_t(blocks) * n, inf);
    std::vector<std::int64_t> arg(std::size_t(blocks) * n, -1);
    std::atomic<std::int32_t> next{0};
    run_team(std::max(1, std::min({workers, blocks, ::dvoronoi::detail::max_team()})), [&](int) {
        for (std::int32_t b; (b = next++) < blocks;) {
            double* bb = best.data() + std::size_t(b) * n;
            std::int64_t* ab = arg.data() + std::size_t(b) * n;
            for (std::int64_t r = std::int64_t(b) * BLOCK; r < std::min<std::int64_t>(rows, (b + 1) * BLOCK); ++r)
                for (std::int64_t c = 0; c < cols; ++c) {
                    const std::int32_t l = f.label[static_cast<std::size_t>(r * cols + c)];
                    if (l < 0) continue;
                    const double du = c + 0.5 - target[l].u, dw = r + 0.5 - target[l].w;
                    const double d = du * du + dw * dw;
                    if (d < bb[l]) {
                        bb[l] = d;
                        ab[l] = r * cols + c;
                    }
                }
        }
    });
    std::vector<std::int64_t> out(static_cast<std::size_t>(n), -1);
    std::vector<double> dbest(static_cast<std::size_t>(n), inf);
    for (std::int32_t b = 0; b < blocks; ++b)  // blocks in pixel order: strict < keeps the lower index
        for (std::int32_t i = 0; i < n; ++i)
            if (best[std::size_t(b) * n + i] < dbest[i]) {
                dbest[i] = best[std::size_t(b) * n + i];
                out[i] = arg[std::size_t(b) * n + i];
            }
    return out;
}

}  // namespace dvoronoi::coverage
