"""Grid Voronoi diagram of obstacles for path planning (Mendes, Aude, Pinto & Aude), traced by
slice-parallel workers.

The diagram is exactly the set of cells of the working area whose corners carry two or more labels,
isolated pieces included (loops around islands, slivers thinner than a cell): the workers trace
from the area's corners as the paper does, and also from every obstacle (a walk right from its
rightmost point, and where obstacles of different labels meet), so nothing depends on the area's
corners being reachable — on real maps they lie inside walls.

>>> import dvoronoi as dv
>>> obstacles = [{"type": "circle", "center": [30, 40], "radius": 8},
...              {"type": "polygon", "vertices": [[60, 10], [80, 10], [70, 35]]},
...              {"type": "point", "position": [75, 75]}]
>>> gv = dv.grid_voronoi(obstacles, area=(0, 0, 100, 100), cells=512, robot_radius=2.0, workers=2)
>>> gv.diagram_mask, gv.blocked_mask, gv.clearance, gv.vertex_points
>>> G = gv.roadmap                      # networkx.MultiGraph (nodes at vertices and ends)
>>> route = gv.path((5, 5), (95, 95))   # (k, 2) array; empty when no collision-free route exists
>>> gv.plot(path=route)

Obstacles use the JSON format of ``dvoronoi gvd`` (README, "Grid Voronoi diagram of obstacles"):
a list of shape dicts (``polygon`` — convex or not, ``circle``, ``point``, ``segment``, ``union``),
a dict ``{"area": ..., "obstacles": [...]}``, or a path to such a JSON file. The working area's
edges are obstacles too, labelled after the user's obstacles. Labels of corners are the nearest
obstacle by Euclidean distance to its region (squared doubles compared, ties to the lower label).

The result relates obstacles like every dvoronoi result relates agents: ``neighbors(i)`` are the
obstacles (and area edges) whose regions meet obstacle ``i``'s along the traced diagram.
"""
from __future__ import annotations

import functools
import os
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _args, _core
from ._io import PathLike, atomic_write_text
from ._result import Result

if TYPE_CHECKING:  # pragma: no cover
    import matplotlib.axes
    import networkx
    import scipy.sparse

__all__ = ["grid_voronoi", "GridVoronoi", "obstacles_from_occupancy_grid", "load_obstacles"]

# Occupancy grids (dvoronoi.occupancy) are dispatched to from grid_voronoi.

_NODE_KINDS = ("vertex", "end", "junction")


def _area_json(area: Any) -> Dict[str, Any]:
    if isinstance(area, dict):
        return area
    arr = np.asarray(area, dtype=np.float64)
    if arr.shape == (4,):
        return {"box": arr.tolist()}
    if arr.ndim == 2 and arr.shape[1] == 2:
        return {"polygon": arr.tolist()}
    raise ValueError("area must be a box (xmin, ymin, xmax, ymax), a convex polygon as a (k, 2) array, "
                     f"or a dict as in the JSON format; got shape {arr.shape}")


def load_obstacles(obstacles: Any, area: Any = None) -> "_core._GvdScene":
    """Parse and check obstacles (and area) into a compiled scene; errors name the field
    (``ValueError: obstacles: obstacles[3].radius: must be a positive finite number, got -1``), and
    for a JSON file the place (``map.json:4:31: duplicate key 'radius' ...``)."""
    if isinstance(obstacles, _core._GvdScene):
        return obstacles
    name = "obstacles"
    if isinstance(obstacles, (str, os.PathLike)):
        # A file is parsed by the compiled loader the CLI uses: the same messages, FILE:LINE:COLUMN for
        # invalid JSON, a repeated key or a number beyond the range of a double.
        name = os.fspath(obstacles)
        if os.path.isdir(name):
            raise ValueError(f"{name}: is a folder, not a file")
        try:
            text = Path(name).read_bytes()
        except FileNotFoundError:
            raise ValueError(f"{name}: cannot open file: it does not exist") from None
        except OSError as e:
            raise ValueError(f"{name}: cannot read file ({e.strerror})") from None
        if not name.lower().endswith(".json") and not text.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"{"):
            from .occupancy import MAP_EXTENSIONS  # a JPEG read as JSON would say "a NUL byte"
            raise ValueError(f"{name}: neither a map file nor an obstacle document (not JSON): maps are read from "
                             f"{', '.join(MAP_EXTENSIONS)} files, obstacle documents from JSON (.json)")
        return _core._GvdScene.from_text(text, name, None if area is None else _area_json(area))
    if isinstance(obstacles, dict):
        doc = dict(obstacles)
    else:
        doc = {"obstacles": list(obstacles)}
    if area is not None:
        doc["area"] = _area_json(area)
    elif "area" not in doc:
        raise ValueError("area: required (a box (xmin, ymin, xmax, ymax) or a convex polygon), "
                         "either as the area= argument or in the obstacle document")
    return _core._GvdScene.from_doc(doc, name)


class GridVoronoi(Result):
    """The grid Voronoi diagram (see :func:`grid_voronoi`).

    Exactly the cells of the working area whose corners carry two or more labels, for every worker
    count and slice approach. Per cell ``k`` (cells sorted by row, then column): ``cells[k] = (col, row)``,
    ``centers[k]``, ``labels[k]`` (nearest obstacle of the corners bottom-left, bottom-right,
    top-right, top-left), ``clearance[k]`` (smallest corner distance to its nearest obstacle) and
    ``blocked[k]`` (``clearance <= robot_radius``). ``vertices`` are the cells with three or more
    labels. Dense ``(ny, nx)`` pictures: ``diagram_mask``, ``blocked_mask``, ``clearance_map``
    (row ``j`` is ``y0 + j h``; use ``origin="lower"`` with imshow).
    """

    def __init__(self, core: "_core._GvdResult", scene: "_core._GvdScene") -> None:
        self._core = core
        self._scene = scene
        x0, y0, h, nx, ny = core.grid
        self.origin = (float(x0), float(y0))
        self.cell_size = float(h)
        self.shape = (int(ny), int(nx))
        self._robot_radius = float(core.robot_radius)
        self.n_obstacles = int(core.n_obstacles)
        self.n_labels = int(core.n_labels)
        self.labels = core.labels
        self.clearance = core.clearance
        self.blocked = core.blocked
        self.vertices = core.vertices
        self.stats: Dict[str, Any] = core.stats
        self._relation: Optional[Tuple[np.ndarray, np.ndarray]] = None

    @property
    def robot_radius(self) -> float:
        """The robot radius the diagram was built for (read-only: ``blocked``, the graph's blocked
        edges and paths were decided with it; build again for another radius)."""
        return self._robot_radius

    # cells and centers are built on first use: a few ms for a large diagram that many callers
    # never read.
    @functools.cached_property
    def cells(self) -> np.ndarray:
        """``(n, 2)`` int64 ``(col, row)`` of every traced cell."""
        return np.stack([self._core.col, self._core.row], axis=1).astype(np.int64)

    @functools.cached_property
    def centers(self) -> np.ndarray:
        """``(n, 2)`` cell centers."""
        x0, y0 = self.origin
        h = self.cell_size
        return np.stack([x0 + (self._core.col + 0.5) * h, y0 + (self._core.row + 0.5) * h], axis=1)

    @property
    def indptr(self) -> np.ndarray:  # type: ignore[override]
        """CSR of the obstacle relation (labels sharing a diagram cell), computed on first use."""
        return self._obstacle_relation()[0]

    @property
    def indices(self) -> np.ndarray:  # type: ignore[override]
        return self._obstacle_relation()[1]

    def _obstacle_relation(self) -> Tuple[np.ndarray, np.ndarray]:
        if self._relation is not None:
            return self._relation
        n = self.n_labels
        lab = np.sort(self.labels, axis=1)
        pairs = []
        for a in range(4):
            for b in range(a + 1, 4):
                d = lab[:, a] != lab[:, b]
                pairs.append(np.stack([lab[d, a], lab[d, b]], axis=1))
        p = np.concatenate(pairs) if pairs else np.zeros((0, 2), np.int64)
        p = np.concatenate([p, p[:, ::-1]]).astype(np.int64)
        p = np.unique(p, axis=0) if len(p) else p.reshape(0, 2)
        indptr = np.zeros(n + 1, dtype=np.int64)
        np.add.at(indptr, p[:, 0] + 1, 1)
        self._relation = (np.cumsum(indptr), p[:, 1].copy())
        return self._relation

    # -- sizes and pictures ---------------------------------------------------------------------
    def __len__(self) -> int:
        return self.n_labels

    @property
    def vertex_points(self) -> np.ndarray:
        """Centers of the Voronoi vertex cells, shape (m, 2)."""
        return self.centers[self.vertices]

    def _dense(self, values: Any, fill: Any, dtype: Any) -> np.ndarray:
        out = np.full(self.shape, fill, dtype=dtype)
        out[self.cells[:, 1], self.cells[:, 0]] = values
        return out

    @property
    def diagram_mask(self) -> np.ndarray:
        """(ny, nx) bool: the traced diagram cells."""
        return self._dense(True, False, bool)

    @property
    def blocked_mask(self) -> np.ndarray:
        """(ny, nx) bool: diagram cells blocked by the robot radius."""
        return self._dense(self.blocked, False, bool)

    @property
    def clearance_map(self) -> np.ndarray:
        """(ny, nx) float64: clearance of diagram cells, NaN elsewhere."""
        return self._dense(self.clearance, np.nan, np.float64)

    # -- roadmap and paths ----------------------------------------------------------------------
    @functools.cached_property
    def roadmap(self) -> "networkx.MultiGraph":
        """The roadmap as a ``networkx.MultiGraph``: nodes at Voronoi vertices, junctions and ends
        (attributes ``pos``, ``cell``, ``kind``), one edge per chain of diagram cells between them
        (``length``, ``min_clearance``, ``blocked``, ``cells``). Needs networkx; see
        :meth:`roadmap_csr` otherwise."""
        import networkx as nx

        c = self._core
        g = nx.MultiGraph()
        cells, kinds = c.node_cell, c.node_kind
        pos = self.centers[cells]
        g.add_nodes_from((v, {"pos": (float(pos[v, 0]), float(pos[v, 1])), "cell": int(cells[v]), "kind": _NODE_KINDS[kinds[v]]})
                         for v in range(len(cells)))
        ptr, chain = c.chain_ptr, c.chain_cells
        g.add_edges_from((int(u), int(v), {"length": float(ln), "min_clearance": float(mc), "blocked": bool(b),
                                           "cells": chain[ptr[e]:ptr[e + 1]]})
                         for e, (u, v, ln, mc, b) in enumerate(zip(c.edge_u.tolist(), c.edge_v.tolist(), c.edge_length.tolist(),
                                                                   c.edge_min_clearance.tolist(), c.edge_blocked.tolist())))
        return g

    def roadmap_csr(self, free_only: bool = False) -> "scipy.sparse.csr_matrix":
        """The roadmap as a symmetric ``scipy.sparse.csr_matrix`` of edge lengths (the shortest of
        parallel edges); with `free_only`, edges through blocked cells are left out."""
        import scipy.sparse

        c = self._core
        keep = ~c.edge_blocked if free_only else np.ones(len(c.edge_u), bool)
        u, v, w = c.edge_u[keep], c.edge_v[keep], c.edge_length[keep]
        n = len(c.node_cell)
        best: Dict[Tuple[int, int], float] = {}
        for a, b, x in zip(np.r_[u, v], np.r_[v, u], np.r_[w, w]):
            k = (int(a), int(b))
            best[k] = min(best.get(k, np.inf), float(x))
        if not best:
            return scipy.sparse.csr_matrix((n, n))
        keys = np.array(list(best.keys()))
        return scipy.sparse.csr_matrix((np.array(list(best.values())), (keys[:, 0], keys[:, 1])), shape=(n, n))

    def path(self, start: Sequence[float], goal: Sequence[float]) -> np.ndarray:
        """Shortest collision-free path for a disk robot of radius ``robot_radius`` along the diagram.

        Returns the path as a (k, 2) array: `start`, cell centers along free diagram cells, `goal`
        (every segment exactly farther than the robot radius from every obstacle). Returns an empty
        (0, 2) array when no such route exists (start or goal cannot reach the free diagram, or the
        free diagram does not connect them).

        Raises ValueError naming `start` or `goal` when it lies outside the working area or within
        the robot radius of an obstacle (blocked).
        """
        pts, _ = self._core.path(start, goal)
        return pts

    def path_length(self, start: Sequence[float], goal: Sequence[float]) -> float:
        """Length of :meth:`path` (inf when there is none)."""
        pts, length = self._core.path(start, goal)
        return float(length) if len(pts) else float("inf")

    # -- export and pictures ----------------------------------------------------------------------
    def _json_text(self, indent: Optional[int]) -> str:
        return self._core.to_json(-1 if indent is None else indent)

    def to_svg(self, path: Optional[PathLike] = None, route: Optional[np.ndarray] = None) -> Optional[str]:
        """The picture ``dvoronoi gvd --svg`` draws (optionally with a route); text or written atomically."""
        text = self._core.to_svg(route)
        if path is None:
            return text
        atomic_write_text(path, text)
        return None

    def plot(self, ax: "Optional[matplotlib.axes.Axes]" = None, path: Optional[np.ndarray] = None,
             obstacles: bool = True, **kwargs: Any) -> "matplotlib.axes.Axes":
        """Draw obstacles (grey), free diagram cells (blue), blocked ones (light red), Voronoi
        vertices (dark red) and an optional path (green); returns the axes."""
        import matplotlib.pyplot as plt
        from matplotlib.colors import ListedColormap
        from matplotlib.patches import Circle, Polygon

        from .plotting import category_image

        if ax is None:
            _, ax = plt.subplots(figsize=kwargs.pop("figsize", (7, 7)))
        x0, y0 = self.origin
        h = self.cell_size
        ny, nx = self.shape
        img = np.zeros(self.shape, dtype=np.int8)
        img[self.cells[:, 1], self.cells[:, 0]] = np.where(self.blocked, 2, 1)
        cmap = ListedColormap([(1, 1, 1, 0), (0.12, 0.47, 0.71, 1), (0.96, 0.65, 0.65, 1)])
        area = self._scene.area
        ax.set_aspect("equal")
        ax.set_xlim(area[:, 0].min(), area[:, 0].max())
        ax.set_ylim(area[:, 1].min(), area[:, 1].max())
        # row 0 of the cells is the bottom one; the image's top row first (a large grid is reduced so
        # that no cell line drops out)
        category_image(ax, img[::-1], (x0, x0 + nx * h, y0, y0 + ny * h), cmap=cmap, vmin=0, vmax=2, zorder=2,
                       gid="dvoronoi-gvd-cells")
        if obstacles:
            for kind, label, verts, center, radius in self._scene.parts():
                if label >= self.n_obstacles:
                    continue
                if kind == "polygon":
                    ax.add_patch(Polygon(verts, closed=True, fc="0.6", ec="0.35", lw=0.5, zorder=1))
                elif kind == "circle":
                    ax.add_patch(Circle(center, radius, fc="0.6", ec="0.35", lw=0.5, zorder=1))
                elif kind == "segment":
                    ax.plot(verts[:, 0], verts[:, 1], color="0.35", lw=2, zorder=1)
                else:
                    ax.plot(verts[:, 0], verts[:, 1], "o", color="0.35", ms=3, zorder=1)
        ax.add_patch(Polygon(area, closed=True, fill=False, ec="k", lw=1, zorder=3))
        vp = self.vertex_points
        ax.plot(vp[:, 0], vp[:, 1], "o", color="#b71c1c", ms=3, zorder=4, gid="dvoronoi-gvd-vertices")
        if path is not None and len(path):
            p = np.asarray(path)
            ax.plot(p[:, 0], p[:, 1], "-", color="#2e7d32", lw=2, zorder=5, gid="dvoronoi-gvd-path")
        return ax

    def __repr__(self) -> str:
        return (f"GridVoronoi({len(self.cells)} cells on a {self.shape[1]}x{self.shape[0]} grid, "
                f"{len(self.vertices)} vertices, {int(self.blocked.sum())} blocked, "
                f"robot_radius={self.robot_radius})")


def _workers(workers: Any) -> int:
    """docs/spec.md: None or -1 = all cores, k >= 1 = k threads (checked by _args.workers); the slice team
    needs the count itself."""
    return _args.workers(workers) or max(1, os.cpu_count() or 1)


def _is_map(source: Any) -> bool:
    from .occupancy import MAP_EXTENSIONS, OccupancyGrid

    if isinstance(source, OccupancyGrid):
        return True
    if isinstance(source, np.ndarray):  # any array is a map; its shape and dtype are checked there
        return True
    if isinstance(source, (str, os.PathLike)):
        return os.fspath(source).lower().endswith(MAP_EXTENSIONS)
    if isinstance(source, (list, tuple)) and source and all(isinstance(row, (list, tuple)) for row in source):
        # nested lists of True/False are an occupancy grid (obstacle documents hold coordinates)
        try:
            a = np.asarray(source)
        except ValueError:  # ragged
            return False
        return a.ndim == 2 and a.dtype == bool
    return False


def grid_voronoi(obstacles: Any, area: Any = None, resolution: Any = None, robot_radius: float = 0.0,
                 workers: Optional[int] = None, mode: str = "cooperative", visibility: bool = True, *,
                 cells: Optional[int] = None, diagram: Optional[str] = None, origin: Any = None,
                 unknown: str = "occupied", occupied_thresh: float = 0.65, min_separation: float = 1.5,
                 prune_length: float = 8.0) -> Any:
    """The grid Voronoi diagram of an occupancy grid or of obstacles.

    **Occupancy grids** (a 2-d array, row 0 at the top; an :class:`OccupancyGrid`; or a map file:
    ROS map_server ``.yaml``, ``.pgm``, ``.png``, MovingAI ``.map``): the diagram grid is the pixel
    grid and ``diagram="medial"`` (default) separates the parts of one wall — see
    :mod:`dvoronoi.occupancy` for the exact definition. Returns an :class:`OccupancyVoronoi`.
    ``diagram="labels"`` gives the paper's labelled diagram of the map's connected occupied regions
    (a :class:`GridVoronoi`, through :func:`obstacles_from_occupancy_grid`).

    **Obstacle documents** (list of shape dicts, ``{"area": ..., "obstacles": [...]}``, a JSON path,
    or a scene from :func:`load_obstacles`): the paper's labelled diagram (Mendes et al.), traced by
    slice workers from the area's corners and from every obstacle: every cell whose corners carry two
    or more labels, isolated pieces included. Returns a :class:`GridVoronoi`; its ``stats`` count the
    work (``corners_labelled``, ``traced_cells``, ``bridged_cells`` explored beside the diagram,
    ``obstacle_walks``/``walk_cells``/``walk_seeds``, ``contact_seeds``, ``boundary_seeds``,
    ``border_lines_scanned``; ``discarded_cells`` is 0: every worker traces exactly its cells). With
    ``diagram="medial"`` the document is drawn on `cells` pixels along the area's longer side (a pixel
    is occupied when its square meets an obstacle or leaves the working area) and gets the occupancy
    grids' medial diagram (an :class:`OccupancyVoronoi`), which separates the parts of one non-convex
    obstacle.

    Parameters
    ----------
    resolution : map units per pixel of an occupancy array or image (a YAML or OccupancyGrid brings
        its own). For obstacle documents it is the deprecated name of `cells`.
    cells : obstacle documents: cells along the longer side of the area's bounding box (default 512).
    robot_radius : diagram cells with clearance not greater than this are blocked (kept, marked);
        paths keep this clearance.
    workers : None or -1 = all cores, k = k threads; the diagram is the same for every count.
    diagram : ``"medial"`` (occupancy grids' default) or ``"labels"`` (obstacle documents' default).
    mode, visibility : the paper's slice approach (``"cooperative"``/``"independent"``) and edge
        visibility test for the labelled diagram of obstacle documents.
    origin, unknown, occupied_thresh : how an array or image becomes an occupancy grid.
    min_separation, prune_length : the medial diagram's parameters in pixels (defaults 1.5 and 8).

    Raises ValueError naming the argument, the file and line of a bad map, or the obstacle and field
    of a bad obstacle; an argument the chosen diagram or input does not read (e.g. `mode` for the
    medial diagram, `origin` for an obstacle document) is an error too.
    """
    robot_radius = _args.real(robot_radius, "robot_radius")
    if not np.isfinite(robot_radius) or robot_radius < 0:
        raise ValueError(f"robot_radius must be a finite number >= 0, got {robot_radius}")
    n_workers = _workers(workers)
    if diagram not in (None, "medial", "labels"):
        raise ValueError(f'diagram must be "medial" or "labels", got {diagram!r}')
    if mode not in ("cooperative", "independent"):
        raise ValueError(f'mode must be "cooperative" or "independent", got {mode!r}')
    if not (isinstance(visibility, (bool, np.bool_)) or (isinstance(visibility, (int, np.integer)) and visibility in (0, 1))):
        raise TypeError(f"visibility must be True or False, got {visibility!r}")
    is_map = _is_map(obstacles)
    # an argument the chosen diagram or input does not read is an error, not silently dropped
    wants_labels = diagram == "labels" or (diagram is None and not is_map)
    if wants_labels and (min_separation != 1.5 or prune_length != 8.0):
        raise ValueError('min_separation and prune_length are the medial diagram\'s parameters; diagram="labels" '
                         'does not use them')
    if not wants_labels and (mode != "cooperative" or not visibility):
        raise ValueError('mode and visibility are the labelled diagram\'s slice approach and edge test; the medial '
                         'diagram does not use them')
    if not is_map and origin is not None:
        raise ValueError("origin: an obstacle document's coordinates are its own; origin= places occupancy "
                         "arrays and images")
    if not is_map and (unknown != "occupied" or occupied_thresh != 0.65):
        raise ValueError("unknown and occupied_thresh say how an occupancy array or image is read; an obstacle "
                         "document has no unknown or probable cells")
    if is_map:
        from .occupancy import as_occupancy_grid, medial_voronoi

        if area is not None:
            raise ValueError("area: an occupancy grid's area is the map itself; do not pass area=")
        if cells is not None:
            raise ValueError("cells: an occupancy grid's diagram grid is its pixel grid; do not pass cells=")
        grid = as_occupancy_grid(obstacles, resolution, origin, unknown, occupied_thresh, copy=False)
        # the rule the grid was read with (an OccupancyGrid's or a YAML's own): updates read arrays by it
        occupied_thresh, unknown = getattr(grid, "occupied_thresh", occupied_thresh), getattr(grid, "unknown", unknown)
        if diagram in (None, "medial"):
            return medial_voronoi(grid, robot_radius, n_workers, min_separation, prune_length, occupied_thresh, unknown)
        # Labelled in pixel units, where the map's obstacles and the cell corners lie on the integer
        # lattice and distances are exact, then placed in map units (in map units, rounding would break
        # the lattice's many exact ties either way, and the diagram would depend on resolution and origin).
        H, W = grid.shape
        regions = _occupied_regions(grid.occupied)
        scene = load_obstacles(_occupancy_document(regions, grid.shape, grid.resolution, grid.origin))
        in_pixels = load_obstacles(_occupancy_document(regions, grid.shape, 1.0, (0.0, 0.0)))
        labelled = GridVoronoi(_core._gvd_run(scene, max(H, W), robot_radius, n_workers, mode, bool(visibility),
                                              in_pixels, grid.resolution, grid.origin[0], grid.origin[1]), scene)
        if len(labelled.cells) == 0:
            from .occupancy import warn_empty_diagram

            warn_empty_diagram(grid, unknown, "the corners of every cell share one nearest occupied region: "
                               "the map's walls are one connected region, which the labelled diagram does not "
                               "split (the medial diagram, the default, does)", stacklevel=3)
        return labelled
    if cells is not None and resolution is not None:
        raise ValueError("pass cells= only (resolution= is its deprecated name for obstacle documents)")
    if resolution is not None:
        warnings.warn("grid_voronoi(obstacles, resolution=N) is deprecated: the cells per side are now cells=N "
                      "(resolution means map units per pixel)", DeprecationWarning, stacklevel=2)
        cells = resolution
    if cells is None:
        cells = 512
    cells = _args.integer(cells, "cells", 1, _args.MAX_COUNT)
    scene = load_obstacles(obstacles, area)
    if diagram == "medial":
        # the document on the pixel grid: a pixel is occupied when it meets an obstacle or leaves the area
        from .occupancy import OccupancyGrid, medial_voronoi

        occ, res, org = scene.rasterize(cells)
        return medial_voronoi(OccupancyGrid(occ, res, org), robot_radius, n_workers, min_separation, prune_length,
                              document=True)
    try:
        core = _core._gvd_run(scene, cells, robot_radius, n_workers, mode, bool(visibility))
    except ValueError as e:  # e.g. out of the exact range: say which file when there is one
        if isinstance(obstacles, (str, os.PathLike)) and os.fspath(obstacles) not in str(e):
            raise ValueError(f"{os.fspath(obstacles)}: {e}") from None
        raise
    result = GridVoronoi(core, scene)
    if len(result.cells) == 0:
        warnings.warn("no diagram cell: the corners of every cell share one nearest obstacle (an obstacle covers "
                      "the working area)", UserWarning, stacklevel=2)
    return result


# -- occupancy grids ------------------------------------------------------------------------------

def _rectangles(mask: np.ndarray) -> list:
    """Cover a boolean region by axis-aligned rectangles: row runs, merged downwards while a run of
    the next row has the same extent. Returns (row0, row1, col0, col1) half-open."""
    rects = []
    open_runs: Dict[Tuple[int, int], int] = {}
    rows = mask.shape[0]
    for r in range(rows + 1):
        runs = set()
        if r < rows:
            line = np.concatenate([[False], mask[r], [False]])
            d = np.flatnonzero(line[1:] != line[:-1])
            runs = set(zip(d[0::2].tolist(), d[1::2].tolist()))
        for run in list(open_runs):
            if run not in runs:
                rects.append((open_runs.pop(run), r, run[0], run[1]))
        for run in runs:
            open_runs.setdefault(run, r)
    return rects


def obstacles_from_occupancy_grid(source: Any, resolution: Optional[float] = None,
                                  origin: Optional[Sequence[float]] = None, occupied_thresh: float = 0.65,
                                  negate: bool = False) -> Dict[str, Any]:
    """Obstacles from an occupancy-grid map: each connected occupied region (8-connected) becomes one
    obstacle (a ``union`` of rectangles, one label), the map's extent the working area — the paper's
    labelled diagram (``diagram="labels"``) of a map.

    `source` is a map file read as :meth:`OccupancyGrid.load` reads it (map_server YAML with its own
    resolution and origin, PGM or PNG with `resolution` (default 1) and `origin`, MovingAI ``.map``;
    `occupied_thresh` and `negate` for images), an :class:`OccupancyGrid`, or a 2-d array of occupancy
    probabilities in [0, 1] (row 0 at the top, as in the image; occupied above `occupied_thresh`) with
    `resolution`. Obstacles are numbered in the order scipy.ndimage.label finds the regions (the
    first occupied pixel in the image's row-major order, top row first). Returns the document
    :func:`grid_voronoi` takes.
    """
    from .occupancy import OccupancyGrid

    if isinstance(source, OccupancyGrid):
        grid = source
    elif isinstance(source, np.ndarray):
        if resolution is None:
            raise ValueError("resolution: required with an array")
        grid = OccupancyGrid(np.asarray(source, dtype=np.float64), resolution, (0.0, 0.0) if origin is None else origin,
                             occupied_thresh=occupied_thresh)
    else:
        grid = OccupancyGrid.load(source, resolution=resolution, origin=origin, occupied_thresh=occupied_thresh,
                                  negate=negate)
    return _occupancy_document(_occupied_regions(grid.occupied), grid.occupied.shape, grid.resolution, grid.origin)


def _occupied_regions(occ: np.ndarray) -> list:
    """Each connected occupied region (8-connected, in scipy.ndimage.label's order) as rectangles
    (x0, y0, x1, y1) in pixel units, y up: image row r spans y in [rows - 1 - r, rows - r]."""
    from scipy import ndimage

    rows = occ.shape[0]
    labels, _ = ndimage.label(occ, structure=np.ones((3, 3), bool))
    regions = []
    for region, sl in enumerate(ndimage.find_objects(labels), start=1):
        sub = labels[sl] == region
        regions.append([(sl[1].start + c0, rows - (sl[0].start + r1), sl[1].start + c1, rows - (sl[0].start + r0))
                        for r0, r1, c0, c1 in _rectangles(sub)])
    return regions


def _occupancy_document(regions: list, shape: Tuple[int, int], res: float, origin: Sequence[float]) -> Dict[str, Any]:
    """The obstacle document of a map's regions (_occupied_regions) placed by `res` and `origin`."""
    rows, cols = shape
    ox, oy = float(origin[0]), float(origin[1])
    obstacles = []
    for rects in regions:
        parts = []
        for x0, y0, x1, y1 in rects:
            xa, xb, ya, yb = ox + x0 * res, ox + x1 * res, oy + y0 * res, oy + y1 * res
            parts.append({"type": "polygon", "vertices": [[xa, ya], [xb, ya], [xb, yb], [xa, yb]]})
        obstacles.append(parts[0] if len(parts) == 1 else {"type": "union", "parts": parts})
    return {"area": {"box": [ox, oy, ox + cols * res, oy + rows * res]}, "obstacles": obstacles}
