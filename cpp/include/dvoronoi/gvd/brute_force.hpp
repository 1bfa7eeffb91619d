// The brute-force oracle of the grid Voronoi diagram (docs/spec.md): every corner of the grid labelled by
// scanning every obstacle part (no index; same distances and tie rule as the tracer), and every
// working-area cell whose corners carry two or more labels marked. Used by the tests; O(grid area x
// obstacles).
#pragma once

#include "dvoronoi/gvd/grid.hpp"
#include "dvoronoi/gvd/obstacle_index.hpp"

#include <cstdint>
#include <vector>

namespace dvoronoi::gvd {

struct BruteForceLabels {
    GridSpec grid;
    std::vector<std::int32_t> corner_label;  ///< (ny + 1) x (nx + 1), row-major: [j * (nx + 1) + i]
    std::vector<double> corner_sq;           ///< squared distances, same layout
    std::vector<std::uint8_t> mixed;         ///< ny x nx: in the area and >= 2 corner labels
};

inline BruteForceLabels brute_force_labels(const Scene& scene, std::int64_t resolution, bool visibility = true) {
    BruteForceLabels out;
    out.grid = make_grid(scene, resolution);
    const GridSpec& g = out.grid;
    const std::size_t w = static_cast<std::size_t>(g.nx) + 1, h = static_cast<std::size_t>(g.ny) + 1;
    out.corner_label.resize(w * h);
    out.corner_sq.resize(w * h);
    for (std::size_t j = 0; j < h; ++j)
        for (std::size_t i = 0; i < w; ++i) {
            const Nearest n = nearest_brute_force(scene, g.corner(static_cast<std::int64_t>(i), static_cast<std::int64_t>(j)), visibility);
            out.corner_label[j * w + i] = n.label;
            out.corner_sq[j * w + i] = n.sq;
        }
    out.mixed.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), 0);
    for (std::int32_t j = 0; j < g.ny; ++j)
        for (std::int32_t i = 0; i < g.nx; ++i) {
            const auto uj = static_cast<std::size_t>(j), ui = static_cast<std::size_t>(i);
            const std::int32_t a = out.corner_label[uj * w + ui], b = out.corner_label[uj * w + ui + 1],
                               c = out.corner_label[(uj + 1) * w + ui + 1], d = out.corner_label[(uj + 1) * w + ui];
            if ((a != b || b != c || c != d) && cell_in_area(scene, g, i, j))
                out.mixed[uj * static_cast<std::size_t>(g.nx) + ui] = 1;
        }
    return out;
}

}  // namespace dvoronoi::gvd
