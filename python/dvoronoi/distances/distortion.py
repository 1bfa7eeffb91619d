"""Distortion between graphs (Elwin, Freeman & Lynch, Sections II-D and IV-C), via shortest paths.

A connected weighted graph is a metric space (shortest-path distances). For two graphs on the same
robots, the identity map has distortion

    delta = max_{x != y} (sigma(x, y) / rho(x, y)) / min_{x != y} (sigma(x, y) / rho(x, y)) >= 1,

the smallest D with gamma rho <= sigma <= gamma D rho (eq. 1). It is symmetric in the two graphs.
Disconnected graphs have no finite metric: the distortion is then ``inf`` (the paper discards those
trials). Shortest paths come from scipy.sparse.csgraph (Dijkstra); memory is O(n^2).

* detection distortion delta_m: the detection graph with true distances d_ij against the same graph
  with measured ones e_ij;
* Delaunay distortion delta_v: the true Delaunay graph (true weights) against the computed graph G_v
  (the robots' answers, measured weights).
"""
from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["distortion", "detection_distortion", "delaunay_distortion", "true_weights"]


def _as_graph(g: Any):
    import scipy.sparse as sp

    m = sp.csr_matrix(g, dtype=float) if not sp.issparse(g) else g.tocsr().astype(float)
    if m.shape[0] != m.shape[1]:
        raise ValueError(f"a graph must be a square matrix, got shape {m.shape}")
    if m.nnz and (not np.all(np.isfinite(m.data)) or np.any(m.data <= 0)):
        raise ValueError("graph edge weights must be positive and finite")
    return m


def distortion(graph_a: Any, graph_b: Any) -> float:
    """Distortion of the identity map between two weighted undirected graphs on the same vertices
    (square matrices, dense or scipy.sparse; absent or 0 entries = no edge). ``inf`` when either is
    disconnected; 1.0 for fewer than two vertices."""
    from scipy.sparse.csgraph import shortest_path

    a, b = _as_graph(graph_a), _as_graph(graph_b)
    if a.shape != b.shape:
        raise ValueError(f"the graphs have different sizes: {a.shape} and {b.shape}")
    n = a.shape[0]
    if n < 2:
        return 1.0
    da = shortest_path(a, method="D", directed=False)
    db = shortest_path(b, method="D", directed=False)
    iu = np.triu_indices(n, 1)
    x, y = da[iu], db[iu]
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        return float("inf")
    ratio = y / x
    return float(ratio.max() / ratio.min())


def true_weights(graph: Any, points) -> Any:
    """The same edges as `graph`, weighted with the true distances between `points`."""
    import scipy.sparse as sp

    g = sp.coo_matrix(graph)
    pts = np.asarray(points, dtype=float)
    w = np.hypot(*(pts[g.row] - pts[g.col]).T)
    return sp.csr_matrix((w, (g.row, g.col)), shape=g.shape)


def detection_distortion(points, measured: Any) -> float:
    """delta_m: detection graph with true weights vs. with the measured ones (`measured` as accepted
    by :func:`dvoronoi.neighbors_from_distances`' sparse form: a square matrix of e_ij)."""
    return distortion(true_weights(measured, points), measured)


def delaunay_distortion(points, result: Any) -> float:
    """delta_v: the true Delaunay graph of `points` (exact, true weights) vs. the computed graph of a
    :class:`~dvoronoi.distances.DistanceNeighbors` result (its edges, measured weights)."""
    import scipy.sparse as sp

    from .._voronoi import voronoi_cells

    pts = np.asarray(points, dtype=float)
    exact = voronoi_cells(pts)
    e = exact.delaunay_edges()
    n = len(pts)
    w = np.hypot(*(pts[e[:, 0]] - pts[e[:, 1]]).T)
    true = sp.csr_matrix((np.concatenate([w, w]), (np.concatenate([e[:, 0], e[:, 1]]), np.concatenate([e[:, 1], e[:, 0]]))), shape=(n, n))
    return distortion(true, result.weighted_graph())
