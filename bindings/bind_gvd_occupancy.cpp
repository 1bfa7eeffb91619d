// The grid diagram on occupancy grids in Python (dvoronoi.gvd wraps these private classes): the
// medial diagram with its incremental updates, paths and clearance queries, map files read by the
// C++ loaders (the CLI's), JSON and SVG by the C++ writers, and the brute-force oracle for tests.
// Heavy work runs with the GIL released.
#include "arrays.hpp"

#include "dvoronoi/core/pages.hpp"
#include "dvoronoi/gvd/grid_path.hpp"
#include "dvoronoi/gvd/medial_brute_force.hpp"
#include "dvoronoi/gvd/medial_update.hpp"
#include "dvoronoi/io/medial_export.hpp"
#include "dvoronoi/io/occupancy_map.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
namespace gvd = dvoronoi::gvd;

namespace {

using OccArray = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

gvd::OccupancyGrid grid_from(const OccArray& occ, double resolution, double ox, double oy, int workers = 1) {
    if (occ.ndim() != 2) throw py::value_error("occupancy must be a 2-d array, got " + std::to_string(occ.ndim()) + " dimensions");
    gvd::OccupancyGrid g;
    g.rows = static_cast<std::int32_t>(occ.shape(0));
    g.cols = static_cast<std::int32_t>(occ.shape(1));
    g.resolution = resolution;
    g.origin = Vec2(ox, oy);
    // A copy into unfilled memory (its pages faulted in by the copying threads), not a zero-fill and
    // a loop. Any nonzero byte is occupied; bool arrays (the Python side's) hold 0 and 1 already.
    const std::size_t n = static_cast<std::size_t>(occ.size());
    g.occupied.resize(n);
    dvoronoi::detail::advise_huge_pages(g.occupied.data(), n);  // before the first touch
    const std::size_t W = std::max<std::size_t>(1, static_cast<std::size_t>(g.cols));
    const auto rows_a_chunk = static_cast<std::int32_t>(std::max<std::size_t>(1, (std::size_t{1} << 20) / W));  // ~1 MB
    dvoronoi::run_chunks(n > (std::size_t{1} << 20) ? workers : 1, g.rows, rows_a_chunk, [] { return 0; },
                         [&](int&, std::int32_t r0, std::int32_t r1) {
        const std::size_t lo = static_cast<std::size_t>(r0) * W, hi = std::min(n, static_cast<std::size_t>(r1) * W);
        if (lo >= hi) return;  // a map of no columns
        std::memcpy(g.occupied.data() + lo, occ.data() + lo, hi - lo);
        std::uint8_t any = 0;  // an OR over the bytes (vectorised): above 1 when a byte is neither 0 nor 1
        for (std::size_t i = lo; i < hi; ++i) any |= g.occupied[i];
        if (any > 1)
            for (std::size_t i = lo; i < hi; ++i) g.occupied[i] = g.occupied[i] != 0;
    });
    return g;
}

template <class Bytes>
py::array_t<bool> bool_image(const Bytes& v, std::int32_t rows, std::int32_t cols) {
    py::array_t<bool> a({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
    bool* out = a.mutable_data();
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] != 0;
    return a;
}

py::dict stats_dict(const gvd::UpdateStats& s) {
    py::dict d;
    d["changed_pixels"] = s.changed_pixels;
    d["column_cells"] = s.column_cells;
    d["feature_changes"] = s.feature_changes;
    d["mask_checks"] = s.mask_checks;
    return d;
}

template <class Fn>
auto without_gil(Fn&& fn) {
    try {
        py::gil_scoped_release release;
        return fn();
    } catch (const dvoronoi::InputError&) {
        throw;  // to the translator (bind_core.cpp): a ValueError whose message stays UTF-8
    }
}


}  // namespace

void bind_gvd_occupancy(py::module_& m) {
    py::class_<gvd::MedialDiagram>(m, "_MedialDiagram", "Medial diagram of an occupancy grid (private; see dvoronoi.OccupancyVoronoi).")
        .def_property_readonly("shape", [](const gvd::MedialDiagram& d) { return py::make_tuple(d.grid.rows, d.grid.cols); })
        .def_property_readonly("resolution", [](const gvd::MedialDiagram& d) { return d.grid.resolution; })
        .def_property_readonly("origin", [](const gvd::MedialDiagram& d) { return py::make_tuple(d.grid.origin.x(), d.grid.origin.y()); })
        .def_property_readonly("count", [](const gvd::MedialDiagram& d) { return d.count(); })
        .def_property_readonly("mask", [](const gvd::MedialDiagram& d) {
            py::array_t<bool> a({static_cast<py::ssize_t>(d.grid.rows), static_cast<py::ssize_t>(d.grid.cols)});
            static_assert(sizeof(bool) == 1, "numpy bools are bytes");
            auto* out = reinterpret_cast<std::uint8_t*>(a.mutable_data());
            py::gil_scoped_release release;
            d.mask.to_bytes(out, d.options.workers);
            return a;
        })
        .def_property_readonly("occupancy", [](const gvd::MedialDiagram& d) { return bool_image(d.grid.occupied, d.grid.rows, d.grid.cols); })
        .def_property_readonly("clearance_map", [](const gvd::MedialDiagram& d) {
            py::array_t<double> a({static_cast<py::ssize_t>(d.grid.rows), static_cast<py::ssize_t>(d.grid.cols)});
            double* out = a.mutable_data();
            {
                py::gil_scoped_release release;
                for (std::int32_t r = 0; r < d.grid.rows; ++r)
                    for (std::int32_t c = 0; c < d.grid.cols; ++c) out[d.grid.at(r, c)] = d.clearance(r, c);
            }
            return a;
        })
        .def_property_readonly("nearest_points", [](const gvd::MedialDiagram& d) {
            py::array_t<double> a({static_cast<py::ssize_t>(d.grid.rows), static_cast<py::ssize_t>(d.grid.cols), py::ssize_t{2}});
            double* out = a.mutable_data();
            for (std::size_t i = 0; i < d.grid.size(); ++i) {
                const Vec2 p = d.grid.from_doubled(d.features.fx[i], d.features.fy[i]);
                out[2 * i] = p.x();
                out[2 * i + 1] = p.y();
            }
            return a;
        })
        .def("update", [](gvd::MedialDiagram& d, const OccArray& occ) {
            if (occ.ndim() != 2 || occ.shape(0) != d.grid.rows || occ.shape(1) != d.grid.cols)
                throw py::value_error("new_occupancy must have the map's shape (" + std::to_string(d.grid.rows) + ", " +
                                      std::to_string(d.grid.cols) + "), got " + shape_str(occ));
            std::vector<std::uint8_t> v(occ.data(), occ.data() + occ.size());
            return stats_dict(without_gil([&] { return gvd::update_occupancy(d, v); }));
        }, py::arg("new_occupancy"))
        .def("set_pixels", [](gvd::MedialDiagram& d, const IndexArray& idx, bool occupied) {
            // a numpy array, not a list: converting a list of Python ints costs more than the update
            if (idx.ndim() != 1) throw py::value_error("indices must be a 1-d array, got " + shape_str(idx));
            std::vector<std::size_t> v(static_cast<std::size_t>(idx.size()));
            const std::int64_t* in = idx.data();
            for (std::size_t k = 0; k < v.size(); ++k) {
                if (in[k] < 0) throw py::value_error("pixel index " + std::to_string(in[k]) + " is negative");
                v[k] = static_cast<std::size_t>(in[k]);
            }
            return stats_dict(without_gil([&] { return gvd::set_pixels(d, v, occupied); }));
        }, py::arg("indices"), py::arg("occupied"))
        .def("set_mask", [](gvd::MedialDiagram& d, const OccArray& mask, bool occupied) {
            if (mask.ndim() != 2 || mask.shape(0) != d.grid.rows || mask.shape(1) != d.grid.cols)
                throw py::value_error("the mask must have the map's shape (" + std::to_string(d.grid.rows) + ", " +
                                      std::to_string(d.grid.cols) + "), got " + shape_str(mask));
            return stats_dict(without_gil([&] { return gvd::set_pixels_where(d, mask.data(), occupied); }));
        }, py::arg("mask"), py::arg("occupied"))
        .def("path", [](const gvd::MedialDiagram& d, py::handle start, py::handle goal, double robot_radius, double off_cost) {
            const Vec2 s = point_arg(start, "start"), g = point_arg(goal, "goal");
            const gvd::GridPath p = without_gil([&] { return gvd::find_grid_path(d, s, g, robot_radius, off_cost); });
            return py::make_tuple(xy_array(p.points), p.length, p.expanded);
        }, py::arg("start"), py::arg("goal"), py::arg("robot_radius"), py::arg("off_diagram_cost"))
        .def("clearance", [](const gvd::MedialDiagram& d, py::handle points) {
            PointsArg a = points_arg(points, "points");
            const auto n = a.ref().rows();
            py::array_t<double> out(static_cast<py::ssize_t>(n));
            double* o = out.mutable_data();
            for (Eigen::Index k = 0; k < n; ++k)
                if (!std::isfinite(a.ref()(k, 0)) || !std::isfinite(a.ref()(k, 1)))
                    throw py::value_error("points[" + std::to_string(k) + "] is not finite");
            without_gil([&] {
                for (Eigen::Index k = 0; k < n; ++k)
                    o[k] = gvd::point_clearance(d, d.grid.to_pixels(Vec2(a.ref()(k, 0), a.ref()(k, 1)))) * d.grid.resolution;
                return 0;
            });
            return out;
        }, py::arg("points"))
        .def("to_json", [](const gvd::MedialDiagram& d, double robot_radius, py::handle path, int indent) {
            nlohmann::json j = dvoronoi::io::medial_to_json(d, robot_radius);
            if (!path.is_none()) {
                gvd::GridPath p;
                p.points = finite_points_arg(path, "route");
                for (std::size_t k = 0; k + 1 < p.points.size(); ++k) p.length += (p.points[k + 1] - p.points[k]).norm();
                j["path"] = dvoronoi::io::path_to_json(p);
            }
            return j.dump(indent);
        }, py::arg("robot_radius"), py::arg("path") = py::none(), py::arg("indent") = -1)
        .def("to_svg", [](const gvd::MedialDiagram& d, double robot_radius, py::handle path) {
            std::ostringstream os;
            dvoronoi::io::write_medial_svg(os, d, robot_radius, finite_points_arg(path, "route"));
            return os.str();
        }, py::arg("robot_radius"), py::arg("path") = py::none());

    m.def("_medial_build", [](const OccArray& occ, double resolution, double ox, double oy, double min_separation,
                              double prune_length, int workers) {
        gvd::OccupancyGrid g = grid_from(occ, resolution, ox, oy, workers);
        gvd::MedialOptions o;
        o.min_separation = min_separation;
        o.prune_length = prune_length;
        o.workers = workers;
        return without_gil([&] { return gvd::medial_diagram(std::move(g), o); });
    }, py::arg("occupancy"), py::arg("resolution"), py::arg("origin_x"), py::arg("origin_y"), py::arg("min_separation"),
       py::arg("prune_length"), py::arg("workers"));

    m.def("_medial_brute_force", [](const OccArray& occ, double min_separation, double prune_length) {
        const gvd::OccupancyGrid g = grid_from(occ, 1.0, 0.0, 0.0);
        gvd::MedialOptions o;
        o.min_separation = min_separation;
        o.prune_length = prune_length;
        const auto mask = without_gil([&] { return gvd::brute_force_medial(g, o); });
        return bool_image(mask, g.rows, g.cols);
    }, py::arg("occupancy"), py::arg("min_separation"), py::arg("prune_length"),
       "Brute-force oracle of the medial diagram (small maps).");

    m.def("_read_movingai", [](const std::string& path, const std::string& free_chars) {
        dvoronoi::io::MapReadOptions o;
        o.movingai_free = free_chars;
        dvoronoi::io::LoadedMap lm = without_gil([&] { return dvoronoi::io::detail::read_movingai(path, o); });
        return bool_image(lm.grid.occupied, lm.grid.rows, lm.grid.cols);
    }, py::arg("path"), py::arg("free_chars"), "A MovingAI .map file as an H x W bool array (True: blocked).");

    m.def("_load_occupancy_map", [](const std::string& path, bool unknown_occupied, double resolution, double ox, double oy,
                                    double occupied_thresh, double free_thresh, bool negate) {
        dvoronoi::io::MapReadOptions o;
        o.unknown_occupied = unknown_occupied;
        o.resolution = resolution;
        o.origin = Vec2(ox, oy);
        o.occupied_thresh = occupied_thresh;
        o.free_thresh = free_thresh;
        o.negate = negate;
        dvoronoi::io::LoadedMap lm = without_gil([&] { return dvoronoi::io::read_occupancy_map(path, o); });
        return py::make_tuple(bool_image(lm.grid.occupied, lm.grid.rows, lm.grid.cols), lm.grid.resolution,
                              py::make_tuple(lm.grid.origin.x(), lm.grid.origin.y()), lm.unknown, lm.image, lm.occupied_thresh);
    }, py::arg("path"), py::arg("unknown_occupied"), py::arg("resolution"), py::arg("origin_x"), py::arg("origin_y"),
       py::arg("occupied_thresh"), py::arg("free_thresh"), py::arg("negate"));
#ifdef DVORONOI_HAVE_PNG
    m.attr("_has_png") = true;
#else
    m.attr("_has_png") = false;
#endif
}
