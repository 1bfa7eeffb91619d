// Exact (unlimited) Voronoi cells in Python: voronoi_cell (one agent) and voronoi_cells (all agents),
// by Adjust-Sensing-Radius with Boundary Scan or EVT as the inner step. Neighbour sets and hull flags
// are exact; arrays are copied out once (the results are small: CSR plus per-agent counters).
#include "arrays.hpp"
#include "progress.hpp"

#include "dvoronoi/cells/asr.hpp"
#include "dvoronoi/partition/voronoi_partition.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
using dvoronoi::AsrInner;
using dvoronoi::ClippedCell;
using dvoronoi::ConvexRegion;
using dvoronoi::VoronoiCell;
using dvoronoi::VoronoiEdge;
using dvoronoi::VoronoiPartition;

namespace {

AsrInner parse_inner(const std::string& name) {
    if (name == "auto") return AsrInner::Auto;
    if (name == "scan") return AsrInner::Scan;
    if (name == "evt") return AsrInner::Evt;
    throw py::value_error("inner must be \"auto\", \"scan\" or \"evt\", got \"" + name + "\"");
}

/// bounds=None | (xmin, ymin, xmax, ymax) | (k, 2) convex polygon.
ConvexRegion region_arg(py::handle obj) {
    if (obj.is_none()) return ConvexRegion();
    const py::array arr = as_array(obj, "bounds", "a box (xmin, ymin, xmax, ymax) or a (k, 2) convex polygon");
    if (arr.ndim() == 1 && arr.shape(0) == 4) {
        const py::array_t<double, py::array::forcecast> b(arr);
        return ConvexRegion::box(b.at(0), b.at(1), b.at(2), b.at(3), "bounds");
    }
    if (arr.ndim() == 2 && arr.shape(1) == 2) {
        const PointsArg poly = points_arg(arr, "bounds");
        return ConvexRegion::polygon(poly.ref(), "bounds");
    }
    throw py::value_error("bounds must be a box (xmin, ymin, xmax, ymax) or a (k, 2) array of convex polygon "
                          "vertices, got shape " + shape_str(arr));
}

py::tuple xy(const Vec2& v) { return py::make_tuple(v.x(), v.y()); }

}  // namespace

void bind_voronoi(py::module_& m) {
    py::class_<ClippedCell>(m, "ClippedCell", "A Voronoi cell cut to the caller's convex region (a convex polygon).")
        .def_property_readonly("vertices", [](const ClippedCell& c) { return xy_array(c.vertices); },
                               "Counter-clockwise vertices, shape (k, 2) (empty when the cell misses the region).")
        .def_property_readonly("side_neighbors", [](const ClippedCell& c) { return copy_array<Index>(c.side_neighbor); },
                               "Per side (vertex k -> k+1): the Voronoi neighbour, or -1 on the region's boundary.")
        .def_readonly("area", &ClippedCell::area)
        .def_property_readonly("centroid", [](const ClippedCell& c) { return xy(c.centroid); })
        .def("__repr__", [](const ClippedCell& c) {
            return "ClippedCell(vertices=" + std::to_string(c.vertices.size()) + ", area=" + std::to_string(c.area) + ")";
        });

    py::class_<VoronoiEdge>(m, "VoronoiEdge",
                            "One edge of an exact Voronoi cell, counter-clockwise. An edge from (to) "
                            "infinity has `start` (`end`) at the foot of its bisector, a point of its line.")
        .def_readonly("neighbor", &VoronoiEdge::neighbor)
        .def_property_readonly("start", [](const VoronoiEdge& e) { return py::make_tuple(e.start.x(), e.start.y()); })
        .def_property_readonly("end", [](const VoronoiEdge& e) { return py::make_tuple(e.end.x(), e.end.y()); })
        .def_property_readonly("direction", [](const VoronoiEdge& e) { return py::make_tuple(e.direction.x(), e.direction.y()); })
        .def_readonly("from_infinity", &VoronoiEdge::from_infinity)
        .def_readonly("to_infinity", &VoronoiEdge::to_infinity)
        .def("__repr__", [](const VoronoiEdge& e) {
            return "VoronoiEdge(neighbor=" + std::to_string(e.neighbor) + (e.from_infinity ? ", from infinity" : "") +
                   (e.to_infinity ? ", to infinity" : "") + ")";
        });

    py::class_<VoronoiCell>(m, "VoronoiCell", "The exact Voronoi cell of one agent (compiled core).")
        .def_property_readonly("center", [](const VoronoiCell& c) { return py::make_tuple(c.center.x(), c.center.y()); })
        .def_readonly("edges", &VoronoiCell::edges, "Counter-clockwise edges (a chain from ray to ray when unbounded).")
        .def_property_readonly("neighbors", [](const VoronoiCell& c) { return copy_array<Index>(c.neighbors()); },
                               "Voronoi neighbours (positive-length edges), int64, ascending.")
        .def_property_readonly("vertices",
                               [](const VoronoiCell& c) {
                                   std::vector<Vec2> v;
                                   for (const VoronoiEdge& e : c.edges)
                                       if (!e.from_infinity) v.push_back(e.start);
                                   return xy_array(v);
                               },
                               "Finite vertices, counter-clockwise, shape (k, 2).")
        .def_readonly("on_hull", &VoronoiCell::on_hull, "The cell is unbounded (the agent is on the convex hull).")
        .def_property_readonly("clipped", [](const VoronoiCell& c) -> py::object {
            return c.is_clipped ? py::cast(c.clipped) : py::none();
        }, "The cell cut to the `bounds` region (a ClippedCell), or None when no bounds were given.")
        .def_property_readonly("area", &VoronoiCell::area,
                               "Area of the clipped cell (with bounds), else of the bounded cell; NaN when unbounded.")
        .def_property_readonly("centroid", [](const VoronoiCell& c) { return xy(c.centroid()); })
        .def_readonly("radius_steps", &VoronoiCell::radius_steps)
        .def_readonly("agents_used", &VoronoiCell::agents_used)
        .def("__repr__", [](const VoronoiCell& c) {
            return "VoronoiCell(edges=" + std::to_string(c.edges.size()) + ", on_hull=" + (c.on_hull ? "True" : "False") +
                   ", radius_steps=" + std::to_string(c.radius_steps) + ")";
        });

    m.def(
        "voronoi_cell",
        [](py::handle center, py::handle others, const std::string& inner, py::handle bounds) {
            const Vec2 c = point_arg(center, "center");
            const PointsArg o = points_arg(others, "others");
            const AsrInner in = parse_inner(inner);
            return dvoronoi::asr_cell(c, o.ref(), in, region_arg(bounds));
        },
        py::arg("center"), py::arg("others"), py::arg("inner") = "auto", py::arg("bounds") = py::none(),
        "voronoi_cell(center, others, inner=\"auto\", bounds=None) -> VoronoiCell\n\n"
        "The exact Voronoi cell of the agent at `center` among `others` by Adjust-Sensing-Radius, with "
        "the Boundary Scan limited cell (\"scan\"; \"auto\" is the same for one agent) or our exact "
        "Delaunay tessellation (\"evt\") as the inner step. Edge neighbours are rows of `others`.");

    py::class_<VoronoiPartition>(m, "VoronoiPartition", "Exact Voronoi neighbours and hull flags of n agents (compiled core).")
        .def_property_readonly("points", [](const py::object& s) { return view(s.cast<const VoronoiPartition&>().points, s); })
        .def_property_readonly("indptr", [](const VoronoiPartition& p) { return copy_array<Index>(p.indptr); })
        .def_property_readonly("indices", [](const VoronoiPartition& p) { return copy_array<Index>(p.indices); })
        .def_property_readonly("on_hull", [](const VoronoiPartition& p) { return copy_array<bool>(p.on_hull); })
        .def_property_readonly("radius_steps", [](const VoronoiPartition& p) { return copy_array<std::int32_t>(p.radius_steps); })
        .def_property_readonly("agents_used", [](const VoronoiPartition& p) { return copy_array<Index>(p.agents_used); })
        .def_property_readonly("areas", [](const VoronoiPartition& p) { return copy_array<double>(p.areas); })
        .def_property_readonly(
            "computed_by",
            [](const VoronoiPartition& p) {
                py::dict d;
                d["one_shot"] = p.computed_by.one_shot;
                d["deferred"] = p.computed_by.deferred;
                d["asr"] = p.computed_by.asr;
                return d;
            },
            "How the cells were found: {\"one_shot\": one certified clipping (auto), \"deferred\": from "
            "the triangulation of the agents it left (auto), \"asr\": Adjust-Sensing-Radius with the inner "
            "step (scan, evt)}; the values add up to n.")
        .def_property_readonly("centroids", [](const py::object& s) { return view(s.cast<const VoronoiPartition&>().centroids, s); })
        .def_property_readonly("bounds", [](const VoronoiPartition& p) -> py::object {
            if (p.bounds.empty()) return py::none();
            return xy_array(p.bounds.vertices());
        })
        .def("cell", [](const VoronoiPartition& p, Index i) { return p.cell(i); }, py::arg("i"))
        .def("__len__", &VoronoiPartition::size);

    m.def(
        "voronoi_cells",
        [](py::handle points, const std::string& inner, int threads, py::object progress, py::handle bounds) {
            const PointsArg pts = points_arg(points, "points");
            const AsrInner in = parse_inner(inner);
            const ConvexRegion region = region_arg(bounds);
            if (threads < 0)
                throw py::value_error("threads must be >= 0 (0 = all cores), got " + std::to_string(threads));
            PyProgress report(std::move(progress));
            const dvoronoi::ProgressFn fn = report.fn();
            VoronoiPartition result;
            {
                py::gil_scoped_release release;
                result = dvoronoi::voronoi_cells(pts.ref(), in, threads, fn, region);
            }
            report.rethrow();
            return result;
        },
        py::arg("points"), py::arg("inner") = "auto", py::arg("threads") = 0, py::arg("progress") = py::none(),
        py::arg("bounds") = py::none(),
        "voronoi_cells(points, inner=\"auto\", threads=0, progress=None, bounds=None) -> VoronoiPartition\n\n"
        "Every agent's exact Voronoi neighbours and hull flag: \"scan\" / \"evt\" run Adjust-Sensing-Radius "
        "with that inner step on every agent, \"auto\" our certified fast path (GIL released).");
}
