// Message-passing networks in Python: one simulation (network::run, bound as _network_run returning
// a typed, picklable result per algorithm that python/dvoronoi/network.py wraps: _NetworkCcRun,
// _NetworkBd07Run, _NetworkBsRun) and a batch of independent networks run in parallel (OpenMP over
// networks, GIL released) for experiments. The JSON is io/network_json.hpp's, as the CLI writes it.
#include "arrays.hpp"
#include "pickle.hpp"
#include "progress.hpp"

#include "dvoronoi/io/network_geojson.hpp"
#include "dvoronoi/io/network_json.hpp"
#include "dvoronoi/network/run.hpp"

#include "dvoronoi/network/bd07.hpp"
#include "dvoronoi/network/cc.hpp"
#include "dvoronoi/network/delaunay_check.hpp"
#include "dvoronoi/network/distributed_boundary_scan.hpp"
#include "dvoronoi/network/dv_hop.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace dvoronoi_bindings;
namespace nw = dvoronoi::network;

namespace {

template <class T, class U = T>
py::array copy_vec(const std::vector<U>& v) {
    py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
    T* out = a.mutable_data();
    for (std::size_t k = 0; k < v.size(); ++k) out[k] = static_cast<T>(v[k]);
    return a;
}

/// Obstacles: None or an (m, 4) array of segments x0, y0, x1, y1.
std::vector<nw::Segment> obstacles_arg(const py::object& obj) {
    std::vector<nw::Segment> out;
    if (obj.is_none()) return out;
    py::array arr = as_array(obj, "obstacles", "an (m, 4) array of segments (x0, y0, x1, y1)");
    if (arr.ndim() == 1 && arr.shape(0) == 0) return out;
    if (arr.ndim() != 2 || arr.shape(1) != 4)
        throw py::value_error("obstacles must be an (m, 4) array of segments (x0, y0, x1, y1), got shape " + shape_str(arr));
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(arr);
    if (!a) throw py::type_error("obstacles must hold real numbers");
    const double* d = a.data();
    for (py::ssize_t k = 0; k < a.shape(0); ++k)
        out.push_back({Vec2(d[4 * k], d[4 * k + 1]), Vec2(d[4 * k + 2], d[4 * k + 3])});
    return out;
}

/// Links as an (E, 2) int64 array of pairs i < j.
py::array links_array(const nw::Network& net) {
    std::vector<Index> flat;
    for (Index i = 0; i < net.size(); ++i)
        for (Index j : net.adj[static_cast<std::size_t>(i)])
            if (j > i) flat.push_back(i), flat.push_back(j);
    py::array_t<Index> a({static_cast<py::ssize_t>(flat.size() / 2), py::ssize_t{2}});
    std::copy(flat.begin(), flat.end(), a.mutable_data());
    return a;
}

/// Neighbour lists as CSR (order kept).
py::tuple csr(const std::vector<std::vector<Index>>& lists) {
    std::vector<Index> indptr{0}, indices;
    for (const auto& l : lists) {
        indices.insert(indices.end(), l.begin(), l.end());
        indptr.push_back(static_cast<Index>(indices.size()));
    }
    return py::make_tuple(copy_vec<Index>(indptr), copy_vec<Index>(indices));
}

/// What every network of a batch runs with (the seed differs per network).
struct SimArgs {
    std::string algorithm;
    double loss = 0.0;
    std::uint64_t seed = 0;
    std::int64_t budget = 0;
    nw::CcOptions cc;
    nw::Bd07Options bd07;
    nw::Box box;
};

/// Totals of one run (for batches): transmissions per type, lost messages, correctness.
struct BatchRow {
    std::vector<std::int64_t> by_type, deliveries_by_type;
    std::int64_t lost = 0;
    bool condition = false, exact = false;
};

BatchRow run_one(const nw::Network& net, const SimArgs& a, bool verify) {
    nw::RunOptions ro{a.loss, a.seed, a.budget};
    BatchRow row;
    const auto totals = [&](const nw::TransmissionCounts& c) {
        for (std::size_t t = 0; t < c.types.size(); ++t) {
            row.by_type.push_back(c.sent_of_type(t));
            row.deliveries_by_type.push_back(c.received_of_type(t));
        }
    };
    if (a.algorithm == "cc") {
        const auto r = nw::run_cc(net, ro, a.cc);
        totals(r.counts);
        row.lost = r.lost;
        if (verify) {
            const auto chk = nw::delaunay_check(net);
            row.condition = chk.condition;
            row.exact = nw::wrong_nodes(chk, r.neighbors, &r.on_hull).empty();
        }
    } else if (a.algorithm == "bd07") {
        const auto r = nw::run_bd07(net, a.box, ro, a.bd07);
        totals(r.counts);
        row.lost = r.lost;
        if (verify) row.condition = nw::delaunay_check(net).condition;
    } else if (a.algorithm == "check") {
        // Theorem 2's condition only; a disconnected network fails it without the exact diagram.
        const auto comp = nw::components(net.adj);
        const bool connected = comp.empty() || *std::max_element(comp.begin(), comp.end()) == 0;
        row.condition = connected && nw::delaunay_check(net).condition;
    } else {
        throw dvoronoi::InputError("batch algorithm must be \"cc\", \"bd07\" or \"check\", got \"" + a.algorithm + "\"");
    }
    return row;
}

// ---- typed results: fields as numpy copies, pickled field by field (pickle.hpp) ----

/// Every stored field of a result, visited by name: one list for the pickled state and its reader.
template <class V>
void visit_fields(nw::RunBase& r, V& v) {
    v("range", r.range);
    v("loss", r.loss);
    v("seed", r.seed);
    v("settings", r.settings);
    v("points", r.points);
    v("obstacles", r.obstacles);
    v("links", r.links);
    v("blocked_links", r.blocked_links);
    v("counts", r.counts);
    v("lost", r.lost);
    v("discoveries", r.discoveries);
    v("delivered", r.delivered);
    v("indptr", r.indptr);
    v("indices", r.indices);
    v("cells", r.cells);
}
template <class V>
void visit_fields(nw::CcRun& r, V& v) {
    visit_fields(static_cast<nw::RunBase&>(r), v);
    v("neighbors_ccw", r.neighbors_ccw);
    v("on_hull", r.on_hull);
    v("refinements", r.refinements);
    v("bounds", r.bounds);
    v("condition", r.condition);
    v("dt_components", r.dt_components);
    v("wrong_nodes", r.wrong_nodes);
}
template <class V>
void visit_fields(nw::Bd07Run& r, V& v) {
    visit_fields(static_cast<nw::RunBase&>(r), v);
    v("bounds", r.bounds);
    v("probes", r.probes);
    v("condition", r.condition);
    v("dt_components", r.dt_components);
}
template <class V>
void visit_fields(nw::BsRun& r, V& v) {
    visit_fields(static_cast<nw::RunBase&>(r), v);
    v("radius", r.radius);
    v("positions", r.positions);
    v("perimeters", r.perimeters);
    v("anchors", r.anchors);
    v("localised", r.localised);
    v("localized", r.localized);
    v("hop_size", r.hop_size);
    v("dv_hop_counts", r.dv_hop_counts);
    v("dropped_coincident", r.dropped_coincident);
}

std::vector<std::uint8_t> bytes_of(const std::vector<char>& v) { return {v.begin(), v.end()}; }

struct Saver {
    py::dict d;
    void operator()(const char* k, double x) { d[k] = x; }
    void operator()(const char* k, bool x) { d[k] = x; }
    void operator()(const char* k, std::int64_t x) { d[k] = x; }
    void operator()(const char* k, std::uint64_t x) { d[k] = x; }
    void operator()(const char* k, const Points& p) { d[k] = np_of(p); }
    void operator()(const char* k, const std::vector<Index>& v) { d[k] = np_of(v); }
    void operator()(const char* k, const std::vector<double>& v) { d[k] = np_of(v); }
    void operator()(const char* k, const std::vector<char>& v) { d[k] = np_of(bytes_of(v)); }
    void operator()(const char* k, const std::vector<nw::Segment>& v) {
        std::vector<double> f;
        for (const auto& s : v) f.insert(f.end(), {s.a.x(), s.a.y(), s.b.x(), s.b.y()});
        d[k] = np_of(f);
    }
    void operator()(const char* k, const std::vector<std::array<Index, 2>>& v) {
        std::vector<Index> f;
        for (const auto& l : v) f.insert(f.end(), {l[0], l[1]});
        d[k] = np_of(f);
    }
    void operator()(const char* k, const nw::TransmissionCounts& c) {
        py::dict e;
        e["types"] = c.types;
        e["nodes"] = c.nodes;
        e["sent"] = np_of(c.sent);
        e["received"] = np_of(c.received);
        d[k] = e;
    }
    void operator()(const char* k, const nw::Settings& o) {
        py::dict e;
        e["budget"] = o.budget;
        e["cap_adjacency"] = o.cc.cap_adjacency;
        e["adjacency_cap"] = o.cc.adjacency_cap;
        e["forward"] = o.cc.forward;
        e["routing"] = o.cc.routing == nw::Routing::Gpsr ? "gpsr" : "shortest";
        e["cc_route_discovery"] = o.cc.route_discovery;
        e["bd07_route_discovery"] = o.bd07.route_discovery;
        e["dv_hop_synchronous"] = o.dv_hop.synchronous;
        e["anchors_relay"] = o.dv_hop.anchors_relay;
        e["verify"] = o.verify;
        d[k] = e;
    }
    void operator()(const char* k, const nw::FlatCells& c) {
        Saver s;
        s("piece_ptr", c.piece_ptr);
        s("piece_neighbor", c.piece_neighbor);
        s("piece_x", c.piece_x);
        s("piece_y", c.piece_y);
        s("piece_span", c.piece_span);
        s("areas", c.areas);
        s("centroids", c.centroids);
        d[k] = s.d;
    }
    void operator()(const char* k, const std::optional<nw::Box>& b) {
        if (b) d[k] = np_of(std::vector<double>{b->xmin, b->ymin, b->xmax, b->ymax});
        else d[k] = py::none();
    }
    void operator()(const char* k, const std::optional<bool>& b) { d[k] = b ? py::cast(*b) : py::none(); }
    void operator()(const char* k, const std::optional<Index>& b) { d[k] = b ? py::cast(*b) : py::none(); }
    void operator()(const char* k, const std::optional<std::vector<Index>>& b) {
        if (b) d[k] = np_of(*b);
        else d[k] = py::none();
    }
};

struct Loader {
    py::dict d;
    const char* type;
    py::object at(const char* k) const {
        if (!d.contains(k)) throw py::value_error(std::string("pickled ") + type + ": no field " + k);
        return d[k];
    }
    void operator()(const char* k, double& x) { x = at(k).cast<double>(); }
    void operator()(const char* k, bool& x) { x = at(k).cast<bool>(); }
    void operator()(const char* k, std::int64_t& x) { x = at(k).cast<std::int64_t>(); }
    void operator()(const char* k, std::uint64_t& x) { x = at(k).cast<std::uint64_t>(); }
    void operator()(const char* k, Points& p) { at(k), p = points_of(d, k); }
    void operator()(const char* k, std::vector<Index>& v) { at(k), v = vec_of<Index>(d, k); }
    void operator()(const char* k, std::vector<double>& v) { at(k), v = vec_of<double>(d, k); }
    void operator()(const char* k, std::vector<char>& v) {
        at(k);
        const auto b = vec_of<std::uint8_t>(d, k);
        v.assign(b.begin(), b.end());
    }
    void operator()(const char* k, std::vector<nw::Segment>& v) {
        at(k);
        const auto f = vec_of<double>(d, k);
        if (f.size() % 4) throw py::value_error(std::string("pickled ") + type + ": bad " + k);
        v.clear();
        for (std::size_t i = 0; i < f.size(); i += 4) v.push_back({Vec2(f[i], f[i + 1]), Vec2(f[i + 2], f[i + 3])});
    }
    void operator()(const char* k, std::vector<std::array<Index, 2>>& v) {
        at(k);
        const auto f = vec_of<Index>(d, k);
        if (f.size() % 2) throw py::value_error(std::string("pickled ") + type + ": bad " + k);
        v.clear();
        for (std::size_t i = 0; i < f.size(); i += 2) v.push_back({f[i], f[i + 1]});
    }
    void operator()(const char* k, nw::TransmissionCounts& c) {
        const py::dict e = at(k).cast<py::dict>();
        c.types = e["types"].cast<std::vector<std::string>>();
        c.nodes = e["nodes"].cast<Index>();
        c.sent = vec_of<std::int64_t>(e, "sent");
        c.received = vec_of<std::int64_t>(e, "received");
        const auto want = static_cast<std::size_t>(c.nodes) * c.types.size();
        if (c.sent.size() != want || c.received.size() != want)
            throw py::value_error(std::string("pickled ") + type + ": counts of inconsistent sizes");
    }
    void operator()(const char* k, nw::Settings& o) {
        const py::dict e = at(k).cast<py::dict>();
        o.budget = e["budget"].cast<std::int64_t>();
        o.cc.cap_adjacency = e["cap_adjacency"].cast<bool>();
        o.cc.adjacency_cap = e["adjacency_cap"].cast<int>();
        o.cc.forward = e["forward"].cast<bool>();
        o.cc.routing = nw::parse_routing(e["routing"].cast<std::string>());
        o.cc.route_discovery = e["cc_route_discovery"].cast<bool>();
        o.bd07.route_discovery = e["bd07_route_discovery"].cast<bool>();
        o.dv_hop.synchronous = e["dv_hop_synchronous"].cast<bool>();
        o.dv_hop.anchors_relay = e["anchors_relay"].cast<bool>();
        o.verify = e["verify"].cast<bool>();
    }
    void operator()(const char* k, nw::FlatCells& c) {
        Loader l{at(k).cast<py::dict>(), type};
        l("piece_ptr", c.piece_ptr);
        l("piece_neighbor", c.piece_neighbor);
        l("piece_x", c.piece_x);
        l("piece_y", c.piece_y);
        l("piece_span", c.piece_span);
        l("areas", c.areas);
        l("centroids", c.centroids);
    }
    void operator()(const char* k, std::optional<nw::Box>& b) {
        if (at(k).is_none()) return b.reset();
        const auto v = vec_of<double>(d, k);
        if (v.size() != 4) throw py::value_error(std::string("pickled ") + type + ": bad " + k);
        b = nw::Box{v[0], v[1], v[2], v[3]};
    }
    void operator()(const char* k, std::optional<bool>& b) {
        if (at(k).is_none()) return b.reset();
        b = at(k).cast<bool>();
    }
    void operator()(const char* k, std::optional<Index>& b) {
        if (at(k).is_none()) return b.reset();
        b = at(k).cast<Index>();
    }
    void operator()(const char* k, std::optional<std::vector<Index>>& b) {
        if (at(k).is_none()) return b.reset();
        b = vec_of<Index>(d, k);
    }
};

template <class R>
py::tuple run_state(const R& r) {
    Saver s;
    visit_fields(const_cast<R&>(r), s);  // the saver only reads
    return make_state(s.d);
}

template <class R>
R run_from_state(const py::tuple& t, const char* type) {
    R r;
    Loader l{state_dict(t, type), type};
    visit_fields(r, l);
    const auto n = static_cast<std::size_t>(r.points.rows());
    if (r.indptr.size() != n + 1 || r.cells.piece_ptr.size() != n + 1 || r.cells.areas.size() != n ||
        static_cast<std::size_t>(r.cells.centroids.rows()) != n || r.counts.nodes != r.size() ||
        r.indptr.back() != static_cast<Index>(r.indices.size()) ||
        r.cells.piece_ptr.back() != static_cast<Index>(r.cells.piece_x.size()))
        throw py::value_error(std::string("pickled ") + type + ": arrays of inconsistent lengths");
    return r;
}

py::array_t<std::int64_t> count_matrix(const std::vector<std::int64_t>& flat, Index nodes, std::size_t types) {
    py::array_t<std::int64_t> a({static_cast<py::ssize_t>(nodes), static_cast<py::ssize_t>(types)});
    std::copy(flat.begin(), flat.end(), a.mutable_data());
    return a;
}

py::array_t<bool> bool_array(const std::vector<char>& v) {
    py::array_t<bool> a(static_cast<py::ssize_t>(v.size()));
    for (std::size_t k = 0; k < v.size(); ++k) a.mutable_data()[k] = v[k] != 0;
    return a;
}

py::object box_tuple(const std::optional<nw::Box>& b) {
    if (!b) return py::none();
    return py::make_tuple(b->xmin, b->ymin, b->xmax, b->ymax);
}

template <class T>
py::object optional_object(const std::optional<T>& v) {
    return v ? py::cast(*v) : py::none();
}

/// The fields every typed result has.
template <class R, class Cls>
void def_base(Cls& c, const char* type) {
    c.def_property_readonly("algorithm", [](const R&) { return std::string(nw::algorithm_name(R::algorithm)); })
        .def_property_readonly("points", [](const R& r) { return np_of(r.points); }, "(n, 2) node positions")
        .def_property_readonly("comm_range", [](const R& r) { return r.range; })
        .def_property_readonly("loss", [](const R& r) { return r.loss; })
        .def_property_readonly("seed", [](const R& r) { return r.seed; })
        .def_property_readonly("obstacles", [](const R& r) {
            py::array_t<double> a({static_cast<py::ssize_t>(r.obstacles.size()), py::ssize_t{4}});
            double* o = a.mutable_data();
            for (const auto& s : r.obstacles) *o++ = s.a.x(), *o++ = s.a.y(), *o++ = s.b.x(), *o++ = s.b.y();
            return a;
        }, "(m, 4) obstacle segments x0, y0, x1, y1")
        .def_property_readonly("links", [](const R& r) {
            py::array_t<Index> a({static_cast<py::ssize_t>(r.links.size()), py::ssize_t{2}});
            Index* o = a.mutable_data();
            for (const auto& l : r.links) *o++ = l[0], *o++ = l[1];
            return a;
        }, "(E, 2) links i < j")
        .def_property_readonly("blocked_links", [](const R& r) { return r.blocked_links; })
        .def_property_readonly("message_types", [](const R& r) { return py::tuple(py::cast(r.counts.types)); })
        .def_property_readonly("sent", [](const R& r) { return count_matrix(r.counts.sent, r.size(), r.counts.types.size()); },
                               "(n, T) transmissions per node and message type")
        .def_property_readonly("received", [](const R& r) { return count_matrix(r.counts.received, r.size(), r.counts.types.size()); },
                               "(n, T) link deliveries per node and message type")
        .def_property_readonly("lost_messages", [](const R& r) { return r.lost; })
        .def_property_readonly("route_discoveries", [](const R& r) { return r.discoveries; })
        .def_property_readonly("delivered", [](const R& r) { return r.delivered; })
        .def_property_readonly("total_transmissions", [](const R& r) { return r.total_transmissions(); })
        .def_property_readonly("total_deliveries", [](const R& r) { return r.total_deliveries(); })
        .def_property_readonly("indptr", [](const R& r) { return np_of(r.indptr); })
        .def_property_readonly("indices", [](const R& r) { return np_of(r.indices); })
        .def_property_readonly("piece_ptr", [](const R& r) { return np_of(r.cells.piece_ptr); })
        .def_property_readonly("piece_neighbor", [](const R& r) { return np_of(r.cells.piece_neighbor); })
        .def_property_readonly("piece_x", [](const R& r) { return np_of(r.cells.piece_x); })
        .def_property_readonly("piece_y", [](const R& r) { return np_of(r.cells.piece_y); })
        .def_property_readonly("piece_span", [](const R& r) { return np_of(r.cells.piece_span); })
        .def_property_readonly("areas", [](const R& r) { return np_of(r.cells.areas); })
        .def_property_readonly("centroids", [](const R& r) { return np_of(r.cells.centroids); })
        .def("__len__", [](const R& r) { return r.size(); })
        .def("to_json", [](const R& r, const py::object& indent) {
            return dvoronoi::io::network_json_text(r, indent.is_none() ? -1 : indent.cast<int>());
        }, py::arg("indent") = py::none(), "The run's JSON document (io/network_json.hpp; what the CLI writes).")
        .def("to_geojson", [](const R& r, double tolerance) {
            return dvoronoi::io::network_geojson_text(r, tolerance);
        }, py::arg("tolerance") = 0.0,
           "The cells as a GeoJSON FeatureCollection (io/network_geojson.hpp; what the CLI writes); "
           "tolerance 0 = radius / 1000.")
        .def(py::pickle([](const R& r) { return run_state(r); },
                        [type](const py::tuple& t) { return run_from_state<R>(t, type); }));
}

void bind_runs(py::module_& m) {
    py::class_<nw::CcRun> cc(m, "_NetworkCcRun", "A CC simulation (network/run.hpp); wrapped by dvoronoi.network.CcResult.");
    def_base<nw::CcRun>(cc, "_NetworkCcRun");
    cc.def_property_readonly("neighbors_ccw", [](const nw::CcRun& r) { return np_of(r.neighbors_ccw); })
        .def_property_readonly("on_hull", [](const nw::CcRun& r) { return bool_array(r.on_hull); })
        .def_property_readonly("refinements", [](const nw::CcRun& r) { return r.refinements; })
        .def_property_readonly("bounds", [](const nw::CcRun& r) { return box_tuple(r.bounds); })
        .def_property_readonly("condition", [](const nw::CcRun& r) { return optional_object(r.condition); })
        .def_property_readonly("dt_components", [](const nw::CcRun& r) { return optional_object(r.dt_components); })
        .def_property_readonly("wrong_nodes", [](const nw::CcRun& r) -> py::object {
            if (!r.wrong_nodes) return py::none();
            return np_of(*r.wrong_nodes);
        });
    py::class_<nw::Bd07Run> bd(m, "_NetworkBd07Run", "A BD07 simulation (network/run.hpp); wrapped by dvoronoi.network.Bd07Result.");
    def_base<nw::Bd07Run>(bd, "_NetworkBd07Run");
    bd.def_property_readonly("bounds", [](const nw::Bd07Run& r) { return box_tuple(r.bounds); })
        .def_property_readonly("probes", [](const nw::Bd07Run& r) { return r.probes; })
        .def_property_readonly("condition", [](const nw::Bd07Run& r) { return optional_object(r.condition); })
        .def_property_readonly("dt_components", [](const nw::Bd07Run& r) { return optional_object(r.dt_components); });
    py::class_<nw::BsRun> bs(m, "_NetworkBsRun",
                             "A distributed Boundary Scan simulation (network/run.hpp); wrapped by "
                             "dvoronoi.network.BoundaryScanResult.");
    def_base<nw::BsRun>(bs, "_NetworkBsRun");
    bs.def_property_readonly("radius", [](const nw::BsRun& r) { return r.radius; })
        .def_property_readonly("positions", [](const nw::BsRun& r) { return np_of(r.positions); })
        .def_property_readonly("perimeters", [](const nw::BsRun& r) { return np_of(r.perimeters); })
        .def_property_readonly("anchors", [](const nw::BsRun& r) -> py::object {
            if (!r.anchors) return py::none();
            return np_of(*r.anchors);
        })
        .def_property_readonly("localised", [](const nw::BsRun& r) { return r.localised; }, "DV-Hop ran")
        .def_property_readonly("localized", [](const nw::BsRun& r) { return bool_array(r.localized); })
        .def_property_readonly("hop_size", [](const nw::BsRun& r) -> py::object {
            if (!r.localised) return py::none();
            return np_of(r.hop_size);
        })
        .def_property_readonly("dv_hop_types", [](const nw::BsRun& r) { return py::tuple(py::cast(r.dv_hop_counts.types)); })
        .def_property_readonly("dv_hop_sent", [](const nw::BsRun& r) {
            return count_matrix(r.dv_hop_counts.sent, r.size(), r.dv_hop_counts.types.size());
        })
        .def_property_readonly("dv_hop_received", [](const nw::BsRun& r) {
            return count_matrix(r.dv_hop_counts.received, r.size(), r.dv_hop_counts.types.size());
        })
        .def_property_readonly("dropped_coincident", [](const nw::BsRun& r) { return r.dropped_coincident; });

    m.def("_network_run", [](const std::string& algorithm, py::handle points, double comm_range, double loss,
                             const py::object& obstacles, const py::object& bounds, std::uint64_t seed,
                             std::int64_t budget, bool cap_adjacency, int adjacency_cap, bool forward,
                             const std::string& routing, const py::object& anchors, double anchor_fraction,
                             double radius, bool verify, bool route_discovery, bool dv_hop_synchronous,
                             bool anchors_relay) -> py::object {
        const PointsArg p = points_arg(points, "points");
        nw::Options o;
        o.algorithm = nw::parse_algorithm(algorithm);
        o.range = comm_range;
        o.obstacles = obstacles_arg(obstacles);
        if (!bounds.is_none()) {
            const auto v = bounds.cast<std::vector<double>>();
            if (v.size() != 4) throw py::value_error("bounds must be (xmin, ymin, xmax, ymax)");
            o.bounds = nw::Box{v[0], v[1], v[2], v[3]};
        }
        o.run = nw::RunOptions{loss, seed, budget};
        o.cc.cap_adjacency = cap_adjacency;
        o.cc.adjacency_cap = adjacency_cap;
        o.cc.forward = forward;
        o.cc.routing = nw::parse_routing(routing);
        o.cc.route_discovery = route_discovery;
        o.bd07.route_discovery = route_discovery;
        if (!anchors.is_none()) o.anchors = anchors.cast<std::vector<Index>>();
        o.anchor_fraction = anchor_fraction;
        o.radius = radius;
        o.dv_hop.synchronous = dv_hop_synchronous;
        o.dv_hop.anchors_relay = anchors_relay;
        o.verify = verify;
        nw::Result r;
        {
            py::gil_scoped_release nogil;
            r = nw::run(p.ref(), o);
        }
        return std::visit([](auto&& x) { return py::cast(std::move(x)); }, std::move(r));
    }, py::arg("algorithm"), py::arg("points"), py::arg("comm_range"), py::arg("loss"), py::arg("obstacles"),
       py::arg("bounds"), py::arg("seed"), py::arg("budget"), py::arg("cap_adjacency"), py::arg("adjacency_cap"),
       py::arg("forward"), py::arg("routing"), py::arg("anchors"), py::arg("anchor_fraction"), py::arg("radius"),
       py::arg("verify"), py::arg("route_discovery"), py::arg("dv_hop_synchronous"), py::arg("anchors_relay"),
       "One simulation (network::run): a _NetworkCcRun, _NetworkBd07Run or _NetworkBsRun.");
}

}  // namespace

void bind_network(py::module_& m) {
    py::register_exception<nw::BudgetExceeded>(m, "BudgetExceeded", PyExc_RuntimeError);

    m.def("_network_links", [](py::handle points, double comm_range, const py::object& obstacles) {
        const PointsArg p = points_arg(points, "points");
        const auto obs = obstacles_arg(obstacles);
        const nw::Network net = nw::make_network(p.ref(), comm_range, obs);
        py::dict d;
        d["links"] = links_array(net);
        d["blocked_links"] = net.blocked_links;
        d["planar"] = csr(nw::gabriel_graph(net));
        return d;
    }, py::arg("points"), py::arg("comm_range"), py::arg("obstacles") = py::none());

    m.def("_network_gpsr", [](py::handle points, double comm_range, const py::object& obstacles, Index source,
                              py::handle target) {
        const PointsArg p = points_arg(points, "points");
        const nw::Network net = nw::make_network(p.ref(), comm_range, obstacles_arg(obstacles));
        if (source < 0 || source >= net.size()) throw py::index_error("source is not a node index");
        const nw::Gpsr g(net);
        std::vector<Index> path;
        const bool ok = g.route(source, point_arg(target, "target"), path);
        return py::make_tuple(ok, copy_vec<Index>(path));
    }, py::arg("points"), py::arg("comm_range"), py::arg("obstacles"), py::arg("source"), py::arg("target"),
       "GPSR route from `source` to the point `target`: (delivered, path of node indices).");

    bind_runs(m);

    m.def("_network_batch", [](const std::string& algorithm, const std::vector<py::object>& points_list,
                               double comm_range, double loss, const std::vector<py::object>& obstacles_list,
                               const std::vector<double>& bounds, const std::vector<std::uint64_t>& seeds,
                               bool verify, int threads, py::object progress, bool route_discovery) {
        const std::size_t N = points_list.size();
        if (obstacles_list.size() != N || seeds.size() != N)
            throw py::value_error("points_list, obstacles_list and seeds must have the same length");
        std::vector<Points> pts(N);
        std::vector<std::vector<nw::Segment>> obs(N);
        for (std::size_t k = 0; k < N; ++k) {
            pts[k] = points_arg(points_list[k], "points").ref();
            obs[k] = obstacles_arg(obstacles_list[k]);
        }
        SimArgs a;
        a.algorithm = algorithm;
        a.loss = loss;
        a.cc.route_discovery = route_discovery;
        a.bd07.route_discovery = route_discovery;
        if (bounds.size() != 4) throw py::value_error("bounds must be (xmin, ymin, xmax, ymax)");
        a.box = nw::Box{bounds[0], bounds[1], bounds[2], bounds[3]};
        nw::require_box(a.box);
        nw::require_run_options(nw::RunOptions{loss, 0, 0});
        std::vector<BatchRow> rows(N);
        PyProgress prog(std::move(progress));
        const auto fn = prog.fn();
        std::exception_ptr failure;
        {
            py::gil_scoped_release nogil;
            dvoronoi::detail::ProgressTracker tracker(fn, static_cast<Index>(N));
            const int team = dvoronoi::detail::thread_team(threads, static_cast<Index>(N));
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
            for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(N); ++k) {
                if (tracker.cancelled()) continue;
                try {
                    const auto kk = static_cast<std::size_t>(k);
                    SimArgs mine = a;
                    mine.seed = seeds[kk];
                    const nw::Network net = nw::make_network(pts[kk], comm_range, obs[kk]);
                    rows[kk] = run_one(net, mine, verify);
                } catch (...) {
#pragma omp critical(dvoronoi_network_batch)
                    if (!failure) failure = std::current_exception();
                }
                tracker.block_done(1);
            }
            if (!failure) tracker.rethrow_if_failed();
        }
        prog.rethrow();
        if (failure) std::rethrow_exception(failure);
        const std::size_t T = N ? rows[0].by_type.size() : (algorithm == "bd07" ? 4 : algorithm == "cc" ? 3 : 0);
        py::array_t<std::int64_t> by_type({static_cast<py::ssize_t>(N), static_cast<py::ssize_t>(T)});
        py::array_t<std::int64_t> deliveries({static_cast<py::ssize_t>(N), static_cast<py::ssize_t>(T)});
        py::array_t<std::int64_t> lost(static_cast<py::ssize_t>(N));
        py::array_t<bool> cond(static_cast<py::ssize_t>(N)), exact(static_cast<py::ssize_t>(N));
        for (std::size_t k = 0; k < N; ++k) {
            for (std::size_t t = 0; t < T; ++t) {
                by_type.mutable_at(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(t)) = rows[k].by_type[t];
                deliveries.mutable_at(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(t)) = rows[k].deliveries_by_type[t];
            }
            lost.mutable_at(static_cast<py::ssize_t>(k)) = rows[k].lost;
            cond.mutable_at(static_cast<py::ssize_t>(k)) = rows[k].condition;
            exact.mutable_at(static_cast<py::ssize_t>(k)) = rows[k].exact;
        }
        py::dict d;
        d["by_type"] = by_type;
        d["deliveries_by_type"] = deliveries;
        d["lost"] = lost;
        d["condition"] = cond;
        d["exact"] = exact;
        return d;
    });
}
