// Range-limited Voronoi cells in Python: limited_cell (one agent) and limited_cells (all agents).
//
// limited_cell is meant to be called once per robot per control step, so its binding does no more
// than convert the arguments (no copy for float64 arrays of any stride), run the algorithm and wrap
// the result; measures and arrays of the returned LimitedCell are computed on first access.
// limited_cells releases the GIL for the whole computation; its arrays are zero-copy read-only views
// into the bound LimitedPartition.
#include "arrays.hpp"
#include "pickle.hpp"
#include "progress.hpp"

#include "dvoronoi/cells/limited_cell.hpp"
#include "dvoronoi/partition/limited_partition.hpp"
#include "dvoronoi/partition/power_partition.hpp"

// JSON and GeoJSON: the CLI's writers (io/), so Python writes exactly what `dvoronoi` writes.
#include "dvoronoi/io/geojson.hpp"
#include "dvoronoi/io/json.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
using dvoronoi::CellMeasures;
using dvoronoi::LimitedCell;
using dvoronoi::LimitedPartition;
using dvoronoi::Method;
using dvoronoi::Piece;

namespace {

/// Above this many `others`, limited_cell releases the GIL (below it, releasing costs more than the
/// call).
constexpr Eigen::Index kReleaseGilAbove = 4096;

/// A LimitedCell with its measures computed on first use.
struct PyCell {
    LimitedCell cell;
    std::optional<CellMeasures> m;

    const CellMeasures& measures() {
        if (!m) m = cell.measures();
        return *m;
    }
};

/// One boundary piece, as Python sees it.
struct PyPiece {
    Index neighbor;
    Vec2 start, end, center;
    double span, radius;
};

/// The partition and the method that made it (the JSON names it).
struct PyPartition {
    LimitedPartition part;
    Method method;
};

py::array vec2_array(const Vec2& v) {
    py::array_t<double> a(2);
    a.mutable_at(0) = v.x();
    a.mutable_at(1) = v.y();
    return a;
}

py::tuple vec2_tuple(const Vec2& v) { return py::make_tuple(v.x(), v.y()); }

std::string fmt(double x) {
    std::ostringstream s;
    s.precision(6);
    s << x;
    return s.str();
}

std::vector<PyPiece> pieces_of(const LimitedCell& c) {
    std::vector<PyPiece> out;
    out.reserve(c.pieces.size());
    for (std::size_t k = 0; k < c.pieces.size(); ++k) {
        const Piece& p = c.pieces[k];
        out.push_back({p.neighbor, p.start, c.piece_end(k), c.center, p.arc_span, c.radius});
    }
    return out;
}

py::array neighbors_array(const LimitedCell& c) {
    const std::vector<Index> nb = c.neighbors();
    py::array_t<Index> a(static_cast<py::ssize_t>(nb.size()));
    std::copy(nb.begin(), nb.end(), a.mutable_data());
    return a;
}

py::array vertices_array(const LimitedCell& c) { return xy_array(c.vertices()); }

template <class F>
py::array piece_array(const LimitedCell& c, F f) {
    using T = decltype(f(c.pieces[0]));
    py::array_t<T> a(static_cast<py::ssize_t>(c.pieces.size()));
    T* out = a.mutable_data();
    for (std::size_t k = 0; k < c.pieces.size(); ++k) out[k] = f(c.pieces[k]);
    return a;
}

py::object cell_object(LimitedCell&& c) { return py::cast(PyCell{std::move(c), std::nullopt}); }

// Pickled states: every field of the cell or partition (see pickle.hpp).
py::tuple cell_state(const LimitedCell& c) {
    py::dict d;
    d["center"] = np_of(c.center);
    d["radius"] = c.radius;
    d["candidates"] = c.candidates;
    d["chords_after_check"] = c.chords_after_check;
    d["piece_neighbor"] = piece_array(c, [](const Piece& p) { return p.neighbor; });
    d["piece_x"] = piece_array(c, [](const Piece& p) { return p.start.x(); });
    d["piece_y"] = piece_array(c, [](const Piece& p) { return p.start.y(); });
    d["piece_span"] = piece_array(c, [](const Piece& p) { return p.arc_span; });
    d["area"] = c.measures_.area;
    d["centroid"] = np_of(c.measures_.centroid);
    d["perimeter"] = c.measures_.perimeter;
    return make_state(d);
}

PyCell cell_from_state(const py::tuple& t) {
    const py::dict d = state_dict(t, "LimitedCell");
    LimitedCell c;
    c.center = vec2_of(d, "center");
    c.radius = d["radius"].cast<double>();
    c.candidates = d["candidates"].cast<Index>();
    c.chords_after_check = d["chords_after_check"].cast<Index>();
    const auto nb = vec_of<Index>(d, "piece_neighbor");
    const auto x = vec_of<double>(d, "piece_x"), y = vec_of<double>(d, "piece_y"), span = vec_of<double>(d, "piece_span");
    if (x.size() != nb.size() || y.size() != nb.size() || span.size() != nb.size())
        throw py::value_error("pickled LimitedCell: piece arrays of different lengths");
    for (std::size_t k = 0; k < nb.size(); ++k) {
        Piece p;
        p.neighbor = nb[k];
        p.start = Vec2(x[k], y[k]);
        p.arc_span = span[k];
        c.pieces.push_back(p);
    }
    c.measures_.area = d["area"].cast<double>();
    c.measures_.centroid = vec2_of(d, "centroid");
    c.measures_.perimeter = d["perimeter"].cast<double>();
    return PyCell{std::move(c), std::nullopt};
}

py::tuple partition_state(const PyPartition& pp) {
    const LimitedPartition& p = pp.part;
    py::dict d;
    d["method"] = dvoronoi::method_name(pp.method);
    d["radius"] = p.radius;
    d["points"] = np_of(p.points);
    d["piece_ptr"] = np_of(p.piece_ptr);
    d["piece_neighbor"] = np_of(p.piece_neighbor);
    d["piece_x"] = np_of(p.piece_x);
    d["piece_y"] = np_of(p.piece_y);
    d["piece_span"] = np_of(p.piece_span);
    d["indptr"] = np_of(p.indptr);
    d["indices"] = np_of(p.indices);
    d["areas"] = np_of(p.areas);
    d["perimeters"] = np_of(p.perimeters);
    d["centroids"] = np_of(p.centroids);
    d["candidates"] = np_of(p.candidates);
    d["computed_by"] = np_of(std::vector<Index>{static_cast<Index>(p.computed_by.clip), static_cast<Index>(p.computed_by.scan),
                                                static_cast<Index>(p.computed_by.chords), static_cast<Index>(p.computed_by.power)});
    d["radii"] = np_of(p.radii);
    return make_state(d);
}

std::unique_ptr<PyPartition> partition_from_state(const py::tuple& t) {
    const py::dict d = state_dict(t, "LimitedPartition");
    auto out = std::make_unique<PyPartition>();
    out->method = dvoronoi::parse_method(d["method"].cast<std::string>());
    LimitedPartition& p = out->part;
    p.method = out->method;
    p.radius = d["radius"].cast<double>();
    p.points = points_of(d, "points");
    p.piece_ptr = vec_of<Index>(d, "piece_ptr");
    p.piece_neighbor = vec_of<Index>(d, "piece_neighbor");
    p.piece_x = vec_of<double>(d, "piece_x");
    p.piece_y = vec_of<double>(d, "piece_y");
    p.piece_span = vec_of<double>(d, "piece_span");
    p.indptr = vec_of<Index>(d, "indptr");
    p.indices = vec_of<Index>(d, "indices");
    p.areas = vec_of<double>(d, "areas");
    p.perimeters = vec_of<double>(d, "perimeters");
    p.centroids = points_of(d, "centroids");
    p.candidates = vec_of<Index>(d, "candidates");
    const auto ran = vec_of<Index>(d, "computed_by");
    // 3 counts: pickled before heterogeneous teams (no "power", no "radii").
    if (ran.size() != 3 && ran.size() != 4) throw py::value_error("pickled LimitedPartition: computed_by is not 3 or 4 counts");
    if (ran.size() == 4) p.computed_by.power = static_cast<decltype(p.computed_by.power)>(ran[3]);
    if (d.contains("radii")) p.radii = vec_of<double>(d, "radii");
    p.computed_by.clip = static_cast<decltype(p.computed_by.clip)>(ran[0]);
    p.computed_by.scan = static_cast<decltype(p.computed_by.scan)>(ran[1]);
    p.computed_by.chords = static_cast<decltype(p.computed_by.chords)>(ran[2]);
    const auto n = static_cast<std::size_t>(p.points.rows());
    if (p.indptr.size() != n + 1 || p.piece_ptr.size() != n + 1 || p.areas.size() != n || p.perimeters.size() != n ||
        static_cast<std::size_t>(p.centroids.rows()) != n || p.candidates.size() != n ||
        p.indices.size() != static_cast<std::size_t>(p.indptr.back()) ||
        p.piece_neighbor.size() != static_cast<std::size_t>(p.piece_ptr.back()) ||
        p.piece_x.size() != p.piece_neighbor.size() || p.piece_y.size() != p.piece_neighbor.size() ||
        p.piece_span.size() != p.piece_neighbor.size() || (!p.radii.empty() && p.radii.size() != n))
        throw py::value_error("pickled LimitedPartition: arrays of inconsistent lengths");
    return out;
}

/// One radius per agent: a 1-D array-like of `n` positive finite numbers (ValueError naming `name`).
std::vector<double> radii_arg(py::handle obj, const char* name, std::size_t n) {
    py::array_t<double, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    } catch (const py::error_already_set&) {
        a = {};
    }
    if (!a || a.ndim() != 1)
        throw py::value_error(std::string(name) + " must be a positive number or a 1-D array of one positive radius per agent");
    if (static_cast<std::size_t>(a.shape(0)) != n)
        throw py::value_error(std::string(name) + " must have one radius per agent: got " + std::to_string(a.shape(0)) +
                              " radii for " + std::to_string(n) + " agents");
    std::vector<double> out(a.data(), a.data() + n);
    for (std::size_t i = 0; i < n; ++i)
        if (!(out[i] > 0.0) || !std::isfinite(out[i]))
            throw py::value_error(std::string(name) + "[" + std::to_string(i) + "] must be a positive finite number, got " +
                                  std::string(py::repr(py::float_(out[i]))));
    return out;
}

const LimitedPartition& part_of(const py::object& self) { return self.cast<const PyPartition&>().part; }

Index checked_index(const LimitedPartition& p, Index i) {
    if (i < 0 || i >= p.size())
        throw py::index_error("agent index " + std::to_string(i) + " out of range [0, " +
                              std::to_string(p.size()) + ")");
    return i;
}

std::string partition_json(const PyPartition& p, int indent) {
    py::gil_scoped_release release;
    if (indent < 0) return dvoronoi::io::to_json_string(p.part, p.method);  // streamed, == dump()
    return dvoronoi::io::to_json(p.part, p.method).dump(indent);
}

/// None -> 0, which io/geojson.hpp reads as its default (radius / 1000).
double tolerance_arg(const py::object& tolerance) {
    if (tolerance.is_none()) return 0.0;
    const double t = py::float_(tolerance);  // TypeError for non-numbers
    if (!(t > 0.0) || !std::isfinite(t))
        throw py::value_error("tolerance must be a positive finite number, got " + std::string(py::repr(tolerance)));
    return t;
}

const char* kLimitedCellDoc = R"doc(limited_cell(center, others, radius, method="auto", other_radii=None) -> LimitedCell

The range-limited Voronoi cell V ∩ B(center, radius) of the agent at `center` among `others`, as a
robot computes it from the positions it knows.

Parameters
----------
center : (2,) array-like of float
    The agent's position.
others : (m, 2) array-like of float
    Positions of the other agents, any memory layout (float64 arrays are not copied). Agents
    farther than 2 * radius are ignored.
radius : float
    The cell radius R > 0.
method : {"auto", "scan", "chords"}
    "scan": Boundary Scan (He, Feng & Ren 2018), O(m log m). "chords": RCVC (Guruprasad &
    Dasgupta 2012), O(m^2) worst case. "auto" (default): for one agent, Boundary Scan (with
    other_radii: the exact power-cell clipping; "scan" and "chords" then run on the radical
    axes). All return the same cell.
other_radii : (m,) array-like of float, optional
    Heterogeneous teams: the radius of each agent of `others`. The cell is then the power cell
    (weights R^2) clipped to B(center, radius), which may be empty (no pieces) or not contain
    `center`; agents farther than radius + R_j are ignored. All equal to `radius`: the same cell as
    without them.

Returns
-------
LimitedCell
    Edge pieces name their neighbour by its row in `others`.

Raises
------
ValueError
    A wrong shape, a NaN/inf coordinate, a radius that is not positive and finite, an unknown
    method, or an agent of `others` at `center` (CoincidentError, a ValueError).
TypeError
    Non-numeric input.

Notes
-----
Neighbour sets and the order of pieces are decided with exact predicates; vertex coordinates and
measures carry floating-point rounding. Thread-safe; the GIL is released for large `others`.
)doc";

const char* kLimitedCellsDoc = R"doc(limited_cells(points, radius, method="auto", threads=0, progress=None) -> LimitedPartition

`radius` is a number or one radius per agent (heterogeneous teams: power cells clipped to each
agent's disk).

Every agent's range-limited Voronoi cell (the compiled core; `dvoronoi.limited_cells` wraps it with a
progress bar and the shared result surface).

`threads` = 0 uses every core; results do not depend on it. `progress(done, total)` is called from
the calling thread with the GIL held; an exception it raises stops further calls and is re-raised
when the computation ends (the computation itself cannot be interrupted). The GIL is released
during the computation.
)doc";

}  // namespace

void bind_cells(py::module_& m) {
    // The docstrings below start with their own Python signatures (pybind11's would say `object`).
    py::options options;
    options.disable_function_signatures();

    // ------------------------------------------------------------------ Piece
    py::class_<PyPiece>(m, "Piece", "One piece of a cell boundary: a straight edge on the bisector "
                                    "with one neighbour, or an arc of the cell's circle.")
        .def_property_readonly("kind", [](const PyPiece& p) { return p.neighbor < 0 ? "arc" : "edge"; },
                               "\"edge\" or \"arc\".")
        .def_property_readonly("is_arc", [](const PyPiece& p) { return p.neighbor < 0; })
        .def_property_readonly("neighbor", [](const PyPiece& p) { return p.neighbor; },
                               "Edges: index of the agent across the edge. Arcs: -1.")
        .def_property_readonly("start", [](const PyPiece& p) { return vec2_tuple(p.start); },
                               "Start point (x, y).")
        .def_property_readonly("end", [](const PyPiece& p) { return vec2_tuple(p.end); },
                               "End point (x, y): the start of the next piece.")
        .def_property_readonly("span", [](const PyPiece& p) { return p.span; },
                               "Arcs: counter-clockwise angle swept, in (0, 2*pi]. Edges: 0.")
        .def_property_readonly("center", [](const PyPiece& p) { return vec2_tuple(p.center); },
                               "Centre of the cell's circle (the agent).")
        .def_property_readonly("radius", [](const PyPiece& p) { return p.radius; })
        .def("__repr__", [](const PyPiece& p) {
            std::string s = p.neighbor < 0 ? "Piece(arc" : "Piece(edge, neighbor=" + std::to_string(p.neighbor);
            s += ", start=(" + fmt(p.start.x()) + ", " + fmt(p.start.y()) + "), end=(" + fmt(p.end.x()) +
                 ", " + fmt(p.end.y()) + ")";
            if (p.neighbor < 0) s += ", span=" + fmt(p.span);
            return s + ")";
        });

    // ------------------------------------------------------------------ LimitedCell
    py::class_<PyCell>(m, "LimitedCell",
                       "A range-limited Voronoi cell V_i ∩ B(p_i, R): a closed counter-clockwise cycle "
                       "of pieces (edges and arcs). Measures are exact for the arcs (circular segments "
                       "included) and computed on first access.")
        .def_property_readonly("center", [](const PyCell& c) { return vec2_array(c.cell.center); },
                               "The agent's position, shape (2,).")
        .def_property_readonly("radius", [](const PyCell& c) { return c.cell.radius; })
        .def_property_readonly("pieces", [](const PyCell& c) { return pieces_of(c.cell); },
                               "The boundary pieces, counter-clockwise.")
        .def_property_readonly("vertices", [](const PyCell& c) { return vertices_array(c.cell); },
                               "Counter-clockwise vertices (the piece start points), shape (k, 2); "
                               "empty for a full disk.")
        .def_property_readonly("neighbors", [](const PyCell& c) { return neighbors_array(c.cell); },
                               "Limited neighbours (int64, ascending): agents sharing an edge of "
                               "positive length.")
        .def_property_readonly("piece_neighbor",
                               [](const PyCell& c) { return piece_array(c.cell, [](const Piece& p) { return p.neighbor; }); },
                               "Per piece: neighbour index (edges) or -1 (arcs), int64.")
        .def_property_readonly("piece_x",
                               [](const PyCell& c) { return piece_array(c.cell, [](const Piece& p) { return p.start.x(); }); },
                               "Per piece: x of the start point.")
        .def_property_readonly("piece_y",
                               [](const PyCell& c) { return piece_array(c.cell, [](const Piece& p) { return p.start.y(); }); },
                               "Per piece: y of the start point.")
        .def_property_readonly("piece_span",
                               [](const PyCell& c) { return piece_array(c.cell, [](const Piece& p) { return p.arc_span; }); },
                               "Per piece: arc angle in (0, 2*pi] for arcs, 0 for edges.")
        .def_property_readonly("area", [](PyCell& c) { return c.measures().area; })
        .def_property_readonly("centroid", [](PyCell& c) { return vec2_array(c.measures().centroid); },
                               "Centroid, shape (2,).")
        .def_property_readonly("perimeter", [](PyCell& c) { return c.measures().perimeter; })
        .def_property_readonly("candidates", [](const PyCell& c) { return c.cell.candidates; },
                               "Agents within 2R the algorithm examined (m in the papers).")
        .def_property_readonly("chords_after_check", [](const PyCell& c) { return c.cell.chords_after_check; },
                               "RCVC only: chords left after checkChords (M'); -1 otherwise.")
        .def_property_readonly("is_full_disk",
                               [](const PyCell& c) { return c.cell.pieces.size() == 1 && c.cell.pieces[0].is_arc(); },
                               "True when no agent shapes the cell.")
        .def("__len__", [](const PyCell& c) { return c.cell.pieces.size(); }, "Number of pieces.")
        .def(py::pickle([](const PyCell& c) { return cell_state(c.cell); }, &cell_from_state))
        .def("to_json", [](const PyCell& c, int indent) {
                 return indent < 0 ? dvoronoi::io::to_json_string(c.cell) : dvoronoi::io::to_json(c.cell).dump(indent);
             },
             py::arg("indent") = -1,
             "to_json(indent=-1) -> str\n\nThe cell as JSON text (io/json.hpp's limited_cell schema).")
        .def("to_geojson",
             [](const PyCell& c, const py::object& tolerance) {
                 return dvoronoi::io::to_geojson(c.cell, tolerance_arg(tolerance)).dump();
             },
             py::arg("tolerance") = py::none(),
             "to_geojson(tolerance=None) -> str\n\nThe cell as a GeoJSON Feature text; arcs become chords within `tolerance` of the arc "
             "(default radius / 1000).")
        .def("__repr__", [](PyCell& c) {
            std::string nb;
            for (Index j : c.cell.neighbors()) nb += (nb.empty() ? "" : ", ") + std::to_string(j);
            return "LimitedCell(center=(" + fmt(c.cell.center.x()) + ", " + fmt(c.cell.center.y()) +
                   "), radius=" + fmt(c.cell.radius) + ", pieces=" + std::to_string(c.cell.pieces.size()) +
                   ", neighbors=[" + nb + "], area=" + fmt(c.measures().area) + ")";
        });

    m.def(
        "limited_cell",
        [](py::handle center, py::handle others, py::handle radius_obj, py::handle method, py::handle other_radii) {
            const Vec2 c = point_arg(center, "center");
            const PointsArg o = points_arg(others, "others");
            const double radius = real_arg(radius_obj, "radius");
            const Method meth = dvoronoi::parse_method(str_arg(method, "method"));
            std::vector<double> ro;
            const bool weighted = !other_radii.is_none();
            if (weighted) ro = radii_arg(other_radii, "other_radii", static_cast<std::size_t>(o.rows));
            const auto run = [&]() {
                return weighted ? dvoronoi::power_limited_cell(c, o.ref(), radius, ro, meth)
                                : dvoronoi::limited_cell(c, o.ref(), radius, meth);
            };
            if (o.rows > kReleaseGilAbove) {
                LimitedCell cell;
                {
                    py::gil_scoped_release release;
                    cell = run();
                }
                return cell_object(std::move(cell));
            }
            return cell_object(run());
        },
        py::arg("center"), py::arg("others"), py::arg("radius"), py::arg("method") = py::str("auto"),
        py::arg("other_radii") = py::none(), kLimitedCellDoc);

    // ------------------------------------------------------------------ LimitedPartition
    using Self = py::object;

    py::class_<PyPartition>(m, "LimitedPartition",
                            "The range-limited Voronoi partition of n agents (compiled core). Arrays "
                            "are read-only views that keep this object alive.")
        .def_property_readonly("radius", [](const PyPartition& p) { return p.part.radius; })
        .def_property_readonly("method", [](const PyPartition& p) { return dvoronoi::method_name(p.method); })
        .def_property_readonly(
            "computed_by",
            [](const PyPartition& p) {
                py::dict d;
                d["clip"] = p.part.computed_by.clip;
                d["scan"] = p.part.computed_by.scan;
                d["chords"] = p.part.computed_by.chords;
                d["power"] = p.part.computed_by.power;
                return d;
            },
            "How many cells each algorithm computed: {\"clip\": certified clipping filter (auto), "
            "\"scan\": Boundary Scan, \"chords\": RCVC, \"power\": exact power-cell clipping (one radius "
            "per agent, auto, where the filter gave up)}; the values add up to n.")
        .def_property_readonly(
            "radii",
            [](const Self& s) {
                const LimitedPartition& p = part_of(s);
                if (!p.radii.empty()) return view(p.radii, s);
                py::array_t<double> same(static_cast<py::ssize_t>(p.size()));
                std::fill(same.mutable_data(), same.mutable_data() + p.size(), p.radius);
                return py::array(same);
            },
            "Each agent's radius, float64, shape (n,).")
        .def_property_readonly(
            "empty",
            [](const Self& s) {
                const LimitedPartition& p = part_of(s);
                py::array_t<bool> out(static_cast<py::ssize_t>(p.size()));
                auto* o = out.mutable_data();
                for (Index i = 0; i < p.size(); ++i) o[i] = p.piece_ptr[static_cast<std::size_t>(i)] == p.piece_ptr[static_cast<std::size_t>(i) + 1];
                return out;
            },
            "True where a cell has zero area (heterogeneous teams: covered by larger disks), bool, shape (n,).")
        .def_property_readonly("points", [](const Self& s) { return view(part_of(s).points, s); },
                               "The agents, shape (n, 2).")
        .def_property_readonly("indptr", [](const Self& s) { return view(part_of(s).indptr, s); },
                               "CSR row pointer of the limited-neighbour relation, int64, shape (n+1,).")
        .def_property_readonly("indices", [](const Self& s) { return view(part_of(s).indices, s); },
                               "CSR column indices (ascending per agent), int64.")
        .def_property_readonly("areas", [](const Self& s) { return view(part_of(s).areas, s); })
        .def_property_readonly("perimeters", [](const Self& s) { return view(part_of(s).perimeters, s); })
        .def_property_readonly("centroids", [](const Self& s) { return view(part_of(s).centroids, s); },
                               "Shape (n, 2).")
        .def_property_readonly("candidates", [](const Self& s) { return view(part_of(s).candidates, s); },
                               "Agents within 2R examined per agent, int64.")
        .def_property_readonly("piece_ptr", [](const Self& s) { return view(part_of(s).piece_ptr, s); },
                               "Agent i owns pieces [piece_ptr[i], piece_ptr[i+1]), int64.")
        .def_property_readonly("piece_neighbor", [](const Self& s) { return view(part_of(s).piece_neighbor, s); },
                               "Per piece: neighbour index (edges) or -1 (arcs), int64.")
        .def_property_readonly("piece_x", [](const Self& s) { return view(part_of(s).piece_x, s); })
        .def_property_readonly("piece_y", [](const Self& s) { return view(part_of(s).piece_y, s); })
        .def_property_readonly("piece_span", [](const Self& s) { return view(part_of(s).piece_span, s); },
                               "Per piece: arc angle in (0, 2*pi] for arcs, 0 for edges.")
        .def("__len__", [](const PyPartition& p) { return p.part.size(); })
        .def(py::pickle(&partition_state, &partition_from_state))
        .def("cell", [](const PyPartition& p, Index i) { return cell_object(p.part.cell(checked_index(p.part, i))); },
             py::arg("i"), "cell(i) -> LimitedCell\n\nAgent i's cell (neighbours in the partition's indexing).")
        .def("neighbors",
             [](const Self& s, Index i) {
                 const LimitedPartition& p = part_of(s);
                 checked_index(p, i);
                 const auto ii = static_cast<std::size_t>(i);
                 return view(p.indices.data() + p.indptr[ii], {static_cast<py::ssize_t>(p.indptr[ii + 1] - p.indptr[ii])},
                             {static_cast<py::ssize_t>(sizeof(Index))}, s);
             },
             py::arg("i"), "neighbors(i) -> numpy.ndarray\n\nLimited neighbours of agent i: int64, ascending (a view into `indices`).")
        .def("to_json", [](const PyPartition& p, int indent) { return partition_json(p, indent); },
             py::arg("indent") = -1,
             "to_json(indent=-1) -> str\n\nThe partition as JSON text, exactly what the CLI writes (compact for indent < 0).")
        .def("to_geojson",
             [](const PyPartition& p, const py::object& tolerance) {
                 const double tol = tolerance_arg(tolerance);
                 py::gil_scoped_release release;
                 return dvoronoi::io::to_geojson_string(p.part, tol);
             },
             py::arg("tolerance") = py::none(),
             "to_geojson(tolerance=None) -> str\n\nThe cells as a GeoJSON FeatureCollection text, exactly what the CLI writes; arcs become "
             "chords within `tolerance` of the arc (default radius / 1000).")
        .def("__repr__", [](const PyPartition& p) {
            return "LimitedPartition(n=" + std::to_string(p.part.size()) + ", radius=" + fmt(p.part.radius) +
                   ", method=\"" + dvoronoi::method_name(p.method) + "\")";
        });

    m.def(
        "limited_cells",
        [](py::handle points, py::handle radius_obj, const std::string& method, int threads, py::object progress) {
            const PointsArg pts = points_arg(points, "points");
            // A number, or one radius per agent (heterogeneous teams).
            const auto as_array = py::array_t<double, py::array::forcecast>::ensure(radius_obj);
            const bool per_agent = as_array && as_array.ndim() > 0;
            std::vector<double> radii;
            double radius = 0.0;
            if (per_agent)
                radii = radii_arg(radius_obj, "radius", static_cast<std::size_t>(pts.rows));
            else
                radius = real_arg(radius_obj, "radius");
            const Method meth = dvoronoi::parse_method(method);
            if (threads < 0)
                throw py::value_error("threads must be >= 0 (0 = all cores), got " + std::to_string(threads));

            PyProgress report(std::move(progress));
            const dvoronoi::ProgressFn fn = report.fn();
            auto result = std::make_unique<PyPartition>();
            result->method = meth;
            {
                py::gil_scoped_release release;
                result->part = per_agent ? dvoronoi::limited_cells(pts.ref(), radii, meth, threads, fn)
                                         : dvoronoi::limited_cells(pts.ref(), radius, meth, threads, fn);
            }
            report.rethrow();
            return result;
        },
        py::arg("points"), py::arg("radius"), py::arg("method") = "auto", py::arg("threads") = 0,
        py::arg("progress") = py::none(), kLimitedCellsDoc);
}
