// Message-passing networks in Python: one simulation (dvoronoi.network.simulate) and a batch of
// independent networks run in parallel (OpenMP over networks, GIL released) for experiments. Results
// are dicts of numpy arrays that python/dvoronoi/network.py turns into result objects.
#include "arrays.hpp"
#include "progress.hpp"

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

py::array copy_points(const Points& p) {
    py::array_t<double> a({static_cast<py::ssize_t>(p.rows()), py::ssize_t{2}});
    double* out = a.mutable_data();
    for (Eigen::Index i = 0; i < p.rows(); ++i) out[2 * i] = p(i, 0), out[2 * i + 1] = p(i, 1);
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

py::dict counts_dict(const nw::TransmissionCounts& c) {
    py::dict d;
    d["types"] = c.types;
    const auto T = static_cast<py::ssize_t>(c.types.size());
    py::array_t<std::int64_t> s({static_cast<py::ssize_t>(c.nodes), T}), r({static_cast<py::ssize_t>(c.nodes), T});
    std::copy(c.sent.begin(), c.sent.end(), s.mutable_data());
    std::copy(c.received.begin(), c.received.end(), r.mutable_data());
    d["sent"] = s;  // transmissions (a broadcast is one)
    d["received"] = r;  // link deliveries
    return d;
}

py::dict polygons_dict(const std::vector<nw::Polygon>& polys) {
    std::vector<Index> ptr{0}, label;
    std::vector<double> xs, ys, areas;
    std::vector<double> cx, cy;
    for (const auto& p : polys) {
        for (std::size_t k = 0; k < p.vertices.size(); ++k) {
            xs.push_back(p.vertices[k].x());
            ys.push_back(p.vertices[k].y());
            label.push_back(p.edge_label[k]);
        }
        ptr.push_back(static_cast<Index>(xs.size()));
        areas.push_back(p.area());
        const Vec2 c = p.centroid();
        cx.push_back(c.x());
        cy.push_back(c.y());
    }
    py::dict d;
    d["piece_ptr"] = copy_vec<Index>(ptr);
    d["piece_neighbor"] = copy_vec<Index>(label);
    d["piece_x"] = copy_vec<double>(xs);
    d["piece_y"] = copy_vec<double>(ys);
    d["areas"] = copy_vec<double>(areas);
    Points c(static_cast<Eigen::Index>(cx.size()), 2);
    for (std::size_t k = 0; k < cx.size(); ++k) c(static_cast<Eigen::Index>(k), 0) = cx[k], c(static_cast<Eigen::Index>(k), 1) = cy[k];
    d["centroids"] = copy_points(c);
    return d;
}

py::dict partition_dict(const dvoronoi::LimitedPartition& p) {
    py::dict d;
    d["radius"] = p.radius;
    d["piece_ptr"] = copy_vec<Index>(p.piece_ptr);
    d["piece_neighbor"] = copy_vec<Index>(p.piece_neighbor);
    d["piece_x"] = copy_vec<double>(p.piece_x);
    d["piece_y"] = copy_vec<double>(p.piece_y);
    d["piece_span"] = copy_vec<double>(p.piece_span);
    d["indptr"] = copy_vec<Index>(p.indptr);
    d["indices"] = copy_vec<Index>(p.indices);
    d["areas"] = copy_vec<double>(p.areas);
    d["perimeters"] = copy_vec<double>(p.perimeters);
    d["centroids"] = copy_points(p.centroids);
    d["points"] = copy_points(p.points);
    return d;
}

struct SimArgs {
    std::string algorithm;
    double loss = 0.0;
    std::uint64_t seed = 0;
    std::int64_t budget = 0;
    nw::CcOptions cc;
    nw::Bd07Options bd07;
    nw::DvHopOptions dv_hop;
    bool has_bounds = false;
    nw::Box box;
    std::vector<Index> anchors;
    bool use_anchors = false;
    double radius = 0.0;  // BS cell radius (0: range / 2)
};

nw::Box bounds_arg(const py::object& obj, const Points& pts, bool& given) {
    given = !obj.is_none();
    if (given) {
        const auto v = obj.cast<std::vector<double>>();
        if (v.size() != 4) throw py::value_error("bounds must be (xmin, ymin, xmax, ymax)");
        nw::Box b{v[0], v[1], v[2], v[3]};
        nw::require_box(b);
        return b;
    }
    if (pts.rows() == 0) return nw::Box{0, 0, 1, 1};
    nw::Box b{pts.col(0).minCoeff(), pts.col(1).minCoeff(), pts.col(0).maxCoeff(), pts.col(1).maxCoeff()};
    if (!(b.xmin < b.xmax)) b.xmin -= 1, b.xmax += 1;
    if (!(b.ymin < b.ymax)) b.ymin -= 1, b.ymax += 1;
    return b;
}

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

    m.def("_network_simulate", [](const std::string& algorithm, py::handle points, double comm_range, double loss,
                                  const py::object& obstacles, const py::object& bounds, std::uint64_t seed,
                                  std::int64_t budget, bool cap_adjacency, int adjacency_cap, bool forward,
                                  const std::string& routing, const py::object& anchors, double radius, bool verify,
                                  bool route_discovery, bool dv_hop_synchronous, bool anchors_relay) {
        const PointsArg p = points_arg(points, "points");
        const auto obs = obstacles_arg(obstacles);
        SimArgs a;
        a.algorithm = algorithm;
        a.cc.cap_adjacency = cap_adjacency;
        a.cc.adjacency_cap = adjacency_cap;
        a.cc.forward = forward;
        a.cc.routing = nw::parse_routing(routing);
        a.cc.route_discovery = route_discovery;
        a.bd07.route_discovery = route_discovery;
        a.dv_hop.synchronous = dv_hop_synchronous;
        a.dv_hop.anchors_relay = anchors_relay;
        nw::RunOptions ro{loss, seed, budget};
        nw::require_run_options(ro);
        if (!anchors.is_none()) a.anchors = anchors.cast<std::vector<Index>>();
        py::dict d;
        nw::Network net;
        {
            py::gil_scoped_release nogil;
            net = nw::make_network(p.ref(), comm_range, obs);
        }
        a.box = bounds_arg(bounds, net.points, a.has_bounds);
        d["links"] = links_array(net);
        d["blocked_links"] = net.blocked_links;
        if (algorithm == "cc") {
            nw::CcResult r;
            {
                py::gil_scoped_release nogil;
                r = nw::run_cc(net, ro, a.cc);
            }
            d["neighbors_ccw"] = csr(r.neighbors);
            d["on_hull"] = copy_vec<bool>(r.on_hull);
            d["counts"] = counts_dict(r.counts);
            d["lost"] = r.lost;
            d["discoveries"] = r.discoveries;
            d["delivered"] = r.delivered;
            d["refinements"] = r.refinements;
            if (a.has_bounds) {
                std::vector<nw::Polygon> polys;
                for (Index i = 0; i < net.size(); ++i) {
                    std::vector<Vec2> nb;
                    for (Index j : r.neighbors[static_cast<std::size_t>(i)]) nb.push_back(net.pos(j));
                    polys.push_back(nw::clipped_cell(net.pos(i), nb, r.neighbors[static_cast<std::size_t>(i)], a.box));
                }
                d["cells"] = polygons_dict(polys);
            }
            if (verify) {
                const auto chk = nw::delaunay_check(net);
                d["condition"] = chk.condition;
                d["dt_components"] = chk.components;
                d["wrong_nodes"] = copy_vec<Index>(nw::wrong_nodes(chk, r.neighbors, &r.on_hull));
            }
        } else if (algorithm == "bd07") {
            nw::Bd07Result r;
            {
                py::gil_scoped_release nogil;
                r = nw::run_bd07(net, a.box, ro, a.bd07);
            }
            d["neighbors"] = csr(r.neighbors);
            d["cells"] = polygons_dict(r.cells);
            d["counts"] = counts_dict(r.counts);
            d["lost"] = r.lost;
            d["delivered"] = r.delivered;
            d["probes"] = r.probes;
            d["discoveries"] = r.discoveries;
            // The region the run used (the points' bounding box when none was given, widened where it
            // is flat); None when there is neither a region nor a node to take one from.
            if (a.has_bounds || net.size() > 0)
                d["bounds"] = py::make_tuple(a.box.xmin, a.box.ymin, a.box.xmax, a.box.ymax);
            else
                d["bounds"] = py::none();
            if (verify) {
                const auto chk = nw::delaunay_check(net);
                d["condition"] = chk.condition;
                d["dt_components"] = chk.components;
            }
        } else if (algorithm == "bs") {
            const double R = radius > 0.0 ? radius : 0.5 * comm_range;
            py::gil_scoped_release nogil;
            nw::DvHopResult dv;
            const bool localise = !a.anchors.empty();
            if (localise) dv = nw::run_dv_hop(net, a.anchors, ro, a.dv_hop);
            const auto bs = nw::run_distributed_bs(net, localise ? dv.estimates : net.points, R, ro);
            py::gil_scoped_acquire gil;
            d["partition"] = partition_dict(bs.partition);
            d["counts"] = counts_dict(bs.counts);
            d["dropped_coincident"] = bs.dropped_coincident;
            if (localise) {
                d["estimates"] = copy_points(dv.estimates);
                d["localized"] = copy_vec<bool>(dv.localized);
                d["hop_size"] = copy_vec<double>(dv.hop_size);
                d["dv_hop_counts"] = counts_dict(dv.counts);
            }
        } else {
            throw py::value_error("algorithm must be \"cc\", \"bd07\" or \"bs\", got \"" + algorithm + "\"");
        }
        return d;
    });

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
