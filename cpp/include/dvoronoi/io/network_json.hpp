// The JSON document of a network simulation (network/run.hpp), written here once for the CLI
// (`dvoronoi network ... -o run.json`) and Python (`result.to_json()`): the same run gives the same
// text. Keys in this order:
//
//   {"kind": "network_cc" | "network_bd07" | "network_bs", "algorithm", "comm_range", "loss", "seed",
//    "options": the run's other options (network::Settings), named as dvoronoi.network.simulate's
//      arguments: cc {"budget", "cap_adjacency", "adjacency_cap", "forward", "routing",
//      "route_discovery", "verify"}, bd07 {"budget", "route_discovery", "verify"}, bs {"budget",
//      "dv_hop": "sync" | "async", "anchors_relay"} (budget 0: the default, 10^9),
//    "points": [[x, y], ...], "links": [[i, j], ...] (i < j), "blocked_links",
//    "obstacles": [[x0, y0, x1, y1], ...],
//    cc:   "indptr", "indices" (ascending), "neighbors_ccw" (CC's order, same indptr), "on_hull",
//          "bounds" ([xmin, ymin, xmax, ymax] or null), "areas" (null: unbounded), "centroids",
//          "condition", "dt_components", "wrong_nodes" (null without verify), "refinements",
//          "route_discoveries", "lost_messages",
//    bd07: "bounds" (the region used; null for an empty network without one), "indptr", "indices",
//          "areas", "centroids", "probes", "condition", "dt_components", "route_discoveries",
//          "lost_messages",
//    bs:   "positions" (used; null where not localised), "radius", "indptr", "indices", "areas",
//          "perimeters", "centroids", "anchors" (null without DV-Hop), "dv_hop_types",
//          "dv_hop_sent", "dv_hop_received" (n rows), "dropped_coincident", "lost_messages",
//    "message_types", "sent", "received" (n rows of one count per type), "total_transmissions",
//    "total_deliveries" (DV-Hop included)}
//
// Non-finite numbers are written as null.
#pragma once

#include "dvoronoi/network/run.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace dvoronoi::io {

namespace detail {

using ojson = nlohmann::ordered_json;

/// A number, or null when it is not finite (NaN: not localised; inf: an unbounded cell's area), so
/// the document holds what its text says.
inline ojson num(double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); }

inline ojson nums(const std::vector<double>& v) {
    ojson out = ojson::array();
    for (double x : v) out.push_back(num(x));
    return out;
}

inline ojson xy_rows(const Points& p) {
    ojson out = ojson::array();
    for (Eigen::Index i = 0; i < p.rows(); ++i) out.push_back(ojson::array({num(p(i, 0)), num(p(i, 1))}));
    return out;
}

inline ojson count_rows(const network::TransmissionCounts& c, Index nodes) {
    ojson out = ojson::array();
    const std::size_t T = c.types.size();
    for (Index i = 0; i < nodes; ++i) {
        ojson row = ojson::array();
        for (std::size_t t = 0; t < T; ++t) row.push_back(c.sent[static_cast<std::size_t>(i) * T + t]);
        out.push_back(std::move(row));
    }
    return out;
}

inline ojson received_rows(const network::TransmissionCounts& c, Index nodes) {
    ojson out = ojson::array();
    const std::size_t T = c.types.size();
    for (Index i = 0; i < nodes; ++i) {
        ojson row = ojson::array();
        for (std::size_t t = 0; t < T; ++t) row.push_back(c.received[static_cast<std::size_t>(i) * T + t]);
        out.push_back(std::move(row));
    }
    return out;
}

inline ojson box_json(const std::optional<network::Box>& b) {
    if (!b) return nullptr;
    return ojson::array({b->xmin, b->ymin, b->xmax, b->ymax});
}

template <class T>
ojson optional_json(const std::optional<T>& v) {
    if (!v) return nullptr;
    return ojson(*v);
}

/// The options of the run that its algorithm reads (see the file comment).
inline ojson options_json(const network::Settings& s, network::Algorithm a) {
    ojson j;
    j["budget"] = s.budget;
    if (a == network::Algorithm::Cc) {
        j["cap_adjacency"] = s.cc.cap_adjacency;
        j["adjacency_cap"] = s.cc.adjacency_cap;
        j["forward"] = s.cc.forward;
        j["routing"] = s.cc.routing == network::Routing::Gpsr ? "gpsr" : "shortest";
        j["route_discovery"] = s.cc.route_discovery;
        j["verify"] = s.verify;
    } else if (a == network::Algorithm::Bd07) {
        j["route_discovery"] = s.bd07.route_discovery;
        j["verify"] = s.verify;
    } else {
        j["dv_hop"] = s.dv_hop.synchronous ? "sync" : "async";
        j["anchors_relay"] = s.dv_hop.anchors_relay;
    }
    return j;
}

inline void head(ojson& j, const network::RunBase& r, network::Algorithm a) {
    j["kind"] = std::string("network_") + network::algorithm_name(a);
    j["algorithm"] = network::algorithm_name(a);
    j["comm_range"] = r.range;
    j["loss"] = r.loss;
    j["seed"] = r.seed;
    j["options"] = options_json(r.settings, a);
    j["points"] = xy_rows(r.points);
    ojson links = ojson::array();
    for (const auto& l : r.links) links.push_back(ojson::array({l[0], l[1]}));
    j["links"] = std::move(links);
    j["blocked_links"] = r.blocked_links;
    ojson obs = ojson::array();
    for (const auto& s : r.obstacles) obs.push_back(ojson::array({s.a.x(), s.a.y(), s.b.x(), s.b.y()}));
    j["obstacles"] = std::move(obs);
}

inline void tail(ojson& j, const network::RunBase& r, std::int64_t transmissions, std::int64_t deliveries) {
    j["message_types"] = r.counts.types;
    j["sent"] = count_rows(r.counts, r.size());
    j["received"] = received_rows(r.counts, r.size());
    j["total_transmissions"] = transmissions;
    j["total_deliveries"] = deliveries;
}

inline ojson body(const network::CcRun& r) {
    ojson j;
    head(j, r, network::Algorithm::Cc);
    j["indptr"] = r.indptr;
    j["indices"] = r.indices;
    j["neighbors_ccw"] = r.neighbors_ccw;
    ojson hull = ojson::array();
    for (char h : r.on_hull) hull.push_back(h != 0);
    j["on_hull"] = std::move(hull);
    j["bounds"] = box_json(r.bounds);
    j["areas"] = nums(r.cells.areas);
    j["centroids"] = xy_rows(r.cells.centroids);
    j["condition"] = optional_json(r.condition);
    j["dt_components"] = optional_json(r.dt_components);
    j["wrong_nodes"] = optional_json(r.wrong_nodes);
    j["refinements"] = r.refinements;
    j["route_discoveries"] = r.discoveries;
    j["lost_messages"] = r.lost;
    tail(j, r, r.total_transmissions(), r.total_deliveries());
    return j;
}

inline ojson body(const network::Bd07Run& r) {
    ojson j;
    head(j, r, network::Algorithm::Bd07);
    j["bounds"] = box_json(r.bounds);
    j["indptr"] = r.indptr;
    j["indices"] = r.indices;
    j["areas"] = nums(r.cells.areas);
    j["centroids"] = xy_rows(r.cells.centroids);
    j["probes"] = r.probes;
    j["condition"] = optional_json(r.condition);
    j["dt_components"] = optional_json(r.dt_components);
    j["route_discoveries"] = r.discoveries;
    j["lost_messages"] = r.lost;
    tail(j, r, r.total_transmissions(), r.total_deliveries());
    return j;
}

inline ojson body(const network::BsRun& r) {
    ojson j;
    head(j, r, network::Algorithm::Bs);
    j["positions"] = xy_rows(r.positions);
    j["radius"] = r.radius;
    j["indptr"] = r.indptr;
    j["indices"] = r.indices;
    j["areas"] = nums(r.cells.areas);
    j["perimeters"] = nums(r.perimeters);
    j["centroids"] = xy_rows(r.cells.centroids);
    j["anchors"] = optional_json(r.anchors);
    j["dv_hop_types"] = r.dv_hop_counts.types;
    j["dv_hop_sent"] = count_rows(r.dv_hop_counts, r.size());
    j["dv_hop_received"] = received_rows(r.dv_hop_counts, r.size());
    j["dropped_coincident"] = r.dropped_coincident;
    j["lost_messages"] = r.lost;
    tail(j, r, r.total_transmissions(), r.total_deliveries());
    return j;
}

}  // namespace detail

/// The document of one run (keys in the order of the file comment).
inline nlohmann::ordered_json network_json(const network::Result& r) {
    return std::visit([](const auto& x) { return detail::body(x); }, r);
}

/// The document as text: compact when indent < 0, else indented by `indent` spaces. No final newline.
inline std::string network_json_text(const network::Result& r, int indent = -1) {
    return network_json(r).dump(indent);
}

/// The same for one typed result (no copy into the variant).
template <class R, class = std::enable_if_t<std::is_base_of_v<network::RunBase, R>>>
std::string network_json_text(const R& r, int indent = -1) {
    return detail::body(r).dump(indent);
}

}  // namespace dvoronoi::io
