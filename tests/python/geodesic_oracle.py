"""The exact geodesic distance on small occupancy grids, by brute force: the test oracle of
dv.coverage.geodesic_cells (tests/python/test_geodesic.py, tools/bench_geodesic.py --accuracy).

Free space = the map's rectangle minus the occupied pixels (closed unit squares). A segment is free
when shapely says the free region covers it and it passes through no pinch point (a pixel corner where
two occupied pixels touch diagonally). Shortest paths bend only at convex corners of occupied pixels,
so the exact distance from the sources to a point q is Dijkstra on the visibility graph of sources and
convex corners, then the minimum over the nodes that see q of D(node) + |q - node|.

Coordinates are image pixel units: u to the right, w down; pixel (r, c) is [c, c+1] x [r, r+1].
"""
from __future__ import annotations

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra


def _blocked(occ: np.ndarray) -> np.ndarray:
    """The occupancy padded with one occupied pixel all round (the outside of the map)."""
    return np.pad(occ.astype(bool), 1, constant_values=True)


def corners(occ: np.ndarray):
    """(convex corners, pinch points) as (k, 2) arrays of (u, w) vertices."""
    b = _blocked(occ)
    # vertex (i, j) is surrounded by pixels (j-1, i-1), (j-1, i), (j, i-1), (j, i): padded + 1
    a, bb, c, d = b[:-1, :-1], b[:-1, 1:], b[1:, :-1], b[1:, 1:]
    count = a.astype(int) + bb + c + d
    convex = np.argwhere(count == 1)[:, ::-1].astype(float)
    pinch = np.argwhere(((a & d) & ~bb & ~c) | ((bb & c) & ~a & ~d))[:, ::-1].astype(float)
    return convex, pinch


def free_region(occ: np.ndarray):
    H, W = occ.shape
    boxes = [shapely.box(c, r, c + 1, r + 1) for r, c in np.argwhere(occ)]
    region = shapely.box(0, 0, W, H)
    return region.difference(shapely.union_all(boxes)) if boxes else region


def visible(region, pinch: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """For pairs of points a[k], b[k]: is the segment free."""
    a = np.asarray(a, float).reshape(-1, 2)
    b = np.asarray(b, float).reshape(-1, 2)
    lines = shapely.linestrings(np.stack([a, b], axis=1))
    ok = shapely.covers(region, lines)
    same = np.all(a == b, axis=1)
    ok |= same & shapely.covers(region, shapely.points(a))
    for p in pinch:  # exact for corner / centre endpoints: small integers and halves
        cross = (b[:, 0] - a[:, 0]) * (p[1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (p[0] - a[:, 0])
        inside = ((np.minimum(a[:, 0], b[:, 0]) <= p[0]) & (p[0] <= np.maximum(a[:, 0], b[:, 0]))
                  & (np.minimum(a[:, 1], b[:, 1]) <= p[1]) & (p[1] <= np.maximum(a[:, 1], b[:, 1])))
        ok &= ~((cross == 0) & inside)
    return ok


def exact_distances(occ: np.ndarray, sources: np.ndarray):
    """Exact geodesic distance from each source to every free pixel centre: (n, H, W), inf where
    unreachable (and on occupied pixels)."""
    occ = np.asarray(occ, bool)
    H, W = occ.shape
    sources = np.asarray(sources, float).reshape(-1, 2)
    n = len(sources)
    convex, pinch = corners(occ)
    region = free_region(occ)
    nodes = np.vstack([sources, convex])
    m = len(nodes)
    i, j = np.triu_indices(m, 1)
    vis = visible(region, pinch, nodes[i], nodes[j])
    w = np.hypot(*(nodes[i] - nodes[j]).T)[vis]
    graph = coo_matrix((np.concatenate([w, w]), (np.concatenate([i[vis], j[vis]]), np.concatenate([j[vis], i[vis]]))),
                       shape=(m, m)).tocsr()
    D = dijkstra(graph, indices=np.arange(n))  # (n, m)
    for k in range(n):  # distinct sources at the same point: the graph drops zero-length edges
        D[k, k] = 0.0
    free = np.argwhere(~occ)
    centres = free[:, ::-1] + 0.5
    out = np.full((n, H, W), np.inf)
    qa = np.repeat(centres, m, axis=0)
    nb = np.tile(nodes, (len(centres), 1))
    see = visible(region, pinch, qa, nb).reshape(len(centres), m)
    leg = np.hypot(*(qa - nb).T).reshape(len(centres), m)
    for k in range(n):
        total = np.where(see, D[k][None, :] + leg, np.inf)
        out[k][free[:, 0], free[:, 1]] = total.min(axis=1)
    return out


def exact_cells(occ: np.ndarray, sources: np.ndarray):
    """(labels, distance): nearest source (ties to the lower index, -1 unreachable) and its distance."""
    d = exact_distances(occ, sources)
    dist = d.min(axis=0)
    labels = np.where(np.isfinite(dist), d.argmin(axis=0), -1)
    return labels, dist
