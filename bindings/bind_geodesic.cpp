// Geodesic cells and geodesic Lloyd on occupancy grids (dvoronoi.geodesic wraps these private names).
// Map units in and out: the frame (resolution, origin) is applied here, the library works in pixels.
#include "dvoronoi/coverage/geodesic_lloyd.hpp"

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace py = pybind11;
namespace cov = dvoronoi::coverage;

namespace {

using OccArray = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;
using F64Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

cov::MapFrame frame_of(const OccArray& occ, double resolution, double ox, double oy) {
    if (occ.ndim() != 2) throw py::value_error("occupancy must be a 2-d array");
    return {static_cast<std::int32_t>(occ.shape(0)), static_cast<std::int32_t>(occ.shape(1)), resolution, ox, oy};
}

std::vector<cov::PixelPoint> agents_of(const OccArray& occ, const cov::MapFrame& fr, const F64Array& pts) {
    if (pts.ndim() != 2 || pts.shape(1) != 2)
        throw py::value_error("points must be an (n, 2) array");
    return cov::agents_on_map(occ.data(), fr, pts.data(), pts.shape(0));
}

// The range in pixel units (None: unlimited; the largest of per-agent ranges).
double limit_of(const py::object& radius, double resolution) {
    if (radius.is_none()) return std::numeric_limits<double>::infinity();
    if (py::isinstance<py::array>(radius)) {
        const F64Array r = radius.cast<F64Array>();
        double m = 0.0;
        for (py::ssize_t i = 0; i < r.size(); ++i) m = std::max(m, r.data()[i]);
        return m / resolution;
    }
    return radius.cast<double>() / resolution;
}

// Per-agent ranges in pixel units when `radius` is an array (a heterogeneous team; the Python layer
// checks each is positive and finite), else empty.
std::vector<double> ranges_of(const py::object& radius, double resolution, std::size_t n) {
    if (radius.is_none() || !py::isinstance<py::array>(radius)) return {};
    const F64Array r = radius.cast<F64Array>();
    if (r.ndim() != 1 || static_cast<std::size_t>(r.shape(0)) != n)
        throw py::value_error("radius must have one range per agent: got " + std::to_string(r.size()) + " for " +
                              std::to_string(n) + " agents");
    std::vector<double> out(r.data(), r.data() + n);
    for (double& v : out) v /= resolution;
    return out;
}

py::array_t<std::int64_t> image_labels(const cov::GeodesicField& f) {
    py::array_t<std::int64_t> a({static_cast<py::ssize_t>(f.rows), static_cast<py::ssize_t>(f.cols)});
    std::int64_t* out = a.mutable_data();
    for (std::size_t i = 0; i < f.label.size(); ++i) out[i] = f.label[i];
    return a;
}

py::array_t<double> image_distances(const cov::GeodesicField& f, double resolution) {
    py::array_t<double> a({static_cast<py::ssize_t>(f.rows), static_cast<py::ssize_t>(f.cols)});
    double* out = a.mutable_data();
    for (std::size_t i = 0; i < f.distance.size(); ++i) out[i] = f.distance[i] * resolution;
    return a;
}

py::array_t<double> map_points(const std::vector<cov::PixelPoint>& pts, const cov::MapFrame& fr) {
    py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t(2)});
    double* out = a.mutable_data();
    for (std::size_t i = 0; i < pts.size(); ++i) fr.to_map(pts[i], out[2 * i], out[2 * i + 1]);
    return a;
}

// Per-agent pixel count, mass (map units: sum phi * pixel area) and centroid (map units; the agent's
// position for an empty cell).
py::dict moments_dict(const cov::GeodesicMoments& m, const std::vector<cov::PixelPoint>& pts, const cov::MapFrame& fr) {
    const std::size_t n = pts.size();
    py::array_t<std::int64_t> pixels(static_cast<py::ssize_t>(n));
    py::array_t<double> mass(static_cast<py::ssize_t>(n));
    std::vector<cov::PixelPoint> c(n);
    for (std::size_t i = 0; i < n; ++i) {
        pixels.mutable_data()[i] = m.pixels[i];
        mass.mutable_data()[i] = m.mass[i] * fr.resolution * fr.resolution;
        c[i] = m.mass[i] > 0 ? cov::PixelPoint{m.mu[i] / m.mass[i], m.mw[i] / m.mass[i]} : pts[i];
    }
    py::dict d;
    d["pixels"] = pixels;
    d["mass"] = mass;
    d["centroids"] = map_points(c, fr);
    const double r2 = fr.resolution * fr.resolution;
    d["cost"] = m.cost * r2 * r2;  // sum phi d^2 (pixel units) -> map units: d^2 * pixel area
    return d;
}

std::vector<double> weights_of(const py::object& weight, const cov::MapFrame& fr) {
    if (weight.is_none()) return {};
    F64Array w = weight.cast<F64Array>();
    if (w.ndim() != 2 || w.shape(0) != fr.rows || w.shape(1) != fr.cols)
        throw py::value_error("density must be an array of the map's shape");
    return std::vector<double>(w.data(), w.data() + w.size());
}

struct Lloyd {
    cov::MapFrame frame;
    cov::GeodesicLloyd core;
};

}  // namespace

void bind_geodesic(py::module_& m) {
    m.def(
        "_geodesic_cells",
        [](const OccArray& occ, double resolution, double ox, double oy, const F64Array& points, const py::object& radius,
           const py::object& weight, int workers) {
            const cov::MapFrame fr = frame_of(occ, resolution, ox, oy);
            const auto agents = agents_of(occ, fr, points);
            const double limit = limit_of(radius, resolution);
            std::vector<double> ranges = ranges_of(radius, resolution, agents.size());
            if (std::all_of(ranges.begin(), ranges.end(), [&](double R) { return R == limit; })) ranges.clear();
            const std::vector<double> w = weights_of(weight, fr);
            cov::GeodesicField f;
            cov::GeodesicMoments mom;
            {
                py::gil_scoped_release release;
                const auto reach = cov::reachable_pixels(occ.data(), fr.rows, fr.cols, agents);
                if (ranges.empty()) {
                    f = cov::geodesic_field(occ.data(), fr.rows, fr.cols, agents, limit);
                    mom = cov::geodesic_moments(f, w.empty() ? nullptr : w.data(), reach.data(), limit, workers);
                } else {  // a heterogeneous team: one wavefront per agent (no anchors in the merged field)
                    std::vector<cov::AgentWave> waves;
                    cov::geodesic_team_field(occ.data(), fr.rows, fr.cols, agents, ranges, workers, f, waves);
                    mom = cov::geodesic_moments(f, w.empty() ? nullptr : w.data(), reach.data(), limit, workers, &ranges);
                }
            }
            py::dict d = moments_dict(mom, agents, fr);
            d["labels"] = image_labels(f);
            d["distances"] = image_distances(f, resolution);
            // each pixel's last bend (pixel units, u right, w down; NaN if unreached): for tests and pictures
            py::array_t<double> anchors({static_cast<py::ssize_t>(f.rows), static_cast<py::ssize_t>(f.cols), py::ssize_t(2)});
            for (std::size_t q = 0; q < f.anchor.size(); ++q) {
                const auto A = f.anchor[q] >= 0 ? f.anchor_point(f.anchor[q]) : cov::PixelPoint{NAN, NAN};
                anchors.mutable_data()[2 * q] = A.u;
                anchors.mutable_data()[2 * q + 1] = A.w;
            }
            d["anchors"] = anchors;
            return d;
        },
        py::arg("occupied"), py::arg("resolution"), py::arg("ox"), py::arg("oy"), py::arg("points"), py::arg("radius"),
        py::arg("weight"), py::arg("workers"),
        "Geodesic cells (private; see dvoronoi.coverage.geodesic_cells): labels, distances, moments, cost.");

    m.def(
        "_segment_free",
        [](const OccArray& occ, double u0, double w0, double u1, double w1) {
            const cov::OccupancyView g{occ.data(), static_cast<std::int32_t>(occ.shape(0)), static_cast<std::int32_t>(occ.shape(1))};
            return cov::segment_free(g, {u0, w0}, {u1, w1});
        },
        py::arg("occupied"), py::arg("u0"), py::arg("w0"), py::arg("u1"), py::arg("w1"),
        "Does the segment (pixel units, u right, w down) stay in free space (private; for tests).");

    py::class_<Lloyd>(m, "_GeodesicLloyd", "Geodesic Lloyd stepper (private; see dvoronoi.coverage.LloydStepper).")
        .def(py::init([](const OccArray& occ, double resolution, double ox, double oy, const F64Array& points,
                         const py::object& radius, const py::object& weight, double gain, int workers) {
                 const cov::MapFrame fr = frame_of(occ, resolution, ox, oy);
                 auto agents = agents_of(occ, fr, points);
                 std::vector<std::uint8_t> o(occ.data(), occ.data() + occ.size());
                 std::vector<double> w = weights_of(weight, fr);
                 const double limit = limit_of(radius, resolution);
                 std::vector<double> ranges = ranges_of(radius, resolution, agents.size());
                 py::gil_scoped_release release;
                 return new Lloyd{fr, cov::GeodesicLloyd(std::move(o), fr.rows, fr.cols, std::move(agents), limit,
                                                         std::move(w), gain, workers, 12, std::move(ranges))};
             }),
             py::arg("occupied"), py::arg("resolution"), py::arg("ox"), py::arg("oy"), py::arg("points"),
             py::arg("radius"), py::arg("weight"), py::arg("gain"), py::arg("workers"))
        .def("step", [](Lloyd& s) { return s.core.step() * std::pow(s.frame.resolution, 4); },
             py::call_guard<py::gil_scoped_release>())
        .def("cost", [](const Lloyd& s) { return s.core.cost() * std::pow(s.frame.resolution, 4); })
        .def("set_points",
             [](Lloyd& s, const F64Array& points, const OccArray& occ) {
                 auto agents = agents_of(occ, s.frame, points);
                 py::gil_scoped_release release;
                 s.core.set_points(std::move(agents));
             },
             py::arg("points"), py::arg("occupied"))
        .def_property_readonly("points", [](const Lloyd& s) { return map_points(s.core.points(), s.frame); })
        .def_property_readonly("labels", [](const Lloyd& s) { return image_labels(s.core.field()); })
        .def_property_readonly("distances", [](const Lloyd& s) { return image_distances(s.core.field(), s.frame.resolution); })
        .def("moments", [](const Lloyd& s) { return moments_dict(s.core.moments(), s.core.points(), s.frame); })
        .def_property_readonly("last_halvings", [](const Lloyd& s) { return s.core.last_halvings(); })
        .def_property_readonly("last_stuck", [](const Lloyd& s) { return s.core.last_stuck(); });
}
