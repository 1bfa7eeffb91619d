// The grid of the diagram: square cells over the working area's bounding box, corner coordinates,
// and which cells belong to the working area.
//
// Cell (i, j) is column i, row j, the square [x0 + i h, x0 + (i+1) h] x [y0 + j h, y0 + (j+1) h];
// corner (i, j) is the point (x0 + i h, y0 + j h), computed by exactly that expression everywhere
// (tracer, oracle, Python checks), so every part of the program labels the same point.
#pragma once

#include "dvoronoi/gvd/obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dvoronoi::gvd {

struct GridSpec {
    double x0 = 0.0, y0 = 0.0, h = 1.0;
    std::int32_t nx = 1, ny = 1;

    Vec2 corner(std::int64_t i, std::int64_t j) const {
        return Vec2(x0 + static_cast<double>(i) * h, y0 + static_cast<double>(j) * h);
    }
    Vec2 center(std::int64_t i, std::int64_t j) const {
        return Vec2(x0 + (static_cast<double>(i) + 0.5) * h, y0 + (static_cast<double>(j) + 0.5) * h);
    }
    /// The cell containing p (clamped to the grid).
    void locate(const Vec2& p, std::int32_t& i, std::int32_t& j) const {
        i = static_cast<std::int32_t>(std::clamp(std::floor((p.x() - x0) / h), 0.0, static_cast<double>(nx - 1)));
        j = static_cast<std::int32_t>(std::clamp(std::floor((p.y() - y0) / h), 0.0, static_cast<double>(ny - 1)));
    }
};

/// The grid for `resolution` cells along the longer side of the area's bounding box.
/// \throws InputError when resolution < 1 or the grid would exceed 2^31 - 2 cells per side.
inline GridSpec make_grid(const Scene& s, std::int64_t resolution) {
    if (resolution < 1) throw InputError("resolution must be at least 1, got " + std::to_string(resolution));
    if (resolution > (std::int64_t{1} << 30)) throw InputError("resolution is too large");
    GridSpec g;
    const double w = s.box.x1 - s.box.x0, hh = s.box.y1 - s.box.y0;
    // finite coordinates can still lie more than DBL_MAX apart: the grid's cell size would be infinite
    if (!std::isfinite(w) || !std::isfinite(hh))
        throw InputError("the working area spans " + ::dvoronoi::detail::shortest_text(w) + " x " +
                         ::dvoronoi::detail::shortest_text(hh) + " map units: its width and height must be finite "
                         "(coordinates less than 8.9e307 apart)");
    g.x0 = s.box.x0;
    g.y0 = s.box.y0;
    g.h = std::max(w, hh) / static_cast<double>(resolution);
    auto count = [&](double len) {
        const double c = std::ceil(len / g.h * (1.0 - 1e-12));
        return static_cast<std::int32_t>(std::max(1.0, c));
    };
    g.nx = w >= hh ? static_cast<std::int32_t>(resolution) : count(w);
    g.ny = hh >= w ? static_cast<std::int32_t>(resolution) : count(hh);
    return g;
}

/// Does cell (i, j) overlap the working area with positive area? (Separating axes: the cell's two
/// axes and the area's edge normals; touching along an edge or a corner is not overlapping.)
/// \note O(area vertices); O(1) for a box area.
inline bool cell_in_area(const Scene& s, const GridSpec& g, std::int64_t i, std::int64_t j) {
    if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) return false;
    const Vec2 lo = g.corner(i, j), hi = g.corner(i + 1, j + 1);
    if (!(lo.x() < s.box.x1 && hi.x() > s.box.x0 && lo.y() < s.box.y1 && hi.y() > s.box.y0)) return false;
    if (s.area_is_box) return true;
    const Vec2 c[4] = {lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
    const std::size_t n = s.area.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& a = s.area[k];
        const Vec2& b = s.area[(k + 1) % n];
        bool all_out = true;  // every cell corner on or outside the edge's line
        for (const Vec2& q : c)
            if (pred::orient(a, b, q) > 0) { all_out = false; break; }
        if (all_out) return false;
    }
    return true;
}

}  // namespace dvoronoi::gvd
