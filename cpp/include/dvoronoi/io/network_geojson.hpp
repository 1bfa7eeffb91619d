// GeoJSON export of a network simulation's cells (network/run.hpp), written here once for the CLI
// (`dvoronoi network ... -o cells.geojson`) and Python (`result.to_geojson()`, `__geo_interface__`):
// the same run gives the same text. A FeatureCollection with one Feature per node, in input order:
//
//   {"features":[{"geometry":{"coordinates":[[[x,y],...]],"type":"Polygon"} | null,
//                 "properties":{"agent":i,"area":a | null,"neighbors":[j,...]},"type":"Feature"},...],
//    "type":"FeatureCollection"}
//
// The ring is the cell's cycle of pieces, counter-clockwise and closed (RFC 7946, section 3.1.6): CC's
// cells (clipped to the bounds when given), BD07's clipped cells, and Boundary Scan's limited cells
// with each arc replaced by chords whose sagitta is at most `tolerance` (as io/geojson.hpp does, around
// the position the node used). A cell without a polygon has a null geometry: a CC hull cell without
// bounds (unbounded), a Boundary Scan node DV-Hop did not localise. `area` is the exact area (null when
// infinite or unknown), `neighbors` the run's neighbour relation (neighbors(i)), ascending.
#pragma once

#include "dvoronoi/io/geojson.hpp"
#include "dvoronoi/io/json.hpp"
#include "dvoronoi/network/run.hpp"

#include <cmath>
#include <ostream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace dvoronoi::io {

namespace detail {

/// Node i's ring: piece starts, points on every arc (span > 0) around `center` with radius `radius`
/// (chords of sagitta <= tol), the first point repeated; empty for a cell without pieces.
inline std::vector<Vec2> network_ring(const network::FlatCells& cells, Index i, const Vec2& center, double radius,
                                      double tol) {
    std::vector<Vec2> ring;
    for (Index k = cells.piece_ptr[static_cast<std::size_t>(i)]; k < cells.piece_ptr[static_cast<std::size_t>(i) + 1]; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const Vec2 start(cells.piece_x[kk], cells.piece_y[kk]);
        ring.push_back(start);
        const double span = cells.piece_span[kk];
        if (!(span > 0.0)) continue;  // an edge (a bisector or a side of the region)
        const Index m = arc_segments(span, radius, tol);
        const Vec2 u = start - center;
        const double a0 = std::atan2(u.y(), u.x());
        for (Index j = 1; j < m; ++j) {
            const double a = a0 + span * static_cast<double>(j) / static_cast<double>(m);
            ring.push_back(center + radius * Vec2(std::cos(a), std::sin(a)));
        }
    }
    if (!ring.empty()) ring.push_back(ring.front());
    return ring;
}

/// The collection; `centers` are the points the cells were computed around, `radius` their circles'
/// radius (0: no arcs).
inline void write_network_collection(JsonText& w, const network::RunBase& r, const Points& centers, double radius,
                                     double tolerance) {
    const double tol = check_tolerance(tolerance, radius > 0.0 ? radius : 1.0);
    w.raw("{\"features\":[");
    for (Index i = 0; i < r.size(); ++i) {
        if (i) w.raw(',');
        const std::vector<Vec2> ring = network_ring(r.cells, i, centers.row(i).transpose(), radius, tol);
        if (ring.size() < 4) {  // no polygon
            w.raw("{\"geometry\":null");
        } else {
            w.raw("{\"geometry\":{\"coordinates\":[[");
            for (std::size_t k = 0; k < ring.size(); ++k) {
                if (k) w.raw(',');
                w.xy(ring[k]);
            }
            w.raw("]],\"type\":\"Polygon\"}");
        }
        const auto ii = static_cast<std::size_t>(i);
        w.raw(",\"properties\":{");
        w.key("agent");
        w.num(i);
        w.raw(',');
        w.key("area");
        w.num(ii < r.cells.areas.size() ? r.cells.areas[ii] : std::nan(""));  // inf, NaN -> null
        w.raw(',');
        w.key("neighbors");
        w.raw('[');
        for (Index q = r.indptr[ii]; q < r.indptr[ii + 1]; ++q) {
            if (q > r.indptr[ii]) w.raw(',');
            w.num(r.indices[static_cast<std::size_t>(q)]);
        }
        w.raw("]},\"type\":\"Feature\"}");
        w.maybe_flush();
    }
    w.raw("],\"type\":\"FeatureCollection\"}");
}

/// One typed run: Boundary Scan's cells around the positions used, with arcs; the others' polygons.
template <class R>
void write_run(JsonText& w, const R& r, double tolerance) {
    if constexpr (std::is_same_v<R, network::BsRun>)
        write_network_collection(w, r, r.positions, r.radius, tolerance);
    else
        write_network_collection(w, r, r.points, 0.0, tolerance);
}

}  // namespace detail

/// Writes the run's cells as a GeoJSON FeatureCollection (see the top of this header), compact, no
/// trailing newline, streaming.
/// \param tolerance largest sagitta of an arc chord (Boundary Scan); 0 = default_tolerance(radius).
/// \throws InputError for a negative or non-finite tolerance, or one so small that an arc would need
///         more than 1e7 chords.
inline void write_network_geojson(std::ostream& os, const network::Result& result, double tolerance = 0.0) {
    detail::JsonText w(&os);
    std::visit([&](const auto& r) { detail::write_run(w, r, tolerance); }, result);
    w.flush();
}

/// The GeoJSON text of one typed run's cells.
template <class R, class = std::enable_if_t<std::is_base_of_v<network::RunBase, R>>>
std::string network_geojson_text(const R& r, double tolerance = 0.0) {
    detail::JsonText w;
    detail::write_run(w, r, tolerance);
    return w.take();
}

}  // namespace dvoronoi::io
