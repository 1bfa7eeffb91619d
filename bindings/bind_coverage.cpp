// Coverage control in Python: the LloydStepper (a swarm stepped in place, its grid kept across steps)
// and the per-step building blocks the MPI driver calls on each rank's owned + halo agents.
// `dvoronoi.coverage` and `dvoronoi.mpi` wrap these; heavy calls release the GIL.
#include "arrays.hpp"

#include "dvoronoi/coverage/lloyd.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
using dvoronoi::ConvexPolygon;
using dvoronoi::CoverageMoments;
using dvoronoi::CoverageQuadrature;
using dvoronoi::LimitedPartition;
using dvoronoi::LloydStepper;
using dvoronoi::Swarm;

namespace {

template <class T>
py::array_t<T> copy_of(const std::vector<T>& v) {
    py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::array_t<double> copy_of(const dvoronoi::Points& p) {
    py::array_t<double> a({static_cast<py::ssize_t>(p.rows()), py::ssize_t{2}});
    std::copy(p.data(), p.data() + 2 * p.rows(), a.mutable_data());
    return a;
}

/// None, or a (k, 2) array of polygon vertices (the Python layer turns boxes into four vertices).
std::optional<ConvexPolygon> bounds_arg(const py::object& bounds) {
    if (bounds.is_none()) return std::nullopt;
    const PointsArg v = points_arg(bounds, "bounds");
    std::vector<Vec2> verts;
    for (Eigen::Index k = 0; k < v.rows; ++k) verts.push_back(v.ref().row(k).transpose());
    return ConvexPolygon(std::move(verts), "bounds");
}

std::vector<Index> ids_arg(const py::object& ids, Eigen::Index n) {
    if (ids.is_none()) return {};
    const auto a = py::array_t<Index, py::array::c_style | py::array::forcecast>::ensure(ids);
    if (!a || a.ndim() != 1 || a.shape(0) != n)
        throw py::value_error("ids must be a 1-d integer array with one entry per point (" +
                              std::to_string(n) + ")");
    return std::vector<Index>(a.data(), a.data() + n);
}

py::array_t<bool> flags_of(const std::vector<char>& v) {
    py::array_t<bool> a(static_cast<py::ssize_t>(v.size()));
    std::transform(v.begin(), v.end(), a.mutable_data(), [](char c) { return c != 0; });
    return a;
}

/// (mass, centroid, polar, open): `open` says which cells reach their circle (the cost needs it).
py::tuple moments_tuple(const CoverageMoments& m) {
    return py::make_tuple(copy_of(m.mass), copy_of(m.centroid), copy_of(m.polar), flags_of(m.open));
}

/// (x, y, w, ptr) of the environment's nodes.
py::tuple quadrature_tuple(const CoverageQuadrature& q) {
    return py::make_tuple(copy_of(q.x), copy_of(q.y), copy_of(q.w), copy_of(q.ptr));
}

/// (x, y, w, ptr, open) of the cells' nodes.
py::tuple cell_quadrature_tuple(const CoverageQuadrature& q) {
    return py::make_tuple(copy_of(q.x), copy_of(q.y), copy_of(q.w), copy_of(q.ptr), flags_of(q.open));
}

py::dict cells_dict(const LimitedPartition& p) {
    py::dict d;
    d["points"] = copy_of(p.points);
    d["radius"] = p.radius;
    if (!p.radii.empty()) d["radii"] = copy_of(p.radii);
    d["piece_ptr"] = copy_of(p.piece_ptr);
    d["piece_neighbor"] = copy_of(p.piece_neighbor);
    d["piece_x"] = copy_of(p.piece_x);
    d["piece_y"] = copy_of(p.piece_y);
    d["piece_span"] = copy_of(p.piece_span);
    d["indptr"] = copy_of(p.indptr);
    d["indices"] = copy_of(p.indices);
    d["areas"] = copy_of(p.areas);
    d["perimeters"] = copy_of(p.perimeters);
    d["centroids"] = copy_of(p.centroids);
    return d;
}

/// A 1-D array of radii (the core checks the length and each value, naming `radius`).
std::vector<double> radii_of(const py::handle& radii) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(radii);
    if (!a || a.ndim() != 1) throw py::value_error("radius must be a positive number or a 1-D array of one radius per agent");
    return std::vector<double>(a.data(), a.data() + a.shape(0));
}

/// f(swarm, radii, environment) on a Swarm of `points` with `ids` and cell radius `radius` (the
/// largest when `radii` gives one radius per agent), the GIL released while it runs.
template <class F>
auto on_swarm(py::handle points, double radius, const py::object& radii, const py::object& bounds, const py::object& ids,
              F&& f) {
    const PointsArg p = points_arg(points, "points");
    const auto env = bounds_arg(bounds);
    std::vector<Index> id = ids_arg(ids, p.rows);
    std::vector<double> r = radii.is_none() ? std::vector<double>{} : radii_of(radii);
    py::gil_scoped_release release;
    const Swarm swarm(p.ref(), radius, std::move(id));
    const dvoronoi::AgentRadii team = radii.is_none() ? dvoronoi::AgentRadii{} : dvoronoi::AgentRadii(swarm, std::move(r));
    return f(swarm, team, env ? &*env : nullptr);
}

int threads_arg(int threads) {
    if (threads < 0) throw py::value_error("threads must be >= 0 (0 = all cores), got " + std::to_string(threads));
    return threads;
}

}  // namespace

void bind_coverage(py::module_& m) {
    py::class_<LloydStepper>(m, "LloydStepper",
                             "Lloyd's algorithm on limited cells, stepped in place (compiled core; use "
                             "dvoronoi.coverage).")
        .def(py::init([](py::handle points, py::handle radius, const py::object& bounds, double gain, int threads) {
                 const PointsArg p = points_arg(points, "points");
                 auto env = bounds_arg(bounds);
                 if (py::isinstance<py::float_>(radius) || py::isinstance<py::int_>(radius))
                     return std::make_unique<LloydStepper>(p.ref(), radius.cast<double>(), std::move(env), gain,
                                                           threads_arg(threads));
                 return std::make_unique<LloydStepper>(p.ref(), radii_of(radius), std::move(env), gain, threads_arg(threads));
             }),
             py::arg("points"), py::arg("radius"), py::arg("bounds") = py::none(), py::arg("gain") = 1.0,
             py::arg("threads") = 0)
        .def_property_readonly("points", [](const LloydStepper& s) { return copy_of(s.points()); })
        .def_property_readonly("radius", &LloydStepper::radius, "The radius (the largest of a heterogeneous team).")
        .def_property_readonly("radii", [](const LloydStepper& s) {
            std::vector<double> r = s.radii().by_row();
            if (r.empty()) r.assign(static_cast<std::size_t>(s.swarm().size()), s.radius());
            return copy_of(r);
        }, "Each agent's radius, (n,).")
        .def_property_readonly("gain", &LloydStepper::gain)
        .def_property_readonly("bounds", [](const LloydStepper& s) -> py::object {
            if (!s.environment()) return py::none();
            const auto& v = s.environment()->vertices();
            py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{2}});
            for (std::size_t k = 0; k < v.size(); ++k) {
                a.mutable_at(static_cast<py::ssize_t>(k), 0) = v[k].x();
                a.mutable_at(static_cast<py::ssize_t>(k), 1) = v[k].y();
            }
            return std::move(a);
        })
        .def_property_readonly("bounds_area", [](const LloydStepper& s) {
            return s.environment() ? s.environment()->area() : 0.0;
        })
        .def_property_readonly("rebucketed", [](const LloydStepper& s) { return s.swarm().rebucketed(); },
                               "Agents the last move put into another grid bucket.")
        .def_property_readonly("rebuilds", [](const LloydStepper& s) { return s.swarm().rebuilds(); },
                               "Full rebuilds of the grid so far (1 = only the first).")
        .def("cost", [](const LloydStepper& s) {
            py::gil_scoped_release release;
            return s.cost();
        })
        .def("step", [](LloydStepper& s) {
            py::gil_scoped_release release;
            return s.step();
        }, "One uniform-density Lloyd step; returns the cost H before the move.")
        .def("run",
             [](LloydStepper& s, int steps, int record_every, py::object progress) {
                 if (steps < 0) throw py::value_error("steps must be >= 0, got " + std::to_string(steps));
                 if (record_every < 1)
                     throw py::value_error("record_every must be >= 1, got " + std::to_string(record_every));
                 const Index n = s.swarm().size();
                 const Index frames = steps / record_every + 1 + (steps % record_every ? 1 : 0);
                 py::array_t<double> traj({static_cast<py::ssize_t>(frames), static_cast<py::ssize_t>(n), py::ssize_t{2}});
                 py::array_t<double> cost(static_cast<py::ssize_t>(steps) + 1);
                 double* tp = traj.mutable_data();
                 double* cp = cost.mutable_data();
                 {
                     py::gil_scoped_release release;
                     Index frame = 0;
                     const auto record = [&] {
                         std::copy(s.points().data(), s.points().data() + 2 * n, tp + 2 * n * frame++);
                     };
                     record();
                     for (int t = 0; t < steps; ++t) {
                         cp[t] = s.step();
                         if ((t + 1) % record_every == 0 || t + 1 == steps) record();
                         // Between steps (the GIL is taken for a moment): Ctrl-C and the progress
                         // callback; an exception from either stops the run here.
                         py::gil_scoped_acquire gil;
                         if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                         if (!progress.is_none()) progress(t + 1, steps);
                     }
                     cp[steps] = s.cost();
                 }
                 return py::make_tuple(traj, cost);
             },
             py::arg("steps"), py::arg("record_every") = 1, py::arg("progress") = py::none(),
             "run(steps, record_every=1, progress=None) -> (trajectory, cost)\n\n"
             "`steps` uniform-density steps without returning to Python; positions recorded every "
             "`record_every` steps (and after the last), cost H at every step (steps + 1 values).")
        .def("moments", [](const LloydStepper& s) {
            CoverageMoments mo;
            {
                py::gil_scoped_release release;
                mo = dvoronoi::coverage_moments(s.swarm(), s.radii(), s.environment());
            }
            return moments_tuple(mo);
        }, "(mass, centroid, polar, open) of every clipped cell, uniform density; open: the cell "
           "reaches its circle.")
        .def("quadrature", [](const LloydStepper& s, int order) {
            CoverageQuadrature q;
            {
                py::gil_scoped_release release;
                q = dvoronoi::coverage_quadrature(s.swarm(), s.radii(), s.environment(), order);
            }
            return cell_quadrature_tuple(q);
        }, py::arg("order") = 8,
           "(x, y, w, ptr, open): quadrature nodes of every clipped cell, and which cells reach their circle.")
        .def("cells", [](const LloydStepper& s) {
            LimitedPartition p;
            {
                py::gil_scoped_release release;
                p = dvoronoi::coverage_cells(s.swarm(), s.radii(), s.environment());
            }
            return cells_dict(p);
        }, "The clipped cells as flat arrays (walls: neighbor -2, span 0).")
        .def("move_to_targets", [](LloydStepper& s, py::handle centroids) {
            const PointsArg c = points_arg(centroids, "centroids");
            const dvoronoi::Points cp = c.ref();
            py::gil_scoped_release release;
            s.move_to_targets(cp);
        }, py::arg("centroids"), "Moves every agent towards its target with the stepper's gain.")
        .def("set_points", [](LloydStepper& s, py::handle points) {
            const PointsArg p = points_arg(points, "points");
            s.set_points(p.ref());
        }, py::arg("points"));

    // Building blocks of one step on an arbitrary set of agents (an MPI rank's owned + halo agents).
    m.def("coverage_moments",
          [](py::handle points, double radius, const py::object& bounds, const py::object& ids, Index owned, int threads,
             const py::object& radii) {
              const int t = threads_arg(threads);
              return moments_tuple(on_swarm(points, radius, radii, bounds, ids,
                                            [&](const Swarm& s, const dvoronoi::AgentRadii& r, const ConvexPolygon* env) {
                                                return dvoronoi::coverage_moments(s, r, env, owned, t);
                                            }));
          },
          py::arg("points"), py::arg("radius"), py::arg("bounds") = py::none(), py::arg("ids") = py::none(),
          py::arg("owned") = -1, py::arg("threads") = 0, py::arg("radii") = py::none(),
          "(mass, centroid, polar, open) of the clipped cells of the first `owned` agents (-1: all; "
          "open: the cell reaches its circle); the others only shape them. Candidates are ordered by "
          "`ids`, so the cells do not depend on how the agents are stored. `radii`: one radius per agent "
          "(a heterogeneous team; `radius` is then the largest of the whole team).");
    m.def("coverage_quadrature",
          [](py::handle points, double radius, int order, const py::object& bounds, const py::object& ids, Index owned,
             int threads, const py::object& radii) {
              const int t = threads_arg(threads);
              return cell_quadrature_tuple(on_swarm(points, radius, radii, bounds, ids,
                                                    [&](const Swarm& s, const dvoronoi::AgentRadii& r, const ConvexPolygon* env) {
                                                        return dvoronoi::coverage_quadrature(s, r, env, order, owned, t);
                                                    }));
          },
          py::arg("points"), py::arg("radius"), py::arg("order") = 8, py::arg("bounds") = py::none(),
          py::arg("ids") = py::none(), py::arg("owned") = -1, py::arg("threads") = 0, py::arg("radii") = py::none());
    m.def("coverage_cells",
          [](py::handle points, double radius, const py::object& bounds, const py::object& ids, Index owned, int threads,
             const py::object& radii) {
              const int t = threads_arg(threads);
              return cells_dict(on_swarm(points, radius, radii, bounds, ids,
                                         [&](const Swarm& s, const dvoronoi::AgentRadii& r, const ConvexPolygon* env) {
                                             return dvoronoi::coverage_cells(s, r, env, owned, t);
                                         }));
          },
          py::arg("points"), py::arg("radius"), py::arg("bounds") = py::none(), py::arg("ids") = py::none(),
          py::arg("owned") = -1, py::arg("threads") = 0, py::arg("radii") = py::none());
    m.def("environment_quadrature",
          [](const py::object& bounds, int order) {
              const auto env = bounds_arg(bounds);
              if (!env) throw py::value_error("bounds must not be None");
              return quadrature_tuple(dvoronoi::environment_quadrature(*env, order));
          },
          py::arg("bounds"), py::arg("order") = 8);
    m.def("lloyd_move",
          [](py::handle points, py::handle targets, double gain, const py::object& bounds) {
              const PointsArg p = points_arg(points, "points");
              const PointsArg t = points_arg(targets, "targets");
              if (t.rows != p.rows) throw py::value_error("targets must have one row per point");
              const auto env = bounds_arg(bounds);
              dvoronoi::Points out(p.rows, 2);
              for (Eigen::Index i = 0; i < p.rows; ++i)
                  out.row(i) = dvoronoi::lloyd_move(p.ref().row(i).transpose(), t.ref().row(i).transpose(), gain,
                                                    env ? &*env : nullptr)
                                   .transpose();
              return copy_of(out);
          },
          py::arg("points"), py::arg("targets"), py::arg("gain"), py::arg("bounds") = py::none(),
          "p + gain (target - p) for every row, kept inside `bounds`.");
    m.def("bounds_contains",
          [](const py::object& bounds, py::handle points) {
              const auto env = bounds_arg(bounds);
              const PointsArg p = points_arg(points, "points");
              py::array_t<bool> out(static_cast<py::ssize_t>(p.rows));
              for (Eigen::Index i = 0; i < p.rows; ++i)
                  out.mutable_at(i) = !env || env->contains(p.ref().row(i).transpose());
              return out;
          },
          py::arg("bounds"), py::arg("points"), "Exact test: which points lie in the closed polygon.");
}
