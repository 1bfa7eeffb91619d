"""Coverage control on occupancy grids: geodesic cells and a Lloyd that goes around walls
(docs/spec.md, "Geodesic cells on maps (coverage)"; docs/geodesic_coverage.md).

The geodesic distance between free points is the length of the shortest path through free space: not
through occupied pixels (closed squares) and not through a point where two occupied pixels touch only
diagonally. A free pixel belongs to the agent at the smallest geodesic distance from its centre (ties to
the lower index), within `radius` (geodesic) if one is given. Integrals over a cell are sums over its
pixel centres times the pixel area.

The distances come from an any-angle wavefront over pixels and wall corners
(cpp/include/dvoronoi/coverage/geodesic_distance.hpp) whose every path is checked to stay in free space:
no distance is shorter than the true one (up to rounding). Against an exact visibility-graph shortest
path (tests/python/geodesic_oracle.py) the largest relative error measured at pixels more than 3 pixels
from the sources is 1.6 % longer, 0.002 % on average (docs/geodesic_coverage.md gives the table and the
command).

>>> import dvoronoi as dv
>>> cells = dv.coverage.geodesic_cells(points, "map.yaml", radius=5.0)
>>> cells.labels, cells.areas, cells.centroids, cells.neighbors(0), cells.distances
>>> run = dv.coverage.lloyd(points, radius=5.0, steps=50, environment="map.yaml")
>>> run.cost                    # never increases
"""
from __future__ import annotations

import json
import os
from typing import Any, Callable, Dict, Optional, Sequence, Tuple, Union, cast

import numpy as np

from . import _args, _core
from ._io import PathLike
from ._result import Result
from .occupancy import OccupancyGrid, as_occupancy_grid

__all__ = ["geodesic_cells", "GeodesicCells", "GeodesicLloydStepper", "GeodesicLloydResult", "lloyd"]


# ----------------------------------------------------------------------------------------- inputs
def as_environment(environment: Any, resolution: Optional[float] = None, origin: Optional[Sequence[float]] = None,
                   unknown: str = "occupied", occupied_thresh: float = 0.65) -> OccupancyGrid:
    """The occupancy grid from what :func:`dvoronoi.grid_voronoi` takes: an :class:`OccupancyGrid`, a map
    file (ROS YAML, PGM, PNG, MovingAI ``.map``) or an H x W array (row 0 at the top)."""
    if environment is None:
        raise ValueError("environment must be an occupancy grid (array, dv.OccupancyGrid or map file), got None")
    return as_occupancy_grid(environment, resolution, origin, unknown, occupied_thresh)


def _team(workers: Any) -> int:
    t = _args.workers(workers, None, stacklevel=4)
    return t if t > 0 else (os.cpu_count() or 1)


def _radius(radius: Any) -> Union[None, float, np.ndarray]:
    """None (no range), a positive range, or one positive finite range per agent (an array)."""
    if radius is None:
        return None
    from ._partition import _radius_arg

    r = _radius_arg(radius)
    if np.ndim(r) == 0:
        return _args.positive(r, "radius")
    bad = np.flatnonzero(~(np.isfinite(r) & (r > 0)))
    if len(bad):
        raise ValueError(f"radius[{bad[0]}] must be a positive finite number, got {r[bad[0]]!r}")
    return np.ascontiguousarray(r)


def _split_radius(radius: Union[None, float, np.ndarray], n: int) -> Tuple[Optional[float], Optional[np.ndarray]]:
    """(radius, radii): the range (the largest of a team) and the per-agent ranges (None unless an
    array was given); checks the array's length."""
    if radius is None or np.ndim(radius) == 0:
        return cast(Optional[float], radius), None
    radii = cast(np.ndarray, radius)
    if len(radii) != n:
        raise ValueError(f"radius must have one range per agent: got {len(radii)} for {n} agents")
    return (float(radii.max()) if n else None), radii


def _points(points: Any) -> np.ndarray:
    try:
        p = np.array(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"points must be an (n, 2) array of real numbers, got {type(points).__name__}") from None
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"points must be an (n, 2) array, got shape {p.shape}")
    return np.ascontiguousarray(p)


def density_weights(density: Any, grid: OccupancyGrid) -> Optional[np.ndarray]:
    """φ at the pixel centres, H x W (None for uniform): an H x W array in the grid's row order, or a
    callable ``f(x, y)`` of map coordinates (vectorised, or called per pixel)."""
    if density is None:
        return None
    if callable(density):
        from .coverage import _evaluate

        H, W = grid.shape
        rr, cc = np.mgrid[0:H, 0:W]
        xy = grid.pixel_centers(np.column_stack([rr.ravel(), cc.ravel()]))
        free = ~grid.occupied.ravel()
        phi = np.zeros(H * W)
        phi[free] = _evaluate(density, xy[free, 0], xy[free, 1])
        return phi.reshape(H, W)
    d = np.asarray(density, dtype=np.float64)
    if d.shape != grid.shape:
        raise ValueError(f"density must be None, a callable f(x, y) or an array of the map's shape {grid.shape}, "
                         f"got shape {d.shape}")
    bad = ~(np.isfinite(d) & (d >= 0)) & ~grid.occupied
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise ValueError(f"density must be finite and >= 0 on free pixels; density[{r}, {c}] = {d[r, c]!r}")
    return np.ascontiguousarray(np.where(grid.occupied, 0.0, d))


def _occupied(grid: OccupancyGrid) -> np.ndarray:
    return np.ascontiguousarray(grid.occupied, dtype=bool).view(np.uint8)


# ----------------------------------------------------------------------------------------- cells
def _neighbours(labels: np.ndarray, n: int) -> Tuple[np.ndarray, np.ndarray]:
    """CSR of the cells that share a pixel edge."""
    pairs = []
    for a, b in ((labels[:, :-1], labels[:, 1:]), (labels[:-1, :], labels[1:, :])):
        m = (a != b) & (a >= 0) & (b >= 0)
        pairs.append(np.stack([a[m], b[m]], axis=1))
    p = np.concatenate(pairs) if pairs else np.empty((0, 2), np.int64)
    p = np.unique(np.concatenate([p, p[:, ::-1]]), axis=0) if len(p) else np.empty((0, 2), np.int64)
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.add.at(indptr, p[:, 0] + 1, 1)
    return np.cumsum(indptr), p[:, 1].astype(np.int64)


class GeodesicCells(Result):
    """Geodesic cells on an occupancy grid.

    Attributes
    ----------
    points : (n, 2) float64, map units.
    labels : (H, W) int64 in the grid's row order (row 0 at the top): the agent of each pixel, -1 for
        occupied pixels, pixels no agent reaches and pixels beyond the range.
    distances : (H, W) float64, the geodesic distance (map units) from each pixel centre to its agent;
        inf where ``labels`` is -1.
    areas, centroids : per agent, the cell's area and centroid (map units; uniform density: pixel
        centres times the pixel area; an empty cell has area 0 and its agent as centroid).
    masses, mass_centroids : the same under the density (equal to areas/centroids without one).
    cost : the coverage cost ``H = Σ_i ∫_{W_i} d_g(q, p_i)^2 φ(q) dq`` (with the range, reachable pixels
        that no agent covers count ``radius^2 φ``; a heterogeneous team's pixels of ``W_i`` count
        ``(d_g^2 + R̄^2 - R_i^2) φ``, docs/geodesic_coverage.md).
    indptr, indices : cells sharing a pixel edge, CSR; ``neighbors(i)``.
    grid : the :class:`~dvoronoi.OccupancyGrid`; radius : the range (the largest of a heterogeneous
        team) or None; radii : each agent's range (a heterogeneous team) or None.
    """

    # A float here; a Lloyd run's per-step array (GeodesicLloydResult), as for the convex LloydResult.
    cost: Any

    def __init__(self, points: np.ndarray, grid: OccupancyGrid, radius: Union[None, float, np.ndarray],
                 arrays: Dict[str, Any], geometric: Optional[Dict[str, Any]] = None) -> None:
        self.points = points
        self.grid = grid
        self.radius, self.radii = _split_radius(radius, len(points))
        self.labels = arrays["labels"]
        self.distances = arrays["distances"]
        self.cost = float(arrays["cost"])
        self.masses = arrays["mass"]
        self.mass_centroids = arrays["centroids"]
        geo = arrays if geometric is None else geometric
        self.areas = geo["pixels"].astype(np.float64) * grid.resolution ** 2
        self.centroids = geo["centroids"]
        self._csr = _neighbours(self.labels, len(points))
        for a in (self.labels, self.distances, self.areas, self.centroids, self.masses, self.mass_centroids):
            a.flags.writeable = False

    @property
    def indptr(self) -> np.ndarray:
        return self._csr[0]

    @property
    def indices(self) -> np.ndarray:
        return self._csr[1]

    def __len__(self) -> int:
        return len(self.points)

    def cell(self, i: int) -> dict:
        """Agent `i`'s cell: ``mask`` (H x W bool), ``area``, ``centroid``, ``neighbors``."""
        i = self._index(i)
        return {"center": tuple(map(float, self.points[i])), "mask": self.labels == i, "area": float(self.areas[i]),
                "centroid": tuple(map(float, self.centroids[i])), "neighbors": self.neighbors(i)}

    def _range(self) -> Union[None, float, np.ndarray]:
        """What `radius=` was: the per-agent ranges of a team, else the range or None."""
        return self.radius if self.radii is None else self.radii

    def _json_doc(self) -> dict:
        team = {} if self.radii is None else {"radii": self.radii.tolist()}
        return {"radius": self.radius, **team, "resolution": self.grid.resolution, "origin": list(self.grid.origin),
                "shape": list(self.grid.shape), "cost": self.cost,
                "cells": [{"agent": i, "center": self.points[i].tolist(), "area": float(self.areas[i]),
                           "centroid": self.centroids[i].tolist(), "neighbors": self.neighbors(i).tolist()}
                          for i in range(len(self))],
                "labels": self.labels.tolist()}

    def _json_text(self, indent: Optional[int]) -> str:
        return json.dumps(self._json_doc(), indent=indent)

    def plot(self, ax: Any = None, centroids: bool = True, figsize: Optional[Tuple[float, float]] = None, **kwargs: Any):
        """The cells (one colour per agent), walls dark grey, agents as black dots and, with
        ``centroids=True``, the centroids as crosses. Returns the axes."""
        import matplotlib.pyplot as plt
        from matplotlib.colors import ListedColormap

        if ax is None:
            H, W = self.grid.shape
            _, ax = plt.subplots(figsize=figsize or (7.0, max(2.0, 7.0 * H / W)))
        extent = self.grid.extent
        n = len(self)
        palette = plt.get_cmap("tab20")(np.arange(20) % 20)
        palette[:, :3] = 0.55 + 0.45 * palette[:, :3]  # pale, so agents and walls stand out
        img = np.where(self.labels >= 0, (self.labels * 7) % 20, np.nan)  # neighbours' colours apart
        ax.imshow(img, extent=extent, cmap=ListedColormap(palette), vmin=0, vmax=19, interpolation="nearest",
                  zorder=0, gid="dvoronoi-geodesic-cells")
        walls = np.where(self.grid.occupied, 1.0, np.nan)
        ax.imshow(walls, extent=extent, cmap=ListedColormap([(0.26, 0.26, 0.26, 1)]), vmin=0, vmax=1,
                  interpolation="nearest", zorder=1)
        if n:
            ax.scatter(self.points[:, 0], self.points[:, 1], s=kwargs.get("point_size", 12), c="k", zorder=3)
            if centroids:
                ax.scatter(self.centroids[:, 0], self.centroids[:, 1], s=14, marker="x", c="#b71c1c", lw=1, zorder=3)
        ax.set_aspect("equal")
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        return ax

    def __repr__(self) -> str:
        reached = int(np.count_nonzero(self.labels >= 0))
        return (f"GeodesicCells(n={len(self)}, {_range_text(self)}, {reached} pixels covered, "
                f"cost={self.cost:.6g})")


def _range_text(obj: Any) -> str:
    radii = getattr(obj, "radii", None)
    if radii is not None and len(radii):
        return f"radii={float(np.min(radii)):g}..{float(np.max(radii)):g}"
    return f"radius={obj.radius}"


def geodesic_cells(points: Any, environment: Any, radius: Union[None, float, Sequence[float], np.ndarray] = None, workers: Optional[int] = None, *,
                   density: Any = None, resolution: Optional[float] = None, origin: Optional[Sequence[float]] = None,
                   unknown: str = "occupied", occupied_thresh: float = 0.65) -> GeodesicCells:
    """Geodesic Voronoi cells of `points` on an occupancy grid.

    Parameters
    ----------
    points : (n, 2) array-like, map units; every agent in a free pixel of the map.
    environment : :class:`~dvoronoi.OccupancyGrid`, map file (ROS YAML, PGM, PNG, MovingAI ``.map``) or
        H x W array (row 0 at the top; bool, probabilities, ROS int8 or 0/1), as :func:`dvoronoi.grid_voronoi`.
    radius : float or (n,) array-like, optional
        The geodesic range (map units): pixels farther from every agent stay unassigned. One range per
        agent makes a heterogeneous team: pixel q goes to the agent with the smallest
        ``d_g(q, p_i)^2 - R_i^2`` among those within range (the geodesic power cells; all ranges equal
        gives the scalar call's cells), each agent's distances from its own range-limited wavefront.
    workers : int, optional
        None or -1 every core, k >= 1 k threads (for the cells' sums; the distances are one sequential
        wavefront). The result does not depend on it.
    density : None, H x W array or callable f(x, y), optional
        φ for ``masses``, ``mass_centroids`` and ``cost``.
    resolution, origin, unknown, occupied_thresh : how an array or image becomes an occupancy grid.

    Raises
    ------
    ValueError
        An agent outside the map or in an occupied pixel (named ``points[i]``), bad radius, workers,
        density or map.
    """
    grid = as_environment(environment, resolution, origin, unknown, occupied_thresh)
    pts = _points(points)
    r = _radius(radius)
    _split_radius(r, len(pts))
    team = _team(workers)
    weights = density_weights(density, grid)
    arrays = _core._geodesic_cells(_occupied(grid), grid.resolution, grid.origin[0], grid.origin[1], pts, r,
                                   weights, team)
    geometric = None
    if weights is not None:
        geometric = _core._geodesic_cells(_occupied(grid), grid.resolution, grid.origin[0], grid.origin[1], pts, r,
                                          None, team)
    return GeodesicCells(pts, grid, r, arrays, geometric)


# ----------------------------------------------------------------------------------------- Lloyd
class GeodesicLloydStepper:
    """Lloyd's algorithm on geodesic cells, one step at a time (``dv.coverage.LloydStepper(...,
    environment=grid)`` makes one).

    A step: each agent's target is its cell's centroid under φ when that lies in one of the cell's
    pixels, else the centre of the cell's pixel nearest to the centroid (the cell point that minimises
    ``Σ_{q in W_i} φ(q) |q - x|^2``); the agent follows its shortest path towards it (every segment checked
    to stay in free space). Backtracking on the cost: all agents go ``gain``, then ``gain/2``, ...
    (at most 12 halvings) of the way along their paths, and the first trial whose cost does not exceed
    the current one is taken (else nobody moves), so the cost never increases.
    """

    def __init__(self, points: Any, radius: Union[None, float, Sequence[float], np.ndarray], density: Any = None,
                 gain: float = 1.0, bounds: Any = None,
                 order: int = 8, workers: Optional[int] = None, *, threads: Optional[int] = None,
                 environment: Any = None) -> None:
        from .coverage import _check_gain

        if bounds is not None:
            raise ValueError("give the region as bounds= (a convex polygon) or environment= (an occupancy grid), not both")
        if threads is not None:
            workers = _args.workers(None, threads) or None
        self.grid = as_environment(environment)
        pts = _points(points)
        self._range = _radius(radius)
        self.radius, self.radii = _split_radius(self._range, len(pts))
        self.gain = _check_gain(gain)
        self.density = density
        self._weights = density_weights(density, self.grid)
        self._team = _team(workers)
        self._core = _core._GeodesicLloyd(_occupied(self.grid), self.grid.resolution, self.grid.origin[0],
                                          self.grid.origin[1], pts, self._range, self._weights, self.gain, self._team)

    @property
    def points(self) -> np.ndarray:
        """Current positions, (n, 2) map units (a copy)."""
        return self._core.points

    def __len__(self) -> int:
        return len(self._core.points)

    def cost(self) -> float:
        """The coverage cost H at the current positions."""
        return float(self._core.cost())

    def step(self) -> float:
        """One step (class docstring); returns H before it."""
        return float(self._core.step())

    @property
    def last_halvings(self) -> int:
        """Halvings of the step the last step needed; -1 when no trial lowered the cost (nobody moved)."""
        return int(self._core.last_halvings)

    def set_points(self, points: Any) -> None:
        """Put the agents somewhere else (same number; each in a free pixel)."""
        self._core.set_points(_points(points), _occupied(self.grid))

    def cells(self) -> GeodesicCells:
        """The geodesic cells at the current positions."""
        arrays = self._core.moments()
        arrays["labels"] = self._core.labels
        arrays["distances"] = self._core.distances
        geometric = None
        if self._weights is not None:
            geometric = _core._geodesic_cells(_occupied(self.grid), self.grid.resolution, self.grid.origin[0],
                                              self.grid.origin[1], self.points, self._range, None, self._team)
        return GeodesicCells(self.points, self.grid, self._range, arrays, geometric)

    def __repr__(self) -> str:
        H, W = self.grid.shape
        return f"GeodesicLloydStepper(n={len(self)}, {_range_text(self)}, gain={self.gain:g}, map {H} x {W})"


class GeodesicLloydResult(GeodesicCells):
    """A geodesic Lloyd run: ``trajectory`` (frames, n, 2), ``frame_steps``, ``cost`` (steps + 1, never
    increasing) and the final cells (every :class:`GeodesicCells` attribute)."""

    def __init__(self, cells: GeodesicCells, trajectory: np.ndarray, frame_steps: np.ndarray, cost: np.ndarray,
                 gain: float, density: Any) -> None:
        self.__dict__.update(cells.__dict__)
        self.trajectory = trajectory
        self.frame_steps = frame_steps
        self.cost = cost  # per step, as for the convex Lloyd (the final cells' cost is cost[-1])
        self.gain = gain
        self.density = density

    @property
    def steps(self) -> int:
        return len(self.cost) - 1

    def _json_doc(self) -> dict:
        doc = super()._json_doc()
        doc.update({"gain": self.gain, "steps": self.steps, "cost": self.cost.tolist(),
                    "frame_steps": self.frame_steps.tolist(), "trajectory": self.trajectory.tolist()})
        return doc

    def animate(self, path: Optional[PathLike] = None, fps: int = 10, dpi: int = 100,
                figsize: Optional[Tuple[float, float]] = None, progress: Any = None):
        """Animate the run: the cells and agents at every recorded frame (recomputed), the cost in the
        title. `path` ending in ``.gif`` (Pillow) or ``.mp4`` (ffmpeg), written as
        :func:`dvoronoi.plotting.save_animation` writes (only when complete, the mode of a new file;
        `progress` as for :func:`dvoronoi.plotting.animation_output`)."""
        import matplotlib.pyplot as plt
        from matplotlib import animation

        from . import plotting
        from .coverage import _check_count

        fps = _check_count(fps, "fps", 1)
        output = plotting.animation_output(path, fps, progress) if path is not None else None  # errors before drawing
        H, W = self.grid.shape
        fig, ax = plt.subplots(figsize=figsize or (6.0, max(2.0, 6.0 * H / W)), dpi=dpi)

        def draw(k: int):
            ax.clear()
            geodesic_cells(self.trajectory[k], self.grid, self._range(), workers=1).plot(ax=ax, centroids=False,
                                                                                      point_size=6)
            ax.set_axis_off()
            s = int(self.frame_steps[k])
            ax.set_title(f"step {s}   H = {self.cost[s]:.4g}")
            return ()

        anim = animation.FuncAnimation(fig, draw, frames=len(self.trajectory), blit=False)
        if output is not None:
            plotting.save_animation(anim, fig, path, len(self.trajectory), output, dpi=dpi, progress=progress)
        return anim

    def __repr__(self) -> str:
        return (f"GeodesicLloydResult(n={len(self)}, {_range_text(self)}, steps={self.steps}, "
                f"cost {self.cost[0]:.6g} -> {self.cost[-1]:.6g})")


def lloyd(points: Any, radius: Union[None, float, Sequence[float], np.ndarray], environment: Any, density: Any = None, steps: int = 100,
          gain: float = 1.0, record_every: int = 1, workers: Optional[int] = None,
          progress: Union[None, bool, Callable[[int, int], Any]] = None) -> GeodesicLloydResult:
    """Lloyd's algorithm on geodesic cells for `steps` steps (``dv.coverage.lloyd(...,
    environment=grid)``; see :class:`GeodesicLloydStepper` for the step)."""
    from .coverage import _check_count

    steps = _check_count(steps, "steps", 0)
    record_every = _check_count(record_every, "record_every", 1)
    stepper = GeodesicLloydStepper(points, radius, density=density, gain=gain, workers=workers,
                                   environment=environment)
    frame_steps = np.unique(np.concatenate([np.arange(0, steps + 1, record_every), [steps]])).astype(np.int64)
    frames = [stepper.points]
    cost = np.empty(steps + 1)
    bar = None
    callback = progress if callable(progress) and not isinstance(progress, bool) else None
    if progress is True:
        from tqdm.auto import tqdm

        bar = tqdm(total=steps, unit="steps", desc="lloyd")
        callback = lambda done, total: bar.update(done - bar.n)  # noqa: E731
    try:
        for t in range(steps):
            cost[t] = stepper.step()
            if (t + 1) % record_every == 0 or t + 1 == steps:
                frames.append(stepper.points)
            if callback:
                callback(t + 1, steps)
        cost[steps] = stepper.cost()
    finally:
        if bar is not None:
            bar.close()
    return GeodesicLloydResult(stepper.cells(), np.stack(frames), frame_steps, cost, stepper.gain, density)

