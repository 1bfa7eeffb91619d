"""Coverage control on range-limited cells: Lloyd's algorithm with limited-range interactions.

Cortés, Martínez & Bullo, "Spatially-distributed coverage optimization and control with
limited-range interactions" (ESAIM COCV 11, 2005). Each agent moves towards the centroid of its
limited cell ``W_i = V_i ∩ B(p_i, R) ∩ Q`` under a density ``φ``::

    p_i <- p_i + gain * (C_i - p_i),    0 < gain <= 1.

The cost reported at every step is the limited-range locational cost (minimised)::

    H(P) = ∫_Q min(min_i |q - p_i|^2, R^2) φ(q) dq  =  R^2 Φ(Q) + Σ_i (J_i - R^2 M_i),

with ``M_i = ∫_{W_i} φ`` and ``J_i = ∫_{W_i} |q - p_i|^2 φ`` (it is ``-H`` of the paper with the
performance function ``f(x) = -min(x, R)^2``). Its gradient is ``2 M_i (p_i - C_i)``, and the step
above never increases it. Without ``bounds`` (Q = the plane) the constant ``R^2 Φ(Q)`` is left out
and the cost is ``Σ_i (J_i - R^2 M_i) <= 0``.

With ``bounds`` the cost is summed as ``Σ_i J_i + R^2 Φ(U)``, ``U`` the part of Q that no disk
``B(p_i, R)`` covers, never as the difference of ``R^2 Φ(Q)`` and ``Σ R^2 M_i`` (they agree to
~1e-16 of ``R^2 Φ(Q)``: more than H itself once R is ~1e5 times the cells' size). ``U`` is empty,
and ``H = Σ J_i`` exactly, when no cell reaches its circle inside Q (always once R exceeds Q's
diameter); else ``Φ(U) = Φ(Q) - Σ M_i``, whose rounding is small against H because some point of Q
is then R away from every agent.

Heterogeneous teams: ``radius`` may give one sensing radius ``R_i`` per agent (Pimenta, Kumar,
Mesquita & Pereira, "Sensing and coverage for a network of heterogeneous robots", CDC 2008). The
cells are then the power cells (weights ``R_i^2``) clipped to the disks and to Q, as
:func:`dvoronoi.limited_cells` with radii, and the cost is Pimenta et al.'s power cost limited to
the disks, with ``R̄ = max R_i``::

    H(P) = ∫_Q min(min_i (|q - p_i|^2 - R_i^2), 0) φ(q) dq + R̄^2 Φ(Q)
         = Σ_i (J_i + (R̄^2 - R_i^2) M_i) + R̄^2 Φ(U)      (the plane: Σ_i (J_i - R_i^2 M_i)),

equal to the cost above when all radii are equal (so are the cells and the runs, bit for bit). Its
gradient is again ``2 M_i (p_i - C_i)`` and the same step never increases it (docs/heterogeneous.md);
an agent's cell need not contain the agent, and an empty cell (zero mass) leaves its agent in place.

Uniform density (``density=None``) is exact: areas, centroids and polar moments in closed form
(circular sectors included). Any other density is integrated by Gauss quadrature over the cell's
exact pieces (a fan of triangles from the agent and circular sectors of at most π/4), ``order``
points per direction: exact for polynomial densities of degree ``<= 2*order - 2`` in the radius and on
triangles, spectrally accurate in the angle. Measured against an independent integration
(tests/python/test_coverage.py), a Gaussian density of width ``sigma = R/2`` has relative errors in
mass and centroid of 4e-8 at ``order=6``, below 1e-9 at the default ``order=8`` and below 1e-12 at
``order=10``; narrower features need a higher order (the error falls geometrically with it).

>>> import dvoronoi as dv
>>> run = dv.coverage.lloyd(points, radius=0.1, steps=200, bounds=(0, 0, 1, 1))
>>> run.cost[-1] <= run.cost[0], run.trajectory.shape      # (frames, n, 2)
>>> run.plot(); run.animate("lloyd.gif")
"""
from __future__ import annotations

import json
import math
import numbers
from typing import Any, Callable, cast, Optional, overload, Sequence, Tuple, Union

import numpy as np

from . import _args, _core
from ._optional import tqdm_class
from ._io import PathLike
from ._partition import _radius_arg
from ._result import CellResult

__all__ = ["lloyd", "step", "LloydStepper", "LloydResult", "CoverageCells", "GridDensity",
           "as_bounds", "animate"]

#: From this many agent-steps on, ``lloyd(progress=None)`` shows a tqdm progress bar.
PROGRESS_BAR_FROM = 2_000_000

BoundsArg = Union[None, Sequence[float], np.ndarray, Any]


# ----------------------------------------------------------------------------------------- inputs
def as_bounds(bounds: BoundsArg) -> Optional[np.ndarray]:
    """The environment as a ``(k, 2)`` array of convex-polygon vertices, or None for the plane.

    Accepts a box ``(xmin, ymin, xmax, ymax)``, a ``(k, 2)`` array-like of vertices (either
    orientation), or an object with ``exterior.coords`` (a shapely Polygon). The polygon is checked
    (convex, finite, at least 3 vertices) by the compiled core when it is used.
    """
    if bounds is None:
        return None
    if hasattr(bounds, "exterior"):
        v = np.asarray(bounds.exterior.coords, dtype=float)
        return v[:-1] if len(v) > 1 and np.array_equal(v[0], v[-1]) else v
    arr = np.asarray(bounds, dtype=float)
    if arr.ndim == 1:
        if arr.shape != (4,):
            raise ValueError("bounds must be a box (xmin, ymin, xmax, ymax) or a (k, 2) array of "
                             f"polygon vertices, got shape {arr.shape}")
        x0, y0, x1, y1 = arr
        if not (np.all(np.isfinite(arr)) and x0 < x1 and y0 < y1):
            raise ValueError(f"bounds must be a box (xmin, ymin, xmax, ymax) with xmin < xmax and "
                             f"ymin < ymax, all finite; got {tuple(arr)}")
        return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"bounds must be a box (xmin, ymin, xmax, ymax) or a (k, 2) array of "
                         f"polygon vertices, got shape {arr.shape}")
    if len(arr) > 1 and np.array_equal(arr[0], arr[-1]):
        arr = arr[:-1]  # a closed ring
    return arr


class GridDensity:
    """A density sampled on a regular grid, bilinearly interpolated.

    ``values[j, i]`` is the density at ``(x_i, y_j)``, ``x_i = linspace(xlim[0], xlim[1], nx)``,
    ``y_j = linspace(ylim[0], ylim[1], ny)`` (image layout: rows are y). Outside the grid the density
    is ``outside`` (default 0). Values must be finite and >= 0.
    """

    def __init__(self, values: Any, xlim: Tuple[float, float], ylim: Tuple[float, float],
                 outside: float = 0.0) -> None:
        v = np.asarray(values, dtype=float)
        if v.ndim != 2 or v.shape[0] < 2 or v.shape[1] < 2:
            raise ValueError(f"values must be a 2-d array of at least 2 x 2 samples, got shape {v.shape}")
        if not np.all(np.isfinite(v)) or np.any(v < 0):
            raise ValueError("values must be finite and >= 0")
        x0, x1 = map(float, xlim)
        y0, y1 = map(float, ylim)
        if not (x0 < x1 and y0 < y1 and all(map(math.isfinite, (x0, x1, y0, y1)))):
            raise ValueError(f"xlim and ylim must be increasing finite pairs, got {xlim}, {ylim}")
        if not (math.isfinite(outside) and outside >= 0):
            raise ValueError(f"outside must be finite and >= 0, got {outside}")
        self.values, self.xlim, self.ylim, self.outside = v, (x0, x1), (y0, y1), float(outside)

    def __call__(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        ny, nx = self.values.shape
        fx = (x - self.xlim[0]) / (self.xlim[1] - self.xlim[0]) * (nx - 1)
        fy = (y - self.ylim[0]) / (self.ylim[1] - self.ylim[0]) * (ny - 1)
        inside = (fx >= 0) & (fx <= nx - 1) & (fy >= 0) & (fy <= ny - 1)
        i = np.clip(np.floor(fx).astype(np.int64), 0, nx - 2)
        j = np.clip(np.floor(fy).astype(np.int64), 0, ny - 2)
        tx = np.clip(fx - i, 0.0, 1.0)
        ty = np.clip(fy - j, 0.0, 1.0)
        v = self.values
        out = ((1 - tx) * (1 - ty) * v[j, i] + tx * (1 - ty) * v[j, i + 1]
               + (1 - tx) * ty * v[j + 1, i] + tx * ty * v[j + 1, i + 1])
        return np.where(inside, out, self.outside)

    def __repr__(self) -> str:
        return f"GridDensity(shape={self.values.shape}, xlim={self.xlim}, ylim={self.ylim})"


def _evaluate(density: Callable, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """φ at the nodes: one vectorised call, or one call per node for scalar-only functions."""
    phi: Optional[np.ndarray]
    try:
        phi = np.asarray(density(x, y), dtype=float)
        if phi.shape != x.shape:
            phi = np.broadcast_to(phi, x.shape) if phi.ndim == 0 else None
    except (TypeError, ValueError):
        phi = None
    if phi is None:  # a scalar function (math.exp, if/else on floats): call it per node
        phi = np.fromiter((float(density(float(a), float(b))) for a, b in zip(x, y)), dtype=float,
                          count=len(x))
    if len(phi) and not (np.all(np.isfinite(phi)) and phi.min() >= 0):
        k = int(np.flatnonzero(~(np.isfinite(phi) & (phi >= 0)))[0])
        raise ValueError(f"density must be finite and >= 0; density({x[k]!r}, {y[k]!r}) = {phi[k]!r}")
    return np.array(phi, dtype=float)


def _check_density(density: Any) -> Optional[Callable]:
    if density is None:
        return None
    if not callable(density):
        raise TypeError("density must be None (uniform), a callable f(x, y) or a GridDensity, got "
                        f"{type(density).__name__}")
    return density


def _check_gain(gain: Any) -> float:
    if isinstance(gain, bool) or not isinstance(gain, numbers.Real):
        raise TypeError(f"gain must be a number in (0, 1], got {gain!r}")
    g = float(gain)
    if not (0.0 < g <= 1.0):
        raise ValueError(f"gain must be in (0, 1], got {gain!r}")
    return g


def _check_count(value: Any, name: str, minimum: int) -> int:
    return _args.integer(value, name, minimum, _args.MAX_COUNT)


# ----------------------------------------------------------------------------------------- cells
def density_moments(points: np.ndarray, quadrature: Tuple[np.ndarray, ...], density: Callable
                    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(mass, centroid, polar) of every cell from its quadrature nodes ``(x, y, w, ptr, ...)``."""
    x, y, w, ptr = quadrature[:4]
    n = len(ptr) - 1
    owner = np.repeat(np.arange(n), np.diff(ptr))
    wf = w * _evaluate(density, x, y)
    dx = x - points[owner, 0]
    dy = y - points[owner, 1]
    mass = np.bincount(owner, wf, minlength=n)
    fx = np.bincount(owner, wf * dx, minlength=n)
    fy = np.bincount(owner, wf * dy, minlength=n)
    polar = np.bincount(owner, wf * (dx * dx + dy * dy), minlength=n)
    safe = np.where(mass > 0, mass, 1.0)
    centroid = points + np.where(mass[:, None] > 0, np.column_stack([fx, fy]) / safe[:, None], 0.0)
    return mass, centroid, polar


def _cost(mass: np.ndarray, polar: np.ndarray, open_cells: np.ndarray, radius: float,
          total: Optional[float], radii: Optional[np.ndarray] = None) -> float:
    """H from per-cell moments (module docstring), summed without cancellation. ``open_cells``: which
    cells reach their circle; ``total``: Φ(Q), or None for the plane; ``radius``: R̄, and ``radii``
    each agent's R_i (None: all equal to R̄)."""
    r2 = radius * radius
    ri2 = r2 if radii is None else radii * radii
    if total is None:
        return float(np.sum(polar - ri2 * mass))
    # No agent: nothing is covered. Else U is empty exactly when no cell reaches its circle.
    uncovered = max(total - math.fsum(mass), 0.0) if len(mass) == 0 or np.any(open_cells) else 0.0
    covered = polar if radii is None else polar + (r2 - ri2) * mass
    return math.fsum(covered) + r2 * uncovered


class CoverageCells(CellResult):
    """Limited cells clipped to the environment, ``W_i = V_i ∩ B(p_i, R) ∩ Q`` (a heterogeneous team:
    the power cell ∩ ``B(p_i, R_i)`` ∩ Q, which may be empty or miss its agent).

    Pieces are edges (``piece_neighbor >= 0``), arcs (``-1``, ``piece_span > 0``) and walls on the
    environment's boundary (``-2``, span 0). ``areas``/``centroids`` are geometric (uniform density);
    ``masses``/``mass_centroids`` are under the run's density (equal to them for uniform density).
    ``radius`` is the radius (the largest of a heterogeneous team), ``radii`` each agent's.
    """

    radius: float  # an attribute here (the base declares a read-only property)
    radii: np.ndarray

    def __init__(self, arrays: dict, bounds: Optional[np.ndarray], masses: Optional[np.ndarray] = None,
                 mass_centroids: Optional[np.ndarray] = None) -> None:
        for key, value in arrays.items():
            setattr(self, key, value)
        self.radius = float(arrays["radius"])
        radii = arrays.get("radii")
        self.radii = np.full(len(self.points), self.radius) if radii is None else np.asarray(radii, dtype=np.float64)
        self.bounds = bounds
        self.masses = self.areas if masses is None else masses
        self.mass_centroids = self.centroids if mass_centroids is None else mass_centroids

    def __len__(self) -> int:
        return len(self.points)

    def cell(self, i: int) -> dict:
        """Agent `i`'s cell: ``pieces`` (kind "edge"/"arc"/"wall", start, end, neighbor, span),
        ``vertices`` (counter-clockwise), ``neighbors``, ``area``, ``centroid``."""
        i = self._index(i)
        lo, hi = int(self.piece_ptr[i]), int(self.piece_ptr[i + 1])
        pieces = []
        for k in range(lo, hi):
            nxt = k + 1 if k + 1 < hi else lo
            nb = int(self.piece_neighbor[k])
            kind = "edge" if nb >= 0 else ("arc" if nb == -1 else "wall")
            pieces.append({"kind": kind, "neighbor": nb if nb >= 0 else None,
                           "start": (float(self.piece_x[k]), float(self.piece_y[k])),
                           "end": (float(self.piece_x[nxt]), float(self.piece_y[nxt])),
                           "span": float(self.piece_span[k])})
        full = hi - lo == 1 and self.piece_neighbor[lo] == -1
        verts = np.column_stack([self.piece_x[lo:hi], self.piece_y[lo:hi]]) if not full else np.empty((0, 2))
        return {"center": tuple(map(float, self.points[i])), "radius": float(self.radii[i]), "pieces": pieces,
                "vertices": verts, "neighbors": self.neighbors(i), "area": float(self.areas[i]),
                "centroid": tuple(map(float, self.centroids[i]))}

    def _heterogeneous(self) -> bool:
        return bool(np.any(self.radii != self.radius))

    def _json_doc(self) -> dict:
        doc = {"kind": "coverage_cells", "radius": self.radius}  # "kind": what dv.load reads back
        if self._heterogeneous():
            doc["radii"] = self.radii.tolist()
        return {**doc, "bounds": None if self.bounds is None else self.bounds.tolist(),
                "points": self.points.tolist(),  # the agents, as the CLI's lloyd JSON has them
                "cells": [{"agent": i, **{k: v for k, v in self.cell(i).items() if k != "vertices"},
                           "neighbors": self.neighbors(i).tolist()} for i in range(len(self))]}

    def _json_text(self, indent: Optional[int]) -> str:
        return json.dumps(self._json_doc(), indent=indent)

    def _geojson_text(self, tolerance: Optional[float]) -> str:
        tol = self.radius / 1000 if tolerance is None else float(tolerance)
        if not (tol > 0 and math.isfinite(tol)):
            raise ValueError(f"tolerance must be a positive finite number, got {tolerance!r}")
        features = []
        for i in range(len(self)):
            ring = []
            lo, hi = int(self.piece_ptr[i]), int(self.piece_ptr[i + 1])
            cx, cy = self.points[i]
            r = float(self.radii[i])
            # Chords of angle d stay within r (1 - cos(d/2)) of the arc.
            dmax = 2 * math.acos(max(-1.0, 1 - tol / r))
            for k in range(lo, hi):
                ring.append([float(self.piece_x[k]), float(self.piece_y[k])])
                if self.piece_neighbor[k] == -1:
                    a0 = math.atan2(self.piece_y[k] - cy, self.piece_x[k] - cx)
                    m = max(1, math.ceil(self.piece_span[k] / dmax))
                    for j in range(1, m):
                        a = a0 + self.piece_span[k] * j / m
                        ring.append([float(cx + r * math.cos(a)), float(cy + r * math.sin(a))])
            if ring:
                ring.append(ring[0])
            features.append({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [ring]},
                             "properties": {"agent": i, "area": float(self.areas[i]),
                                            "neighbors": self.neighbors(i).tolist()}})
        return json.dumps({"type": "FeatureCollection", "features": features})

    def plot(self, ax: Any = None, **kwargs: Any):
        """The cells and the environment's outline; a Lloyd run adds its density and trajectories
        (see :func:`dvoronoi.plotting.plot_coverage`)."""
        from . import plotting

        return plotting.plot_coverage(self, ax=ax, **kwargs)

    def __repr__(self) -> str:
        return f"CoverageCells(n={len(self)}, {_radius_text(self)}, total_area={float(np.sum(self.areas)):.6g})"


def _radius_text(result: Any) -> str:
    """``radius=R`` or, for a heterogeneous team, ``radii=lo..hi`` (reprs)."""
    radii = np.asarray(result.radii)
    if len(radii) and np.any(radii != result.radius):
        return f"radii={float(radii.min()):g}..{float(radii.max()):g}"
    return f"radius={result.radius:g}"


# ----------------------------------------------------------------------------------------- stepping
class LloydStepper:
    """Lloyd's algorithm on limited cells, for users who drive their own loop.

    Holds the swarm in the compiled core, whose spatial grid survives the steps (only agents that
    cross into another grid bucket are rebucketed), the environment, the density and the gain.

    >>> s = dv.coverage.LloydStepper(points, radius=0.1, bounds=(0, 0, 1, 1), gain=0.8)
    >>> for t in range(100):
    ...     cost = s.step()          # H before the move; s.points are the new positions
    """

    def __new__(cls, *args: Any, environment: Any = None, **kwargs: Any) -> Any:
        if environment is not None:  # an occupancy grid: geodesic cells (dvoronoi.geodesic)
            from .geodesic import GeodesicLloydStepper

            return GeodesicLloydStepper(*args, environment=environment, **kwargs)
        return super().__new__(cls)

    def __init__(self, points: Any, radius: Union[float, Sequence[float], np.ndarray], density: Any = None,
                 gain: float = 1.0, bounds: BoundsArg = None, order: int = 8, workers: Optional[int] = None, *,
                 threads: Optional[int] = None, environment: Any = None) -> None:
        team = _args.workers(workers, threads)
        radius = _radius_arg(radius)
        self.density = _check_density(density)
        self.gain = _check_gain(gain)
        self.order = _args.integer(order, "order", 1, 64)
        self.bounds = as_bounds(bounds)
        self._core = _core.LloydStepper(points, radius, self.bounds, self.gain, team)
        self._total: Optional[float] = None  # Φ(Q) under the density, computed once

    @property
    def points(self) -> np.ndarray:
        """Current positions, (n, 2) (a copy)."""
        return self._core.points

    @property
    def radius(self) -> float:
        """The radius R (the largest, R̄, of a heterogeneous team)."""
        return self._core.radius

    @property
    def radii(self) -> np.ndarray:
        """Each agent's radius, (n,)."""
        return self._core.radii

    def _radii(self) -> Optional[np.ndarray]:
        """The radii when they are not all R̄ (the cost's per-agent terms), else None."""
        radii = self._core.radii
        return radii if np.any(radii != self._core.radius) else None

    def __len__(self) -> int:
        return len(self._core.points)

    def _phi_total(self) -> Optional[float]:
        if self.bounds is None:
            return None
        if self.density is None:
            return self._core.bounds_area
        if self._total is None:
            x, y, w, _ = _core.environment_quadrature(self.bounds, self.order)
            self._total = float(np.sum(w * _evaluate(self.density, x, y)))
        return self._total

    def _moments(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(mass, centroid, polar, open): open says which cells reach their circle."""
        if self.density is None:
            return self._core.moments()
        q = self._core.quadrature(self.order)
        return density_moments(self._core.points, q, self.density) + (q[4],)

    def moments(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(mass, centroid, polar moment) of every clipped cell at the current positions."""
        return self._moments()[:3]

    def cost(self) -> float:
        """The locational cost H at the current positions (module docstring)."""
        if self.density is None:
            return self._core.cost()
        mass, _, polar, open_cells = self._moments()
        return _cost(mass, polar, open_cells, self.radius, self._phi_total(), self._radii())

    def step(self) -> float:
        """One Lloyd step: cells at the current positions, every agent moves ``gain`` of the way to
        its centroid (staying in the environment). Returns H before the move."""
        if self.density is None:
            return self._core.step()
        mass, centroid, polar, open_cells = self._moments()
        self._core.move_to_targets(centroid)
        return _cost(mass, polar, open_cells, self.radius, self._phi_total(), self._radii())

    def set_points(self, points: Any) -> None:
        """Put the agents somewhere else (same number); the grid is updated, not rebuilt."""
        self._core.set_points(points)

    def cells(self) -> CoverageCells:
        """The clipped cells at the current positions (for plots and export)."""
        arrays = self._core.cells()
        if self.density is None:
            return CoverageCells(arrays, self.bounds)
        mass, centroid, _ = self.moments()
        return CoverageCells(arrays, self.bounds, mass, centroid)

    @property
    def rebucketed(self) -> int:
        """Agents the last step moved into another grid bucket."""
        return self._core.rebucketed

    def __repr__(self) -> str:
        return (f"LloydStepper(n={len(self)}, {_radius_text(self)}, gain={self.gain:g}, "
                f"bounds={'None' if self.bounds is None else len(self.bounds)}, "
                f"density={'uniform' if self.density is None else 'callable'})")


def step(points: Any, radius: Union[float, Sequence[float], np.ndarray], density: Any = None, gain: float = 1.0,
         bounds: BoundsArg = None,
         order: int = 8, workers: Optional[int] = None, *, threads: Optional[int] = None) -> Tuple[np.ndarray, float]:
    """One Lloyd step from `points`: returns ``(new_points, cost)``, the cost H at `points`.

    For many steps, :class:`LloydStepper` (or :func:`lloyd`) keeps the spatial index between steps.
    """
    s = LloydStepper(points, radius, density=density, gain=gain, bounds=bounds, order=order,
                     workers=_args.workers(workers, threads) or None)
    cost = s.step()
    return s.points, cost


class LloydResult(CoverageCells):
    """A Lloyd run: the trajectory, the cost per step and the final clipped cells.

    Attributes
    ----------
    trajectory : (frames, n, 2) float64
        Positions at ``frame_steps`` (step 0 first, the last step last).
    frame_steps : (frames,) int64
    cost : (steps + 1,) float64
        H at every step's positions (``cost[0]`` initial, ``cost[-1]`` final); never increases.
    points, areas, centroids, cell(i), ... : the final positions' clipped cells.
    """

    def __init__(self, cells: CoverageCells, trajectory: np.ndarray, frame_steps: np.ndarray,
                 cost: np.ndarray, gain: float, density: Any) -> None:
        self.__dict__.update(cells.__dict__)
        self.trajectory = trajectory
        self.frame_steps = frame_steps
        self.cost = cost
        self.gain = gain
        self.density = density

    @property
    def steps(self) -> int:
        return len(self.cost) - 1

    def _json_doc(self) -> dict:
        doc = super()._json_doc()
        doc.update({"kind": "lloyd", "gain": self.gain, "steps": self.steps, "cost": self.cost.tolist(),
                    "frame_steps": self.frame_steps.tolist(), "trajectory": self.trajectory.tolist()})
        return doc

    def animate(self, path: Optional[PathLike] = None, fps: int = 10, **kwargs: Any):
        """See :func:`animate`."""
        return animate(self, path, fps=fps, **kwargs)

    def __repr__(self) -> str:
        return (f"LloydResult(n={len(self)}, {_radius_text(self)}, steps={self.steps}, "
                f"cost {self.cost[0]:.6g} -> {self.cost[-1]:.6g})")


@overload
def lloyd(points: Any, radius: Union[float, Sequence[float], np.ndarray], density: Any = None, steps: int = 100, gain: float = 1.0,
          bounds: BoundsArg = None, order: int = 8, record_every: int = 1,
          workers: Optional[int] = None, progress: Union[None, bool, Callable[[int, int], Any]] = None, *,
          threads: Optional[int] = None, environment: None = None) -> LloydResult: ...


@overload
def lloyd(points: Any, radius: Union[None, float, Sequence[float], np.ndarray], density: Any = None, steps: int = 100, gain: float = 1.0,
          bounds: None = None, order: int = 8, record_every: int = 1,
          workers: Optional[int] = None, progress: Union[None, bool, Callable[[int, int], Any]] = None, *,
          threads: Optional[int] = None,
          environment: Union[np.ndarray, str, PathLike, OccupancyGrid]) -> GeodesicLloydResult: ...


def lloyd(points: Any, radius: Union[None, float, Sequence[float], np.ndarray], density: Any = None, steps: int = 100,
          gain: float = 1.0,
          bounds: BoundsArg = None, order: int = 8, record_every: int = 1,
          workers: Optional[int] = None, progress: Union[None, bool, Callable[[int, int], Any]] = None, *,
          threads: Optional[int] = None, environment: Any = None) -> Union[LloydResult, GeodesicLloydResult]:
    """Run Lloyd's algorithm on limited cells for `steps` steps.

    Parameters
    ----------
    points : (n, 2) array-like
        Initial positions; with `bounds` every agent must lie in the environment.
    radius : float or (n,) array-like
        The cell radius R > 0, or one sensing radius per agent (a heterogeneous team: power cells
        clipped to the disks and the power cost, module docstring; all equal gives the scalar run).
    density : None, callable or GridDensity
        None: uniform (exact, and the whole run stays in the compiled core). A callable ``f(x, y)``
        taking and returning arrays (a scalar-only function is called per node), or a
        :class:`GridDensity`; values must be finite and >= 0.
    steps : int
        Number of steps (>= 0).
    gain : float in (0, 1]
        Fraction of the way to the centroid moved per step.
    bounds : box ``(xmin, ymin, xmax, ymax)``, (k, 2) convex polygon, shapely Polygon or None
        The environment Q; cells are clipped to it and agents stay in it. None: the plane.
    order : int
        Gauss points per direction of the density quadrature (ignored for uniform density).
    record_every : int
        Positions are recorded every `record_every` steps (and after the last).
    workers : int, optional
        Worker threads: None or -1 every core, k >= 1 k threads (``threads`` is a deprecated alias,
        0 = every core). Results do not depend on it.
    progress : bool or callable, optional
        None: a tqdm bar over the steps from ``PROGRESS_BAR_FROM`` agent-steps on; True/False:
        always/never; a callable is called as ``progress(done_steps, steps)``.
    environment : occupancy grid, optional
        Instead of `bounds`: an :class:`~dvoronoi.OccupancyGrid`, a map file or an H x W array (what
        :func:`dvoronoi.grid_voronoi` takes). Cells are then geodesic, agents move along shortest paths
        around walls, `radius` is the geodesic range (None: unlimited) and `density` may also be an
        H x W array; see :mod:`dvoronoi.geodesic` (`order` is not used).

    Returns
    -------
    LloydResult

    Raises
    ------
    ValueError
        Bad shape, NaN/inf, radius, gain, bounds (not convex, too few vertices), an agent outside
        `bounds` (named by index), coinciding agents (:class:`dvoronoi.CoincidentError`), a density
        value that is negative or not finite.
    TypeError
        A density that is not callable, non-integer counts.
    """
    if environment is not None:  # an occupancy grid: geodesic cells (dvoronoi.geodesic)
        from . import geodesic

        if bounds is not None:
            raise ValueError("give the region as bounds= (a convex polygon) or environment= (an occupancy grid), not both")
        return geodesic.lloyd(points, radius, environment, density=density, steps=steps, gain=gain,
                              record_every=record_every, workers=_args.workers(workers, threads) or None,
                              progress=progress)
    team = _args.workers(workers, threads)
    steps = _check_count(steps, "steps", 0)
    record_every = _check_count(record_every, "record_every", 1)
    # None (no range) is for environment= only: LloydStepper refuses it, naming `radius`.
    stepper = LloydStepper(points, cast(Any, radius), density=density, gain=gain, bounds=bounds, order=order,
                           workers=team or None)
    n = len(stepper)
    frame_steps = np.unique(np.concatenate([np.arange(0, steps + 1, record_every), [steps]])).astype(np.int64)

    bar = None
    callback = None
    if callable(progress) and not isinstance(progress, bool):
        callback = progress
    elif progress or (progress is None and n * steps >= PROGRESS_BAR_FROM):
        tqdm = tqdm_class(required=bool(progress))  # optional: no bar that was not asked for without it
        bar = None if tqdm is None else tqdm(total=steps, unit="steps", desc="lloyd")
        callback = None if bar is None else lambda done, total: bar.update(done - bar.n)  # noqa: E731
    try:
        if stepper.density is None:
            trajectory, cost = stepper._core.run(steps, record_every, callback)
        else:
            frames = [stepper.points]
            cost = np.empty(steps + 1)
            for t in range(steps):
                cost[t] = stepper.step()
                if (t + 1) % record_every == 0 or t + 1 == steps:
                    frames.append(stepper.points)
                if callback:
                    callback(t + 1, steps)
            cost[steps] = stepper.cost()
            trajectory = np.stack(frames)
    finally:
        if bar is not None:
            bar.close()
    return LloydResult(stepper.cells(), trajectory, frame_steps, cost, stepper.gain, stepper.density)


# ----------------------------------------------------------------------------------------- pictures
def animate(result: LloydResult, path: Optional[PathLike] = None, fps: int = 10, **kwargs: Any):
    """Animate a Lloyd run with matplotlib; see :func:`dvoronoi.plotting.animate` (cells, density,
    trails, a progress bar while writing `path`, ``.gif`` or ``.mp4``)."""
    from . import plotting

    anim = plotting.animate(result, path, fps=fps, **kwargs)
    return anim


# Geodesic cells on occupancy grids live in dvoronoi.geodesic; reachable from here as the rest of coverage.
from .geodesic import GeodesicCells, GeodesicLloydResult, geodesic_cells  # noqa: E402
from .occupancy import OccupancyGrid  # noqa: E402  (the environment= type of lloyd's overloads)

__all__ += ["geodesic_cells", "GeodesicCells"]
