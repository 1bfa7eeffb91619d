"""Matplotlib pictures of range-limited Voronoi cells.

Cells are filled, straight edges are drawn as line segments and arcs as arcs: cubic Bezier arcs of
at most 1/16 turn each (the construction of matplotlib's ``Path.arc`` and ``patches.Arc``; such a
curve stays within ``7e-8 R`` of the circle, far below a pixel), agents as dots, equal aspect.
Everything is built with numpy in one pass over the flat piece arrays, so large partitions draw fast.

The artists carry gids so they can be found again: ``"dvoronoi-cells"`` (one filled path per cell),
``"dvoronoi-edges"`` (a LineCollection, each shared edge once), ``"dvoronoi-arcs"`` (one compound
path: a MOVETO and CURVE4 segments per arc) and ``"dvoronoi-agents"`` (the agents).
"""
from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np

__all__ = ["plot", "plot_cell", "cell_paths"]

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


def _draw(ax, ptr, xs, ys, spans, nbs, centers, radius, points, *, single: bool, facecolor: Any,
          cmap: str, alpha: float, edgecolor: Any, arccolor: Any, linewidth: float,
          show_points: bool, point_color: Any, point_size: float, labels: bool):
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.path import Path

    if ax is None:
        _, ax = plt.subplots()
    g = _pieces_geometry(ptr, xs, ys, spans, centers, radius)
    off, verts, codes = g["offsets"], g["verts"], g["codes"]
    n = len(ptr) - 1
    paths = [Path(verts[off[i]:off[i + 1]], codes[off[i]:off[i + 1]]) for i in range(n)]
    if facecolor is None:
        palette = plt.get_cmap(cmap)
        colors = palette(np.arange(n) % getattr(palette, "N", 256))
    else:
        colors = [facecolor]
    fill = PathCollection(paths, facecolors=colors, edgecolors="none", alpha=alpha)
    fill.set_gid("dvoronoi-cells")
    ax.add_collection(fill, autolim=True)

    # Edges: each shared edge once (owner < neighbour), every edge of a single cell.
    k = np.flatnonzero(spans <= 0.0)
    if not single:
        k = k[g["owner"][k] < nbs[k]]
    segments = np.stack([np.column_stack([xs[k], ys[k]]),
                         np.column_stack([xs[g["nxt"][k]], ys[g["nxt"][k]]])], axis=1)
    edges = LineCollection(segments, colors=edgecolor, linewidths=linewidth)
    edges.set_gid("dvoronoi-edges")
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
                          edgecolors=arccolor, linewidths=linewidth)
    arcs.set_gid("dvoronoi-arcs")
    ax.add_collection(arcs, autolim=True)

    if show_points and len(points):
        dots = ax.scatter(points[:, 0], points[:, 1], s=point_size, c=[point_color], zorder=3,
                          linewidths=0)
        dots.set_gid("dvoronoi-agents")
    if labels:
        for i, (x, y) in enumerate(points):
            ax.annotate(str(i), (x, y), textcoords="offset points", xytext=(2, 2), fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    return ax


_DEFAULTS = dict(facecolor=None, cmap="tab20", alpha=0.45, edgecolor="0.15", arccolor="tab:blue",
                 linewidth=0.8, show_points=True, point_color="k", point_size=8.0, labels=False)


def _options(kwargs: Dict[str, Any]) -> Dict[str, Any]:
    unknown = set(kwargs) - set(_DEFAULTS)
    if unknown:
        raise TypeError(f"plot() got unexpected keyword arguments {sorted(unknown)}")
    return {**_DEFAULTS, **kwargs}


def plot(result: Any, ax: Any = None, **kwargs: Any):
    """Draw every cell of a cell result (e.g. a :class:`~dvoronoi.LimitedPartition`).

    Keyword arguments: ``facecolor`` (one colour for every cell; default: ``cmap`` by agent index),
    ``cmap`` ("tab20"), ``alpha`` (0.45), ``edgecolor`` ("0.15"), ``arccolor`` ("tab:blue"),
    ``linewidth`` (0.8), ``show_points`` (True), ``point_color`` ("k"), ``point_size`` (8),
    ``labels`` (False: annotate agents with their index).

    Returns the matplotlib Axes.
    """
    opts = _options(kwargs)
    ptr, xs, ys, sp, nb, pts, radius = _arrays(result)
    return _draw(ax, ptr, xs, ys, sp, nb, pts, radius, pts, single=False, **opts)


def plot_cell(cell: Any, ax: Any = None, others: Optional[np.ndarray] = None, **kwargs: Any):
    """Draw one :class:`~dvoronoi.LimitedCell` (and, if given, the `others` it was computed from)."""
    opts = _options(kwargs)
    center = np.asarray(cell.center, dtype=float)[None, :]
    ptr = np.array([0, len(cell)], dtype=np.int64)
    pts = center if others is None else np.vstack([center, np.asarray(others, dtype=float)])
    return _draw(ax, ptr, np.asarray(cell.piece_x), np.asarray(cell.piece_y),
                 np.asarray(cell.piece_span), np.asarray(cell.piece_neighbor), center,
                 float(cell.radius), pts, single=True, **opts)
