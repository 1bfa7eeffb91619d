"""The result surface every dvoronoi result shares (docs/spec.md, "One surface for every result").

A result that relates agents has ``neighbors(i)`` (int64, ascending unless the result defines an
order), the relation as CSR arrays ``indptr``/``indices`` (scipy's layout, input order), ``to_csr()``,
``to_json(path=None)`` and ``plot(ax=None, ...)``. A result with cells adds ``areas``, ``centroids``,
``cell(i)`` and ``to_geojson(path=None, tolerance=None)``, ``__geo_interface__``, ``to_shapely()``
and ``to_geopandas()`` (:class:`GeoMixin`).

Subclasses provide the arrays and ``_json_text(indent)``; cell results also provide the flat piece
arrays (``piece_ptr``, ``piece_neighbor``, ``piece_x``, ``piece_y``, ``piece_span``), ``points`` and
``radius`` from which plots are drawn, and ``_geojson_text(tolerance)``.
"""
from __future__ import annotations

import functools
import json
import operator
from typing import TYPE_CHECKING, Any, Dict, List, Optional

import numpy as np

from . import _core
from ._io import PathLike, atomic_write_text

if TYPE_CHECKING:  # pragma: no cover
    import geopandas
    import matplotlib.axes
    import scipy.sparse
    import shapely


class Result:
    """Base of every result that relates agents (neighbour relation as CSR arrays)."""

    if TYPE_CHECKING:  # what every result has; subclasses provide them as attributes or (cached) properties
        @property
        def indptr(self) -> np.ndarray: ...

        @property
        def indices(self) -> np.ndarray: ...

    def __len__(self) -> int:
        return int(len(self.indptr) - 1)

    def __getstate__(self) -> Dict[str, Any]:
        """Pickled state: the attributes without the cached views of the compiled result (which
        pickles itself), so a pickle holds each array once."""
        cls = type(self)
        return {k: v for k, v in self.__dict__.items()
                if not isinstance(getattr(cls, k, None), functools.cached_property)}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__dict__.update(state)

    def _index(self, i: Any) -> int:
        i = operator.index(i)
        n = len(self)
        if not 0 <= i < n:
            raise IndexError(f"agent index {i} out of range [0, {n})")
        return i

    def neighbors(self, i: int) -> np.ndarray:
        """Neighbours of agent `i` as an int64 array (ascending unless the result defines an order)."""
        i = self._index(i)
        return self.indices[self.indptr[i] : self.indptr[i + 1]]

    def to_csr(self) -> "scipy.sparse.csr_matrix":
        """The neighbour relation as an ``n x n`` ``scipy.sparse.csr_matrix`` of ones (needs scipy)."""
        try:
            import scipy.sparse
        except ImportError as e:  # pragma: no cover - scipy is a test dependency
            raise ImportError("to_csr() needs scipy: pip install scipy") from e
        n = len(self)
        data = np.ones(len(self.indices), dtype=np.float64)
        return scipy.sparse.csr_matrix(
            (data, np.array(self.indices), np.array(self.indptr)), shape=(n, n)
        )

    def _json_text(self, indent: Optional[int]) -> str:  # pragma: no cover - abstract
        raise NotImplementedError

    def to_json(self, path: Optional[PathLike] = None, *, indent: Optional[int] = None) -> Optional[str]:
        """The result as JSON, with the field names the ``dvoronoi`` CLI writes.

        Returns the text when `path` is None; otherwise writes it to `path` atomically and returns None.
        """
        text = self._json_text(indent)
        if path is None:
            return text
        atomic_write_text(path, text if text.endswith("\n") else text + "\n")
        return None

    def plot(self, ax: "Optional[matplotlib.axes.Axes]" = None, **kwargs: Any) -> "matplotlib.axes.Axes":
        """Draw the result with matplotlib and return the axes (see :mod:`dvoronoi.plotting`)."""
        from . import plotting

        return plotting.plot(self, ax=ax, **kwargs)


def _import_optional(module: str, caller: str) -> Any:
    """Import an optional dependency, or say which call needs it and how to install it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as e:
        package = module.split(".")[0]
        raise ImportError(f"{caller} needs {package}, which is not installed: pip install {package}") from e


class GeoMixin:
    """The cells as geometries for the GIS world: ``__geo_interface__`` (read by shapely, geopandas,
    fiona and others), ``to_shapely()`` and ``to_geopandas()``.

    All three are built from :meth:`to_geojson`'s FeatureCollection: one Feature per agent in input
    order, polygon rings closed and counter-clockwise, properties ``agent``, the exact ``area`` and the
    ``neighbors``. Arcs are replaced by inscribed chords no farther than `tolerance` from the arc
    (default ``radius / 1000``; ``__geo_interface__`` uses the default), so a polygon's area is below
    the exact ``areas[i]`` by at most ``tolerance`` times the cell's arc length.
    """

    def _geo_text(self, tolerance: Optional[float]) -> str:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def __geo_interface__(self) -> Dict[str, Any]:
        """The cells as a GeoJSON FeatureCollection mapping, arcs densified to the default tolerance."""
        doc: Dict[str, Any] = json.loads(self._geo_text(None))
        return doc

    def to_shapely(self, tolerance: Optional[float] = None) -> "List[Optional[shapely.Polygon]]":
        """One ``shapely.Polygon`` per agent in input order (None for a cell without a polygon, such as
        an unbounded Voronoi cell without ``bounds``), arcs densified to `tolerance` (see
        :class:`GeoMixin`). Needs shapely."""
        geometry = _import_optional("shapely.geometry", "to_shapely()")
        features = json.loads(self._geo_text(tolerance))["features"]
        return [None if f["geometry"] is None else geometry.shape(f["geometry"]) for f in features]

    def to_geopandas(self, tolerance: Optional[float] = None) -> "geopandas.GeoDataFrame":
        """The cells as a ``geopandas.GeoDataFrame``, one row per agent (index = agent), columns
        ``geometry``, ``area`` (exact), ``neighbors`` and any others the GeoJSON properties carry;
        arcs densified to `tolerance` (see :class:`GeoMixin`). No CRS is set. Needs geopandas."""
        gpd = _import_optional("geopandas", "to_geopandas()")
        frame = gpd.GeoDataFrame.from_features(json.loads(self._geo_text(tolerance))["features"])
        return frame.set_index("agent", drop=True) if "agent" in frame.columns else frame


class CellResult(GeoMixin, Result):
    """Base of every result with cells: ``areas``, ``centroids``, ``cell(i)``, GeoJSON export."""

    if TYPE_CHECKING:  # provided by subclasses as attributes or (cached) properties
        @property
        def areas(self) -> np.ndarray: ...

        @property
        def centroids(self) -> np.ndarray: ...

        @property
        def points(self) -> np.ndarray: ...

        @property
        def radius(self) -> float: ...

        @property
        def piece_ptr(self) -> np.ndarray: ...

        @property
        def piece_neighbor(self) -> np.ndarray: ...

        @property
        def piece_x(self) -> np.ndarray: ...

        @property
        def piece_y(self) -> np.ndarray: ...

        @property
        def piece_span(self) -> np.ndarray: ...

    def cell(self, i: int) -> Any:  # pragma: no cover - abstract
        raise NotImplementedError

    def cells(self):
        """Iterate over the cells in input order."""
        for i in range(len(self)):
            yield self.cell(i)

    def to_geojson(self, path: Optional[PathLike] = None, tolerance: Optional[float] = None) -> Optional[str]:
        """The cells as a GeoJSON FeatureCollection of polygons, one Feature per agent in input order
        (exactly what the CLI writes).

        GeoJSON has no arcs: each arc is replaced by inscribed chords no farther than `tolerance`
        from it (default ``radius / 1000``), so a polygon's area is below the exact ``areas[i]`` by
        at most ``tolerance`` times the cell's arc length. Each Feature's properties are ``agent``,
        the exact ``area`` and the ``neighbors``; rings are closed and counter-clockwise.

        Returns the text when `path` is None; otherwise writes it atomically and returns None.
        """
        text = self._geojson_text(tolerance)
        if path is None:
            return text
        atomic_write_text(path, text + "\n")
        return None

    def _geojson_text(self, tolerance: Optional[float]) -> str:  # pragma: no cover - abstract
        raise NotImplementedError

    def _geo_text(self, tolerance: Optional[float]) -> str:
        return self._geojson_text(tolerance)


def _limited_cell_feature(self: Any) -> Dict[str, Any]:
    """A limited cell as a GeoJSON Feature: its own export, arcs densified to ``radius / 1000``."""
    feature: Dict[str, Any] = json.loads(self.to_geojson())
    return feature


def _exact_cell_feature(self: Any) -> Dict[str, Any]:
    """An exact cell as a GeoJSON Feature: its polygon (clipped to ``bounds`` if given), no geometry
    for an unbounded cell."""
    shape = self.clipped if self.clipped is not None else (None if self.on_hull else self)
    ring = [] if shape is None else np.asarray(shape.vertices, dtype=float).tolist()
    geometry = {"type": "Polygon", "coordinates": [ring + ring[:1]]} if len(ring) >= 3 else None
    return {"type": "Feature", "geometry": geometry,
            "properties": {"area": float(self.area), "neighbors": np.asarray(self.neighbors).tolist()}}


def _cell_to_shapely(self: Any) -> "Optional[shapely.Polygon]":
    """The cell as a ``shapely.Polygon`` (None for an unbounded cell); needs shapely."""
    geometry = _import_optional("shapely.geometry", "to_shapely()")
    g = self.__geo_interface__["geometry"]
    return None if g is None else geometry.shape(g)


# The single cells are compiled classes: they get the GIS bridge here, as every result with cells has.
# (setattr: the stub declares both members on the compiled classes.)
for _cls, _feature in ((_core.LimitedCell, _limited_cell_feature), (_core.VoronoiCell, _exact_cell_feature)):
    setattr(_cls, "__geo_interface__", property(_feature, doc="The cell as a GeoJSON Feature mapping."))
    setattr(_cls, "to_shapely", _cell_to_shapely)
