"""Message-passing sensor networks: each node computes its Voronoi cell by exchanging messages, and we
count what that costs (SPEC "Networks of agents").

>>> import dvoronoi as dv
>>> res = dv.network.simulate("cc", points, comm_range=20.0, loss=0.2, seed=1)
>>> res.neighbors(0), res.on_hull, res.total_transmissions, res.total_deliveries
>>> res.plot_messages()

One call in C++ runs the whole simulation, ``dvoronoi::network::run`` (``network/run.hpp``): the
graph, the algorithm, and every node's cell with its area and centroid. The result classes here wrap
that compiled result (they pickle), and ``to_json()`` is the document ``io/network_json.hpp`` writes,
the same bytes as ``dvoronoi network ... -o run.json`` for the same run.

Algorithms (the simulator is C++: ``cpp/include/dvoronoi/network/``):

``"cc"``
    The completely cooperative algorithm (Núñez-Rodríguez et al.): the complete Voronoi diagram,
    Delaunay triangulation and convex hull. Exact whenever the Delaunay edges that are links form a
    connected graph (Theorem 2); ``condition`` and ``wrong_nodes`` report it (``verify=True``).
    Options: ``cap_adjacency`` / ``adjacency_cap`` and ``forward`` (Section 2.3's optimisations),
    ``routing`` ("gpsr" as in the paper, or "shortest": hop-shortest paths).
``"bd07"``
    Bash & Desnoyers: cells of the bounded region ``bounds`` (default: the points' bounding box,
    widened by 1 where it is flat), refined by probing cell vertices through GPSR. An empty network
    gives an empty result (``bounds`` None unless given).
``"bs"``
    Distributed Boundary Scan: every node broadcasts its position once and computes its limited cell
    of radius ``radius`` (default ``comm_range / 2``) by Boundary Scan. With ``anchors`` (node
    indices) or ``anchor_fraction`` the other nodes first localise themselves by DV-Hop and the cells
    are built from the estimated positions. DV-Hop's floods run in breadth-first rounds, each node
    forwarding each anchor's flood once (``dv_hop="sync"``, default) or in random asynchronous order
    passing on every improvement (``"async"``); anchors forward other anchors' floods only with
    ``anchors_relay=True`` (the Boundary Scan paper: anchors broadcast twice, their position and
    their hop size).

Route discovery (``route_discovery=True``, default, for CC and BD07 alike): where GPSR cannot deliver a
message addressed to a node (obstacles make the planar subgraph fail), the node floods a route request
and the message follows the answer; counted as message type ``discovery``. Neither paper has it; off,
such a message is lost (``lost_messages``).

Two counts (docs/spec.md), per node and message type: ``sent`` = **transmissions** (radio sends: a
broadcast to all neighbours is one, a unicast one per hop, every try counted) and ``received`` =
**link deliveries** (one per message per link that receives it). ``total_transmissions`` and
``total_deliveries`` sum them.

Links are the unit-disk graph (``|p - q| <= comm_range``) minus the links whose segment meets an
obstacle segment (``obstacles``: an ``(m, 4)`` array ``x0, y0, x1, y1``). Each try over a link fails
with probability ``loss`` and is repeated (a broadcast until every neighbour has it); every try is
counted. Messages are delivered in a random
order drawn from ``seed`` (one seed, one reproducible interleaving). A run that would send more than
``budget`` transmissions raises :class:`BudgetExceeded`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Dict, Optional, Sequence

import numpy as np

from . import _args, _core
from ._result import CellResult, Result

__all__ = ["simulate", "BudgetExceeded", "CcResult", "Bd07Result", "BoundaryScanResult", "NetworkCell",
           "links", "gpsr_route", "random_bars"]

BudgetExceeded = _core.BudgetExceeded

ALGORITHMS = ("cc", "bd07", "bs")


@dataclass(frozen=True)
class NetworkCell:
    """One node's cell: a closed counter-clockwise cycle of pieces starting at ``vertices[k]``.

    ``piece_neighbor[k]`` is the node across an edge, ``-1`` for an arc of the limiting circle
    (Boundary Scan) and ``-2 .. -5`` for the bottom, right, top and left side of the bounded region.
    """

    center: np.ndarray
    vertices: np.ndarray
    piece_neighbor: np.ndarray
    piece_span: np.ndarray
    area: float
    centroid: np.ndarray

    @property
    def neighbors(self) -> np.ndarray:
        nb = self.piece_neighbor[self.piece_neighbor >= 0]
        return np.unique(nb).astype(np.int64)


class _NetworkMixin:
    """Transmission counts and network pictures shared by every network result."""

    _core: Any

    # -- the compiled result's fields (network::run; copies cached per result)
    @property
    def algorithm(self) -> str:
        return str(self._core.algorithm)

    @cached_property
    def points(self) -> np.ndarray:
        return self._core.points

    @property
    def comm_range(self) -> float:
        return float(self._core.comm_range)

    @property
    def loss(self) -> float:
        return float(self._core.loss)

    @property
    def seed(self) -> int:
        return int(self._core.seed)

    @cached_property
    def obstacles(self) -> np.ndarray:
        """``(m, 4)`` obstacle segments ``x0, y0, x1, y1``."""
        return self._core.obstacles

    @cached_property
    def links(self) -> np.ndarray:
        """``(E, 2)`` int64 links ``i < j``."""
        return self._core.links

    @property
    def blocked_links(self) -> int:
        return int(self._core.blocked_links)

    @property
    def message_types(self) -> tuple:
        return tuple(self._core.message_types)

    @cached_property
    def sent(self) -> np.ndarray:
        return self._core.sent

    @cached_property
    def received(self) -> np.ndarray:
        return self._core.received

    @property
    def lost_messages(self) -> int:
        return int(self._core.lost_messages)

    @property
    def route_discoveries(self) -> int:
        """CC and BD07: route discoveries (floods) after GPSR could not deliver (obstacles)."""
        return int(self._core.route_discoveries)

    @cached_property
    def indptr(self) -> np.ndarray:
        return self._core.indptr

    @cached_property
    def indices(self) -> np.ndarray:
        return self._core.indices

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

    @cached_property
    def areas(self) -> np.ndarray:
        """Cell areas (``inf`` for an unbounded CC cell), computed in C++."""
        return self._core.areas

    @cached_property
    def centroids(self) -> np.ndarray:
        """Cell centroids (NaN for an unbounded CC cell), computed in C++."""
        return self._core.centroids

    def _json_text(self, indent: Optional[int]) -> str:
        """The document io/network_json.hpp writes (the CLI's ``-o run.json``, byte for byte)."""
        return str(self._core.to_json(indent))

    @property
    def total_transmissions(self) -> int:
        """Radio sends: a broadcast is one, a unicast one per hop, every try counted."""
        return int(self.sent.sum())

    @property
    def transmissions_by_type(self) -> Dict[str, int]:
        return {t: int(self.sent[:, k].sum()) for k, t in enumerate(self.message_types)}

    @property
    def total_deliveries(self) -> int:
        """Link deliveries: one per message per link that receives it."""
        return int(self.received.sum())

    @property
    def deliveries_by_type(self) -> Dict[str, int]:
        return {t: int(self.received[:, k].sum()) for k, t in enumerate(self.message_types)}

    @property
    def sent_per_node(self) -> np.ndarray:
        return self.sent.sum(axis=1)

    @property
    def received_per_node(self) -> np.ndarray:
        return self.received.sum(axis=1)

    def plot_network(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw the nodes, their links and the obstacles; returns the Axes (see
        :func:`dvoronoi.plotting.plot_network`)."""
        from . import plotting

        return plotting.plot_network(self, ax=ax, **kwargs)

    def _sent_columns(self):
        """(message type, transmissions sent per node) for the bar chart, in protocol order."""
        return [(t, self.sent[:, k]) for k, t in enumerate(self.message_types)]

    def plot_messages(self, ax: Any = None, received: bool = True) -> Any:
        """Bar chart of transmissions sent per node, stacked by message type (DV-Hop first for
        Boundary Scan with localisation, as the paper's Figure 12), received ones as dots."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(10, 3.5))
        x = np.arange(len(self.points))
        bottom = np.zeros(len(x))
        for t, v in self._sent_columns():
            ax.bar(x, v, bottom=bottom, width=0.8, label=f"sent: {t}")
            bottom += v
        if received:
            ax.plot(x, self.received_per_node, "k.", markersize=4, label="received (all types)")
        ax.set_xlabel("node")
        ax.set_ylabel("transmissions")
        ax.legend(fontsize="small")
        return ax


class _CellsMixin:
    """cell(i), GeoJSON and plots from flat piece arrays (polygons, or limited cells with arcs)."""

    piece_ptr: np.ndarray
    piece_neighbor: np.ndarray
    piece_x: np.ndarray
    piece_y: np.ndarray
    piece_span: np.ndarray
    areas: np.ndarray
    centroids: np.ndarray
    points: np.ndarray

    @property
    def radius(self) -> float:
        """The limiting circle's radius; NaN for polygon cells (CC, BD07)."""
        return float("nan")

    def cell(self, i: int) -> NetworkCell:
        i = self._index(i)  # type: ignore[attr-defined]
        a, b = self.piece_ptr[i], self.piece_ptr[i + 1]
        return NetworkCell(center=self.points[i].copy(),
                           vertices=np.column_stack([self.piece_x[a:b], self.piece_y[a:b]]),
                           piece_neighbor=self.piece_neighbor[a:b].copy(), piece_span=self.piece_span[a:b].copy(),
                           area=float(self.areas[i]), centroid=self.centroids[i].copy())

    def _geojson_text(self, tolerance: Optional[float]) -> str:
        """The document io/network_geojson.hpp writes (the CLI's ``-o cells.geojson``, byte for byte):
        one Feature per node, null geometry for a cell without a polygon (an unbounded CC hull cell,
        a node DV-Hop did not localise), properties ``agent``, ``area`` (null when infinite) and
        ``neighbors`` (``neighbors(i)``)."""
        return str(self._core.to_geojson(0.0 if tolerance is None else float(tolerance)))  # type: ignore[attr-defined]

    def plot_cells(self, ax: Any = None, network: bool = True, **kwargs: Any) -> Any:
        """The cells over the network (links and obstacles); returns the Axes."""
        from . import plotting

        ax = plotting.plot(self, ax=ax, **kwargs)
        if network:
            self.plot_network(ax=ax)  # type: ignore[attr-defined]
        return ax


class CcResult(_CellsMixin, _NetworkMixin, CellResult):
    """The CC algorithm's answer: every node's Voronoi neighbours, the Delaunay graph, the hull.

    Attributes
    ----------
    indptr, indices : int64
        Voronoi neighbours, CSR, ascending per node (``neighbors_ccw(i)`` keeps CC's own order).
    on_hull : (n,) bool
        The node's cell is unbounded (it is on the convex hull).
    condition : bool or None
        Theorem 2's condition: the Delaunay edges that are links form a connected graph (None when
        ``verify=False``).
    wrong_nodes : (k,) int64 or None
        Nodes whose neighbours or hull flag differ from the exact (centralised) answer.
    areas, centroids, cell(i)
        Only with ``bounds``: cells clipped to the box (hull cells are unbounded otherwise: their area
        is ``inf`` and ``cell(i)`` raises).
    sent, received : (n, T) int64
        Transmissions and link deliveries per node and message type (``message_types``: location,
        notify, discovery).
        ``discovery`` counts the route discoveries (floods and answers) that take over where GPSR
        cannot deliver (obstacles); ``route_discoveries`` is how many there were.
    """

    def __init__(self, core: "_core._NetworkCcRun") -> None:
        if not isinstance(core, _core._NetworkCcRun):
            raise TypeError("CcResult wraps a CC run; call dvoronoi.network.simulate('cc', ...)")
        self._core = core

    @cached_property
    def _ccw(self) -> np.ndarray:
        return self._core.neighbors_ccw

    @cached_property
    def on_hull(self) -> np.ndarray:
        return self._core.on_hull

    @property
    def condition(self) -> Optional[bool]:
        return self._core.condition

    @property
    def dt_components(self) -> Optional[int]:
        return self._core.dt_components

    @cached_property
    def wrong_nodes(self) -> Optional[np.ndarray]:
        return self._core.wrong_nodes

    @property
    def refinements(self) -> int:
        return int(self._core.refinements)

    @property
    def bounds(self) -> Optional[tuple]:
        """The box the cells were clipped to (None: not clipped)."""
        return self._core.bounds

    def cell(self, i: int) -> NetworkCell:
        i = self._index(i)
        if self.bounds is None and self.on_hull[i]:
            raise ValueError(f"node {i} is on the convex hull: its Voronoi cell is unbounded; pass "
                             "bounds=(xmin, ymin, xmax, ymax) to clip the cells")
        return super().cell(i)

    @property
    def exact(self) -> Optional[bool]:
        """Every node has its exact Voronoi neighbours and hull flag (None when not verified)."""
        return None if self.wrong_nodes is None else len(self.wrong_nodes) == 0

    def neighbors_ccw(self, i: int) -> np.ndarray:
        """Node `i`'s Voronoi neighbours counter-clockwise (a hull node's list runs from the neighbour
        across its incoming ray to the one across its outgoing ray)."""
        i = self._index(i)
        return self._ccw[self.indptr[i]:self.indptr[i + 1]]

    def delaunay_edges(self) -> np.ndarray:
        """The Delaunay graph as an ``(E, 2)`` int64 array of pairs ``i < j``."""
        n = len(self)
        rows = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.indptr))
        keep = self.indices > rows
        return np.stack([rows[keep], self.indices[keep]], axis=1)

    def convex_hull(self) -> np.ndarray:
        """Hull nodes in counter-clockwise order, starting at the lowest index (a hull node's
        counter-clockwise neighbour list starts with the next hull node), nodes inside hull edges
        included. Needs no message: CC's cells already say it (Section 3)."""
        hull = np.flatnonzero(self.on_hull)
        if len(hull) <= 2:
            return hull
        nxt = {int(i): int(self.neighbors_ccw(int(i))[0]) for i in hull if len(self.neighbors_ccw(int(i)))}
        start = int(hull[0])
        order, cur = [start], nxt.get(start)
        while cur is not None and cur != start and len(order) <= len(hull):
            order.append(cur)
            cur = nxt.get(cur)
        return np.asarray(order, dtype=np.int64)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Cells (clipped if bounds were given; interior cells otherwise), the Delaunay graph, the
        network and wrong nodes; returns the Axes (see :func:`dvoronoi.plotting.plot_cc`)."""
        from . import plotting

        return plotting.plot_cc(self, ax=ax, **kwargs)

    def __repr__(self) -> str:
        return (f"CcResult(n={len(self)}, transmissions={self.total_transmissions}, "
                f"hull_nodes={int(self.on_hull.sum())}, condition={self.condition}, exact={self.exact})")


class Bd07Result(_CellsMixin, _NetworkMixin, CellResult):
    """BD07's answer: the Voronoi cells clipped to the bounded region, found by GPSR probes.

    ``indptr``/``indices``: nodes across an edge of the clipped cell (ascending); ``cell(i)``,
    ``areas``, ``centroids``; ``probes`` vertices probed; message types location, probe, reply.
    """

    def __init__(self, core: "_core._NetworkBd07Run") -> None:
        if not isinstance(core, _core._NetworkBd07Run):
            raise TypeError("Bd07Result wraps a BD07 run; call dvoronoi.network.simulate('bd07', ...)")
        self._core = core

    @property
    def bounds(self) -> Optional[tuple]:
        """The region of the run; None for an empty network without bounds."""
        return self._core.bounds

    @property
    def probes(self) -> int:
        return int(self._core.probes)

    @property
    def condition(self) -> Optional[bool]:
        return self._core.condition

    @property
    def dt_components(self) -> Optional[int]:
        return self._core.dt_components

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        return self.plot_cells(ax=ax, **kwargs)

    def __repr__(self) -> str:
        return f"Bd07Result(n={len(self)}, transmissions={self.total_transmissions}, probes={self.probes})"


class BoundaryScanResult(_CellsMixin, _NetworkMixin, CellResult):
    """Distributed Boundary Scan (optionally after DV-Hop localisation): limited cells of radius
    ``radius`` around the positions the nodes used (``positions``: true, or DV-Hop estimates).

    ``sent``/``received`` count the Boundary Scan phase (message type position); with DV-Hop,
    ``dv_hop_sent``/``dv_hop_received`` count the localisation (anchor_flood, hop_size), and
    ``estimates``, ``localized``, ``position_error``, ``anchors`` describe it.
    """

    def __init__(self, core: "_core._NetworkBsRun") -> None:
        if not isinstance(core, _core._NetworkBsRun):
            raise TypeError("BoundaryScanResult wraps a Boundary Scan run; call dvoronoi.network.simulate('bs', ...)")
        self._core = core

    @property
    def radius(self) -> float:
        return float(self._core.radius)

    @cached_property
    def positions(self) -> np.ndarray:
        """The positions the nodes used: true ones, or DV-Hop estimates (NaN: not localised)."""
        return self._core.positions

    @cached_property
    def perimeters(self) -> np.ndarray:
        return self._core.perimeters

    @property
    def dropped_coincident(self) -> int:
        return int(self._core.dropped_coincident)

    @cached_property
    def anchors(self) -> Optional[np.ndarray]:
        """The anchor nodes (given, or picked with ``anchor_fraction``); None without DV-Hop."""
        return self._core.anchors

    @cached_property
    def estimates(self) -> Optional[np.ndarray]:
        """DV-Hop's positions (the ``positions`` used); None without DV-Hop."""
        return self.positions if self._core.localised else None

    @cached_property
    def localized(self) -> np.ndarray:
        return self._core.localized

    @cached_property
    def hop_size(self) -> Optional[np.ndarray]:
        return self._core.hop_size

    @property
    def dv_hop_types(self) -> tuple:
        return tuple(self._core.dv_hop_types)

    @cached_property
    def dv_hop_sent(self) -> np.ndarray:
        return self._core.dv_hop_sent

    @cached_property
    def dv_hop_received(self) -> np.ndarray:
        return self._core.dv_hop_received

    @property
    def position_error(self) -> np.ndarray:
        """Distance between the position used and the true one (0 for anchors, NaN if not localised)."""
        return np.linalg.norm(self.positions - self.points, axis=1)

    @property
    def total_transmissions(self) -> int:
        return int(self.sent.sum() + self.dv_hop_sent.sum())

    @property
    def transmissions_by_type(self) -> Dict[str, int]:
        out = {t: int(self.dv_hop_sent[:, k].sum()) for k, t in enumerate(self.dv_hop_types)}
        out.update({t: int(self.sent[:, k].sum()) for k, t in enumerate(self.message_types)})
        return out

    @property
    def total_deliveries(self) -> int:
        return int(self.received.sum() + self.dv_hop_received.sum())

    @property
    def deliveries_by_type(self) -> Dict[str, int]:
        out = {t: int(self.dv_hop_received[:, k].sum()) for k, t in enumerate(self.dv_hop_types)}
        out.update({t: int(self.received[:, k].sum()) for k, t in enumerate(self.message_types)})
        return out

    @property
    def sent_per_node(self) -> np.ndarray:
        return self.sent.sum(axis=1) + self.dv_hop_sent.sum(axis=1)

    @property
    def received_per_node(self) -> np.ndarray:
        return self.received.sum(axis=1) + self.dv_hop_received.sum(axis=1)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The limited cells around the positions used, with the network drawn at the true positions."""
        from . import plotting

        view = _PositionsView(self)
        ax = plotting.plot(view, ax=ax, **kwargs)
        self.plot_network(ax=ax)
        if self.estimates is not None:
            from matplotlib.collections import LineCollection

            ok = self.localized
            ax.add_collection(LineCollection(list(np.stack([self.points[ok], self.positions[ok]], axis=1)),
                                             colors="tab:orange", linewidths=0.8))
            if self.anchors is not None:
                a = self.points[self.anchors]
                ax.scatter(a[:, 0], a[:, 1], marker="^", c="tab:red", s=30, zorder=5, label="anchors")
        return ax

    def _sent_columns(self):
        cols = [(t, self.dv_hop_sent[:, k]) for k, t in enumerate(self.dv_hop_types)]
        return cols + super()._sent_columns()

    def __repr__(self) -> str:
        return (f"BoundaryScanResult(n={len(self)}, radius={self.radius:g}, "
                f"transmissions={self.total_transmissions}, localized={int(self.localized.sum())})")


class _PositionsView:
    """The piece arrays of a BoundaryScanResult with the positions used as cell centres (for plots)."""

    def __init__(self, r: BoundaryScanResult) -> None:
        self.piece_ptr, self.piece_x, self.piece_y = r.piece_ptr, r.piece_x, r.piece_y
        self.piece_span, self.piece_neighbor, self.radius = r.piece_span, r.piece_neighbor, r.radius
        self.points = np.where(np.isfinite(r.positions), r.positions, 0.0)


def _points(points: Any) -> np.ndarray:
    arr = np.asarray(points, dtype=np.float64)
    if arr.ndim == 1 and arr.size == 0:
        arr = arr.reshape(0, 2)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"points must be an (n, 2) array, got shape {arr.shape}")
    return arr


def _obstacles(obstacles: Any) -> np.ndarray:
    if obstacles is None:
        return np.zeros((0, 4))
    arr = np.asarray(obstacles, dtype=np.float64)
    if arr.size == 0:
        return np.zeros((0, 4))
    if arr.ndim == 3 and arr.shape[1:] == (2, 2):
        arr = arr.reshape(-1, 4)
    if arr.ndim != 2 or arr.shape[1] != 4:
        raise ValueError("obstacles must be an (m, 4) array of segments (x0, y0, x1, y1) or (m, 2, 2), "
                         f"got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError("obstacles has a non-finite coordinate (NaN or inf)")
    return arr


def _bounds(bounds: Any) -> Optional[tuple]:
    if bounds is None:
        return None
    b = tuple(float(v) for v in np.asarray(bounds, dtype=float).ravel())
    if len(b) != 4:
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax), got {len(b)} numbers")
    if not all(map(math.isfinite, b)) or not (b[0] < b[2] and b[1] < b[3]):
        raise ValueError(f"bounds must be finite with xmin < xmax and ymin < ymax, got {b}")
    return b


def simulate(algorithm: str, points: Any, comm_range: float, loss: float = 0.0, obstacles: Any = None,
             bounds: Any = None, seed: int = 0, *, budget: Optional[int] = None, cap_adjacency: bool = True,
             adjacency_cap: int = 6, forward: bool = True, routing: str = "gpsr", radius: Optional[float] = None,
             anchors: Any = None, anchor_fraction: Optional[float] = None, verify: bool = True,
             route_discovery: bool = True, dv_hop: str = "sync", anchors_relay: bool = False):
    """Run one network algorithm and return its result (see the module docstring).

    Parameters
    ----------
    algorithm : "cc", "bd07" or "bs"
    points : (n, 2) array of node positions
    comm_range : float
        Communication range: nodes at distance <= comm_range are linked unless an obstacle cuts the link.
    loss : float in [0, 1)
        Probability that one try over a link fails (the try is repeated and counted).
    obstacles : (m, 4) array of segments (x0, y0, x1, y1), optional
    bounds : (xmin, ymin, xmax, ymax), optional
        BD07's region (default: the points' bounding box); CC clips its cells to it when given.
    seed : int
        Delivery order and link failures.
    budget : int, optional
        Most transmissions allowed (default 10^9); past it :class:`BudgetExceeded` is raised.
    cap_adjacency, adjacency_cap, forward, routing
        CC's options (Section 2.3 optimisations; "gpsr" or "shortest" routing of notifications).
    radius : float, optional
        Boundary Scan cell radius (default comm_range / 2).
    anchors : int array, optional; anchor_fraction : float, optional
        Boundary Scan with DV-Hop: the anchor nodes (or the fraction of nodes picked as anchors with
        ``seed``); the others localise themselves first.
    verify : bool
        CC and BD07: also compute the exact diagram centrally and report Theorem 2's condition
        (``condition``) and, for CC, the nodes that got a wrong answer (``wrong_nodes``).
    route_discovery : bool
        CC and BD07: where GPSR cannot deliver to a node, find a route by flooding (default);
        False loses the message.
    dv_hop : "sync" or "async"; anchors_relay : bool
        Boundary Scan with DV-Hop: breadth-first rounds with each node forwarding each anchor's flood
        once (default), or asynchronous delivery passing on every improvement; whether anchors forward
        other anchors' floods (default False, as the paper's anchors "broadcast twice").
    """
    if algorithm not in ALGORITHMS:
        raise ValueError(f"algorithm must be one of {ALGORITHMS}, got {algorithm!r}")
    pts = _points(points)
    comm_range = _args.positive(comm_range, "comm_range")
    loss = _args.real(loss, "loss")
    if not 0.0 <= loss < 1.0:
        raise ValueError(f"loss must be a probability in [0, 1), got {loss!r}")
    seed = _args.seed(seed)
    budget = 0 if budget is None else _args.integer(budget, "budget", 1, 2**63 - 1)
    adjacency_cap = _args.integer(adjacency_cap, "adjacency_cap", 0, _args.MAX_COUNT)
    routing = _args.text(routing, "routing")
    dv_hop = _args.text(dv_hop, "dv_hop")
    if dv_hop not in ("sync", "async"):
        raise ValueError(f'dv_hop must be "sync" or "async", got {dv_hop!r}')
    obs = _obstacles(obstacles)
    b = _bounds(bounds)
    anchor_list = None
    fraction = 0.0
    if algorithm == "bs":
        if anchors is not None and anchor_fraction is not None:
            raise ValueError("give anchors or anchor_fraction, not both")
        if anchor_fraction is not None:
            fraction = _args.real(anchor_fraction, "anchor_fraction")
            if not 0.0 < fraction <= 1.0:
                raise ValueError(f"anchor_fraction must be in (0, 1], got {anchor_fraction!r}")
        elif anchors is not None:
            a = np.asarray(anchors).ravel()
            # node indices: a cast would truncate 0.9 to node 0 and read a bool mask as nodes 0 and 1
            if a.size and (a.dtype == bool or a.dtype.kind not in "iuf" or
                           (a.dtype.kind == "f" and not np.all(np.isfinite(a) & (a == np.round(a))))):
                k = 0 if a.dtype == bool or a.dtype.kind not in "iuf" else int(np.flatnonzero(~(np.isfinite(a) & (a == np.round(a))))[0])
                raise ValueError(f"anchors[{k}] = {a[k].item()!r} is not a node index (anchors lists node indices)")
            anchor_list = a.astype(np.int64).tolist()
        if radius is not None:
            radius = _args.positive(radius, "radius")
    elif anchors is not None or anchor_fraction is not None:
        raise ValueError("anchors / anchor_fraction apply to algorithm='bs' only")
    core = _core._network_run(algorithm, pts, comm_range, loss, obs if len(obs) else None, b, seed, budget,
                              bool(cap_adjacency), adjacency_cap, bool(forward), routing, anchor_list, fraction,
                              radius or 0.0, bool(verify), bool(route_discovery), dv_hop == "sync",
                              bool(anchors_relay))
    if isinstance(core, _core._NetworkCcRun):
        return CcResult(core)
    if isinstance(core, _core._NetworkBd07Run):
        return Bd07Result(core)
    return BoundaryScanResult(core)


def links(points: Any, comm_range: float, obstacles: Any = None) -> np.ndarray:
    """The network's links as an ``(E, 2)`` int64 array of pairs ``i < j``."""
    obs = _obstacles(obstacles)
    d = _core._network_links(_points(points), _args.positive(comm_range, "comm_range"), obs if len(obs) else None)
    return np.asarray(d["links"], dtype=np.int64).reshape(-1, 2)


def gpsr_route(points: Any, comm_range: float, source: int, target: Any, obstacles: Any = None):
    """GPSR from node `source` to the point `target`: ``(delivered, path)``; ``path[-1]`` is the node
    that received the packet (the node nearest `target` when the planar graph is connected)."""
    obs = _obstacles(obstacles)
    pts = _points(points)
    ok, path = _core._network_gpsr(pts, _args.positive(comm_range, "comm_range"), obs if len(obs) else None,
                                   _args.integer(source, "source", 0, max(len(pts) - 1, 0)),
                                   tuple(_args.real(v, "target") for v in target))
    return bool(ok), np.asarray(path, dtype=np.int64)


def random_bars(rng: np.random.Generator, count: int, length: float, bounds: Sequence[float]) -> np.ndarray:
    """`count` bar obstacles of the given length, uniformly placed (centre) and oriented in `bounds`
    (the CC paper's "opaque obstacles in the form of bars")."""
    xmin, ymin, xmax, ymax = bounds
    c = np.column_stack([rng.uniform(xmin, xmax, count), rng.uniform(ymin, ymax, count)])
    t = rng.uniform(0.0, np.pi, count)
    h = 0.5 * length * np.column_stack([np.cos(t), np.sin(t)])
    return np.hstack([c - h, c + h])


def batch(algorithm: str, networks: Sequence[Any], comm_range: float, loss: float, obstacles: Sequence[Any],
          bounds: Sequence[float], seeds: Sequence[int], verify: bool = True, workers: Optional[int] = None,
          progress: Any = None, *, threads: Optional[int] = None,
          route_discovery: bool = True) -> Dict[str, np.ndarray]:
    """Run ``cc`` or ``bd07`` on many independent networks in parallel (C++ threads over networks), or
    ``check`` Theorem 2's condition only. ``route_discovery`` as in :func:`simulate`.

    Returns per network: ``by_type`` (transmissions per message type: cc location, notify,
    discovery; bd07 location, probe, reply, discovery), ``deliveries_by_type`` (link deliveries), ``lost``, ``condition``
    (Theorem 2's, when verified or checked) and ``exact`` (CC only: every node's neighbours and hull
    flag exact).
    ``progress`` is a callable (done, total) called from the calling thread. ``workers``: None or -1
    = all cores, k >= 1 = k threads (``threads`` is a deprecated alias, 0 = all cores).
    """
    team = _args.workers(workers, threads)
    obs = [o if o is not None and len(o) else None for o in (_obstacles(o) for o in obstacles)]
    return _core._network_batch(algorithm, [_points(p) for p in networks], _args.positive(comm_range, "comm_range"),
                                _args.real(loss, "loss"), obs, [_args.real(v, "bounds") for v in bounds],
                                [_args.seed(v, "seeds") for v in seeds], bool(verify), team, progress,
                                bool(route_discovery))
