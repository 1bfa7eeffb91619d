"""Voronoi neighbours from inter-robot distances only (Elwin, Freeman & Lynch, RA-L 2017).

:func:`neighbors_from_distances` takes measured distances (a dense ``n x n`` matrix with ``inf`` for
"not detected", a scipy.sparse matrix, or an edge list) and returns a :class:`DistanceNeighbors`
result: every robot's Voronoi neighbours in Delaunay-path order and its Hull/Interior flag, found by
the paper's VORONOI-NEIGHBORS (compiled, multithreaded), then the consistency step.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Iterator, Optional, Tuple

import numpy as np

from .. import _args, _core
from .._partition import ProgressArg, progress_callback
from .._result import Result
from ._frames import FrameTransform, Frames, FrameTransforms, SecondRound, check_pose

__all__ = ["neighbors_from_distances", "DistanceNeighbors", "LocalRegion", "as_distance_graph"]


@dataclass(frozen=True)
class LocalRegion:
    """A robot's Voronoi region in its own coordinates (shape known up to rotation and reflection):
    the robot at the origin, its first path neighbour on the +x axis, the path turning
    counter-clockwise.

    ``positions[t]`` are the local coordinates of ``neighbors[t]``; ``vertices`` the region's
    vertices in boundary order (circumcentres of consecutive path triangles). A bounded region
    (``bounded``) is the polygon of its vertices; an unbounded one (hull robot) runs in from infinity
    along ``ray_in`` to ``vertices[0]`` and leaves ``vertices[-1]`` along ``ray_out`` (unit vectors
    pointing away from the vertex).
    """

    robot: int
    neighbors: np.ndarray
    positions: np.ndarray
    vertices: np.ndarray
    bounded: bool
    ray_in: Tuple[float, float]
    ray_out: Tuple[float, float]

    @property
    def area(self) -> float:
        """Area of a bounded region (shoelace); inf for an unbounded one."""
        if not self.bounded:
            return float("inf")
        x, y = self.vertices[:, 0], self.vertices[:, 1]
        return float(abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) / 2.0)


def _edge_list(arr: np.ndarray, n: Optional[int]):
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"distances as an edge list must have shape (m, 3) rows 'i j d', got {arr.shape}")
    idx = arr[:, :2]
    if arr.size and not np.all(np.isfinite(idx)) or np.any(idx != np.round(idx)):
        bad = int(np.flatnonzero(~np.isfinite(idx).all(axis=1) | (idx != np.round(idx)).any(axis=1))[0])
        raise ValueError(f"distances edge list row {bad}: robot indices must be integers, got {arr[bad, :2].tolist()}")
    rows, cols = idx[:, 0].astype(np.int64), idx[:, 1].astype(np.int64)
    need = int(max(rows.max(initial=-1), cols.max(initial=-1))) + 1
    if n is None:
        # Indices are positions 0..n-1, so the robot count would follow the largest index: IDs such as
        # serial numbers would size every per-robot array by the largest ID (2e9 robots for one row).
        # Refuse sparse IDs clearly instead; the CLI, which reads files of IDs, renumbers them itself.
        present = len(np.unique(np.concatenate([rows, cols]))) if len(rows) else 0
        if need > max(4 * present, present + 65536):
            raise ValueError(
                f"distances edge list: robot indices go up to {need - 1} but only {present} robots appear; "
                "indices are positions 0..n-1, not IDs. Renumber IDs such as serial numbers first: "
                "ids, inv = np.unique(edges[:, :2], return_inverse=True); edges[:, :2] = inv.reshape(-1, 2) "
                "(robot k is then ids[k]), or pass n to size the team explicitly")
        n = need
    return int(n), rows, cols, np.ascontiguousarray(arr[:, 2], dtype=np.float64), "edges"


_READ_3X3 = ("a (3, 3) array is read as an edge list of three rows 'i j d' unless its diagonal is all "
             "0 or inf, as a distance matrix's is; pass (rows, cols, values) to give an edge list explicitly")


def _edge_list_3x3(arr: np.ndarray) -> bool:
    """Is this (3, 3) array an edge list? The documented rule: yes unless its diagonal is all 0 or
    inf. Every distance matrix has such a diagonal; an edge list has it only when its third row's
    distance is inf (a row that measures nothing) and its first two rows start '0 ...' and '. 0',
    so a real edge list of three measurements is never taken for a matrix."""
    if arr.shape != (3, 3):
        return False
    d = np.diagonal(arr)
    return not bool(np.all((d == 0) | np.isposinf(d)))


def _dense(mat: np.ndarray, symmetrize: bool):
    n = mat.shape[0]
    diag = np.diagonal(mat)
    bad = np.flatnonzero(~((diag == 0) | np.isposinf(diag)))
    if len(bad):
        i = int(bad[0])
        raise ValueError(f"distances[{i}, {i}] must be 0 (or inf), got {float(diag[i])!r}")
    off = ~np.eye(n, dtype=bool)
    nan = np.argwhere(np.isnan(mat) & off)
    if len(nan):
        i, j = nan[0]
        raise ValueError(f"distances[{i}, {j}] is NaN (use inf for robots that do not detect each other)")
    finite = np.isfinite(mat) & off
    one_sided = finite != finite.T
    if one_sided.any():
        if not symmetrize:
            i, j = np.argwhere(one_sided)[0]
            raise ValueError(
                f"distances[{i}, {j}] = {float(mat[i, j])!r} but distances[{j}, {i}] = {float(mat[j, i])!r}: a pair must be "
                "detected in both directions (pass symmetrize=True to drop one-sided detections and "
                "average the two measurements of each pair)")
        finite &= finite.T  # the paper: an edge exists when both robots detect each other
    rows, cols = np.nonzero(finite)
    return n, rows.astype(np.int64), cols.astype(np.int64), mat[rows, cols].astype(np.float64), "distances"


def as_distance_graph(distances: Any, *, n: Optional[int] = None, squared: bool = False,
                      symmetrize: bool = False) -> "_core.DistanceGraph":
    """Validate measured distances and build the compiled detection graph (see
    :func:`neighbors_from_distances` for the accepted forms). Errors name the entry."""
    if isinstance(distances, _core.DistanceGraph):
        return distances
    if n is not None:
        n = _args.integer(n, "n", 0, 2**63 - 1)
    label = "distances"
    try:
        import scipy.sparse as sp
        is_sparse = sp.issparse(distances)
    except ImportError:  # pragma: no cover - scipy is optional for dense input
        is_sparse = False
    if is_sparse:
        if distances.ndim != 2 or distances.shape[0] != distances.shape[1]:
            raise ValueError(f"distances as a sparse matrix must be square, got shape {distances.shape}")
        coo = distances.tocoo()
        keep = coo.row != coo.col
        diag_bad = (coo.row == coo.col) & (coo.data != 0) & ~np.isposinf(coo.data)
        if diag_bad.any():
            k = int(np.flatnonzero(diag_bad)[0])
            raise ValueError(f"distances[{coo.row[k]}, {coo.col[k]}] must be 0 (or absent), got {float(coo.data[k])!r}")
        nn = distances.shape[0] if n is None else n
        rows, cols, vals = coo.row[keep].astype(np.int64), coo.col[keep].astype(np.int64), coo.data[keep].astype(np.float64)
    elif isinstance(distances, tuple) and len(distances) == 3:
        rows = np.asarray(distances[0])
        cols = np.asarray(distances[1])
        vals = np.asarray(distances[2], dtype=np.float64)
        if not (rows.shape == cols.shape == vals.shape) or rows.ndim != 1:
            raise ValueError("distances as (rows, cols, values) needs three 1-d arrays of one length")
        nn, rows, cols, vals, label = _edge_list(np.column_stack([rows, cols, vals]).astype(np.float64), n)
    else:
        try:
            arr = np.asarray(distances)
        except ValueError:  # rows of different lengths: numpy's message names no argument
            raise ValueError("distances must be an (n, n) matrix, an (m, 3) edge list or (rows, cols, values); "
                             "its rows have different lengths") from None
        if arr.dtype.kind not in "fiu":
            raise TypeError(f"distances must be numeric, got dtype {arr.dtype}")
        arr = arr.astype(np.float64, copy=False)
        if arr.ndim == 2 and arr.shape[0] == arr.shape[1] and not _edge_list_3x3(arr):
            if n is not None and n != arr.shape[0]:
                raise ValueError(f"n = {n} does not match the {arr.shape[0]} x {arr.shape[0]} distance matrix")
            nn, rows, cols, vals, label = _dense(arr, symmetrize)
        elif arr.ndim == 2 and arr.shape[1] == 3:
            if arr.shape[0] == 3:  # read as an edge list by the rule: a mistake names the rule
                try:
                    nn, rows, cols, vals, _ = _edge_list(arr, n)
                    return _core.distance_graph(nn, rows, cols, vals, bool(squared), bool(symmetrize), "edges")
                except ValueError as e:
                    raise ValueError(f"{e} [{_READ_3X3}]") from None
            nn, rows, cols, vals, label = _edge_list(arr, n)
        elif arr.size == 0:
            nn, rows, cols, vals = (0 if n is None else int(n)), np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
        else:
            raise ValueError("distances must be a square (n, n) matrix (inf = not detected), an (m, 3) edge "
                             f"list 'i j d', a (rows, cols, values) tuple or a scipy.sparse matrix; got shape {arr.shape}")
    return _core.distance_graph(int(nn), rows, cols, vals, bool(squared), bool(symmetrize), label)


class DistanceNeighbors(Result):
    """Every robot's Voronoi neighbours found from distances only (Elwin, Freeman & Lynch).

    Attributes
    ----------
    indptr, indices : int64
        The neighbour relation in scipy's CSR layout, input order. Row i lists robot i's own answer in
        Delaunay-path order (``path(i)``: consecutive entries are mutual Voronoi neighbours; a cycle for
        interior robots, a path whose ends are the hull neighbours for hull robots), followed by the
        robots the consistency step added (ascending).
    on_hull : (n,) bool
        The robot found an end of its Delaunay path (o = Hull): it lies on the convex hull.
    path_length, added, detected : (n,) int64
        Entries of the robot's own answer, entries added by the consistency step, detected robots.
    consistency : bool
        Whether the consistency step was applied (the relation is then symmetric).
    graph : the compiled detection graph (measured distances, CSR).
    """

    def __init__(self, core: "_core.DistanceNeighbors", graph: "_core.DistanceGraph") -> None:
        self._core = core
        self.graph = graph
        self.consistency = bool(core.consistency)
        self.squared = bool(graph.squared)

    @cached_property
    def indptr(self) -> np.ndarray:
        return self._core.indptr

    @cached_property
    def indices(self) -> np.ndarray:
        return self._core.indices

    @cached_property
    def on_hull(self) -> np.ndarray:
        return self._core.on_hull

    @cached_property
    def path_length(self) -> np.ndarray:
        return self._core.path_length

    @cached_property
    def added(self) -> np.ndarray:
        return self._core.added

    @cached_property
    def detected(self) -> np.ndarray:
        return self._core.detected

    def path(self, i: int) -> np.ndarray:
        """Robot i's own answer in Delaunay-path order (without consistency additions)."""
        i = self._index(i)
        return self.indices[self.indptr[i]: self.indptr[i] + self.path_length[i]]

    def region(self, i: int) -> LocalRegion:
        """Robot i's Voronoi region in its local coordinates (see :class:`LocalRegion`)."""
        i = self._index(i)
        d = _core.local_region(self.graph, i, self.path(i).tolist(), bool(self.on_hull[i]))
        return LocalRegion(i, d["neighbors"], d["positions"], d["vertices"], bool(d["bounded"]),
                           tuple(d["ray_in"]), tuple(d["ray_out"]))

    def regions(self) -> Iterator[LocalRegion]:
        for i in range(len(self)):
            yield self.region(i)

    # ------------------------------------------------------------ the second round (Section IV-A)
    @cached_property
    def _frames(self) -> Frames:
        return Frames(len(self), self.indptr, self.indices, self.path_length, self.graph)

    def frame_transform(self, i: int, j: int) -> FrameTransform:
        """The second round seen by robot i: the rigid motion (rotation, translation, flip) taking
        Voronoi neighbour j's local frame (:meth:`region`) to i's, fitted over the robots both frames
        place (i, j and their common neighbours) from the coordinates j sent. Exact up to rounding
        with exact distances; a least-squares (orthogonal Procrustes, reflection allowed) fit with
        noisy ones, its RMS misfit in ``residual``. Raises ValueError when j is not in row i."""
        return self._frames.transform(self._index(i), self._index(j))

    def frame_transforms(self) -> FrameTransforms:
        """Every directed edge's transform at once, aligned with ``indices`` (see
        :class:`~dvoronoi.distances.FrameTransforms`)."""
        return self._frames.all_transforms()

    def two_hop(self, i: int) -> Tuple[np.ndarray, np.ndarray]:
        """What robot i knows after the second round: ``(robots, xy)``, every robot that i or one of
        its Voronoi neighbours places (its neighbours and its neighbours' neighbours), ascending, with
        coordinates in i's local frame (:meth:`region`): i's own for itself and its neighbours, the
        neighbours' coordinates mapped by :meth:`frame_transform` for the others (the mean where
        several neighbours place one robot; neighbours without a valid fit are left out)."""
        return self._frames.two_hop(self._index(i))

    @property
    def second_round(self) -> SecondRound:
        """Message counts of the second round (one message per directed Voronoi edge, payload the
        sender's path); see :class:`~dvoronoi.distances.SecondRound`."""
        return self._frames.second_round()

    def localize(self, anchor: int = 0, position: Tuple[float, float] = (0.0, 0.0), heading: float = 0.0,
                 flip: bool = False) -> np.ndarray:
        """Place the team in global coordinates from one robot's absolute pose (the paper's "if one
        robot knows its absolute position and orientation").

        The anchor is at `position`; `heading` (radians, counter-clockwise from the global +x axis)
        is the direction of its local +x axis, i.e. towards its first path neighbour
        ``path(anchor)[0]``; `flip` says its local frame is mirrored in the global one (its path turns
        clockwise there). Every other robot is placed by chaining second-round transforms outward
        from the anchor along fewest hops (breadth-first over the edges with a valid fit). Returns
        ``(n, 2)`` positions; robots not connected to the anchor through valid fits are NaN.
        """
        anchor = self._index(anchor)
        position, heading = check_pose(position, heading)
        return self._frames.localize(anchor, position, heading, bool(flip))

    def edges(self) -> np.ndarray:
        """The (symmetrised) neighbour graph as an ``(E, 2)`` int64 array of pairs ``i < j``, sorted."""
        n = len(self)
        rows = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.indptr))
        pairs = np.stack([np.minimum(rows, self.indices), np.maximum(rows, self.indices)], axis=1)
        return np.unique(pairs, axis=0) if len(pairs) else pairs.reshape(0, 2)

    def weighted_graph(self) -> "Any":
        """The computed graph G_v of the paper: the neighbour edges weighted with the measured
        distances, as a symmetric ``scipy.sparse.csr_matrix``."""
        import scipy.sparse as sp

        e = self.edges()
        g = self.graph
        meas = sp.csr_matrix((np.asarray(g.values), np.asarray(g.indices), np.asarray(g.indptr)), shape=(len(self), len(self)))
        w = np.asarray(meas[e[:, 0], e[:, 1]]).ravel()
        if self.squared:
            w = np.sqrt(w)
        n = len(self)
        m = sp.coo_matrix((np.concatenate([w, w]), (np.concatenate([e[:, 0], e[:, 1]]), np.concatenate([e[:, 1], e[:, 0]]))), shape=(n, n))
        return m.tocsr()

    def _json_text(self, indent: Optional[int]) -> str:
        return json.dumps({
            "kind": "distance_neighbors",
            "n": len(self),
            "consistency": self.consistency,
            "squared": self.squared,
            "indptr": self.indptr.tolist(),
            "indices": self.indices.tolist(),
            "on_hull": self.on_hull.tolist(),
            "path_length": self.path_length.tolist(),
            "added": self.added.tolist(),
            "detected": self.detected.tolist(),
        }, indent=indent)

    def plot(self, ax: Any = None, points: Optional[np.ndarray] = None, **kwargs: Any) -> Any:
        """Draw the neighbour graph (hull robots circled). Robots have no coordinates: pass the true
        `points` to draw them where they are; otherwise they are placed by classical MDS of the
        shortest-path distances in the detection graph (a picture, not a localisation)."""
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection

        if ax is None:
            _, ax = plt.subplots()
        pts = np.asarray(points, dtype=float) if points is not None else _mds_layout(self.graph)
        e = self.edges()
        ax.add_collection(LineCollection(pts[e], colors=kwargs.get("edgecolor", "0.5"), linewidths=kwargs.get("linewidth", 0.8)))
        ax.scatter(pts[:, 0], pts[:, 1], s=kwargs.get("point_size", 8), c="k", zorder=3)
        hull = pts[self.on_hull]
        ax.scatter(hull[:, 0], hull[:, 1], s=3 * kwargs.get("point_size", 8), facecolors="none",
                   edgecolors="tab:red", zorder=4, label="hull robots")
        ax.set_aspect("equal")
        ax.autoscale_view()
        return ax

    def __repr__(self) -> str:
        n = len(self)
        return (f"DistanceNeighbors(n={n}, hull_robots={int(np.sum(self.on_hull))}, consistency={self.consistency}, "
                f"added={int(np.sum(self.added))}, mean_neighbors={(len(self.indices) / n) if n else 0.0:.3g})")


def _mds_layout(graph: "_core.DistanceGraph") -> np.ndarray:
    """2-d classical MDS of graph shortest-path distances (components placed side by side)."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components, shortest_path

    n = len(graph)
    vals = np.asarray(graph.values)
    m = sp.csr_matrix((np.sqrt(vals) if graph.squared else vals, np.asarray(graph.indices), np.asarray(graph.indptr)), shape=(n, n))
    ncomp, labels = connected_components(m, directed=False)
    out = np.zeros((n, 2))
    x0 = 0.0
    for c in range(ncomp):
        idx = np.flatnonzero(labels == c)
        if len(idx) > 1:
            d = shortest_path(m[idx][:, idx], directed=False)
            j = np.eye(len(idx)) - 1.0 / len(idx)
            b = -0.5 * j @ (d ** 2) @ j
            w, v = np.linalg.eigh(b)
            xy = v[:, -2:] * np.sqrt(np.maximum(w[-2:], 0.0))
        else:
            xy = np.zeros((1, 2))
        xy -= xy.min(axis=0)
        out[idx] = xy + [x0, 0.0]
        x0 += float(np.ptp(xy[:, 0])) * 1.1 + 1.0
    return out


def neighbors_from_distances(distances: Any, consistency: bool = True, *, squared: bool = False,
                             symmetrize: bool = False, n: Optional[int] = None, workers: Optional[int] = None,
                             progress: ProgressArg = None, threads: Optional[int] = None) -> DistanceNeighbors:
    """Every robot's Voronoi neighbours (Delaunay-path order) and hull flag from measured
    inter-robot distances only, by VORONOI-NEIGHBORS (Elwin, Freeman & Lynch), then, if
    `consistency`, the consistency step that makes the relation symmetric.

    Parameters
    ----------
    distances
        * a dense ``(n, n)`` array: ``distances[i, j]`` the measured distance, ``inf`` where robots do
          not detect each other, 0 on the diagonal;
        * a ``scipy.sparse`` ``(n, n)`` matrix: stored entries are the measurements (absent = not
          detected);
        * an edge list: an ``(m, 3)`` array of rows ``i j d`` or a tuple ``(rows, cols, values)``;
          a pair may be listed once or in both directions. A ``(3, 3)`` array is read as a distance
          matrix when its diagonal is all 0 or inf (as every distance matrix's is), else as an edge
          list of three rows; the tuple form is never ambiguous.

        A pair given in both directions must have one value unless ``symmetrize=True``, which averages
        them, ``e_ij = (sigma_ij + sigma_ji) / 2`` as in the paper (and, for a dense matrix, drops
        pairs detected in one direction only).
    squared
        The values are squared distances. Decisions are exact signs of polynomials in the given
        values; with exact squared distances (e.g. integer coordinates) the answer is exact even for
        collinear and cocircular robots, with rounded distances it is exact except where rounding
        moves an exactly degenerate configuration (see the C++ header distance_predicates.hpp).
    n
        Number of robots for an edge list (default: largest index + 1). Indices are positions, not
        IDs: an edge list whose largest index is far above the number of robots it mentions (IDs
        such as serial numbers) is refused with the renumbering to apply (the CLI renumbers IDs
        itself).
    workers
        Threads: None or -1 = all cores, k >= 1 = k (``threads`` is a deprecated alias, 0 = all
        cores). ``progress``: as in :func:`dvoronoi.limited_cells`.

    With noise-free distances the answer equals the exact Voronoi neighbours and hull flags whenever
    every robot detects its Voronoi neighbours and robots opposite a shared Delaunay edge measure each
    other (a detection radius of twice the longest Delaunay edge is enough; per robot, twice the
    longest edge of its Delaunay star).

    Raises ValueError naming the entry for negative, zero, NaN, one-sided or contradictory values.
    """
    team = _args.workers(workers, threads)
    graph = as_distance_graph(distances, n=n, squared=squared, symmetrize=symmetrize)
    with progress_callback(np.empty((len(graph), 2)), progress, "voronoi neighbours") as callback:
        core = _core.neighbors_from_distances(graph, bool(consistency), team, callback)
    return DistanceNeighbors(core, graph)
