"""Occupancy grids and their medial diagram (docs/spec.md, "Grid diagram on occupancy grids").

>>> import dvoronoi as dv
>>> grid = dv.OccupancyGrid.load("map.yaml")              # ROS map_server, .pgm, .png or MovingAI .map
>>> gv = dv.grid_voronoi(grid, robot_radius=0.3)           # or a 2-d array (row 0 at the top)
>>> gv.diagram_mask, gv.clearance_map                      # H x W, in the image's row order
>>> route = gv.path((1.0, 2.0), (8.5, 3.0))               # (k, 2) map coordinates; empty if none
>>> gv.set_occupied([(40, 17), (40, 18)])                  # incremental: only what changed is redone
>>> gv.plot(path=route)

The diagram (``diagram="medial"``): for every free pixel the nearest point of the occupied set
(occupied pixels are closed squares; the outside of the map counts as occupied). A pair of 4-adjacent
free pixels whose nearest points are more than `min_separation` pixels apart puts the pixel nearer
their bisector on the diagram — unless the two nearest points are at most `prune_length` pixels apart
and joined by walls inside the box they span (grown by one pixel): that drops the spurs of pixel
staircases, bumps and room corners, and keeps every passage two or more pixels wide, including a
corridor between two parts of one wall. The result is exact (integer arithmetic), the same for every
worker count, and the same after any sequence of updates as a full build.
"""
from __future__ import annotations

import os
import threading
import warnings
from typing import TYPE_CHECKING, Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from . import _args, _core
from ._io import PathLike, atomic_write_text

if TYPE_CHECKING:  # pragma: no cover
    import matplotlib.axes

__all__ = ["OccupancyGrid", "OccupancyVoronoi", "MAP_EXTENSIONS"]

MAP_EXTENSIONS = (".yaml", ".yml", ".pgm", ".png", ".map")


def _positive(value: Any, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {type(value).__name__}") from None
    if not np.isfinite(v) or v <= 0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return v


def _origin(origin: Any) -> Tuple[float, float]:
    try:
        o = np.asarray(origin, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise TypeError(f"origin must be two numbers (x, y), got {origin!r}") from None
    if o.shape == (3,):  # map_server's [x, y, yaw]
        if o[2] != 0:
            raise ValueError(f"origin: a rotated map (yaw {o[2]}) is not supported")
        o = o[:2]
    if o.shape != (2,) or not np.all(np.isfinite(o)):
        raise ValueError(f"origin must be two finite numbers (x, y), got {origin!r}")
    return float(o[0]), float(o[1])


def _occupied(data: Any, occupied_thresh: float, unknown: str, name: str = "occupancy") -> np.ndarray:
    """Occupancy values as a bool array: bool as is; floats are probabilities in [0, 1] (occupied
    above `occupied_thresh`, NaN unknown); int8 is ROS's OccupancyGrid (-1 unknown, 0..100 percent);
    other integers must be 0/1. Errors name the argument `name`."""
    a = np.asarray(data)
    if a.ndim != 2:
        raise ValueError(f"{name} must be a 2-d array (rows x cols, row 0 at the top), got shape {a.shape}")
    if a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError(f"{name} must have at least one row and one column, got shape {a.shape}")
    unknown_occ = unknown == "occupied"
    if a.dtype == bool:
        return a
    if a.dtype.kind == "f":
        bad = ~np.isnan(a) & ((a < 0) | (a > 1))
        if bad.any():
            r, c = np.argwhere(bad)[0]
            raise ValueError(f"{name}[{r}, {c}] = {float(a[r, c])!r}: probabilities must lie in [0, 1] (NaN = unknown)")
        return np.where(np.isnan(a), unknown_occ, a > occupied_thresh)
    if a.dtype == np.int8:
        bad = (a < -1) | (a > 100)
        if bad.any():
            r, c = np.argwhere(bad)[0]
            raise ValueError(f"{name}[{r}, {c}] = {int(a[r, c])}: ROS occupancy values are -1 (unknown) or 0..100")
        return np.where(a < 0, unknown_occ, a > occupied_thresh * 100)
    if a.dtype.kind in "iu":
        if not np.isin(a, (0, 1)).all():
            r, c = np.argwhere(~np.isin(a, (0, 1)))[0]
            raise ValueError(f"{name}[{r}, {c}] = {int(a[r, c])}: integer maps must be 0/1 (or int8 ROS values "
                             "-1..100, or probabilities as floats)")
        return a.astype(bool)
    raise TypeError(f"{name} must be a bool, float, int8 or 0/1 integer array, got dtype {a.dtype}")


def _unknown_count(data: Any) -> int:
    """Unknown values in an occupancy array (_occupied's encodings: NaN, or -1 in int8)."""
    a = np.asarray(data)
    if a.dtype.kind == "f":
        return int(np.isnan(a).sum())
    return int((a < 0).sum()) if a.dtype == np.int8 else 0


class OccupancyGrid:
    """An occupancy grid: ``occupied`` (H x W bool, row 0 at the top, as in the image), ``resolution``
    (map units per pixel) and ``origin`` (map coordinates of the lower-left corner of pixel (H-1, 0),
    as ROS map_server writes it). Pixel ``(r, c)`` covers ``[c, c+1] x [H-1-r, H-r]`` in pixel units,
    scaled by the resolution and shifted by the origin.

    `data` is a bool array, probabilities in [0, 1] (occupied above `occupied_thresh`, NaN unknown),
    ROS int8 values (-1 unknown, 0..100) or 0/1 integers. Unknown pixels count as occupied unless
    ``unknown="free"``; ``unknown_pixels`` counts them (a diagram's ``grid`` counts those of the map it
    was built on or last given by ``update``). ``occupied_thresh`` and ``unknown`` keep the rule the
    grid was read with (a YAML's own threshold): a diagram's ``update`` reads new arrays by it.
    """

    occupied: np.ndarray
    resolution: float
    origin: Tuple[float, float]
    unknown_pixels: int
    occupied_thresh: float
    unknown: str

    def __init__(self, data: Any, resolution: float = 1.0, origin: Sequence[float] = (0.0, 0.0), *,
                 occupied_thresh: float = 0.65, unknown: str = "occupied") -> None:
        self._set(data, resolution, origin, occupied_thresh, unknown)
        self.occupied = np.array(self.occupied, dtype=bool, order="C")  # its own: the caller may edit theirs

    def _set(self, data: Any, resolution: float, origin: Sequence[float], occupied_thresh: float, unknown: str) -> None:
        """__init__ without the copy (for a build, which copies the occupancy into C++ and keeps none)."""
        if unknown not in ("occupied", "free"):
            raise ValueError(f'unknown must be "occupied" or "free", got {unknown!r}')
        t = float(occupied_thresh)
        if not 0.0 <= t <= 1.0:
            raise ValueError(f"occupied_thresh must lie in [0, 1], got {occupied_thresh!r}")
        self.occupied = np.ascontiguousarray(_occupied(data, t, unknown), dtype=bool)
        self.resolution = _positive(resolution, "resolution")
        self.origin = _origin(origin)
        self.unknown_pixels = _unknown_count(data)
        self.occupied_thresh, self.unknown = t, unknown

    @classmethod
    def load(cls, path: PathLike, *, unknown: str = "occupied", resolution: Optional[float] = None,
             origin: Optional[Sequence[float]] = None, occupied_thresh: float = 0.65, free_thresh: float = 0.196,
             negate: bool = False) -> "OccupancyGrid":
        """Read a ROS map_server YAML (with its PGM/PNG image: origin, resolution, negate and thresholds
        from the YAML), a PGM or PNG image (map_server's trinary rule; give `resolution`, default 1) or
        a MovingAI ``.map`` (``.`` and ``G`` free). Errors name the file (and line)."""
        if unknown not in ("occupied", "free"):
            raise ValueError(f'unknown must be "occupied" or "free", got {unknown!r}')
        path = os.fspath(path)
        if not isinstance(negate, (bool, np.bool_)):
            raise TypeError(f"negate must be True or False, got {type(negate).__name__}")
        if path.lower().endswith((".yaml", ".yml")):
            if resolution is not None or origin is not None:
                raise ValueError(f"{path}: a map_server YAML brings its own resolution and origin; do not pass "
                                 "resolution= or origin=")
            if occupied_thresh != 0.65 or free_thresh != 0.196 or negate:
                raise ValueError(f"{path}: a map_server YAML brings its own occupied_thresh, free_thresh and negate; "
                                 "do not pass them (edit the YAML)")
        elif path.lower().endswith(".map"):
            if occupied_thresh != 0.65 or free_thresh != 0.196 or negate or unknown != "occupied":
                raise ValueError(f"{path}: a MovingAI map has no grey levels and no unknown cells; do not pass "
                                 "occupied_thresh, free_thresh, negate or unknown")
        res = 1.0 if resolution is None else _positive(resolution, "resolution")
        ox, oy = (0.0, 0.0) if origin is None else _origin(origin)
        try:
            occ, res, org, n_unknown, _image, thresh = _core._load_occupancy_map(
                path, unknown == "occupied", res, ox, oy, float(occupied_thresh), float(free_thresh), bool(negate))
        except ValueError as e:
            raise ValueError(str(e)) from None
        g = cls.__new__(cls)
        g.occupied = occ
        g.resolution = float(res)
        g.origin = (float(org[0]), float(org[1]))
        g.unknown_pixels = int(n_unknown)
        g.occupied_thresh, g.unknown = float(thresh), unknown
        return g

    @classmethod
    def from_ros(cls, data: Any, width: int, height: int, resolution: float, origin: Sequence[float], *,
                 occupied_thresh: float = 0.65, unknown: str = "occupied") -> "OccupancyGrid":
        """From a ROS ``nav_msgs/OccupancyGrid`` message's fields (``msg.data``, ``msg.info.width``,
        ``msg.info.height``, ``msg.info.resolution``, ``(msg.info.origin.position.x, .y)``): its data
        starts at the origin cell, the map's bottom row, so the rows are flipped to put row 0 at the top."""
        a = np.asarray(data, dtype=np.int8)
        if a.size != int(width) * int(height):
            raise ValueError(f"data has {a.size} values for a {width} x {height} map")
        return cls(np.flipud(a.reshape(int(height), int(width))), resolution, origin,
                   occupied_thresh=occupied_thresh, unknown=unknown)

    @property
    def shape(self) -> Tuple[int, int]:
        return (int(self.occupied.shape[0]), int(self.occupied.shape[1]))

    def pixel_centers(self, pixels: Any) -> np.ndarray:
        """Map coordinates ``(k, 2)`` of the centres of pixels given as ``set_occupied`` takes them:
        (row, col) pairs, one pair, np.nonzero's tuple or an H x W bool mask (its pixels row-major)."""
        idx = _pixel_indices(pixels, self.shape, "pixels")
        if idx.ndim == 2:  # a mask's bytes
            idx = np.flatnonzero(idx)
        H, W = self.shape
        rows, cols = idx // W, idx % W
        return np.stack([self.origin[0] + (cols + 0.5) * self.resolution,
                         self.origin[1] + (H - 1 - rows + 0.5) * self.resolution], axis=1)

    def pixels_at(self, points: Any) -> np.ndarray:
        """The (row, col) pairs ``(k, 2)`` int64 of the pixels holding map points ``(k, 2)`` (or one
        point): pixel (r, c) holds ``[c, c+1) x (H-1-r, H-r]`` in pixel units (a point on a shared edge
        goes to the pixel right of it or below it; the map's far edges to the last pixel). ValueError
        naming the first point outside the map or not finite."""
        p = np.asarray(points, dtype=np.float64)
        if p.shape == (2,):
            p = p.reshape(1, 2)
        if p.ndim != 2 or p.shape[1] != 2:
            raise ValueError(f"points must be an (n, 2) array or one point (x, y), got shape {p.shape}")
        H, W = self.shape
        u = (p - np.asarray(self.origin)) / self.resolution  # pixel units, y up
        tol = 1e-9 * max(H, W)  # the map's own edges (extent) round to a hair outside
        bad = ~np.isfinite(u).all(axis=1) | (u[:, 0] < -tol) | (u[:, 0] > W + tol) | (u[:, 1] < -tol) | (u[:, 1] > H + tol)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise ValueError(f"points[{k}] = ({float(p[k, 0])!r}, {float(p[k, 1])!r}) is outside the {H} x {W} map")
        cols = np.clip(np.floor(u[:, 0]), 0, W - 1).astype(np.int64)
        rows = np.clip(np.floor(H - u[:, 1]), 0, H - 1).astype(np.int64)
        return np.stack([rows, cols], axis=1)

    @property
    def extent(self) -> Tuple[float, float, float, float]:
        """(xmin, xmax, ymin, ymax) in map coordinates (matplotlib's imshow extent)."""
        H, W = self.shape
        x0, y0 = self.origin
        return (x0, x0 + W * self.resolution, y0, y0 + H * self.resolution)

    def __repr__(self) -> str:
        H, W = self.shape
        return (f"OccupancyGrid({H} x {W} pixels, {int(self.occupied.sum())} occupied, resolution={self.resolution}, "
                f"origin={self.origin})")

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, OccupancyGrid) and self.resolution == other.resolution and self.origin == other.origin
                and np.array_equal(self.occupied, other.occupied))


def _as_bytes(occupied: np.ndarray) -> np.ndarray:
    """A bool array as contiguous bytes for the core, without a copy when it is contiguous already."""
    return np.ascontiguousarray(occupied, dtype=bool).view(np.uint8)


def as_occupancy_grid(source: Any, resolution: Optional[float], origin: Optional[Sequence[float]], unknown: str,
                      occupied_thresh: float, copy: bool = True) -> OccupancyGrid:
    """An OccupancyGrid from a grid, a map file path or an array (copied unless `copy` is False: for a
    build, which copies the occupancy into C++ and keeps none of it)."""
    if isinstance(source, OccupancyGrid):
        if resolution is not None or origin is not None:
            raise ValueError("resolution and origin come with the OccupancyGrid; do not pass them again")
        if unknown != "occupied" or occupied_thresh != 0.65:
            raise ValueError("unknown and occupied_thresh say how an array or image is read; an OccupancyGrid is "
                             "read already (pass them to OccupancyGrid(...))")
        return source
    if isinstance(source, (str, os.PathLike)):
        return OccupancyGrid.load(source, unknown=unknown, resolution=resolution, origin=origin,
                                  occupied_thresh=occupied_thresh)
    res, org = 1.0 if resolution is None else resolution, (0.0, 0.0) if origin is None else origin
    if copy:
        return OccupancyGrid(source, res, org, occupied_thresh=occupied_thresh, unknown=unknown)
    g = OccupancyGrid.__new__(OccupancyGrid)
    g._set(source, res, org, occupied_thresh, unknown)
    return g


def _pixel_indices(pixels: Any, shape: Tuple[int, int], name: str) -> np.ndarray:
    """Linear indices (int64) of (row, col) pairs — a (k, 2) array, a list of pairs, one pair, or the
    (rows, cols) tuple np.nonzero gives — checked against the map; an H x W bool mask is returned as
    its bytes (uint8 view), for the C++ side to scan. Anything else is refused: a (2, k) array or an
    integer mask would be read as other pixels."""
    H, W = shape
    if isinstance(pixels, tuple) and len(pixels) == 2 and all(isinstance(p, np.ndarray) for p in pixels):
        rows, cols = pixels  # numpy's index arrays (np.nonzero, np.where)
        if rows.ndim != 1 or rows.shape != cols.shape:
            raise ValueError(f"{name}: a (rows, cols) tuple needs two 1-d arrays of one length, got shapes "
                             f"{rows.shape} and {cols.shape}")
        a = np.stack([rows, cols], axis=1) if rows.size else np.empty((0, 2), dtype=np.int64)
    else:
        try:
            a = np.asarray(pixels)
        except ValueError as e:  # ragged: numpy's message alone would not name the argument
            raise ValueError(f"{name} must be (row, col) pairs of shape (k, 2) or an H x W bool mask: {e}") from None
    if a.dtype == bool:
        if a.shape != shape:
            raise ValueError(f"{name}: a mask must have the map's shape {shape}, got {a.shape}")
        return np.ascontiguousarray(a).view(np.uint8)
    if a.shape == shape and shape[1] == 2 and a.dtype.kind in "iu" and np.isin(a, (0, 1)).all():
        # on a 2-column map an integer mask also has the shape of pairs: refused, not guessed
        raise ValueError(f"{name}: an integer array of the map's shape {shape} with 0/1 values reads both as a "
                         "mask and as (row, col) pairs; pass mask.astype(bool) for a mask")
    if a.size == 0:
        return np.empty(0, dtype=np.int64)
    if a.ndim == 1 and a.shape[0] == 2:
        a = a.reshape(1, 2)  # one pair
    if a.ndim != 2 or a.shape[1] != 2:
        hint = " (an integer mask? pass mask.astype(bool))" if a.shape == shape else \
            (" (np.nonzero's rows and columns as one array? pass np.nonzero(mask) itself, or the bool mask)"
             if a.ndim == 2 and a.shape[0] == 2 else "")
        raise ValueError(f"{name} must be (row, col) pairs of shape (k, 2) or an H x W bool mask, got shape "
                         f"{a.shape}{hint}")
    if a.dtype.kind not in "iu" and not (a.dtype.kind == "f" and np.all(a == np.round(a))):
        raise TypeError(f"{name} must be (row, col) integer pairs or an H x W bool mask, got dtype {a.dtype}")
    # checked in the given type: a cast first would wrap huge integers and infinities into the map
    bad = ~((a[:, 0] >= 0) & (a[:, 0] < H) & (a[:, 1] >= 0) & (a[:, 1] < W))
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        show = [repr(v.item()) if a.dtype.kind == "f" else str(v) for v in a[k]]
        raise ValueError(f"{name}[{k}] = ({show[0]}, {show[1]}) is outside the {H} x {W} map")
    a = a.astype(np.int64)
    return a[:, 0] * W + a[:, 1]


class OccupancyVoronoi:
    """The medial diagram of an occupancy grid (see :func:`dvoronoi.grid_voronoi` and the module
    docstring). Arrays are in the image's row order (row 0 at the top):

    - ``diagram_mask`` (H x W bool), ``pixels`` (k x 2 ``(row, col)`` of diagram pixels, row-major),
      ``points`` (their centres, map coordinates), ``clearance`` (their distance to the nearest
      occupied point, map units) and ``blocked`` (clearance <= robot_radius);
    - ``clearance_map`` (H x W, map units; 0 on occupied pixels), ``nearest_points`` (H x W x 2);
    - ``path(start, goal)``, ``clearance_at(points)``, ``update(new_occupancy)``, ``set_occupied``,
      ``set_free``, ``to_json``, ``to_svg``, ``plot``.
    """

    def __init__(self, core: "_core._MedialDiagram", grid: OccupancyGrid, robot_radius: float,
                 options: Dict[str, Any]) -> None:
        self._core = core
        # One call at a time: the core releases the GIL while it works, so two threads (a map callback
        # and a planner) could otherwise update it together, or cache a result of the map before.
        self._lock = threading.RLock()
        self._unknown_pixels = grid.unknown_pixels  # the map itself lives in the core
        self._cache: Dict[str, np.ndarray] = {}
        self.robot_radius = robot_radius
        self.options = dict(options)
        self.stats: Dict[str, Any] = {}

    @property
    def robot_radius(self) -> float:
        """The robot radius (map units) of ``blocked``, ``blocked_mask``, ``path`` and the exports.
        Settable: the diagram does not depend on it, and what does is recomputed."""
        return self._robot_radius

    @robot_radius.setter
    def robot_radius(self, value: float) -> None:
        r = _args.real(value, "robot_radius")
        if not np.isfinite(r) or r < 0:
            raise ValueError(f"robot_radius must be a finite number >= 0, got {r}")
        with self._lock:
            self._robot_radius = r
            self._cache.pop("blocked", None)
            self._cache.pop("blocked_mask", None)

    # -- the map and the diagram ---------------------------------------------------------------
    @property
    def grid(self) -> OccupancyGrid:
        """The occupancy grid as it is now: a snapshot with a read-only ``occupied`` array (the
        diagram's own copy lives in C++). After an update, read ``grid`` again for the new map; a
        snapshot taken before keeps showing the map it was taken of."""
        with self._lock:
            return self._grid_snapshot()

    def _grid_snapshot(self) -> OccupancyGrid:
        if "grid" not in self._cache:
            occ = self._core.occupancy
            occ.flags.writeable = False
            snap = OccupancyGrid.__new__(OccupancyGrid)
            snap.occupied, snap.resolution, snap.origin = occ, self.resolution, self.origin
            snap.unknown_pixels = self._unknown_pixels
            snap.occupied_thresh = self.options.get("occupied_thresh", 0.65)
            snap.unknown = self.options.get("unknown", "occupied")
            self._cache["grid"] = snap  # type: ignore[assignment]
        return self._cache["grid"]  # type: ignore[return-value]

    @property
    def shape(self) -> Tuple[int, int]:
        return tuple(self._core.shape)  # type: ignore[return-value]

    @property
    def resolution(self) -> float:
        return float(self._core.resolution)

    @property
    def origin(self) -> Tuple[float, float]:
        return tuple(self._core.origin)  # type: ignore[return-value]

    def _cached(self, key: str, make: Any) -> np.ndarray:
        with self._lock:
            if key not in self._cache:
                self._cache[key] = make()
                self._cache[key].flags.writeable = False
            return self._cache[key]

    @property
    def diagram_mask(self) -> np.ndarray:
        """H x W bool: the diagram's pixels."""
        return self._cached("mask", lambda: self._core.mask)

    @property
    def pixels(self) -> np.ndarray:
        """(k, 2) int64 ``(row, col)`` of the diagram's pixels, row-major order."""
        return self._cached("pixels", lambda: np.argwhere(self.diagram_mask).astype(np.int64))

    @property
    def points(self) -> np.ndarray:
        """(k, 2) map coordinates of the diagram pixels' centres."""
        return self._cached("points", lambda: self.grid.pixel_centers(self.pixels))

    @property
    def clearance_map(self) -> np.ndarray:
        """H x W float64: each pixel centre's distance to the nearest occupied point (map units)."""
        return self._cached("clearance_map", lambda: self._core.clearance_map)

    @property
    def clearance(self) -> np.ndarray:
        """Clearance of each diagram pixel (map units), in the order of ``pixels``."""
        return self._cached("clearance", lambda: self.clearance_map[self.diagram_mask])

    @property
    def blocked(self) -> np.ndarray:
        """Diagram pixels whose clearance is not greater than the robot radius."""
        return self._cached("blocked", lambda: self.clearance <= self.robot_radius)

    @property
    def blocked_mask(self) -> np.ndarray:
        """H x W bool: blocked diagram pixels."""
        return self._cached("blocked_mask", lambda: self.diagram_mask & (self.clearance_map <= self.robot_radius))

    @property
    def nearest_points(self) -> np.ndarray:
        """H x W x 2: each pixel's nearest occupied point (map coordinates; an occupied pixel's own centre)."""
        return self._cached("nearest", lambda: self._core.nearest_points)

    def __len__(self) -> int:
        with self._lock:
            return int(self._core.count)

    # -- updates -------------------------------------------------------------------------------
    def _after_update(self, stats: Dict[str, Any]) -> Dict[str, Any]:
        self._cache.clear()
        self.stats = {**self.stats, "last_update": stats}
        return stats

    def update(self, new_occupancy: Any) -> Dict[str, Any]:
        """Replace the map's occupancy (same shape; any form :class:`OccupancyGrid` accepts, or an
        OccupancyGrid) and recompute only what the change can affect. Returns what was touched."""
        if isinstance(new_occupancy, (str, os.PathLike)):
            raise TypeError("new_occupancy: give an array or an OccupancyGrid (read a map file with "
                            "dv.OccupancyGrid.load(path) first), got a path")
        if isinstance(new_occupancy, OccupancyGrid):
            if new_occupancy.resolution != self.resolution or tuple(new_occupancy.origin) != tuple(self.origin):
                raise ValueError(f"new_occupancy has resolution {new_occupancy.resolution} and origin "
                                 f"{tuple(new_occupancy.origin)}, the map has {self.resolution} and {tuple(self.origin)}: "
                                 "an update changes occupancy only (build a new diagram for another frame)")
            occ, unknown = new_occupancy.occupied, new_occupancy.unknown_pixels
        else:  # read as the map was: the build's threshold and unknown rule
            occ = _occupied(new_occupancy, self.options.get("occupied_thresh", 0.65), self.options.get("unknown", "occupied"),
                            "new_occupancy")
            unknown = _unknown_count(new_occupancy)
        if occ.shape != self.shape:
            raise ValueError(f"new_occupancy must have the map's shape {self.shape}, got {occ.shape}")
        with self._lock:
            stats = self._after_update(self._core.update(_as_bytes(occ)))
            self._unknown_pixels = unknown
        return stats

    def _set(self, pixels: Any, occupied: bool) -> Dict[str, Any]:
        idx = _pixel_indices(pixels, self.shape, "pixels")
        with self._lock:
            if idx.ndim == 2:  # a mask's bytes
                return self._after_update(self._core.set_mask(idx, occupied))
            return self._after_update(self._core.set_pixels(idx, occupied))

    def set_occupied(self, pixels: Any) -> Dict[str, Any]:
        """Mark pixels occupied: ``(row, col)`` pairs or an H x W bool mask."""
        return self._set(pixels, True)

    def set_free(self, pixels: Any) -> Dict[str, Any]:
        """Mark pixels free: ``(row, col)`` pairs or an H x W bool mask."""
        return self._set(pixels, False)

    # -- planning ------------------------------------------------------------------------------
    def path(self, start: Sequence[float], goal: Sequence[float], *, robot_radius: Optional[float] = None,
             off_diagram_cost: float = 3.0) -> np.ndarray:
        """A collision-free path for a disk robot (map coordinates): ``(k, 2)`` from `start` to `goal`,
        along the diagram where it serves and across free pixels where a passage has none. Every
        segment keeps a distance greater than the robot radius from every occupied pixel; an empty
        ``(0, 2)`` array means start and goal are not connected for this radius (a path is always found
        when they are connected with one pixel to spare).

        Raises ValueError naming `start` or `goal` when it is outside the map or blocked.
        """
        r = self.robot_radius if robot_radius is None else _args.real(robot_radius, "robot_radius")
        cost = _args.real(off_diagram_cost, "off_diagram_cost")
        with self._lock:
            pts, length, expanded = self._core.path(start, goal, r, cost)
        self.stats = {**self.stats, "last_path": {"length": float(length) if len(pts) else float("inf"),
                                                  "expanded": int(expanded)}}
        return pts

    def path_length(self, start: Sequence[float], goal: Sequence[float], **kwargs: Any) -> float:
        """Length of :meth:`path` (inf when there is none)."""
        self.path(start, goal, **kwargs)
        return float(self.stats["last_path"]["length"])

    def clearance_at(self, points: Any) -> Any:
        """Distance (map units) from each point to the nearest occupied pixel or the map's edge (0 inside
        an occupied pixel or outside the map): for costmaps. ``(n, 2)`` points give ``(n,)``; one point
        ``(x, y)`` gives a float."""
        with self._lock:
            if np.ndim(points) == 1 and np.shape(points) == (2,):
                return float(self._core.clearance(np.reshape(points, (1, 2)))[0])
            return self._core.clearance(points)

    # -- export and pictures ---------------------------------------------------------------------
    def to_json(self, path: Optional[PathLike] = None, *, route: Optional[np.ndarray] = None,
                indent: Optional[int] = None) -> Optional[str]:
        """The JSON ``dvoronoi gvd MAP`` writes (optionally with a route); text or written atomically."""
        with self._lock:
            text = self._core.to_json(self.robot_radius, route, -1 if indent is None else indent)
        if path is None:
            return text
        atomic_write_text(path, text + "\n")
        return None

    def to_svg(self, path: Optional[PathLike] = None, route: Optional[np.ndarray] = None) -> Optional[str]:
        """The picture ``dvoronoi gvd MAP --svg`` draws (optionally with a route); text or written atomically."""
        with self._lock:
            text = self._core.to_svg(self.robot_radius, route)
        if path is None:
            return text
        atomic_write_text(path, text)
        return None

    def plot(self, ax: "Optional[matplotlib.axes.Axes]" = None, path: Optional[np.ndarray] = None,
             clearance: bool = False, figsize: Optional[Tuple[float, float]] = None) -> "matplotlib.axes.Axes":
        """Occupied pixels (dark grey), diagram pixels (blue; blocked ones light red), an optional path
        (green); with ``clearance=True`` the clearance map underneath. Returns the axes (a new figure of
        `figsize` when `ax` is None)."""
        import matplotlib.pyplot as plt
        from matplotlib.colors import ListedColormap

        from .plotting import category_image

        if ax is None:
            H, W = self.shape
            side = figsize or (7.0, max(2.0, 7.0 * H / W))
            _, ax = plt.subplots(figsize=side)
        extent = self.grid.extent
        if clearance:
            cm = np.where(self.grid.occupied, np.nan, self.clearance_map)
            ax.imshow(cm, extent=extent, cmap="Greens", interpolation="nearest", zorder=0)
        img = np.zeros(self.shape, dtype=np.int8)
        img[self.grid.occupied] = 1
        img[self.diagram_mask] = 2
        img[self.blocked_mask] = 3
        cmap = ListedColormap([(1, 1, 1, 0), (0.26, 0.26, 0.26, 1), (0.12, 0.47, 0.71, 1), (0.96, 0.65, 0.65, 1)])
        # crisp pixels at any size: no antialiasing (it would blur thin diagram lines), and a map larger
        # than the axes is reduced block by block, diagram over walls, so no line drops out. The view
        # is set first: the reduction follows it (and stays: later artists do not autoscale it).
        ax.set_aspect("equal")
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        category_image(ax, img, extent, cmap=cmap, vmin=0, vmax=3, zorder=1, gid="dvoronoi-gvd-medial")
        if path is not None and len(path):
            p = np.asarray(path)
            ax.plot(p[:, 0], p[:, 1], "-", color="#2e7d32", lw=2, zorder=3, gid="dvoronoi-gvd-path")
            ax.plot(p[[0, -1], 0], p[[0, -1], 1], "o", color="#2e7d32", ms=5, zorder=4)
        return ax

    # -- pickling: the map and the options; the diagram is rebuilt (exactly the same) -------------
    def __getstate__(self) -> Dict[str, Any]:
        return {"occupied": self.grid.occupied, "resolution": self.resolution, "origin": self.origin,
                "unknown_pixels": self.grid.unknown_pixels, "robot_radius": self.robot_radius, "options": self.options}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        grid = OccupancyGrid(state["occupied"], state["resolution"], state["origin"])
        grid.unknown_pixels = int(state.get("unknown_pixels", 0))
        o = state["options"]
        core = _core._medial_build(_as_bytes(grid.occupied), grid.resolution, grid.origin[0], grid.origin[1],
                                   o["min_separation"], o["prune_length"], o["workers"])
        self.__init__(core, grid, state["robot_radius"], o)  # type: ignore[misc]

    def __repr__(self) -> str:
        H, W = self.shape
        return (f"OccupancyVoronoi({len(self)} diagram pixels on a {H} x {W} map, resolution={self.resolution}, "
                f"robot_radius={self.robot_radius}, {int(self.blocked.sum())} blocked)")


def warn_empty_diagram(grid: OccupancyGrid, unknown: str, why: str, document: bool = False, stacklevel: int = 4) -> None:
    """The warning for a diagram without a pixel: a map (or an obstacle document drawn on pixels,
    `document`) that is all occupied, or `why` otherwise."""
    if grid.occupied.all():
        if document:
            why = (f"every pixel of the document drawn on {grid.shape[0]} x {grid.shape[1]} pixels meets an obstacle "
                   f"(no free space, or none a pixel wide: a larger cells= draws finer)")
        else:
            unknown_note = (f"; {grid.unknown_pixels} of them are unknown, which unknown='free' would make free"
                            if grid.unknown_pixels and unknown == "occupied" else "")
            why = (f"every pixel of the {grid.shape[0]} x {grid.shape[1]} map is occupied (check the map's negate "
                   f"and thresholds{unknown_note})")
    warnings.warn(f"no diagram pixel: {why}", UserWarning, stacklevel=stacklevel)


def medial_voronoi(grid: OccupancyGrid, robot_radius: float, workers: int, min_separation: float,
                   prune_length: float, occupied_thresh: float = 0.65, unknown: str = "occupied",
                   document: bool = False) -> OccupancyVoronoi:
    # The core copies the occupancy and the result keeps no reference to `grid`: updates never touch
    # the caller's grid, and the caller's later edits never reach the result.
    min_separation = _args.real(min_separation, "min_separation")
    prune_length = _args.real(prune_length, "prune_length")
    options: Dict[str, Any] = {"min_separation": min_separation, "prune_length": prune_length,
                               "workers": int(workers), "occupied_thresh": float(occupied_thresh), "unknown": unknown}
    try:
        core = _core._medial_build(_as_bytes(grid.occupied), grid.resolution, grid.origin[0], grid.origin[1],
                                   min_separation, prune_length, int(workers))
    except ValueError as e:
        raise ValueError(str(e)) from None
    if core.count == 0:
        warn_empty_diagram(grid, unknown, f"no two neighbouring free pixels have nearest walls more than "
                           f"min_separation={min_separation} pixels apart that are not joined by walls within "
                           f"prune_length={prune_length} pixels (the free space is under 2 pixels wide, or only "
                           f"small pockets); paths still search the free pixels", document=document)
    return OccupancyVoronoi(core, grid, robot_radius, options)
