// Exact (unlimited) Voronoi cells in Python: voronoi_cell (one agent) and voronoi_cells (all agents),
// by Adjust-Sensing-Radius with Boundary Scan or EVT as the inner step. Neighbour sets and hull flags
// are exact; arrays are copied out once (the results are small: CSR plus per-agent counters).
#include "arrays.hpp"
#include "pickle.hpp"
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

// Pickled states: every field (see pickle.hpp).
py::tuple voronoi_cell_state(const VoronoiCell& c) {
    py::dict d;
    d["center"] = np_of(c.center);
    std::vector<Index> nb;
    std::vector<Vec2> start, end, dir;
    std::vector<std::uint8_t> from_inf, to_inf;
    for (const VoronoiEdge& e : c.edges) {
        nb.push_back(e.neighbor);
        start.push_back(e.start);
        end.push_back(e.end);
        dir.push_back(e.direction);
        from_inf.push_back(e.from_infinity ? 1 : 0);
        to_inf.push_back(e.to_infinity ? 1 : 0);
    }
    d["edge_neighbor"] = np_of(nb);
    d["edge_start"] = xy_array(start);
    d["edge_end"] = xy_array(end);
    d["edge_direction"] = xy_array(dir);
    d["edge_from_infinity"] = np_of(from_inf);
    d["edge_to_infinity"] = np_of(to_inf);
    d["on_hull"] = c.on_hull;
    d["radius_steps"] = c.radius_steps;
    d["agents_used"] = c.agents_used;
    d["is_clipped"] = c.is_clipped;
    d["clipped_vertices"] = xy_array(c.clipped.vertices);
    d["clipped_side_neighbor"] = np_of(c.clipped.side_neighbor);
    d["clipped_area"] = c.clipped.area;
    d["clipped_centroid"] = np_of(c.clipped.centroid);
    return make_state(d);
}

VoronoiCell voronoi_cell_from_state(const py::tuple& t) {
    const py::dict d = state_dict(t, "VoronoiCell");
    VoronoiCell c;
    c.center = vec2_of(d, "center");
    const auto nb = vec_of<Index>(d, "edge_neighbor");
    const auto start = vec2s_of(d, "edge_start"), end = vec2s_of(d, "edge_end"), dir = vec2s_of(d, "edge_direction");
    const auto from_inf = vec_of<std::uint8_t>(d, "edge_from_infinity"), to_inf = vec_of<std::uint8_t>(d, "edge_to_infinity");
    if (start.size() != nb.size() || end.size() != nb.size() || dir.size() != nb.size() || from_inf.size() != nb.size() ||
        to_inf.size() != nb.size())
        throw py::value_error("pickled VoronoiCell: edge arrays of different lengths");
    for (std::size_t k = 0; k < nb.size(); ++k)
        c.edges.push_back({nb[k], start[k], end[k], dir[k], from_inf[k] != 0, to_inf[k] != 0});
    c.on_hull = d["on_hull"].cast<bool>();
    c.radius_steps = d["radius_steps"].cast<int>();
    c.agents_used = d["agents_used"].cast<Index>();
    c.is_clipped = d["is_clipped"].cast<bool>();
    c.clipped.vertices = vec2s_of(d, "clipped_vertices");
    c.clipped.side_neighbor = vec_of<Index>(d, "clipped_side_neighbor");
    c.clipped.area = d["clipped_area"].cast<double>();
    c.clipped.centroid = vec2_of(d, "clipped_centroid");
    return c;
}

py::tuple voronoi_partition_state(const VoronoiPartition& p) {
    py::dict d;
    d["points"] = np_of(p.points);
    d["indptr"] = np_of(p.indptr);
    d["indices"] = np_of(p.indices);
    d["on_hull"] = np_of(std::vector<std::uint8_t>(p.on_hull.begin(), p.on_hull.end()));
    d["radius_steps"] = np_of(p.radius_steps);
    d["agents_used"] = np_of(p.agents_used);
    d["bounds"] = xy_array(p.bounds.empty() ? std::vector<Vec2>{} : p.bounds.vertices());
    d["areas"] = np_of(p.areas);
    d["centroids"] = np_of(p.centroids);
    d["computed_by"] = np_of(std::vector<Index>{static_cast<Index>(p.computed_by.one_shot),
                                                static_cast<Index>(p.computed_by.deferred), static_cast<Index>(p.computed_by.asr)});
    return make_state(d);
}

VoronoiPartition voronoi_partition_from_state(const py::tuple& t) {
    const py::dict d = state_dict(t, "VoronoiPartition");
    VoronoiPartition p;
    p.points = points_of(d, "points");
    p.indptr = vec_of<Index>(d, "indptr");
    p.indices = vec_of<Index>(d, "indices");
    const auto hull = vec_of<std::uint8_t>(d, "on_hull");
    p.on_hull.assign(hull.begin(), hull.end());
    p.radius_steps = vec_of<int>(d, "radius_steps");
    p.agents_used = vec_of<Index>(d, "agents_used");
    const Points b = points_of(d, "bounds");
    if (b.rows() > 0) p.bounds = ConvexRegion::polygon(b, "bounds");
    p.areas = vec_of<double>(d, "areas");
    p.centroids = points_of(d, "centroids");
    const auto ran = vec_of<Index>(d, "computed_by");
    if (ran.size() != 3) throw py::value_error("pickled VoronoiPartition: computed_by is not 3 counts");
    p.computed_by.one_shot = static_cast<decltype(p.computed_by.one_shot)>(ran[0]);
    p.computed_by.deferred = static_cast<decltype(p.computed_by.deferred)>(ran[1]);
    p.computed_by.asr = static_cast<decltype(p.computed_by.asr)>(ran[2]);
    const auto n = static_cast<std::size_t>(p.points.rows());
    if (p.indptr.size() != n + 1 || p.on_hull.size() != n || p.radius_steps.size() != n || p.agents_used.size() != n ||
        p.areas.size() != n || static_cast<std::size_t>(p.centroids.rows()) != n ||
        p.indices.size() != static_cast<std::size_t>(p.indptr.back()))
        throw py::value_error("pickled VoronoiPartition: arrays of inconsistent lengths");
    return p;
}

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
        .def(py::pickle(&voronoi_cell_state, &voronoi_cell_from_state))
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
        .def("__len__", &VoronoiPartition::size)
        .def(py::pickle(&voronoi_partition_state, &voronoi_partition_from_state));

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
