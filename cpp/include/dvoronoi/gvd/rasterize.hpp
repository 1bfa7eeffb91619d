// Obstacle documents on the pixel grid, for the medial diagram (docs/spec.md: diagram="medial" also applies
// to obstacle documents, where it separates the parts of one non-convex obstacle).
//
// The area's bounding box is cut into `cells` square pixels along its longer side (make_grid, as the
// labelled diagram does). A pixel is occupied when its closed square meets an obstacle (any convex
// part of it), or when it is not wholly inside the working area (the area's edges become walls).
// The tests are done in double precision on the pixel's corners: a square that only touches an
// obstacle within rounding may go either way, which moves walls by far less than a pixel.
#pragma once

#include "dvoronoi/gvd/grid.hpp"
#include "dvoronoi/gvd/grid_path.hpp"
#include "dvoronoi/gvd/obstacle_index.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dvoronoi::gvd {

namespace detail {

/// Does convex part `part` meet the closed square [x0, x1] x [y0, y1]?
inline bool part_meets_square(const Scene& s, const ConvexPart& part, double x0, double x1, double y0, double y1) {
    const Vec2* v = s.part_vertices(part);
    switch (part.kind) {
        case ShapeKind::Point: return v[0].x() >= x0 && v[0].x() <= x1 && v[0].y() >= y0 && v[0].y() <= y1;
        case ShapeKind::Segment: return sq_segment_box(v[0], v[1], x0, x1, y0, y1) == 0.0;
        case ShapeKind::Circle: {
            const double dx = std::max({x0 - part.center.x(), 0.0, part.center.x() - x1});
            const double dy = std::max({y0 - part.center.y(), 0.0, part.center.y() - y1});
            return dx * dx + dy * dy <= part.radius * part.radius;
        }
        case ShapeKind::Polygon: {
            for (std::uint32_t k = 0; k < part.count; ++k)  // an edge meets the square
                if (sq_segment_box(v[k], v[k + 1 == part.count ? 0 : k + 1], x0, x1, y0, y1) == 0.0) return true;
            const Vec2 c(x0, y0);  // or the square lies inside the (counter-clockwise) polygon
            for (std::uint32_t k = 0; k < part.count; ++k)
                if (pred::orient(v[k], v[k + 1 == part.count ? 0 : k + 1], c) < 0) return false;
            return true;
        }
    }
    return false;
}

}  // namespace detail

/// The occupancy grid of a scene at `cells` pixels along the area's longer side: resolution = the
/// pixel's side, origin = the area's lower-left bounding-box corner.
/// \throws InputError for cells < 1 or a grid larger than kMaxMapSide per side.
/// \note O(pixels + sum over parts of the pixels their bounding boxes cover).
inline OccupancyGrid rasterize(const Scene& scene, std::int64_t cells) {
    const GridSpec spec = make_grid(scene, cells);
    if (spec.nx > kMaxMapSide || spec.ny > kMaxMapSide)
        throw InputError("cells: a grid of " + std::to_string(spec.nx) + " x " + std::to_string(spec.ny) +
                         " pixels exceeds " + std::to_string(kMaxMapSide) + " per side");
    OccupancyGrid g(spec.ny, spec.nx, spec.h, Vec2(spec.x0, spec.y0));
    auto pixel = [&](std::int32_t i, std::int32_t j) -> std::uint8_t& { return g.occupied[g.at(spec.ny - 1 - j, i)]; };
    // outside the working area (or partly): a wall. Pixel corners are rounded (x0 + i h), so each is
    // taken a hair (1e-9 of a pixel) toward the pixel's centre: a pixel whose side lies on the area's
    // edge is inside.
    const double eps = 1e-9 * spec.h;
    for (std::int32_t j = 0; j < spec.ny; ++j)
        for (std::int32_t i = 0; i < spec.nx; ++i) {
            const Vec2 lo = spec.corner(i, j) + Vec2(eps, eps), hi = spec.corner(i + 1, j + 1) - Vec2(eps, eps);
            const Vec2 c[4] = {lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
            bool inside = true;
            for (const Vec2& q : c) {
                if (q.x() < scene.box.x0 || q.x() > scene.box.x1 || q.y() < scene.box.y0 || q.y() > scene.box.y1) inside = false;
                for (std::size_t k = 0, n = scene.area.size(); inside && k < n; ++k)
                    if (pred::orient(scene.area[k], scene.area[(k + 1) % n], q) < 0) inside = false;
            }
            if (!inside) pixel(i, j) = 1;
        }
    for (const ConvexPart& part : scene.parts) {
        if (part.label >= scene.n_obstacles) continue;  // the area's edges are the walls above
        auto index = [&](double v, double v0, std::int32_t n) {
            return static_cast<std::int32_t>(std::clamp(std::floor((v - v0) / spec.h), 0.0, static_cast<double>(n - 1)));
        };
        // one pixel of slack: a part on a pixel boundary meets the pixels on both sides
        const std::int32_t i0 = std::max(0, index(part.box.x0, spec.x0, spec.nx) - 1);
        const std::int32_t i1 = std::min(spec.nx - 1, index(part.box.x1, spec.x0, spec.nx) + 1);
        const std::int32_t j0 = std::max(0, index(part.box.y0, spec.y0, spec.ny) - 1);
        const std::int32_t j1 = std::min(spec.ny - 1, index(part.box.y1, spec.y0, spec.ny) + 1);
        for (std::int32_t j = j0; j <= j1; ++j)
            for (std::int32_t i = i0; i <= i1; ++i) {
                std::uint8_t& p = pixel(i, j);
                if (p) continue;
                const Vec2 lo = spec.corner(i, j), hi = spec.corner(i + 1, j + 1);
                if (detail::part_meets_square(scene, part, lo.x(), hi.x(), lo.y(), hi.y())) p = 1;
            }
    }
    return g;
}

}  // namespace dvoronoi::gvd
