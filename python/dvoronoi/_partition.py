"""All agents' range-limited Voronoi cells: :func:`limited_cells` and :class:`LimitedPartition`."""
from __future__ import annotations

from contextlib import contextmanager
from functools import cached_property
from typing import Any, Callable, Iterator, Optional, Union

import numpy as np

from . import _args, _core
from ._optional import tqdm_class
from ._result import CellResult

#: From this many agents on, ``limited_cells(progress=None)`` shows a tqdm progress bar.
PROGRESS_BAR_FROM = 200_000

ProgressArg = Union[None, bool, Callable[[int, int], Any]]


class LimitedPartition(CellResult):
    """The range-limited Voronoi partition of n agents: cell ``i`` is ``V_i ∩ B(p_i, R)``.

    Arrays are read-only numpy views into the compiled result (no copies); they keep it alive.

    Attributes
    ----------
    points : (n, 2) float64
        The agents, in input order.
    radius : float
        The cell radius R (with one radius per agent: the largest).
    radii : (n,) float64
        Each agent's radius (all R for a scalar radius).
    empty : (n,) bool
        True where a cell has zero area (only with one radius per agent: a larger disk covers it);
        an empty cell has no pieces and no neighbours, area 0 and its centroid at the agent.
    method : str
        ``"auto"``, ``"scan"`` or ``"chords"``.
    computed_by : dict
        How many cells each algorithm computed: ``{"clip": ..., "scan": ..., "chords": ...,
        "power": ...}`` (the certified clipping filter, Boundary Scan, RCVC, and for heterogeneous
        teams under "auto" the exact power-cell clipping where the filter gave up); the values add
        up to n.
    indptr, indices : int64
        Limited neighbours in scipy's CSR layout (ascending per agent).
    areas, perimeters : (n,) float64
        Exact (circular segments included).
    centroids : (n, 2) float64
    candidates : (n,) int64
        Agents within 2R each cell's computation examined.
    piece_ptr, piece_neighbor, piece_x, piece_y, piece_span
        The flat boundary pieces: agent ``i`` owns pieces ``piece_ptr[i]:piece_ptr[i+1]``, each starting
        at ``(piece_x, piece_y)``; an edge has ``piece_neighbor >= 0``, an arc has ``-1`` and sweeps
        ``piece_span`` radians counter-clockwise.
    """

    def __init__(self, core: "_core.LimitedPartition") -> None:
        if not isinstance(core, _core.LimitedPartition):
            raise TypeError("LimitedPartition wraps the result of dvoronoi.limited_cells(); "
                            "call limited_cells(points, radius) instead")
        self._core = core

    # -- arrays (views, cached so repeated access is free)
    @cached_property
    def points(self) -> np.ndarray:
        return self._core.points

    @property
    def radius(self) -> float:
        return self._core.radius

    @cached_property
    def radii(self) -> np.ndarray:
        return self._core.radii

    @cached_property
    def empty(self) -> np.ndarray:
        return self._core.empty

    @property
    def method(self) -> str:
        return self._core.method

    @property
    def computed_by(self) -> dict:
        return self._core.computed_by

    @cached_property
    def indptr(self) -> np.ndarray:
        return self._core.indptr

    @cached_property
    def indices(self) -> np.ndarray:
        return self._core.indices

    @cached_property
    def areas(self) -> np.ndarray:
        return self._core.areas

    @cached_property
    def perimeters(self) -> np.ndarray:
        return self._core.perimeters

    @cached_property
    def centroids(self) -> np.ndarray:
        return self._core.centroids

    @cached_property
    def candidates(self) -> np.ndarray:
        return self._core.candidates

    @cached_property
    def piece_ptr(self) -> np.ndarray:
        return self._core.piece_ptr

    @cached_property
    def piece_neighbor(self) -> np.ndarray:
        return self._core.piece_neighbor

    @cached_property
    def piece_x(self) -> np.ndarray:
        return self._core.piece_x

    @cached_property
    def piece_y(self) -> np.ndarray:
        return self._core.piece_y

    @cached_property
    def piece_span(self) -> np.ndarray:
        return self._core.piece_span

    # -- the shared surface
    def __len__(self) -> int:
        return len(self._core)

    def neighbors(self, i: int) -> np.ndarray:
        """Limited neighbours of agent `i`: int64, ascending (a read-only view into ``indices``)."""
        return self._core.neighbors(self._index(i))

    def cell(self, i: int) -> "_core.LimitedCell":
        """Agent `i`'s cell; edge pieces name neighbours by their index in ``points``."""
        return self._core.cell(self._index(i))

    def _json_text(self, indent: Optional[int]) -> str:
        return self._core.to_json(-1 if indent is None else int(indent))

    def _geojson_text(self, tolerance: Optional[float]) -> str:
        return self._core.to_geojson(tolerance)

    def __repr__(self) -> str:
        n = len(self)
        mean = (len(self.indices) / n) if n else 0.0
        return (f"LimitedPartition(n={n}, radius={self.radius:g}, method={self.method!r}, "
                f"mean_neighbors={mean:.3g}, total_area={float(np.sum(self.areas)):.6g})")


def _agent_count(points: Any) -> Optional[int]:
    shape = getattr(points, "shape", None)
    if shape is not None and len(shape) >= 1:
        return int(shape[0])
    try:
        return len(points)
    except TypeError:
        return None


@contextmanager
def progress_callback(points: Any, progress: ProgressArg, desc: str) -> Iterator[Optional[Callable[[int, int], Any]]]:
    """The `progress` argument of the all-agents calls as a ``(done, total)`` callback for the core.

    A callable is used as is; True/False show a tqdm bar always/never; None shows one from
    ``PROGRESS_BAR_FROM`` agents on. The bar is closed when the block exits, also on errors.
    """
    if callable(progress) and not isinstance(progress, bool):
        yield progress
        return
    n = _agent_count(points)
    show = bool(progress) if progress is not None else (n is not None and n >= PROGRESS_BAR_FROM)
    if not (show and n):
        yield None
        return
    tqdm = tqdm_class(required=bool(progress))  # optional: no bar that was not asked for without it
    if tqdm is None:
        yield None
        return
    bar = tqdm(total=n, unit="agents", desc=desc)
    try:
        yield lambda done, total: bar.update(done - bar.n)
    finally:
        bar.close()


def _radius_arg(radius: Any) -> Any:
    """A scalar radius as a float (TypeError for non-numbers); an array-like of radii as a 1-D
    float64 array (ValueError naming ``radius`` for another shape or non-numeric entries; the core
    checks the length and that every radius is positive and finite)."""
    if isinstance(radius, (list, tuple, np.ndarray)) and np.ndim(radius) > 0:
        try:
            radii = np.asarray(radius, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError("radius must be a positive number or a 1-D array of one positive radius per agent, "
                             f"got entries that are not numbers") from None
        if radii.ndim != 1:
            raise ValueError(f"radius must be a positive number or a 1-D array of one radius per agent, got shape {radii.shape}")
        return radii
    return _args.real(radius, "radius")


def limited_cells(points: Any, radius: Any, method: str = "auto", workers: Optional[int] = None,
                  progress: ProgressArg = None, *, threads: Optional[int] = None) -> LimitedPartition:
    """Every agent's range-limited Voronoi cell ``V_i ∩ B(p_i, radius)``.

    Parameters
    ----------
    points : (n, 2) array-like of float
        Agent positions, any memory layout (C-contiguous float64 is not copied). Empty input gives an
        empty partition; one agent gets the full disk.
    radius : float or (n,) array-like of float
        The cell radius R > 0 (only agents closer than 2R shape a cell), between 1e-150 and 1e150.
        Or one radius per agent (a heterogeneous team, :doc:`heterogeneous`): agent i's cell is then
        its power cell (weights ``R_i**2``) clipped to ``B(p_i, R_i)``; cells may be empty (``empty``)
        and need not contain their agent. All radii equal gives the scalar call's result exactly.
    method : {"auto", "scan", "chords"}
        Which algorithm runs; all three give the same cells (``computed_by`` counts which one
        computed each).

        - ``"auto"`` (default): our fast path, not a published algorithm. A certified floating-point
          clipping filter (O(m) per agent in a swarm) gives Boundary Scan's cell bit for bit and
          defers to Boundary Scan whenever a decision is not certain (ties, lattices, cocircular
          agents; in a uniform swarm it never defers). About half of "scan"'s time.
        - ``"scan"``: Boundary Scan (He, Feng & Ren 2018) on every agent, O(m log m).
        - ``"chords"``: RCVC (Guruprasad & Dasgupta 2012) on every agent, O(m^2) worst case, so at
          most 1024 agents within 2R of any agent.

        With one radius per agent all three run on the radical axes (:doc:`heterogeneous`): "auto"
        a certified clipping filter with the exact power-cell clipping behind it, "scan" and
        "chords" Boundary Scan and RCVC generalised to cells that need not contain their agent.
    workers : int, optional
        Worker threads: None or -1 uses every core, k >= 1 uses k. The result does not depend on
        it. (``threads=`` is a deprecated alias, 0 = every core.)
    progress : bool or callable, optional
        None: a tqdm progress bar from ``PROGRESS_BAR_FROM`` (200 000) agents on. True/False: always/never.
        A callable is called as ``progress(done, total)`` instead.

    Returns
    -------
    LimitedPartition

    Raises
    ------
    ValueError
        A wrong shape, NaN/inf coordinates (the message names the index), a radius that is not
        positive and finite or outside [1e-150, 1e150], an unknown method, a bad ``workers``,
        coinciding agents (:class:`CoincidentError`, which names the first pair); outside the exact
        range (below), naming the agent: ``points[17]: out of the exact range ...``; "chords" with
        more than 1024 agents within 2R of an agent. Per-agent radii: a wrong length or shape, a
        radius that is not positive and finite (the message names ``radius[i]``), two agents with the
        same position and radius.
    TypeError
        Non-numeric input (a radius given as a string, too).

    Notes
    -----
    The GIL is released during the computation. Limited-neighbour sets are exact (exact predicates)
    for every input of finite doubles whose exact tests neither over- nor underflow: always for
    nonzero coordinate differences between about 1e-45 and 1e45; beyond, an exact test that would
    lose bits raises ValueError instead of guessing. Vertices, areas and centroids carry
    floating-point rounding.
    """
    team = _args.workers(workers, threads)
    radius = _radius_arg(radius)
    method = _args.text(method, "method")
    with progress_callback(points, progress, "limited cells") as callback:
        core = _core.limited_cells(points, radius, method, team, callback)
    return LimitedPartition(core)
