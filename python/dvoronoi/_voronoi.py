"""Exact (unlimited) Voronoi cells: :func:`voronoi_cell`, :func:`voronoi_cells` and
:class:`VoronoiPartition` (neighbours, hull flags and the Delaunay graph).

Clipping to a bounding box or polygon (``bounds=``), cell areas and the CLI ``voronoi`` command are
not there yet; neighbour sets and hull flags are exact (they equal CGAL's exact answer in the tests).
"""
from __future__ import annotations

import json
from functools import cached_property
from typing import Any, Optional

import numpy as np

from . import _core
from ._partition import ProgressArg, progress_callback
from ._result import Result

class VoronoiPartition(Result):
    """Exact Voronoi neighbours (cells sharing an edge of positive length) and hull flags of n agents.

    Attributes
    ----------
    points : (n, 2) float64
    inner : str
        The inner step of Adjust-Sensing-Radius: ``"scan"`` (Boundary Scan) or ``"evt"``.
    indptr, indices : int64
        Voronoi neighbours in scipy's CSR layout (ascending per agent).
    on_hull : (n,) bool
        The agent's cell is unbounded (it lies on the convex hull).
    radius_steps : (n,) int32
        Limited cells the radius schedule computed per agent.
    agents_used : (n,) int64
        Agents within the final sensing radius per agent (all of them for hull agents).
    """

    def __init__(self, core: "_core.VoronoiPartition", inner: str) -> None:
        self._core = core
        self.inner = inner

    @cached_property
    def points(self) -> np.ndarray:
        return self._core.points

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
    def radius_steps(self) -> np.ndarray:
        return self._core.radius_steps

    @cached_property
    def agents_used(self) -> np.ndarray:
        return self._core.agents_used

    def delaunay_edges(self) -> np.ndarray:
        """The Delaunay graph (positive-length Voronoi edges only) as an ``(E, 2)`` int64 array of
        pairs ``i < j``, sorted."""
        n = len(self)
        rows = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.indptr))
        keep = self.indices > rows
        return np.stack([rows[keep], self.indices[keep]], axis=1)

    def delaunay_matrix(self) -> "Any":
        """The Delaunay graph as a symmetric ``n x n`` ``scipy.sparse.csr_matrix`` of ones."""
        return self.to_csr()

    def _json_text(self, indent: Optional[int]) -> str:
        return json.dumps({
            "kind": "voronoi_partition",
            "inner": self.inner,
            "points": self.points.tolist(),
            "indptr": self.indptr.tolist(),
            "indices": self.indices.tolist(),
            "on_hull": self.on_hull.tolist(),
            "radius_steps": self.radius_steps.tolist(),
            "agents_used": self.agents_used.tolist(),
        }, indent=indent)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw the agents (hull agents highlighted) and the Delaunay graph; returns the Axes."""
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection

        if ax is None:
            _, ax = plt.subplots()
        pts = self.points
        edges = self.delaunay_edges()
        ax.add_collection(LineCollection(pts[edges], colors=kwargs.get("edgecolor", "0.5"),
                                         linewidths=kwargs.get("linewidth", 0.8)))
        ax.scatter(pts[:, 0], pts[:, 1], s=kwargs.get("point_size", 8), c="k", zorder=3)
        hull = pts[self.on_hull]
        ax.scatter(hull[:, 0], hull[:, 1], s=3 * kwargs.get("point_size", 8), facecolors="none",
                   edgecolors="tab:red", zorder=4, label="hull agents")
        ax.set_aspect("equal")
        ax.autoscale_view()
        return ax

    def __repr__(self) -> str:
        n = len(self)
        return (f"VoronoiPartition(n={n}, inner={self.inner!r}, hull_agents={int(np.sum(self.on_hull))}, "
                f"mean_neighbors={(len(self.indices) / n) if n else 0.0:.3g})")


def voronoi_cell(center: Any, others: Any, inner: str = "scan") -> "_core.VoronoiCell":
    """The exact Voronoi cell of the agent at `center` among `others` (rows of `others` name the
    neighbours), by Adjust-Sensing-Radius with Boundary Scan (``inner="scan"``) or our exact Delaunay
    tessellation (``inner="evt"``) as the inner step. ``on_hull`` says whether it is unbounded; its
    ``edges`` then run from one ray to the other."""
    return _core.voronoi_cell(center, others, inner)


def voronoi_cells(points: Any, inner: str = "scan", threads: Optional[int] = None,
                  progress: ProgressArg = None) -> VoronoiPartition:
    """Every agent's exact Voronoi neighbours and hull flag by Adjust-Sensing-Radius (see
    :func:`voronoi_cell`); ``threads`` None or 0 uses every core; ``progress`` as in
    :func:`limited_cells`. Raises ValueError for bad shapes, NaN/inf or coinciding agents."""
    threads = 0 if threads is None else int(threads)
    with progress_callback(points, progress, "voronoi cells") as callback:
        core = _core.voronoi_cells(points, inner, threads, callback)
    return VoronoiPartition(core, inner)
