// The JSON form of a grid Voronoi diagram, shared by `dvoronoi gvd`, `dvoronoi_gvd_mpi` and Python's
// GridVoronoi.to_json() (one writer, the same document everywhere):
//
//   {"kind": "grid_voronoi",
//    "grid": {"x0": ., "y0": ., "cell_size": h, "nx": ., "ny": .},   cell (i, j) = [x0 + i h, x0 + (i+1) h] x ...
//    "robot_radius": r, "n_obstacles": n, "n_labels": n + area edges,
//    "cells": {"col": [...], "row": [...],                          traced cells sorted by (row, col)
//              "labels": [[bl, br, tr, tl], ...],                     corner labels
//              "clearance": [...], "blocked": [0/1, ...]},            smallest corner distance; <= r
//    "vertices": [cell, ...],                                         cells with >= 3 labels
//    "roadmap": {"nodes": [{"cell": k, "x": ., "y": ., "kind": "vertex"|"end"|"junction"}, ...],
//                "edges": [{"u": ., "v": ., "length": ., "min_clearance": ., "blocked": bool,
//                           "cells": [interior cells]}, ...]},
//    "stats": {"workers": K, "mode": ..., "corners_labelled": ., ...}}
#pragma once

#include "dvoronoi/gvd/result.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace dvoronoi::io {

inline const char* mode_name(gvd::SliceMode m) { return m == gvd::SliceMode::Cooperative ? "cooperative" : "independent"; }

/// \throws Error when the graph is not built (gvd::build_graph).
inline nlohmann::json gvd_to_json(const gvd::GridVoronoi& r) {
    using nlohmann::json;
    if (!r.has_graph) throw Error("gvd_to_json: build the graph first (gvd::build_graph)");
    json j;
    j["kind"] = "grid_voronoi";
    j["grid"] = {{"x0", r.grid.x0}, {"y0", r.grid.y0}, {"cell_size", r.grid.h}, {"nx", r.grid.nx}, {"ny", r.grid.ny}};
    j["robot_radius"] = r.robot_radius;
    j["n_obstacles"] = r.n_obstacles;
    j["n_labels"] = r.n_labels;
    json labels = json::array();
    for (std::size_t k = 0; k < r.size(); ++k)
        labels.push_back({r.labels[4 * k], r.labels[4 * k + 1], r.labels[4 * k + 2], r.labels[4 * k + 3]});
    json blocked = json::array();
    for (auto b : r.blocked) blocked.push_back(static_cast<int>(b));
    j["cells"] = {{"col", r.col}, {"row", r.row}, {"labels", std::move(labels)}, {"clearance", r.clearance}, {"blocked", std::move(blocked)}};
    j["vertices"] = r.vertices;
    static const char* kinds[] = {"vertex", "end", "junction"};
    json nodes = json::array(), edges = json::array();
    const auto& m = r.roadmap;
    for (std::size_t v = 0; v < m.node_cell.size(); ++v) {
        const Vec2 c = r.center(static_cast<std::size_t>(m.node_cell[v]));
        nodes.push_back({{"cell", m.node_cell[v]}, {"x", c.x()}, {"y", c.y()}, {"kind", kinds[m.node_kind[v]]}});
    }
    for (std::size_t e = 0; e < m.edge_u.size(); ++e) {
        std::vector<std::int64_t> cells(m.chain_cells.begin() + m.chain_ptr[e], m.chain_cells.begin() + m.chain_ptr[e + 1]);
        edges.push_back({{"u", m.edge_u[e]}, {"v", m.edge_v[e]}, {"length", m.edge_length[e]},
                         {"min_clearance", m.edge_min_clearance[e]}, {"blocked", m.edge_blocked[e] != 0}, {"cells", cells}});
    }
    j["roadmap"] = {{"nodes", std::move(nodes)}, {"edges", std::move(edges)}};
    const auto& s = r.stats;
    j["stats"] = {{"workers", s.workers}, {"mode", mode_name(s.mode)}, {"corners_labelled", s.corners_labelled},
                  {"part_evaluations", s.part_evaluations}, {"edge_evaluations", s.edge_evaluations},
                  {"traced_cells", s.traced_cells}, {"discarded_cells", s.discarded_cells},
                  {"border_lines_scanned", s.border_lines_scanned}, {"peak_worker_bytes", s.peak_worker_bytes},
                  {"worker_seconds", s.worker_seconds}, {"worker_cpu_seconds", s.worker_cpu_seconds},
                  {"worker_evaluations", s.worker_evaluations}};
    return j;
}

}  // namespace dvoronoi::io
