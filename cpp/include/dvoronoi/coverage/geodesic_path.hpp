// Shortest paths out of a geodesic field (geodesic_distance.hpp); every segment passes the exact test of
// grid_segment.hpp before an agent moves along it.
#pragma once

#include "dvoronoi/coverage/geodesic_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dvoronoi::coverage {

/*! The polyline from pixel q's source to point `t` (in pixel q): source, the anchors (bends) in order,
    then `t`; each segment checked with segment_free. When the segment from `t` to q's anchor is not free
    the path goes through q's centre first. Empty when q is unreached or a segment is not free (the
    wavefront checks every segment it uses, so this is a guard, not an expected case). */
inline std::vector<PixelPoint> geodesic_path(const GeodesicField& f, const OccupancyView& g, std::int64_t q,
                                             PixelPoint t) {
    std::vector<PixelPoint> path;
    if (q < 0 || f.anchor[static_cast<std::size_t>(q)] < 0) return path;
    path.push_back(t);
    std::int64_t a = f.anchor[static_cast<std::size_t>(q)];
    const PixelPoint centre{double(q % f.cols) + 0.5, double(q / f.cols) + 0.5};
    if (!segment_free(g, t, f.anchor_point(a))) path.push_back(centre);
    const std::int64_t guard = std::int64_t(f.distance.size()) + f.vertices() + f.sources;
    for (std::int64_t k = 0; a >= 0 && k <= guard; ++k) {
        const PixelPoint A = f.anchor_point(a);
        if (!segment_free(g, path.back(), A)) return {};
        path.push_back(A);
        a = f.anchor_parent(a);
    }
    if (a >= 0) return {};  // a cycle of relays (cannot happen with a settled field; guarded)
    std::reverse(path.begin(), path.end());
    return path;
}

//! The point at arc length `s` along a polyline (its end when s >= its length).
inline PixelPoint point_along(const std::vector<PixelPoint>& path, double s) {
    for (std::size_t k = 1; k < path.size(); ++k) {
        const double len = std::hypot(path[k].u - path[k - 1].u, path[k].w - path[k - 1].w);
        if (s < len) {
            const double t = s / len;
            return {path[k - 1].u + t * (path[k].u - path[k - 1].u), path[k - 1].w + t * (path[k].w - path[k - 1].w)};
        }
        s -= len;
    }
    return path.back();
}

inline double path_length(const std::vector<PixelPoint>& path) {
    double s = 0;
    for (std::size_t k = 1; k < path.size(); ++k) s += std::hypot(path[k].u - path[k - 1].u, path[k].w - path[k - 1].w);
    return s;
}

}  // namespace dvoronoi::coverage
