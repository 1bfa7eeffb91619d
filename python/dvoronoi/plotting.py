"""Matplotlib pictures of range-limited Voronoi cells.

Cells are filled, straight edges are drawn as line segments and arcs as arcs: cubic Bezier arcs of
at most 1/16 turn each (the construction of matplotlib's ``Path.arc`` and ``patches.Arc``; such a
curve stays within ``7e-8 R`` of the circle, far below a pixel), agents as dots, equal aspect.
Everything is built with numpy in one pass over the flat piece arrays, so large partitions draw fast.

The artists carry gids so they can be found again: ``"dvoronoi-cells"`` (one filled path per cell),
``"dvoronoi-edges"`` (a LineCollection, each shared edge once), ``"dvoronoi-arcs"`` (one compound
path: a MOVETO and CURVE4 segments per arc) and ``"dvoronoi-agents"`` (the agents); network, CC
and Lloyd plots add ``"dvoronoi-links"``, ``"dvoronoi-delaunay"``, ``"dvoronoi-hull"``,
``"dvoronoi-wrong-nodes"``, ``"dvoronoi-density"``, ``"dvoronoi-trajectories"`` and
``"dvoronoi-bounds"``.

Defaults work at any size: cells are coloured so that neighbours differ, line widths and dot sizes
follow the typical cell's size on the figure (edges are left out below a few pixels), and results
whose cells reach far out (exact or CC cells of hull nodes) are cut at the data's box. matplotlib and
tqdm are optional: ``pip install "dvoronoi[plot]"``.
"""
from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from ._optional import INSTALL_HINT, require_matplotlib, tqdm_class

__all__ = ["plot", "plot_cell", "cell_paths", "plot_network", "plot_cc", "plot_voronoi", "plot_coverage",
           "animate", "neighbor_coloring", "data_box", "density_image", "category_image", "require_matplotlib",
           "INSTALL_HINT"]

_MAX_SEGMENT = np.pi / 8.0  # largest angle of one Bezier arc segment


def _pieces_geometry(ptr: np.ndarray, xs: np.ndarray, ys: np.ndarray, spans: np.ndarray,
                     centers: np.ndarray, radius: Any) -> Dict[str, np.ndarray]:
    """Vertices and codes of every cell outline, vectorised over all pieces.

    Returns ``verts`` (V, 2), ``codes`` (V,), ``offsets`` (n + 1,) (cell i is
    ``verts[offsets[i]:offsets[i+1]]``: MOVETO, one LINETO per edge, three CURVE4 per Bezier arc
    segment, CLOSEPOLY), ``owner`` (piece -> cell), ``nxt`` (piece -> next piece of its cell),
    ``segs`` (arc segments per piece, 0 for edges).
    """
    from matplotlib.path import Path

    ptr = np.asarray(ptr, dtype=np.int64)
    n, m = len(ptr) - 1, int(ptr[-1])
    counts = np.diff(ptr)
    owner = np.repeat(np.arange(n), counts)
    nxt = np.arange(m) + 1
    last = ptr[1:] - 1
    nxt[last[counts > 0]] = ptr[:-1][counts > 0]
    is_arc = spans > 0.0
    segs = np.where(is_arc, np.maximum(1, np.ceil(spans / _MAX_SEGMENT - 1e-12)).astype(np.int64), 0)
    per_piece = np.where(is_arc, 3 * segs, 1)  # vertices each piece contributes
    total = int(per_piece.sum())

    # Vertex v of the pieces' stream belongs to piece `pid` and is its `local`-th vertex.
    pid = np.repeat(np.arange(m), per_piece)
    start_of = (np.cumsum(per_piece) - per_piece).astype(np.int64)
    local = np.arange(total) - start_of[pid]
    pv = np.empty((total, 2))
    pcode = np.full(total, Path.LINETO, dtype=Path.code_type)

    edge_v = ~is_arc[pid]
    pv[edge_v, 0] = xs[nxt[pid[edge_v]]]
    pv[edge_v, 1] = ys[nxt[pid[edge_v]]]

    arc_v = ~edge_v
    k = pid[arc_v]
    c = centers[owner[k]]
    a0 = np.arctan2(ys[k] - c[:, 1], xs[k] - c[:, 0])
    delta = spans[k] / segs[k]
    s, t = local[arc_v] // 3, local[arc_v] % 3
    a = a0 + s * delta
    b = a + delta
    kappa = 4.0 / 3.0 * np.tan(delta / 4.0)
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    px = np.select([t == 0, t == 1], [ca - kappa * sa, cb + kappa * sb], cb)
    py = np.select([t == 0, t == 1], [sa + kappa * ca, sb - kappa * cb], sb)
    # One radius, or one per agent (heterogeneous teams).
    r = radius if np.ndim(radius) == 0 else np.asarray(radius, dtype=float)[owner[k]]
    pv[arc_v, 0] = c[:, 0] + r * px
    pv[arc_v, 1] = c[:, 1] + r * py
    pcode[arc_v] = Path.CURVE4

    # Cell i: MOVETO, its pieces' vertices, CLOSEPOLY -> piece vertex v lands at v + 2 * cell + 1.
    cell_of_v = owner[pid]
    verts = np.empty((total + 2 * n, 2))
    codes = np.empty(total + 2 * n, dtype=Path.code_type)
    pos = np.arange(total) + 2 * cell_of_v + 1
    verts[pos] = pv
    codes[pos] = pcode
    cum = np.concatenate([[0], np.cumsum(np.bincount(owner, weights=per_piece, minlength=n))])
    cum = cum.astype(np.int64)  # piece vertices before cell i
    move = cum[:-1] + 2 * np.arange(n)
    close = cum[1:] + 2 * np.arange(n) + 1
    first = np.where(counts > 0, ptr[:-1], 0)
    verts[move, 0] = xs[first]
    verts[move, 1] = ys[first]
    codes[move] = Path.MOVETO
    verts[close] = verts[move]
    codes[close] = Path.CLOSEPOLY
    offsets = np.concatenate([move, [total + 2 * n]])
    return dict(verts=verts, codes=codes, offsets=offsets, owner=owner, nxt=nxt, segs=segs,
                arc_start=start_of)


def cell_paths(result: Any) -> List[Any]:
    """One closed matplotlib Path per cell of `result` (edges as lines, arcs as Bezier arcs)."""
    require_matplotlib("cell_paths()")
    from matplotlib.path import Path

    g = _geometry_of(result)
    off = g["offsets"]
    return [Path(g["verts"][off[i]:off[i + 1]], g["codes"][off[i]:off[i + 1]])
            for i in range(len(off) - 1)]


def _arrays(result: Any):
    return (np.asarray(result.piece_ptr, dtype=np.int64), np.asarray(result.piece_x, dtype=float),
            np.asarray(result.piece_y, dtype=float), np.asarray(result.piece_span, dtype=float),
            np.asarray(result.piece_neighbor, dtype=np.int64), np.asarray(result.points, dtype=float),
            np.asarray(result.radii, dtype=float) if hasattr(result, "radii") else float(result.radius))


def _geometry_of(result: Any) -> Dict[str, np.ndarray]:
    ptr, xs, ys, sp, _, pts, radius = _arrays(result)
    return _pieces_geometry(ptr, xs, ys, sp, pts, radius)


# ----------------------------------------------------------------------------- colours and sizes
#: The small palette of the neighbour colouring (ColorBrewer Set2): smallest-last greedy colouring
#: needs at most 6 colours on a planar graph (every cell neighbour relation here is planar).
PALETTE = ("#66c2a5", "#fc8d62", "#8da0cb", "#e78ac3", "#a6d854", "#ffd92f", "#e5c494", "#b3b3b3")

#: Edges and arcs are drawn only when a typical cell is at least this many pixels across.
MIN_CELL_PIXELS = 8.0


def neighbor_coloring(indptr: Any, indices: Any) -> np.ndarray:
    """Colour indices (0, 1, ...) such that neighbours in the CSR relation get different colours.

    Greedy colouring in smallest-last order (Matula & Beck): a graph whose every subgraph has a
    vertex of degree at most d gets at most d + 1 colours, so planar graphs (Voronoi and Delaunay
    neighbours) get at most 6. The relation is made symmetric first. O(n log n + m).
    """
    import heapq

    indptr = np.asarray(indptr, dtype=np.int64)
    indices = np.asarray(indices, dtype=np.int64)
    n = len(indptr) - 1
    rows = np.repeat(np.arange(n, dtype=np.int64), np.diff(indptr))
    ok = (indices >= 0) & (indices < n) & (indices != rows)
    a = np.concatenate([rows[ok], indices[ok]])
    b = np.concatenate([indices[ok], rows[ok]])
    pairs = np.unique(np.stack([a, b], axis=1), axis=0) if len(a) else np.zeros((0, 2), dtype=np.int64)
    ptr = np.searchsorted(pairs[:, 0], np.arange(n + 1))
    adj = [pairs[ptr[i]:ptr[i + 1], 1].tolist() for i in range(n)]
    degree = np.diff(ptr).tolist()
    heap = [(d, i) for i, d in enumerate(degree)]
    heapq.heapify(heap)
    removed = [False] * n
    order = []
    while heap:
        d, i = heapq.heappop(heap)
        if removed[i] or d != degree[i]:
            continue
        removed[i] = True
        order.append(i)
        for j in adj[i]:
            if not removed[j]:
                degree[j] -= 1
                heapq.heappush(heap, (degree[j], j))
    color = [-1] * n
    for i in reversed(order):
        used = {color[j] for j in adj[i]}
        c = 0
        while c in used:
            c += 1
        color[i] = c
    return np.asarray(color, dtype=np.int64)


def _relation(ptr: np.ndarray, nbs: np.ndarray, result: Any = None):
    """(indptr, indices): cell i has an edge piece towards j, or `result` names j among i's neighbours
    (a clipped cell may lose the edge it shares with a neighbour; the two get different colours anyway)."""
    n = len(ptr) - 1
    rows = [np.repeat(np.arange(n, dtype=np.int64), np.diff(ptr))[nbs >= 0]]
    cols = [nbs[nbs >= 0]]
    indptr = getattr(result, "indptr", None)
    indices = getattr(result, "indices", None)
    if indptr is not None and indices is not None and len(indptr) == n + 1:
        indptr = np.asarray(indptr, dtype=np.int64)
        rows.append(np.repeat(np.arange(n, dtype=np.int64), np.diff(indptr)))
        cols.append(np.asarray(indices, dtype=np.int64))
    r, c = np.concatenate(rows), np.concatenate(cols)
    order = np.argsort(r, kind="stable")
    return np.searchsorted(r[order], np.arange(n + 1)), c[order]


def _bounds_box(bounds: Any) -> Optional[np.ndarray]:
    """(xmin, ymin, xmax, ymax) of a box tuple or a (k, 2) polygon; None for None."""
    if bounds is None:
        return None
    arr = np.asarray(bounds, dtype=float)
    if arr.ndim == 1 and arr.shape == (4,):
        return arr.copy()
    arr = arr.reshape(-1, 2)
    return np.concatenate([arr.min(axis=0), arr.max(axis=0)])


def data_box(points: Any, radius: Any = None, bounds: Any = None) -> np.ndarray:
    """The box a plot shows by default, ``(xmin, ymin, xmax, ymax)``.

    With `bounds` (the region the result was computed in): its bounding box, 2 % wider. Else the
    agents' bounding box widened by the cell radius when it is finite (every limited cell fits), or
    by 5 % of its size (exact and network cells: hull cells and far circumcentres are cut there).
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    b = _bounds_box(bounds)
    if b is not None:
        lo, hi = b[:2], b[2:]
        if len(pts):
            lo, hi = np.minimum(lo, pts.min(axis=0)), np.maximum(hi, pts.max(axis=0))
        pad = 0.02 * float(np.max(hi - lo))
    elif len(pts):
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        r = np.atleast_1d(np.asarray(np.nan if radius is None else radius, dtype=float))
        r = r[np.isfinite(r) & (r > 0)]  # one radius, one per agent (heterogeneous teams) or none
        pad = float(r.max()) if len(r) else 0.05 * float(np.max(hi - lo))
    else:
        lo, hi, pad = np.zeros(2), np.ones(2), 0.0
    if not pad > 0:
        pad = 1.0
    return np.concatenate([lo - pad, hi + pad])


def _result_box(result: Any, points: Optional[np.ndarray] = None) -> np.ndarray:
    pts = np.asarray(result.points if points is None else points, dtype=float)
    traj = getattr(result, "trajectory", None)  # a Lloyd run: every position it went through
    if points is None and traj is not None:
        pts = np.asarray(traj, dtype=float).reshape(-1, 2)
    radius = getattr(result, "radii", getattr(result, "radius", None))
    return data_box(pts, radius, getattr(result, "bounds", None))


def _cell_points(ax: Any, n: int, box: np.ndarray) -> float:
    """The side of a typical cell in points (1/72 inch) when `box` fills `ax` at equal aspect."""
    fig = ax.figure
    pos = ax.get_position()
    w = max(fig.get_figwidth() * pos.width * 72.0, 1e-9)
    h = max(fig.get_figheight() * pos.height * 72.0, 1e-9)
    dx, dy = max(box[2] - box[0], 1e-300), max(box[3] - box[1], 1e-300)
    units_per_point = max(dx / w, dy / h)
    return float(np.sqrt(dx * dy / max(n, 1)) / units_per_point)


def _sizes(ax: Any, n: int, box: np.ndarray) -> Dict[str, Any]:
    """Line width and marker size (points) for `n` cells in `box`, and whether edges are visible."""
    cell = _cell_points(ax, n, box)
    pixels = cell * ax.figure.dpi / 72.0
    dot = float(np.clip(0.15 * cell, 0.6, 2.8))  # marker diameter
    return dict(linewidth=float(min(0.8, 0.06 * cell)), point_size=dot * dot,
                edges=pixels >= MIN_CELL_PIXELS, cell_pixels=pixels)


def _axes(ax: Any) -> Any:
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


def _clip_box(clip: Any, box: np.ndarray) -> Optional[np.ndarray]:
    if clip is True:
        return box
    if clip is False or clip is None:
        return None
    b = np.asarray(clip, dtype=float)
    if b.shape != (4,) or not (b[0] < b[2] and b[1] < b[3]):
        raise ValueError(f"clip must be True, False or a box (xmin, ymin, xmax, ymax), got {clip!r}")
    return b


def _clip(ax: Any, artists: List[Any], box: Optional[np.ndarray]) -> None:
    if box is None:
        return
    from matplotlib.patches import Rectangle

    rect = Rectangle((box[0], box[1]), box[2] - box[0], box[3] - box[1], transform=ax.transData)
    for a in artists:
        a.set_clip_path(rect)


def _finish(ax: Any, box: Optional[np.ndarray]) -> Any:
    """Equal aspect; the axes show `box` (or everything drawn, when not clipping)."""
    if box is None:
        ax.set_aspect("equal", adjustable="datalim")
        ax.autoscale_view()
    else:
        ax.set_xlim(box[0], box[2])
        ax.set_ylim(box[1], box[3])
        ax.set_aspect("equal", adjustable="box")
    return ax


# ----------------------------------------------------------------------------- cells
def _draw(ax, ptr, xs, ys, spans, nbs, centers, radius, points, *, single: bool, facecolor: Any,
          coloring: str, cmap: str, alpha: float, edgecolor: Any, arccolor: Any, linewidth: Optional[float],
          show_points: bool, point_color: Any, point_size: Optional[float], labels: bool, clip: Any,
          box: np.ndarray, result: Any = None):
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.path import Path

    ax = _axes(ax)
    g = _pieces_geometry(ptr, xs, ys, spans, centers, radius)
    off, verts, codes = g["offsets"], g["verts"], g["codes"]
    n = len(ptr) - 1
    size = _sizes(ax, n, box)
    lw = size["linewidth"] if linewidth is None else float(linewidth)
    show_lines = size["edges"] or linewidth is not None
    paths = [Path(verts[off[i]:off[i + 1]], codes[off[i]:off[i + 1]]) for i in range(n)]
    if facecolor is not None:
        colors: Any = [facecolor]
    elif coloring == "neighbors":
        color = neighbor_coloring(*_relation(ptr, nbs, result))
        colors = [PALETTE[c % len(PALETTE)] for c in color]
    elif coloring == "index":
        import matplotlib.pyplot as plt

        palette = plt.get_cmap(cmap)
        colors = palette(np.arange(n) % getattr(palette, "N", 256))
    else:
        raise ValueError(f'coloring must be "neighbors" or "index", got {coloring!r}')
    fill = PathCollection(paths, facecolors=colors, edgecolors="none", alpha=alpha)
    fill.set_gid("dvoronoi-cells")
    ax.add_collection(fill, autolim=True)

    # Edges: each shared edge once (owner < neighbour), every edge of a single cell.
    k = np.flatnonzero(spans <= 0.0)
    if not single:
        k = k[g["owner"][k] < nbs[k]]
    segments = np.stack([np.column_stack([xs[k], ys[k]]),
                         np.column_stack([xs[g["nxt"][k]], ys[g["nxt"][k]]])], axis=1)
    edges = LineCollection(list(segments), colors=edgecolor, linewidths=lw)
    edges.set_gid("dvoronoi-edges")
    edges.set_visible(show_lines)
    ax.add_collection(edges, autolim=True)

    # Arcs: one compound path, a MOVETO at each arc's start then its CURVE4 segments.
    arc = np.flatnonzero(spans > 0.0)
    segs = g["segs"][arc]
    piece_vertex_pos = g["arc_start"][arc] + 2 * g["owner"][arc] + 1  # first CURVE4 of each arc
    nv = 3 * segs
    within = np.arange(int(nv.sum())) - np.repeat(np.cumsum(nv) - nv, nv)
    idx = np.repeat(piece_vertex_pos, nv) + within
    starts = np.column_stack([xs[arc], ys[arc]])
    arc_verts = np.empty((len(arc) + len(idx), 2))
    arc_codes = np.empty(len(arc) + len(idx), dtype=Path.code_type)
    head = (np.cumsum(1 + nv) - (1 + nv)).astype(np.int64)
    body = np.ones(len(arc_verts), dtype=bool)
    body[head] = False
    arc_verts[head] = starts
    arc_codes[head] = Path.MOVETO
    arc_verts[body] = verts[idx]
    arc_codes[body] = Path.CURVE4
    arcs = PathCollection([Path(arc_verts, arc_codes)] if len(arc) else [], facecolors="none",
                          edgecolors=arccolor, linewidths=lw)
    arcs.set_gid("dvoronoi-arcs")
    arcs.set_visible(show_lines)
    ax.add_collection(arcs, autolim=True)
    shown = _clip_box(clip, box)
    _clip(ax, [fill, edges, arcs], shown)

    if show_points and len(points):
        s = size["point_size"] if point_size is None else float(point_size)
        dots = ax.scatter(points[:, 0], points[:, 1], s=s, c=[point_color], zorder=3, linewidths=0)
        dots.set_gid("dvoronoi-agents")
    if labels:
        for i, (x, y) in enumerate(points):
            ax.annotate(str(i), (x, y), textcoords="offset points", xytext=(2, 2), fontsize=7)
    return _finish(ax, shown)


_DEFAULTS: Dict[str, Any] = dict(facecolor=None, coloring="neighbors", cmap="tab20", alpha=0.55,
                                 edgecolor="0.15", arccolor="tab:blue", linewidth=None, show_points=True,
                                 point_color="k", point_size=None, labels=False, clip=True)


def _options(kwargs: Dict[str, Any], extra: Dict[str, Any] = {}) -> Dict[str, Any]:  # noqa: B006
    unknown = set(kwargs) - set(_DEFAULTS) - set(extra)
    if unknown:
        raise TypeError(f"plot() got unexpected keyword arguments {sorted(unknown)}")
    return {**_DEFAULTS, **extra, **kwargs}


def _wrong_nodes(ax: Any, result: Any, points: np.ndarray, size: float) -> None:
    """Mark the nodes whose answer differs from the exact one (``wrong_nodes``), if any."""
    wrong = getattr(result, "wrong_nodes", None)
    if wrong is None or len(wrong) == 0:
        return
    p = points[np.asarray(wrong, dtype=np.int64)]
    dots = ax.scatter(p[:, 0], p[:, 1], s=max(36.0, 6.0 * size), marker="X", c="red", edgecolors="k",
                      linewidths=0.5, zorder=6, label=f"wrong nodes ({len(p)})")
    dots.set_gid("dvoronoi-wrong-nodes")


def plot(result: Any, ax: Any = None, **kwargs: Any):
    """Draw every cell of a cell result (e.g. a :class:`~dvoronoi.LimitedPartition`).

    Defaults suit any number of cells: cells are filled by a neighbour colouring (neighbours differ,
    :data:`PALETTE`); line widths and dot sizes follow the typical cell's size on the figure, and
    edges are left out when a cell is below :data:`MIN_CELL_PIXELS` pixels across; the axes show
    :func:`data_box` and cells are clipped to it. Nodes in a ``wrong_nodes`` attribute are marked
    with a red X (gid ``"dvoronoi-wrong-nodes"``).

    Keyword arguments: ``facecolor`` (one colour for every cell), ``coloring`` ("neighbors", or
    "index": ``cmap`` by agent index), ``cmap`` ("tab20"), ``alpha`` (0.55), ``edgecolor`` ("0.15"),
    ``arccolor`` ("tab:blue"), ``linewidth`` (None: by size; a number draws edges at any size),
    ``show_points`` (True), ``point_color`` ("k"), ``point_size`` (None: by size), ``labels``
    (False: annotate agents with their index), ``clip`` (True: :func:`data_box`; False: show
    everything; or a box ``(xmin, ymin, xmax, ymax)``).

    Returns the matplotlib Axes.
    """
    require_matplotlib("plot()")
    opts = _options(kwargs)
    ptr, xs, ys, sp, nb, pts, radius = _arrays(result)
    box = _result_box(result)
    ax = _draw(ax, ptr, xs, ys, sp, nb, pts, radius, pts, single=False, box=box, result=result, **opts)
    _wrong_nodes(ax, result, pts, _sizes(ax, len(pts), box)["point_size"])
    return ax


def plot_cell(cell: Any, ax: Any = None, others: Optional[np.ndarray] = None, **kwargs: Any):
    """Draw one :class:`~dvoronoi.LimitedCell` (and, if given, the `others` it was computed from)."""
    require_matplotlib("plot_cell()")
    opts = _options(kwargs)
    if opts["point_size"] is None:
        opts["point_size"] = 8.0
    center = np.asarray(cell.center, dtype=float)[None, :]
    ptr = np.array([0, len(cell)], dtype=np.int64)
    pts = center if others is None else np.vstack([center, np.asarray(others, dtype=float)])
    if opts["clip"] is True:  # one cell: show it and the others, whatever their spread
        opts["clip"] = False
    return _draw(ax, ptr, np.asarray(cell.piece_x), np.asarray(cell.piece_y),
                 np.asarray(cell.piece_span), np.asarray(cell.piece_neighbor), center,
                 float(cell.radius), pts, single=True, box=data_box(center, float(cell.radius)), **opts)


# ----------------------------------------------------------------------------- networks
def plot_network(result: Any, ax: Any = None, *, link_color: Any = "0.7", linewidth: Optional[float] = None,
                 point_size: Optional[float] = None, clip: Any = True) -> Any:
    """Draw a network result's nodes, links (gid ``"dvoronoi-links"``) and obstacles, sized as
    :func:`plot` sizes cells; the axes show :func:`data_box` unless ``clip=False``."""
    require_matplotlib("plot_network()")
    from matplotlib.collections import LineCollection

    ax = _axes(ax)
    pts = np.asarray(result.points, dtype=float).reshape(-1, 2)
    box = _result_box(result)
    size = _sizes(ax, len(pts), box)
    links = LineCollection(list(pts[np.asarray(result.links, dtype=np.int64).reshape(-1, 2)]), colors=link_color,
                           linewidths=0.75 * size["linewidth"] if linewidth is None else linewidth, zorder=1)
    links.set_gid("dvoronoi-links")
    ax.add_collection(links)
    artists = [links]
    obstacles = np.asarray(getattr(result, "obstacles", np.zeros((0, 4))), dtype=float)
    if len(obstacles):
        walls = LineCollection(list(obstacles.reshape(-1, 2, 2)), colors="tab:red", zorder=2, label="obstacles",
                               linewidths=max(1.0, 2.5 * size["linewidth"]))
        walls.set_gid("dvoronoi-obstacles")
        ax.add_collection(walls)
        artists.append(walls)
    shown = _clip_box(clip, box)
    _clip(ax, artists, shown)
    nodes = ax.scatter(pts[:, 0], pts[:, 1], s=size["point_size"] if point_size is None else point_size,
                       c="k", zorder=3, linewidths=0)
    nodes.set_gid("dvoronoi-nodes")
    return _finish(ax, shown)


def _circumcenter(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    u, v = a - p, b - p
    d = 2.0 * (u[0] * v[1] - u[1] * v[0])
    uu, vv = u @ u, v @ v
    with np.errstate(divide="ignore", invalid="ignore"):
        return p + np.array([v[1] * uu - u[1] * vv, u[0] * vv - v[0] * uu]) / d


def _rot(v: np.ndarray) -> np.ndarray:
    return np.array([-v[1], v[0]])


def _hull_cell(result: Any, i: int, pts: np.ndarray, far: float) -> Optional[List[tuple]]:
    """Hull node `i`'s unbounded cell from CC's own counter-clockwise neighbour list, as pieces
    (x, y, neighbour) whose rays end `far` away (closed by two pieces of neighbour -1 through a point
    far out between them; the caller cuts the cell at the data's box). None when it has no finite
    shape (no neighbour, parallel bisectors)."""
    ccw = [int(j) for j in result.neighbors_ccw(i)]
    if not ccw:
        return None
    p = pts[i]
    t_in = _rot(pts[ccw[0]] - p)    # direction of the incoming ray (bisector with the first neighbour)
    t_out = _rot(pts[ccw[-1]] - p)  # and of the outgoing one (bisector with the last)
    t_in, t_out = t_in / np.linalg.norm(t_in), t_out / np.linalg.norm(t_out)
    if len(ccw) == 1:  # two nodes: a half-plane
        verts = [(pts[ccw[0]] + p) / 2.0]
    else:
        verts = [_circumcenter(p, pts[a], pts[b]) for a, b in zip(ccw[:-1], ccw[1:])]
    if not all(np.all(np.isfinite(v)) for v in verts):
        return None
    # The cell's directions to infinity turn counter-clockwise from t_out to -t_in: go out halfway.
    turn = np.arctan2(t_out[0] * -t_in[1] - t_out[1] * -t_in[0], t_out @ -t_in) % (2 * np.pi)
    c, s = np.cos(turn / 2), np.sin(turn / 2)
    mid = np.array([c * t_out[0] - s * t_out[1], s * t_out[0] + c * t_out[1]])
    start, end = verts[0] - far * t_in, verts[-1] + far * t_out
    out = 0.5 * (start + end) + far * mid
    # A piece starts at its vertex: the incoming ray (on the bisector with ccw[0]), the edge after
    # vertex j (with ccw[j + 1]; the outgoing ray with the last neighbour), then the closing pieces.
    pieces = [(start[0], start[1], ccw[0])]
    pieces += [(v[0], v[1], ccw[min(j + 1, len(ccw) - 1)]) for j, v in enumerate(verts)]
    pieces += [(end[0], end[1], -1), (out[0], out[1], -1)]
    return pieces


def _cc_pieces(result: Any, pts: np.ndarray, box: np.ndarray):
    """CC's piece arrays, with the hull cells of a run without bounds added (see _hull_cell)."""
    ptr, xs, ys, sp, nb = _arrays(result)[:5]
    if getattr(result, "bounds", None) is not None or not hasattr(result, "neighbors_ccw"):
        return ptr, xs, ys, sp, nb
    on_hull = np.asarray(result.on_hull, dtype=bool)
    reach = np.concatenate([np.abs(xs - (box[0] + box[2]) / 2), np.abs(ys - (box[1] + box[3]) / 2), [0.0]])
    far = 10.0 * (float(np.max(box[2:] - box[:2])) + float(np.max(reach)))
    out_ptr, out_x, out_y, out_nb = [0], [], [], []
    for i in range(len(ptr) - 1):
        a, b = int(ptr[i]), int(ptr[i + 1])
        pieces = _hull_cell(result, i, pts, far) if on_hull[i] and a == b else None
        if pieces is None:
            out_x.extend(xs[a:b])
            out_y.extend(ys[a:b])
            out_nb.extend(nb[a:b])
        else:
            out_x.extend(q[0] for q in pieces)
            out_y.extend(q[1] for q in pieces)
            out_nb.extend(q[2] for q in pieces)
        out_ptr.append(len(out_x))
    return (np.asarray(out_ptr, dtype=np.int64), np.asarray(out_x, dtype=float), np.asarray(out_y, dtype=float),
            np.zeros(len(out_x)), np.asarray(out_nb, dtype=np.int64))


def plot_cc(result: Any, ax: Any = None, *, network: bool = True, delaunay: bool = True, **kwargs: Any) -> Any:
    """A CC result (:class:`dvoronoi.network.CcResult`): the network, the cells (clipped to
    ``bounds`` when the run had them; else every cell, hull cells included, cut at :func:`data_box`;
    hull cells are built from CC's own neighbour order, so a wrong node's cell shows its error), the
    Delaunay graph (dashed, gid ``"dvoronoi-delaunay"``), hull nodes circled (``"dvoronoi-hull"``)
    and wrong nodes marked (``"dvoronoi-wrong-nodes"``). Keyword arguments as :func:`plot`."""
    require_matplotlib("plot()")
    from matplotlib.collections import LineCollection

    opts = _options(kwargs)
    ax = _axes(ax)
    pts = np.asarray(result.points, dtype=float).reshape(-1, 2)
    box = _result_box(result)
    shown = _clip_box(opts["clip"], box)
    size = _sizes(ax, len(pts), box)
    if network:
        plot_network(result, ax=ax, clip=opts["clip"])
    ptr, xs, ys, sp, nb = _cc_pieces(result, pts, box)
    if len(xs):
        _draw(ax, ptr, xs, ys, sp, nb, pts, float("nan"), pts, single=False, box=box, result=result,
              **{**opts, "show_points": False})
    lw = size["linewidth"] if opts["linewidth"] is None else float(opts["linewidth"])
    if delaunay:
        e = result.delaunay_edges()
        dt = LineCollection(pts[e], colors="tab:blue", linewidths=0.7 * lw, linestyles="--", zorder=2)
        dt.set_gid("dvoronoi-delaunay")
        dt.set_visible(size["edges"] or opts["linewidth"] is not None)
        ax.add_collection(dt)
        _clip(ax, [dt], shown)
    hull = pts[np.asarray(result.on_hull, dtype=bool)]
    ring = ax.scatter(hull[:, 0], hull[:, 1], s=max(4.0, 4.0 * size["point_size"]), facecolors="none",
                      edgecolors="tab:red", linewidths=max(0.3, lw), zorder=4)
    ring.set_gid("dvoronoi-hull")
    _wrong_nodes(ax, result, pts, size["point_size"])
    return _finish(ax, shown)


# ----------------------------------------------------------------------------- exact cells
def _turn_half(d_out: np.ndarray, d_back: np.ndarray) -> np.ndarray:
    """The unit direction halfway from `d_out` counter-clockwise to `d_back`."""
    turn = np.arctan2(d_out[0] * d_back[1] - d_out[1] * d_back[0], d_out @ d_back) % (2 * np.pi)
    c, s = np.cos(turn / 2), np.sin(turn / 2)
    return np.array([c * d_out[0] - s * d_out[1], s * d_out[0] + c * d_out[1]])


def _unbounded_polygon(edges: List[Any], far: float) -> List[tuple]:
    """An unbounded exact cell as pieces (x, y, neighbour): rays end `far` away and are joined through
    a point far out between them (neighbour -1), so the cell is right wherever it is cut nearer."""
    k = len(edges)
    out: List[tuple] = []
    for j, e in enumerate(edges):
        s, t, d = np.asarray(e.start, float), np.asarray(e.end, float), np.asarray(e.direction, float)
        if e.from_infinity:  # `start` is a point of the line, the finite vertex (if any) is `end`
            p = (s if e.to_infinity else t) - far * d
            out.append((p[0], p[1], int(e.neighbor)))
        else:
            out.append((s[0], s[1], int(e.neighbor)))
        if e.to_infinity:
            q = s + far * d
            nxt = edges[(j + 1) % k]
            d_in = np.asarray(nxt.direction, float)
            n_s, n_t = np.asarray(nxt.start, float), np.asarray(nxt.end, float)
            p_in = (n_s if nxt.to_infinity else n_t) - far * d_in
            m = 0.5 * (q + p_in) + far * _turn_half(d, -d_in)
            out += [(q[0], q[1], -1), (m[0], m[1], -1)]
    return out


def _voronoi_pieces(result: Any, box: np.ndarray):
    """Piece arrays of an exact partition: clipped cells with bounds; else bounded cells as they are
    and hull cells with their rays ended far beyond `box`."""
    n = len(result)
    pts = np.asarray(result.points, dtype=float).reshape(-1, 2)
    far = 10.0 * float(np.max(box[2:] - box[:2]) + np.max(np.abs(box)))
    ptr, xs, ys, nbs = [0], [], [], []
    for i in range(n):
        c = result.cell(i)
        clipped = getattr(c, "clipped", None)
        if clipped is not None:
            v = np.asarray(clipped.vertices, dtype=float).reshape(-1, 2)
            side = np.asarray(clipped.side_neighbors, dtype=np.int64)
            pieces = [(x, y, int(side[k]) if k < len(side) else -1) for k, (x, y) in enumerate(v)]
        elif not result.on_hull[i]:
            pieces = [(e.start[0], e.start[1], int(e.neighbor)) for e in c.edges]
        elif len(c.edges):
            pieces = _unbounded_polygon(list(c.edges), far)
        else:  # a single agent: the plane
            pieces = [(pts[i, 0] + far * a, pts[i, 1] + far * b, -1) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        xs += [q[0] for q in pieces]
        ys += [q[1] for q in pieces]
        nbs += [q[2] for q in pieces]
        ptr.append(len(xs))
    return (np.asarray(ptr, dtype=np.int64), np.asarray(xs, dtype=float), np.asarray(ys, dtype=float),
            np.zeros(len(xs)), np.asarray(nbs, dtype=np.int64))


def plot_voronoi(result: Any, ax: Any = None, *, cells: bool = True, delaunay: bool = False, **kwargs: Any) -> Any:
    """An exact partition (:class:`dvoronoi.VoronoiPartition`): the cells (clipped to ``bounds`` when
    given; else every cell, hull cells included, cut at :func:`data_box`), the agents, hull agents
    circled (gid ``"dvoronoi-hull"``) and, with ``delaunay=True``, the Delaunay graph
    (``"dvoronoi-delaunay"``). Keyword arguments as :func:`plot`."""
    require_matplotlib("plot()")
    from matplotlib.collections import LineCollection

    opts = _options(kwargs)
    ax = _axes(ax)
    pts = np.asarray(result.points, dtype=float).reshape(-1, 2)
    box = _result_box(result)
    shown = _clip_box(opts["clip"], box)
    size = _sizes(ax, len(pts), box)
    lw = size["linewidth"] if opts["linewidth"] is None else float(opts["linewidth"])
    if cells and len(pts):
        ptr, xs, ys, sp, nb = _voronoi_pieces(result, box)
        _draw(ax, ptr, xs, ys, sp, nb, pts, float("nan"), pts, single=False, box=box, result=result, **opts)
    elif opts["show_points"] and len(pts):
        dots = ax.scatter(pts[:, 0], pts[:, 1], s=size["point_size"] if opts["point_size"] is None
                          else opts["point_size"], c=[opts["point_color"]], zorder=3, linewidths=0)
        dots.set_gid("dvoronoi-agents")
    if delaunay and len(pts):
        dt = LineCollection(pts[result.delaunay_edges()], colors="tab:orange", linewidths=0.75 * lw, zorder=2)
        dt.set_gid("dvoronoi-delaunay")
        dt.set_visible(size["edges"] or opts["linewidth"] is not None)
        ax.add_collection(dt)
        _clip(ax, [dt], shown)
    hull = pts[np.asarray(result.on_hull, dtype=bool)] if len(pts) else pts
    ring = ax.scatter(hull[:, 0], hull[:, 1], s=max(4.0, 4.0 * size["point_size"]), facecolors="none",
                      edgecolors="tab:red", linewidths=max(0.3, lw), zorder=4, label="hull agents")
    ring.set_gid("dvoronoi-hull")
    bounds = getattr(result, "bounds", None)
    if bounds is not None:
        r = np.asarray(bounds, dtype=float).reshape(-1, 2)
        if len(r) == 2:  # a (2, 2) box
            r = np.array([[r[0, 0], r[0, 1]], [r[1, 0], r[0, 1]], [r[1, 0], r[1, 1]], [r[0, 0], r[1, 1]]])
        r = np.vstack([r, r[:1]])
        ax.plot(r[:, 0], r[:, 1], color="0.15", linewidth=max(0.5, lw), gid="dvoronoi-bounds")
    return _finish(ax, shown)


# ----------------------------------------------------------------------------- coverage (Lloyd)
def _block_max(img: np.ndarray, k: int) -> np.ndarray:
    """The largest value of each k x k block (the last blocks of a row or column may be smaller)."""
    if k <= 1:
        return img
    rows = np.maximum.reduceat(img, np.arange(0, img.shape[0], k), axis=0)
    return np.maximum.reduceat(rows, np.arange(0, img.shape[1], k), axis=1)


_BLOCK_MAX_IMAGE: Any = None


def _block_max_image_type() -> Any:
    """An AxesImage that shows its full image (``_full``, extent ``_full_extent``) reduced by
    _block_max for each drawing: k follows the renderer's pixels and the axes' view. Made on first
    use (matplotlib is optional)."""
    global _BLOCK_MAX_IMAGE
    if _BLOCK_MAX_IMAGE is not None:
        return _BLOCK_MAX_IMAGE
    from matplotlib.image import AxesImage

    def reduce_for(self: Any, box: Any) -> None:
        H, W = self._full.shape
        e = self._full_extent
        (x0, x1), (y0, y1) = sorted(self.axes.get_xlim()), sorted(self.axes.get_ylim())
        cols = W * (x1 - x0) / abs(e[1] - e[0])  # image pixels across the view
        rows = H * (y1 - y0) / abs(e[3] - e[2])
        k = max(1, int(np.ceil(max(rows / max(box.height, 1.0), cols / max(box.width, 1.0)))))
        if k != self.block:
            self.block = k
            self.set_data(_block_max(self._full, k))

    def make_image(self: Any, renderer: Any, magnification: float = 1.0, unsampled: bool = False) -> Any:
        self.reduce_for(self.axes.get_window_extent(renderer))  # this renderer's dpi and the view
        return AxesImage.make_image(self, renderer, magnification, unsampled)

    _BLOCK_MAX_IMAGE = type("BlockMaxImage", (AxesImage,), {"block": 0, "reduce_for": reduce_for, "make_image": make_image})
    return _BLOCK_MAX_IMAGE


def category_image(ax: Any, img: np.ndarray, extent: Tuple[float, float, float, float], **imshow: Any) -> Any:
    """An image of small integers (row 0 at the top; larger values are drawn over smaller ones) that
    stays readable at any size: when the axes show more of its pixels than they have display pixels
    (a large map, a small figure, a low savefig dpi), each drawing shows the largest value of each
    k x k block, so that a line one pixel wide stays visible (nearest-neighbour sampling would keep
    one row in k and drop the rest); zoomed in, the pixels themselves. Blocks are placed to within a
    display pixel. Returns the AxesImage (``gid`` and the other keywords as for imshow)."""
    vmin, vmax = imshow.pop("vmin", None), imshow.pop("vmax", None)
    image = _block_max_image_type()(ax, interpolation="nearest", origin="upper", extent=extent, **imshow)
    image._full, image._full_extent = img, extent
    image.set_clim(vmin, vmax)
    image.reduce_for(ax.get_window_extent())
    ax.add_image(image)
    image.set_extent(extent)  # the axes' data limits, as imshow sets them
    return image


def density_image(density: Any, box: Any, bounds: Any = None, pixels: int = 200) -> np.ndarray:
    """The density sampled at pixel centres of `box` (rows are y, row 0 at ``ymin``), NaN outside
    the convex polygon `bounds` when given; what the Lloyd plots show as background."""
    from matplotlib.path import Path

    from .coverage import _evaluate

    x0, y0, x1, y1 = map(float, box)
    nx = max(2, int(round(pixels * min(1.0, (x1 - x0) / (y1 - y0)))))
    ny = max(2, int(round(pixels * min(1.0, (y1 - y0) / (x1 - x0)))))
    xs = x0 + (np.arange(nx) + 0.5) * (x1 - x0) / nx
    ys = y0 + (np.arange(ny) + 0.5) * (y1 - y0) / ny
    gx, gy = np.meshgrid(xs, ys)
    img = _evaluate(density, gx.ravel(), gy.ravel())
    if bounds is not None and np.ndim(bounds) == 2:
        inside = Path(np.asarray(bounds, dtype=float)).contains_points(np.column_stack([gx.ravel(), gy.ravel()]))
        img = np.where(inside, img, np.nan)
    return img.reshape(ny, nx)


def _density_artist(ax: Any, image: np.ndarray, box: np.ndarray, cmap: str) -> Any:
    top = float(np.nanmax(image)) if np.any(np.isfinite(image)) else 1.0
    im = ax.imshow(image, origin="lower", extent=(box[0], box[2], box[1], box[3]), cmap=cmap,
                   interpolation="bilinear", zorder=0, aspect="equal", vmin=0.0,
                   vmax=1.6 * top if top > 0 else 1.0)  # the densest place mid-grey: cells stay readable
    im.set_gid("dvoronoi-density")
    return im


def _trajectories(ax: Any, traj: np.ndarray, linewidth: float) -> Any:
    from matplotlib.collections import LineCollection

    lines = LineCollection(list(np.transpose(traj, (1, 0, 2))), colors="0.25", linewidths=linewidth,
                           zorder=2)
    lines.set_gid("dvoronoi-trajectories")
    ax.add_collection(lines)
    return lines


def plot_coverage(result: Any, ax: Any = None, *, density: bool = True, trajectories: bool = True,
                  density_cmap: str = "Greys", **kwargs: Any) -> Any:
    """Coverage cells (:class:`dvoronoi.coverage.CoverageCells`) and the environment's outline (gid
    ``"dvoronoi-bounds"``); for a Lloyd run also the density as a background image (``density=True``
    and a non-uniform density; gid ``"dvoronoi-density"``) and every agent's path (``trajectories=True``;
    one line per agent in the LineCollection ``"dvoronoi-trajectories"``). Other keyword arguments as
    :func:`plot` (cells are more transparent over a density)."""
    require_matplotlib("plot()")
    ax = _axes(ax)
    box = _result_box(result)
    phi = getattr(result, "density", None)
    bounds = getattr(result, "bounds", None)
    if density and phi is not None:
        _density_artist(ax, density_image(phi, box, bounds), box, density_cmap)
        kwargs.setdefault("alpha", 0.25)
    plot(result, ax=ax, **kwargs)
    traj = getattr(result, "trajectory", None)
    if trajectories and traj is not None and len(traj) > 1:
        size = _sizes(ax, len(result.points), box)
        lines = _trajectories(ax, np.asarray(traj, dtype=float), max(0.3, size["linewidth"]))
        _clip(ax, [lines], _clip_box(kwargs.get("clip", True), box))
    if bounds is not None:
        ring = np.asarray(bounds, dtype=float).reshape(-1, 2)
        ring = np.vstack([ring, ring[:1]])
        ax.plot(ring[:, 0], ring[:, 1], color="0.15", linewidth=1.2, gid="dvoronoi-bounds")
    return _finish(ax, _clip_box(kwargs.get("clip", True), box))


def _output_mode() -> int:
    """The mode a new file gets: 0666 less the process's umask (0644 under the usual 022)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def _writer(path: Any, fps: int) -> Any:
    """The matplotlib writer for `path`: Pillow for ``.gif``, ffmpeg for ``.mp4``."""
    from matplotlib import animation

    suffix = os.path.splitext(os.fspath(path))[1].lower()
    if suffix == ".gif":
        return animation.PillowWriter(fps=fps)
    if suffix == ".mp4":
        if not animation.FFMpegWriter.isAvailable():
            raise RuntimeError("writing .mp4 needs ffmpeg on the PATH; write a .gif instead")
        return animation.FFMpegWriter(fps=fps)
    raise ValueError(f"path must end in .gif or .mp4, got {os.fspath(path)!r}")


def animation_output(path: Any, fps: int, progress: Any) -> Tuple[Any, Any]:
    """What writing an animation to `path` needs, checked before any drawing: the writer (``.gif``:
    Pillow, ``.mp4``: ffmpeg) and the progress bar's class (None for no bar). `progress`: None shows a
    tqdm bar over the frames when tqdm is installed; True always (tqdm needed), False never; a
    callable is called as ``progress(done_frames, frames)`` instead."""
    writer = _writer(path, fps)
    bar_class = None if callable(progress) or progress is False else tqdm_class(required=progress is True)
    return writer, bar_class


def save_animation(anim: Any, fig: Any, path: Any, frames: int, output: Tuple[Any, Any], dpi: int = 100,
                   progress: Any = None) -> None:
    """Writes `anim` (`frames` frames) to `path` with `output` (animation_output's) so that the file
    appears only when complete, with the mode of any new file (0644 under umask 022); then closes
    `fig`."""
    import tempfile

    import matplotlib.pyplot as plt

    writer, bar_class = output
    folder = os.path.dirname(os.path.abspath(os.fspath(path)))
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(os.fspath(path)) + ".", suffix=suffix, dir=folder)
    os.close(fd)
    bar = bar_class(total=frames, unit="frames", desc="animate") if bar_class is not None else None

    def report(i: int, total: int) -> None:  # matplotlib counts frames from 0
        if bar is not None:
            bar.update(i + 1 - bar.n)
        else:
            progress(i + 1, total)

    try:
        anim.save(tmp, writer=writer, dpi=dpi,
                  progress_callback=report if bar is not None or callable(progress) else None)
        os.chmod(tmp, _output_mode())  # mkstemp makes 0600; give it what any new file gets
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    finally:
        if bar is not None:
            bar.close()
        plt.close(fig)


def coverage_frame(result: Any, k: int) -> Any:
    """The clipped cells of a Lloyd run's recorded frame k (each agent with its own radius)."""
    from . import _core
    from .coverage import CoverageCells

    radii = np.asarray(result.radii, dtype=float) if hasattr(result, "radii") else None
    arrays = _core.coverage_cells(np.asarray(result.trajectory[k], dtype=float), float(result.radius),
                                  result.bounds, radii=radii)
    return CoverageCells(arrays, result.bounds)


def animate(result: Any, path: Any = None, fps: int = 10, cells: bool = True, dpi: int = 100,
            figsize: Tuple[float, float] = (6.0, 6.0), progress: Any = None, density: bool = True,
            trails: bool = True):
    """Animate a Lloyd run (:class:`dvoronoi.coverage.LloydResult`): agents (and, with
    ``cells=True``, their clipped cells recomputed at every recorded frame) over the recorded
    frames, the density as background (``density=True``), each agent's path so far (``trails``), the
    cost in the title.

    `path` ending in ``.gif`` is written with Pillow, ``.mp4`` with ffmpeg (must be installed); the
    file appears only when complete, with the mode of any new file (0644 under umask 022). `progress`:
    None shows a tqdm bar over the frames while writing a file when tqdm is installed; True always
    (tqdm needed), False never; a callable is called as ``progress(done_frames, frames)``. Returns the
    ``matplotlib.animation.FuncAnimation``.
    """
    require_matplotlib("animate()")
    import matplotlib.pyplot as plt
    from matplotlib import animation

    from . import _args

    fps = _args.integer(fps, "fps", 1, _args.MAX_COUNT)
    output = animation_output(path, fps, progress) if path is not None else None  # errors before drawing
    traj = np.asarray(result.trajectory, dtype=float)
    fig, ax = plt.subplots(figsize=figsize, dpi=dpi)
    lo = traj.reshape(-1, 2).min(axis=0) - result.radius
    hi = traj.reshape(-1, 2).max(axis=0) + result.radius
    if result.bounds is not None:
        lo = np.minimum(lo, result.bounds.min(axis=0))
        hi = np.maximum(hi, result.bounds.max(axis=0))
    box = np.concatenate([lo, hi])
    phi = getattr(result, "density", None)
    image = density_image(phi, box, result.bounds) if density and phi is not None else None
    size = _sizes(ax, traj.shape[1], box)

    def draw(k: int):
        ax.clear()
        if image is not None:
            _density_artist(ax, image, box, "Greys")
        if cells:
            extra: Dict[str, Any] = {"alpha": 0.25} if image is not None else {}
            plot_coverage(coverage_frame(result, k), ax=ax, clip=tuple(box), **extra)
        else:
            ax.scatter(traj[k, :, 0], traj[k, :, 1], s=size["point_size"], c="k")
        if trails and k > 0:
            _trajectories(ax, traj[:k + 1], max(0.3, size["linewidth"]))
        _finish(ax, box)
        s = int(result.frame_steps[k])
        ax.set_title(f"step {s}   H = {result.cost[s]:.6g}")
        return ()

    anim = animation.FuncAnimation(fig, draw, frames=len(traj), blit=False)
    if output is not None:
        save_animation(anim, fig, path, len(traj), output, dpi=dpi, progress=progress)
    return anim
