// Voronoi neighbours from inter-robot distances only (Elwin, Freeman & Lynch) in Python: the detection
// graph, every robot's neighbours (GIL released, tqdm progress), one robot's, its local region, and the
// distance-only predicates. The Python layer (dvoronoi/distances) turns matrices and edge lists into
// (rows, cols, values) and wraps the result in the shared Result surface.
#include "arrays.hpp"
#include "pickle.hpp"
#include "progress.hpp"

#include "dvoronoi/distances/local_region.hpp"
#include "dvoronoi/distances/neighbors_from_distances.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
namespace dd = dvoronoi::dist;

namespace {

template <class T>
std::vector<T> to_vector(const py::array& a, const char* name) {
    auto c = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!c || c.ndim() != 1) throw py::value_error(std::string(name) + " must be a 1-d array");
    return std::vector<T>(c.data(), c.data() + c.size());
}

py::array bool_out(const std::vector<char>& v) {
    py::array_t<bool> a(static_cast<py::ssize_t>(v.size()));
    for (std::size_t k = 0; k < v.size(); ++k) a.mutable_data()[k] = v[k] != 0;
    return a;
}

py::array xy_out(const std::vector<Vec2>& v) {
    py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{2}});
    for (std::size_t k = 0; k < v.size(); ++k) {
        a.mutable_data()[2 * k] = v[k].x();
        a.mutable_data()[2 * k + 1] = v[k].y();
    }
    return a;
}

}  // namespace

void bind_distances(py::module_& m) {
    py::class_<dd::DistanceGraph>(m, "DistanceGraph", "Symmetric detection graph of measured distances (CSR, compiled core).")
        .def_readonly("n", &dd::DistanceGraph::n)
        .def_readonly("squared", &dd::DistanceGraph::squared)
        .def_property_readonly("indptr", [](const dd::DistanceGraph& g) { return np_of(g.indptr); })
        .def_property_readonly("indices", [](const dd::DistanceGraph& g) { return np_of(g.indices); })
        .def_property_readonly("values", [](const dd::DistanceGraph& g) { return np_of(g.values); })
        .def("__len__", &dd::DistanceGraph::size)
        .def(py::pickle(
            [](const dd::DistanceGraph& g) {
                py::dict d;
                d["n"] = g.n;
                d["squared"] = g.squared;
                d["indptr"] = np_of(g.indptr);
                d["indices"] = np_of(g.indices);
                d["values"] = np_of(g.values);
                return make_state(d);
            },
            [](const py::tuple& t) {
                const py::dict d = state_dict(t, "DistanceGraph");
                dd::DistanceGraph g;
                g.n = d["n"].cast<Index>();
                g.squared = d["squared"].cast<bool>();
                g.indptr = vec_of<Index>(d, "indptr");
                g.indices = vec_of<Index>(d, "indices");
                g.values = vec_of<double>(d, "values");
                if (g.indptr.size() != static_cast<std::size_t>(g.n) + 1 || g.indices.size() != g.values.size() ||
                    g.indices.size() != static_cast<std::size_t>(g.indptr.back()))
                    throw py::value_error("pickled DistanceGraph: arrays of inconsistent lengths");
                return g;
            }));

    m.def(
        "distance_graph",
        [](Index n, py::array rows, py::array cols, py::array values, bool squared, bool symmetrize, const std::string& label) {
            const auto r = to_vector<Index>(rows, "rows"), c = to_vector<Index>(cols, "cols");
            const auto v = to_vector<double>(values, "values");
            // Entry k is named as the user wrote it: distances[i, j] (matrix) or edges[k] (edge list).
            const auto where = [&](std::size_t k) {
                if (label == "edges") return "edges[" + std::to_string(k) + "]";
                return label + "[" + std::to_string(r[k]) + ", " + std::to_string(c[k]) + "]";
            };
            py::gil_scoped_release release;
            return dd::make_distance_graph(n, r, c, v, squared, symmetrize ? dd::Symmetry::Average : dd::Symmetry::Require, where);
        },
        py::arg("n"), py::arg("rows"), py::arg("cols"), py::arg("values"), py::arg("squared") = false,
        py::arg("symmetrize") = false, py::arg("label") = "distances",
        "distance_graph(n, rows, cols, values, squared=False, symmetrize=False, label='distances') -> DistanceGraph\n\n"
        "Validated symmetric detection graph; errors name the entry (label[i, j], or edges[k]).");

    py::class_<dd::DistanceNeighbors>(m, "DistanceNeighbors", "Voronoi neighbours from distances (compiled core).")
        .def_readonly("n", &dd::DistanceNeighbors::n)
        .def_readonly("consistency", &dd::DistanceNeighbors::consistency)
        .def_property_readonly("indptr", [](const dd::DistanceNeighbors& r) { return np_of(r.indptr); })
        .def_property_readonly("indices", [](const dd::DistanceNeighbors& r) { return np_of(r.indices); })
        .def_property_readonly("on_hull", [](const dd::DistanceNeighbors& r) { return bool_out(r.on_hull); })
        .def_property_readonly("path_length", [](const dd::DistanceNeighbors& r) { return np_of(r.path_length); })
        .def_property_readonly("added", [](const dd::DistanceNeighbors& r) { return np_of(r.added); })
        .def_property_readonly("detected", [](const dd::DistanceNeighbors& r) { return np_of(r.detected); })
        .def("__len__", &dd::DistanceNeighbors::size)
        .def(py::pickle(
            [](const dd::DistanceNeighbors& r) {
                py::dict d;
                d["n"] = r.n;
                d["consistency"] = r.consistency;
                d["indptr"] = np_of(r.indptr);
                d["indices"] = np_of(r.indices);
                d["on_hull"] = np_of(std::vector<std::uint8_t>(r.on_hull.begin(), r.on_hull.end()));
                d["path_length"] = np_of(r.path_length);
                d["added"] = np_of(r.added);
                d["detected"] = np_of(r.detected);
                return make_state(d);
            },
            [](const py::tuple& t) {
                const py::dict d = state_dict(t, "DistanceNeighbors");
                dd::DistanceNeighbors r;
                r.n = d["n"].cast<Index>();
                r.consistency = d["consistency"].cast<bool>();
                r.indptr = vec_of<Index>(d, "indptr");
                r.indices = vec_of<Index>(d, "indices");
                const auto hull = vec_of<std::uint8_t>(d, "on_hull");
                r.on_hull.assign(hull.begin(), hull.end());
                r.path_length = vec_of<Index>(d, "path_length");
                r.added = vec_of<Index>(d, "added");
                r.detected = vec_of<Index>(d, "detected");
                const auto n = static_cast<std::size_t>(r.n);
                if (r.indptr.size() != n + 1 || r.on_hull.size() != n || r.path_length.size() != n || r.added.size() != n ||
                    r.detected.size() != n || r.indices.size() != static_cast<std::size_t>(r.indptr.back()))
                    throw py::value_error("pickled DistanceNeighbors: arrays of inconsistent lengths");
                return r;
            }));

    m.def(
        "neighbors_from_distances",
        [](const dd::DistanceGraph& g, bool consistency, int threads, py::object progress) {
            if (threads < 0) throw py::value_error("threads must be >= 0 (0 = all cores), got " + std::to_string(threads));
            PyProgress report(std::move(progress));
            const dvoronoi::ProgressFn fn = report.fn();
            dd::DistanceNeighbors out;
            {
                py::gil_scoped_release release;
                out = dd::neighbors_from_distances(g, consistency, threads, fn);
            }
            report.rethrow();
            return out;
        },
        py::arg("graph"), py::arg("consistency") = true, py::arg("threads") = 0, py::arg("progress") = py::none(),
        "neighbors_from_distances(graph, consistency=True, threads=0, progress=None) -> DistanceNeighbors");

    m.def(
        "voronoi_neighbors_of",
        [](const dd::DistanceGraph& g, Index i) {
            const dd::RobotNeighbors r = dd::voronoi_neighbors(g, i);
            return py::make_tuple(np_of(r.order), r.hull);
        },
        py::arg("graph"), py::arg("i"),
        "voronoi_neighbors_of(graph, i) -> (order, on_hull): one robot's VORONOI-NEIGHBORS (no consistency step).");

    m.def(
        "local_region",
        [](const dd::DistanceGraph& g, Index i, std::vector<Index> order, bool hull) {
            const dd::LocalRegion r = dd::local_region(g, i, order, hull);
            py::dict d;
            d["neighbors"] = np_of(r.neighbors);
            d["positions"] = xy_out(r.positions);
            d["vertices"] = xy_out(r.vertices);
            d["bounded"] = r.bounded;
            d["ray_in"] = py::make_tuple(r.ray_in.x(), r.ray_in.y());
            d["ray_out"] = py::make_tuple(r.ray_out.x(), r.ray_out.y());
            return d;
        },
        py::arg("graph"), py::arg("i"), py::arg("order"), py::arg("on_hull"));

    m.def("circumradius", &dd::circumradius, py::arg("d1"), py::arg("d2"), py::arg("d3"),
          "Circumradius of a triangle from its side lengths (eq. 3 of Elwin et al.); inf when degenerate.");
    m.def("signed_circumradius", &dd::signed_circumradius, py::arg("d1"), py::arg("d2"), py::arg("d3"),
          "-r when the angle opposite d3 is obtuse (decided exactly), r otherwise.");
    m.def("obtuse", &dd::obtuse, py::arg("d1"), py::arg("d2"), py::arg("d3"),
          "The angle opposite d3 is obtuse (exact).");
    m.def(
        "opposite_sides",
        [](double dij, double dik, double djk, double dil, double djl, double dkl, bool squared) {
            return dd::opposite_sides(dij, dik, djk, dil, djl, dkl, squared);
        },
        py::arg("dij"), py::arg("dik"), py::arg("djk"), py::arg("dil"), py::arg("djl"), py::arg("dkl"), py::arg("squared") = false,
        "Exact sign of S_ijkl (Theorem 3): -1 when k and l lie strictly on opposite sides of the line ij, 0 on it, +1 same side.");
}
