// The grid Voronoi diagram of obstacles in Python (dvoronoi.gvd wraps these private classes):
// a compiled scene parsed from the one JSON schema (io/obstacles_json.hpp), the slice-parallel
// tracer with the GIL released, the result's arrays, paths, JSON and SVG, and the brute-force oracle
// for the tests.
#include "arrays.hpp"

#include "dvoronoi/gvd/brute_force.hpp"
#include "dvoronoi/gvd/grid_voronoi.hpp"
#include "dvoronoi/gvd/path.hpp"
#include "dvoronoi/gvd/rasterize.hpp"
#include "dvoronoi/io/gvd_json.hpp"
#include "dvoronoi/io/gvd_svg.hpp"
#include "dvoronoi/io/obstacles_json.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
namespace gvd = dvoronoi::gvd;

namespace {

/// A parsed obstacle file with its nearest-obstacle index for paths (built on the first path).
struct PyScene {
    dvoronoi::io::ObstacleFile file;
    nlohmann::json doc;  ///< the document it was compiled from (its pickled state)
    std::string name;
    std::unique_ptr<gvd::ObstacleIndex> index;
    std::mutex mutex;
    const gvd::ObstacleIndex& path_index() {
        std::lock_guard<std::mutex> lock(mutex);
        if (!index) index = std::make_unique<gvd::ObstacleIndex>(file.scene);
        return *index;
    }
};

/// Where an occupancy map's labelled diagram is computed: its scene in pixel units, placed in map
/// units by scale and offset (gvd::placed).
struct PixelFrame {
    std::shared_ptr<PyScene> scene;
    double scale = 1.0;
    Vec2 offset = Vec2::Zero();
};

struct PyResult {
    gvd::GridVoronoi r;
    std::shared_ptr<PyScene> scene;  ///< in map units: paths, pictures and JSON
    gvd::GvdOptions options;  ///< what made r (a pickled result is rebuilt from its scene and these)
    PixelFrame pixels;        ///< the labels' scene when it is a map's (else no scene)
    /// The roadmap and cell adjacency are built on first use (the diagram itself is ready at once).
    gvd::GridVoronoi& graph() {
        if (!r.has_graph) {
            py::gil_scoped_release release;
            gvd::build_graph(r);
        }
        return r;
    }
};

/// A Python value that json.dumps would reject; `path` grows as the exception unwinds.
struct NotJson {
    std::string path, type;
};

/// Python objects (dict, list, tuple, str, int, float, bool, None, numpy arrays and scalars) as a
/// JSON value, without the text round trip (json.dumps and parsing the text again cost a noticeable
/// part of a diagram of many obstacles). Written by hand: pybind11_json would be one more dependency for
/// twenty lines.
nlohmann::json to_json(py::handle o) {
    using nlohmann::json;
    if (py::isinstance<py::float_>(o)) return PyFloat_AS_DOUBLE(o.ptr());
    if (py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o)) {
        json j = json::array();
        std::size_t k = 0;
        for (py::handle x : o) {
            try {
                j.push_back(to_json(x));
            } catch (NotJson& e) {
                e.path = "[" + std::to_string(k) + "]" + e.path;
                throw;
            }
            ++k;
        }
        return j;
    }
    if (py::isinstance<py::dict>(o)) {
        json j = json::object();
        for (auto kv : py::reinterpret_borrow<py::dict>(o)) {
            if (!py::isinstance<py::str>(kv.first)) throw NotJson{"", "dict key " + std::string(py::str(py::type::handle_of(kv.first).attr("__name__")))};
            const std::string key = kv.first.cast<std::string>();
            try {
                j[key] = to_json(kv.second);
            } catch (NotJson& e) {
                e.path = "." + key + e.path;
                throw;
            }
        }
        return j;
    }
    if (py::isinstance<py::str>(o)) return o.cast<std::string>();
    if (py::isinstance<py::bool_>(o)) return o.cast<bool>();  // before int: bool is an int
    if (py::isinstance<py::int_>(o)) {
        int overflow = 0;
        const long long v = PyLong_AsLongLongAndOverflow(o.ptr(), &overflow);
        if (overflow == 0) return static_cast<std::int64_t>(v);
        return PyLong_AsDouble(o.ptr());  // beyond 64 bits: as json.loads would read the text
    }
    if (o.is_none()) return nullptr;
    const py::module_ np = py::module_::import("numpy");
    if (py::isinstance(o, np.attr("ndarray"))) return to_json(o.attr("tolist")());
    if (py::isinstance(o, np.attr("generic"))) return to_json(o.attr("item")());
    throw NotJson{"", std::string(py::str(py::type::handle_of(o).attr("__name__")))};
}

/// A document of Python objects as JSON; a TypeError naming `name` and the path of a value json.dumps
/// would reject.
nlohmann::json doc_json(py::handle doc, const std::string& name) {
    try {
        return to_json(doc);
    } catch (const NotJson& e) {
        throw py::type_error(name + (e.path.empty() ? "" : ": " + e.path.substr(e.path[0] == '.' ? 1 : 0)) +
                             ": object of type " + e.type + " is not JSON serialisable");
    }
}

/// The scene of a parsed document (the GIL released while it is checked and compiled).
std::shared_ptr<PyScene> scene_of(const nlohmann::json& j, const std::string& name) {
    auto s = std::make_shared<PyScene>();
    s->doc = j;
    s->name = name;
    py::gil_scoped_release release;
    s->file = dvoronoi::io::obstacles_from_json(j, name);
    return s;
}

/// The labelled diagram of `scene` with options `o` (GIL released; InputError as ValueError).
std::unique_ptr<PyResult> run_gvd(std::shared_ptr<PyScene> scene, const gvd::GvdOptions& o, PixelFrame pixels = {}) {
    auto out = std::make_unique<PyResult>();
    out->scene = std::move(scene);
    out->options = o;
    out->pixels = std::move(pixels);
    py::gil_scoped_release release;
    try {
        if (out->pixels.scene) {
            gvd::GvdOptions in_pixels = o;
            in_pixels.robot_radius = 0.0;  // blocked is decided in map units
            out->r = gvd::placed(gvd::grid_voronoi(out->pixels.scene->file.scene, in_pixels), out->pixels.scale,
                                 out->pixels.offset, o.robot_radius);
        } else {
            out->r = gvd::grid_voronoi(out->scene->file.scene, o);
        }
    } catch (const dvoronoi::InputError&) {
        py::gil_scoped_acquire gil;
        throw;  // to the translator (bind_core.cpp): a ValueError whose message stays UTF-8
    }
    return out;
}

gvd::SliceMode parse_mode(const std::string& m) {
    if (m == "cooperative") return gvd::SliceMode::Cooperative;
    if (m == "independent") return gvd::SliceMode::Independent;
    throw py::value_error("mode must be \"cooperative\" or \"independent\", got \"" + m + "\"");
}

}  // namespace

void bind_gvd(py::module_& m) {
    py::class_<PyScene, std::shared_ptr<PyScene>>(m, "_GvdScene", "Compiled obstacles and working area (private).")
        .def_static("from_doc", [](py::handle doc, const std::string& name) { return scene_of(doc_json(doc, name), name); },
             py::arg("doc"), py::arg("name"), "The scene from a document of Python objects (private).")
        .def_static("from_text",
             [](const std::string& text, const std::string& name, py::handle area) {
                 nlohmann::json j = dvoronoi::io::parse_json(text, name);
                 if (!area.is_none() && j.is_object()) j["area"] = doc_json(area, name);
                 return scene_of(j, name);
             },
             py::arg("text"), py::arg("name"), py::arg("area") = py::none(),
             "The scene from JSON text (a file's bytes), with `area` (a document value) in place of the "
             "text's own when given; errors name NAME:LINE:COLUMN (private).")
        // pickled as its document (JSON text), compiled again when loaded
        .def(py::pickle([](const PyScene& s) { return py::make_tuple(s.doc.dump(), s.name); },
                        [](const py::tuple& t) {
                            if (t.size() != 2) throw py::value_error("not a pickled _GvdScene state");
                            const std::string name = t[1].cast<std::string>();
                            return scene_of(dvoronoi::io::parse_json(t[0].cast<std::string>(), name), name);
                        }))
        .def_property_readonly("n_obstacles", [](const PyScene& s) { return s.file.scene.n_obstacles; })
        .def_property_readonly("n_labels", [](const PyScene& s) { return s.file.scene.n_labels; })
        .def_property_readonly("area", [](const PyScene& s) { return xy_array(s.file.scene.area); })
        .def_property_readonly("names", [](const PyScene& s) { return s.file.names; })
        .def("parts", [](const PyScene& s) {
            // (kind, label, vertices (k, 2), center, radius) per convex part, area edges included
            py::list out;
            const char* kinds[] = {"point", "segment", "polygon", "circle"};
            for (const auto& p : s.file.scene.parts) {
                std::vector<Vec2> v(s.file.scene.part_vertices(p), s.file.scene.part_vertices(p) + p.count);
                out.append(py::make_tuple(kinds[static_cast<int>(p.kind)], p.label, xy_array(v),
                                          py::make_tuple(p.center.x(), p.center.y()), p.radius));
            }
            return out;
        })
        .def("rasterize", [](const PyScene& s, std::int64_t cells) {
            gvd::OccupancyGrid g;
            try {
                py::gil_scoped_release release;
                g = gvd::rasterize(s.file.scene, cells);
            } catch (const dvoronoi::InputError&) {
                throw;  // to the translator (bind_core.cpp): a ValueError whose message stays UTF-8
            }
            py::array_t<bool> occ({static_cast<py::ssize_t>(g.rows), static_cast<py::ssize_t>(g.cols)});
            std::copy(g.occupied.begin(), g.occupied.end(), reinterpret_cast<std::uint8_t*>(occ.mutable_data()));
            return py::make_tuple(occ, g.resolution, py::make_tuple(g.origin.x(), g.origin.y()));
        }, py::arg("cells"), "The scene on `cells` pixels along the area's longer side (gvd/rasterize.hpp): "
                             "(occupancy H x W bool, resolution, origin).")
        .def("nearest", [](const PyScene& s, py::handle p) {
            const Vec2 q = point_arg(p, "point");
            const gvd::Nearest n = gvd::nearest_brute_force(s.file.scene, q, true);
            return py::make_tuple(n.label, n.sq);
        }, "Brute-force nearest obstacle (label, squared distance) of a point.");

    py::class_<PyResult>(m, "_GvdResult", "Grid Voronoi diagram (private; see dvoronoi.GridVoronoi).")
        // Pickled as its scene and options; loading runs the build again, which gives the same
        // diagram for any worker count (the run statistics are the new run's).
        .def(py::pickle(
            [](const PyResult& p) {
                py::object frame = py::none();
                if (p.pixels.scene) frame = py::make_tuple(p.pixels.scene, p.pixels.scale, p.pixels.offset.x(), p.pixels.offset.y());
                return py::make_tuple(p.scene, p.options.resolution, p.options.robot_radius, p.options.workers,
                                      dvoronoi::io::mode_name(p.options.mode), p.options.visibility, frame);
            },
            [](const py::tuple& t) {
                if (t.size() != 6 && t.size() != 7) throw py::value_error("not a pickled _GvdResult state");
                gvd::GvdOptions o;
                o.resolution = t[1].cast<std::int64_t>();
                o.robot_radius = t[2].cast<double>();
                o.workers = t[3].cast<int>();
                o.mode = parse_mode(t[4].cast<std::string>());
                o.visibility = t[5].cast<bool>();
                o.graph = false;
                PixelFrame pixels;
                if (t.size() == 7 && !t[6].is_none()) {
                    const auto f = t[6].cast<py::tuple>();
                    pixels = {f[0].cast<std::shared_ptr<PyScene>>(), f[1].cast<double>(), Vec2(f[2].cast<double>(), f[3].cast<double>())};
                }
                return run_gvd(t[0].cast<std::shared_ptr<PyScene>>(), o, std::move(pixels));
            }))
        .def_property_readonly("grid", [](const PyResult& p) {
            const auto& g = p.r.grid;
            return py::make_tuple(g.x0, g.y0, g.h, g.nx, g.ny);
        })
        .def_property_readonly("robot_radius", [](const PyResult& p) { return p.r.robot_radius; })
        .def_property_readonly("n_obstacles", [](const PyResult& p) { return p.r.n_obstacles; })
        .def_property_readonly("n_labels", [](const PyResult& p) { return p.r.n_labels; })
        .def_property_readonly("col", [](const PyResult& p) { return copy_array<std::int32_t>(p.r.col); })
        .def_property_readonly("row", [](const PyResult& p) { return copy_array<std::int32_t>(p.r.row); })
        .def_property_readonly("labels", [](const PyResult& p) {
            py::array_t<std::int32_t> a({static_cast<py::ssize_t>(p.r.size()), py::ssize_t{4}});
            std::copy(p.r.labels.begin(), p.r.labels.end(), a.mutable_data());
            return a;
        })
        .def_property_readonly("clearance", [](const PyResult& p) { return copy_array<double>(p.r.clearance); })
        .def_property_readonly("blocked", [](const PyResult& p) { return copy_array<bool>(p.r.blocked); })
        .def_property_readonly("vertices", [](const PyResult& p) { return copy_array<std::int64_t>(p.r.vertices); })
        .def_property_readonly("node_cell", [](PyResult& p) { return copy_array<std::int64_t>(p.graph().roadmap.node_cell); })
        .def_property_readonly("node_kind", [](PyResult& p) { return copy_array<std::uint8_t>(p.graph().roadmap.node_kind); })
        .def_property_readonly("edge_u", [](PyResult& p) { return copy_array<std::int64_t>(p.graph().roadmap.edge_u); })
        .def_property_readonly("edge_v", [](PyResult& p) { return copy_array<std::int64_t>(p.graph().roadmap.edge_v); })
        .def_property_readonly("edge_length", [](PyResult& p) { return copy_array<double>(p.graph().roadmap.edge_length); })
        .def_property_readonly("edge_min_clearance", [](PyResult& p) { return copy_array<double>(p.graph().roadmap.edge_min_clearance); })
        .def_property_readonly("edge_blocked", [](PyResult& p) { return copy_array<bool>(p.graph().roadmap.edge_blocked); })
        .def_property_readonly("chain_ptr", [](PyResult& p) { return copy_array<std::int64_t>(p.graph().roadmap.chain_ptr); })
        .def_property_readonly("chain_cells", [](PyResult& p) { return copy_array<std::int64_t>(p.graph().roadmap.chain_cells); })
        .def_property_readonly("stats", [](const PyResult& p) {
            const auto& s = p.r.stats;
            py::dict d;
            d["workers"] = s.workers;
            d["mode"] = dvoronoi::io::mode_name(s.mode);
            d["corners_labelled"] = s.corners_labelled;
            d["part_evaluations"] = s.part_evaluations;
            d["edge_evaluations"] = s.edge_evaluations;
            d["traced_cells"] = s.traced_cells;
            d["discarded_cells"] = s.discarded_cells;
            d["bridged_cells"] = s.bridged_cells;
            d["obstacle_walks"] = s.obstacle_walks;
            d["walk_cells"] = s.walk_cells;
            d["walk_seeds"] = s.walk_seeds;
            d["contact_seeds"] = s.contact_seeds;
            d["boundary_seeds"] = s.boundary_seeds;
            d["border_lines_scanned"] = s.border_lines_scanned;
            d["peak_worker_bytes"] = s.peak_worker_bytes;
            d["worker_seconds"] = s.worker_seconds;
            d["worker_cpu_seconds"] = s.worker_cpu_seconds;
            d["worker_evaluations"] = s.worker_evaluations;
            return d;
        })
        .def("to_json", [](PyResult& p, int indent) { return dvoronoi::io::gvd_to_json(p.graph()).dump(indent); },
             py::arg("indent") = -1)
        .def("to_svg", [](PyResult& p, py::object path) {
            const std::vector<Vec2> pts = finite_points_arg(path, "route");
            std::ostringstream os;
            dvoronoi::io::write_gvd_svg(os, p.scene->file.scene, p.r, pts);
            return os.str();
        }, py::arg("path") = py::none())
        .def("path", [](PyResult& p, py::handle start, py::handle goal) {
            const Vec2 s = point_arg(start, "start"), g = point_arg(goal, "goal");
            p.graph();
            gvd::PathResult res;
            {
                py::gil_scoped_release release;
                try {
                    res = gvd::find_path(p.r, p.scene->file.scene, p.scene->path_index(), s, g);
                } catch (const dvoronoi::InputError&) {
                    py::gil_scoped_acquire gil;
                    throw;  // to the translator (bind_core.cpp): a ValueError whose message stays UTF-8
                }
            }
            return py::make_tuple(xy_array(res.points), res.length);
        }, py::arg("start"), py::arg("goal"));

    m.def("_gvd_run", [](std::shared_ptr<PyScene> scene, std::int64_t resolution, double robot_radius, int workers,
                         const std::string& mode, bool visibility, std::shared_ptr<PyScene> pixel_scene, double scale,
                         double ox, double oy) {
        gvd::GvdOptions o;
        o.resolution = resolution;
        o.robot_radius = robot_radius;
        o.workers = workers;
        o.mode = parse_mode(mode);
        o.visibility = visibility;
        o.graph = false;  // built on first use of the roadmap or a path
        return run_gvd(std::move(scene), o, {std::move(pixel_scene), scale, Vec2(ox, oy)});
    }, py::arg("scene"), py::arg("resolution"), py::arg("robot_radius"), py::arg("workers"), py::arg("mode"),
       py::arg("visibility"), py::arg("pixel_scene") = py::none(), py::arg("scale") = 1.0, py::arg("ox") = 0.0,
       py::arg("oy") = 0.0,
       "The labelled diagram of `scene`; with `pixel_scene` (an occupancy map's obstacles in pixel units) its "
       "labels are computed there and placed in map units by scale and (ox, oy) (gvd::placed).");

    m.def("_gvd_brute_force", [](std::shared_ptr<PyScene> scene, std::int64_t resolution, bool visibility) {
        gvd::BruteForceLabels b;
        {
            py::gil_scoped_release release;
            b = gvd::brute_force_labels(scene->file.scene, resolution, visibility);
        }
        const auto w = static_cast<py::ssize_t>(b.grid.nx) + 1, h = static_cast<py::ssize_t>(b.grid.ny) + 1;
        py::array_t<std::int32_t> lab({h, w});
        std::copy(b.corner_label.begin(), b.corner_label.end(), lab.mutable_data());
        py::array_t<double> sq({h, w});
        std::copy(b.corner_sq.begin(), b.corner_sq.end(), sq.mutable_data());
        py::array_t<bool> mixed({h - 1, w - 1});
        std::copy(b.mixed.begin(), b.mixed.end(), mixed.mutable_data());
        return py::make_tuple(lab, sq, mixed);
    }, py::arg("scene"), py::arg("resolution"), py::arg("visibility") = true,
       "Brute-force oracle: corner labels (ny+1, nx+1), squared distances, mixed cells (ny, nx).");
}
