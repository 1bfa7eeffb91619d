"""Exact (unlimited) Voronoi cells: :func:`voronoi_cell`, :func:`voronoi_cells` and
:class:`VoronoiPartition` (neighbours, hull flags, the Delaunay graph, cells clipped to ``bounds``).

Neighbour sets and hull flags are exact (they equal CGAL's exact answer in the tests). Hull agents'
cells are unbounded: they are reported as rays (``cell(i).edges``), and measured only when the caller
gives a convex region to clip to (``bounds=(xmin, ymin, xmax, ymax)`` or a ``(k, 2)`` convex
polygon); the library never invents a boundary.
"""
from __future__ import annotations

import json
import math
import warnings
from functools import cached_property
from typing import Any, Optional

import numpy as np

from . import _args, _core
from ._partition import ProgressArg, progress_callback
from ._io import PathLike, atomic_write_text
from ._result import GeoMixin, Result

class VoronoiPartition(GeoMixin, Result):
    """Exact Voronoi neighbours (cells sharing an edge of positive length) and hull flags of n agents.

    Attributes
    ----------
    points : (n, 2) float64
    inner : str
        ``"auto"`` (our certified fast path), or the inner step Adjust-Sensing-Radius runs on every
        agent: ``"scan"`` (Boundary Scan) or ``"evt"``.
    computed_by : dict
        How the cells were found: ``{"one_shot": ..., "deferred": ..., "asr": ...}`` (see
        :func:`voronoi_cells`); the values add up to n.
    indptr, indices : int64
        Voronoi neighbours in scipy's CSR layout (ascending per agent).
    on_hull : (n,) bool
        The agent's cell is unbounded (it lies on the convex hull).
    radius_steps : (n,) int32
        Limited cells ASR's radius schedule computes for the agent (doubling from its
        nearest-neighbour distance until the cell certifies itself, or every agent is in range):
        the same as ``voronoi_cell`` reports for that agent alone, however the cell was found here.
    agents_used : (n,) int64
        Agents strictly within twice the final radius (all others when the radius never certified
        the cell), likewise ASR's own number.
    areas : (n,) float64
        Area of each cell clipped to ``bounds``; without bounds, of each bounded cell (NaN for hull
        agents).
    centroids : (n, 2) float64
        Centroids, same rules (NaN where the area is NaN or 0).
    bounds : (k, 2) float64 or None
        The clipping region's vertices, counter-clockwise.
    """

    def __init__(self, core: "_core.VoronoiPartition", inner: str) -> None:
        self._core = core
        self.inner = inner

    @property
    def computed_by(self) -> dict:
        return self._core.computed_by

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

    @cached_property
    def areas(self) -> np.ndarray:
        return self._core.areas

    @cached_property
    def centroids(self) -> np.ndarray:
        return self._core.centroids

    @cached_property
    def bounds(self) -> Optional[np.ndarray]:
        return self._core.bounds

    def cell(self, i: int) -> "_core.VoronoiCell":
        """The exact cell of agent `i`: ``edges`` (counter-clockwise; rays for hull agents),
        ``vertices``, ``neighbors``, ``on_hull``, ``area``/``centroid`` and, with bounds, ``clipped``
        (the polygon cut to the region, with the neighbour of each side, -1 on the region's boundary)."""
        return self._core.cell(self._index(i))

    def cells(self):
        """Iterate over the cells in input order."""
        for i in range(len(self)):
            yield self.cell(i)

    def polygon(self, i: int) -> Optional[np.ndarray]:
        """Agent `i`'s cell as a ``(k, 2)`` counter-clockwise polygon: clipped to ``bounds`` when
        given (may be empty), else the bounded cell; None for a hull agent without bounds."""
        c = self.cell(i)
        if c.clipped is not None:
            return c.clipped.vertices
        return None if c.on_hull else c.vertices

    def to_geojson(self, path: Optional[PathLike] = None) -> Optional[str]:
        """The cells as a GeoJSON FeatureCollection, one Feature per agent in input order (what the
        CLI writes): a Polygon per clipped (or bounded) cell, closed and counter-clockwise; ``null``
        geometry for a hull agent's unbounded cell when no bounds were given (or a cell that misses
        the region). Properties: ``agent``, ``on_hull``, ``area`` and ``neighbors``."""
        feats = []
        for i in range(len(self)):
            poly = self.polygon(i)
            geom = None
            if poly is not None and len(poly) >= 3:
                ring = np.vstack([poly, poly[:1]]).tolist()
                geom = {"type": "Polygon", "coordinates": [ring]}
            area = float(self.areas[i])
            feats.append({"type": "Feature", "geometry": geom, "properties": {
                "agent": i, "on_hull": bool(self.on_hull[i]),
                "area": None if np.isnan(area) else area,
                "neighbors": self.neighbors(i).tolist()}})
        text = json.dumps({"type": "FeatureCollection", "features": feats})
        if path is None:
            return text
        atomic_write_text(path, text + "\n")
        return None

    def delaunay_edges(self) -> np.ndarray:
        """The Delaunay graph (positive-length Voronoi edges only) as an ``(E, 2)`` int64 array of
        pairs ``i < j``, sorted."""
        n = len(self)
        rows = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.indptr))
        keep = self.indices > rows
        return np.stack([rows[keep], self.indices[keep]], axis=1)

    def delaunay_matrix(self) -> "Any":
        """Deprecated alias of :meth:`to_csr` (the Delaunay graph as a symmetric ``n x n``
        ``scipy.sparse.csr_matrix`` of ones): every result names its CSR matrix ``to_csr()``."""
        warnings.warn("VoronoiPartition.delaunay_matrix() is deprecated; use to_csr()", DeprecationWarning,
                      stacklevel=2)
        return self.to_csr()

    def _geo_text(self, tolerance: Optional[float]) -> str:
        # Exact Voronoi cells are polygons (no arcs): `tolerance` is accepted for the shared
        # signature of to_shapely()/to_geopandas() and has no effect.
        if tolerance is not None and not (isinstance(tolerance, (int, float)) and tolerance > 0
                                          and math.isfinite(tolerance)):
            raise ValueError(f"tolerance must be a positive finite number or None, got {tolerance!r}")
        text = self.to_geojson()
        assert text is not None
        return text

    def _json_text(self, indent: Optional[int]) -> str:
        areas = [None if np.isnan(a) else float(a) for a in self.areas]
        cents = [None if np.isnan(c[0]) else [float(c[0]), float(c[1])] for c in self.centroids]
        return json.dumps({
            "kind": "voronoi_partition",
            "inner": self.inner,
            "bounds": None if self.bounds is None else self.bounds.tolist(),
            "points": self.points.tolist(),
            "indptr": self.indptr.tolist(),
            "indices": self.indices.tolist(),
            "on_hull": self.on_hull.tolist(),
            "radius_steps": self.radius_steps.tolist(),
            "agents_used": self.agents_used.tolist(),
            "areas": areas,
            "centroids": cents,
        }, indent=indent)

    def plot(self, ax: Any = None, *, cells: bool = True, delaunay: bool = False, **kwargs: Any) -> Any:
        """Draw the cells (clipped to ``bounds`` when given; else every cell, hull cells cut at the
        agents' box), the agents (hull agents circled) and, with ``delaunay=True``, the Delaunay
        graph. Returns the Axes (see :func:`dvoronoi.plotting.plot_voronoi`)."""
        from . import plotting

        return plotting.plot_voronoi(self, ax=ax, cells=cells, delaunay=delaunay, **kwargs)

    def __repr__(self) -> str:
        n = len(self)
        return (f"VoronoiPartition(n={n}, inner={self.inner!r}, hull_agents={int(np.sum(self.on_hull))}, "
                f"mean_neighbors={(len(self.indices) / n) if n else 0.0:.3g})")


BoundsArg = Any  # None | (xmin, ymin, xmax, ymax) | (k, 2) convex polygon


def voronoi_cell(center: Any, others: Any, inner: str = "auto", bounds: BoundsArg = None) -> "_core.VoronoiCell":
    """The exact Voronoi cell of the agent at `center` among `others` (rows of `others` name the
    neighbours), by Adjust-Sensing-Radius with Boundary Scan (``inner="scan"``; ``"auto"`` is the same
    for one agent) or our exact Delaunay tessellation (``inner="evt"``) as the inner step. ``on_hull`` says whether it is unbounded; its
    ``edges`` then run from one ray to the other. With ``bounds`` (a box ``(xmin, ymin, xmax, ymax)``
    or a ``(k, 2)`` convex polygon) the cell is also clipped: ``clipped``, ``area``, ``centroid``."""
    return _core.voronoi_cell(center, others, _args.text(inner, "inner"), bounds)


def voronoi_cells(points: Any, method: str = "asr", inner: str = "auto", bounds: BoundsArg = None,
                  workers: Optional[int] = None, progress: ProgressArg = None, *,
                  threads: Optional[int] = None) -> VoronoiPartition:
    """Every agent's exact Voronoi cell by Adjust-Sensing-Radius (``method="asr"``, see
    :func:`voronoi_cell`): neighbours, hull flags, the Delaunay graph, and areas/centroids of the
    cells clipped to ``bounds`` (a box, or a convex polygon whose ring may be closed: a last vertex
    equal to the first is dropped; of the bounded cells when no bounds are given). ``workers`` None
    or -1 uses every core, k >= 1 uses k (``threads`` is a deprecated alias, 0 = every core);
    ``progress`` as in :func:`limited_cells`.

    ``inner`` chooses what runs; all give the same neighbours and hull flags (``computed_by`` says
    which route found each cell):

    - ``"auto"`` (default): our fast path, not a published algorithm. One certified clipping per
      agent at 1.5 mean spacings certifies ~97% of a uniform swarm's cells; the rest are finished
      from a Delaunay triangulation of just those agents.
    - ``"scan"``: ASR+BS, Adjust-Sensing-Radius with Boundary Scan on every radius step of every agent
      (the Boundary Scan paper's route).
    - ``"evt"``: ASR+EVT, the same schedule with our exact Delaunay tessellation of the agents in range.

    Both ASR routes add, from a few radius steps on, a certificate by empty vertex circles and the
    global hull, so hull agents do not sweep every agent. Raises ValueError for bad shapes, NaN/inf, coinciding
    agents, bounds that are not a box or a convex polygon, or coordinates so far apart in scale that
    an exact test would over- or underflow (see :func:`limited_cells`)."""
    if method != "asr":
        raise ValueError(f'method must be "asr", got {method!r}')
    team = _args.workers(workers, threads)
    inner = _args.text(inner, "inner")
    with progress_callback(points, progress, "voronoi cells") as callback:
        core = _core.voronoi_cells(points, inner, team, callback, bounds)
    return VoronoiPartition(core, inner)
