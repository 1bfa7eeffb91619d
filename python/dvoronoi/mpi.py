"""Limited cells and Lloyd coverage control across MPI ranks (mpi4py), for swarms that outgrow one
machine.

Agents are partitioned by space: rank ``r`` owns the agents whose x lies in slab ``r`` (the x-range
cut into equal slabs). Every step a rank

1. receives the agents of other ranks that lie within ``2R`` (in x) of its slab -- the halo, the only
   agents that can shape its owned cells (Alltoallv of ``(id, x, y)`` triples);
2. computes the clipped limited cells of its owned agents from owned + halo agents;
3. moves its agents (the Lloyd step), sums the cost (Allreduce), and
4. hands agents that left its slab to their new owner (migration, Alltoallv).

Heterogeneous teams (``radius`` one sensing radius per agent, :mod:`dvoronoi.coverage`): agent j
with radius ``R_j`` is sent to every rank whose slab lies within ``R_j + R̄`` of it (``R̄`` the largest
radius), since it shapes only cells of agents closer than ``R_i + R_j <= R̄ + R_j``; rows carry
``(id, x, y, R)``.

Each agent's cell depends only on the positions within 2R, and candidates are ordered by global id,
so cells and trajectories on K ranks are bit-for-bit those of one process
(:class:`dvoronoi.coverage.LloydStepper`); the cost, a sum over ranks, agrees to rounding (1e-12
relative). Communication per step is measured (``bytes_halo``, ``bytes_migration``).

Run from the command line::

    mpirun -n 4 python -m dvoronoi.mpi --random 100000 -r 0.004 --steps 100 --bounds 0 0 1 1

or from Python, collectively on every rank::

    from mpi4py import MPI
    run = dv.mpi.lloyd(points if rank == 0 else None, radius, steps=100, bounds=(0, 0, 1, 1))
    # rank 0: run.trajectory, run.cost, run.stats; other ranks: None
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _args, _core
from ._partition import _radius_arg
from .coverage import (BoundsArg, CoverageCells, _check_count, _check_density, _check_gain, _evaluate,
                       as_bounds, density_moments)

__all__ = ["DistributedLloyd", "lloyd", "cells", "main"]


def _mpi():
    try:
        from mpi4py import MPI
    except ImportError as e:  # pragma: no cover - exercised only without mpi4py
        raise ImportError("dvoronoi.mpi needs mpi4py: pip install 'dvoronoi[mpi]' (and an MPI "
                          "library such as OpenMPI)") from e
    return MPI


def _pack(ids: np.ndarray, pts: np.ndarray, radii: Optional[np.ndarray] = None) -> np.ndarray:
    """(k, 3) float64 rows (id bits, x, y), or (k, 4) with each agent's radius: one buffer per message."""
    out = np.empty((len(ids), 3 if radii is None else 4))
    out[:, 0] = np.ascontiguousarray(ids, dtype=np.int64).view(np.float64)
    out[:, 1:3] = pts
    if radii is not None:
        out[:, 3] = radii
    return out


def _unpack(buf: np.ndarray) -> Tuple[np.ndarray, np.ndarray, Optional[np.ndarray]]:
    radii = np.ascontiguousarray(buf[:, 3]) if buf.shape[1] == 4 else None
    return np.ascontiguousarray(buf[:, 0]).view(np.int64).copy(), np.ascontiguousarray(buf[:, 1:3]), radii


class DistributedLloyd:
    """One rank's share of a swarm distributed in x-slabs (collective: every rank constructs it).

    Parameters
    ----------
    comm : mpi4py communicator
    ids, points : this rank's agents (global ids, positions); any rank may start with any agents:
        they are sent to their owners at construction.
    radius : float, or one radius per agent of this rank (a heterogeneous team; every rank must then
        pass an array, possibly empty).
    gain, bounds, density, order : as :func:`dvoronoi.coverage.lloyd`.
    x_range : (x0, x1) cut into ``comm.size`` equal slabs; default: the bounds' x-extent, or the
        agents' initial x-extent (agents outside it belong to the first or last slab).
    """

    def __init__(self, comm: Any, ids: Any, points: Any, radius: Any, gain: float = 1.0,
                 bounds: BoundsArg = None, density: Any = None, order: int = 8,
                 x_range: Optional[Tuple[float, float]] = None, workers: Optional[int] = None, *,
                 threads: Optional[int] = None) -> None:
        MPI = _mpi()
        self.comm = comm
        self.size, self.rank = comm.Get_size(), comm.Get_rank()
        radii: Optional[np.ndarray] = None
        if np.ndim(radius) > 0:  # a heterogeneous team: R̄ over every rank
            radii = np.asarray(radius, dtype=float).reshape(-1)
            if len(radii) != len(np.asarray(points).reshape(-1, 2)):
                raise ValueError(f"radius must have one radius per point, got {len(radii)} for "
                                 f"{len(np.asarray(points).reshape(-1, 2))}")
            radius = comm.allreduce(float(radii.max()) if len(radii) else 0.0, op=MPI.MAX)
        self.radius = _args.positive(radius, "radius")
        self.gain = _check_gain(gain)
        self.bounds = as_bounds(bounds)
        self.density = _check_density(density)
        self.order = _check_count(order, "order", 1)
        self.threads = _args.workers(workers, threads)  # the core's count: 0 = all cores
        ids = np.asarray(ids, dtype=np.int64).reshape(-1)
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        if len(ids) != len(points):
            raise ValueError(f"ids and points must have the same length, got {len(ids)} and {len(points)}")
        if x_range is None:
            if self.bounds is not None:
                x_range = (float(self.bounds[:, 0].min()), float(self.bounds[:, 0].max()))
            else:
                lo = comm.allreduce(float(points[:, 0].min()) if len(points) else np.inf, op=MPI.MIN)
                hi = comm.allreduce(float(points[:, 0].max()) if len(points) else -np.inf, op=MPI.MAX)
                x_range = (lo, hi) if lo < hi else (lo - 1.0, lo + 1.0)
        self.edges = np.linspace(float(x_range[0]), float(x_range[1]), self.size + 1)
        # Slab r: [edges[r], edges[r+1]), the outer slabs open-ended. A halo reaches 2R beyond it
        # (R_j + R̄ for agent j of a heterogeneous team); the margin covers rounding (extra agents are
        # harmless: the exact test drops them).
        self.reach = 2.0 * self.radius * (1.0 + 1e-6)
        self.lo = np.concatenate([[-np.inf], self.edges[1:-1]])
        self.hi = np.concatenate([self.edges[1:-1], [np.inf]])
        self.ids = np.empty(0, dtype=np.int64)
        self.points = np.empty((0, 2))
        self.radii: Optional[np.ndarray] = None  # this rank's agents' radii (a heterogeneous team)
        self.bytes_halo = 0        # sent by this rank in the last step
        self.bytes_migration = 0
        self._phi_total: Optional[float] = None

        def check():
            bad = np.flatnonzero(~np.isfinite(points).all(axis=1))
            if len(bad):
                raise ValueError(f"points[{ids[bad[0]]}] is not finite (NaN or inf)")
            if self.bounds is not None and len(points):
                out = np.flatnonzero(~_core.bounds_contains(self.bounds, points))
                if len(out):
                    raise ValueError(f"points[{ids[out[0]]}] lies outside bounds")

        self._collective(check)
        self._migrate(ids, points, radii)

    # -- communication
    def owner(self, x: np.ndarray) -> np.ndarray:
        """The rank owning each x (the slab it falls in)."""
        return np.searchsorted(self.edges[1:-1], x, side="right").astype(np.int64)

    def _alltoallv(self, parts: List[np.ndarray]) -> Tuple[np.ndarray, int]:
        """Send parts[q] (k_q x w float64, w = 3, or 4 with radii) to rank q; returns what this rank
        received and the bytes it sent to other ranks."""
        MPI = _mpi()
        width = parts[0].shape[1]
        send_counts = np.array([width * len(p) for p in parts], dtype=np.int64)
        recv_counts = np.empty(self.size, dtype=np.int64)
        self.comm.Alltoall(send_counts, recv_counts)
        send = np.concatenate(parts) if parts else np.empty((0, width))
        recv = np.empty((int(recv_counts.sum()) // width, width))
        sdispl = np.concatenate([[0], np.cumsum(send_counts)[:-1]])
        rdispl = np.concatenate([[0], np.cumsum(recv_counts)[:-1]])
        self.comm.Alltoallv([np.ascontiguousarray(send), (send_counts, sdispl), MPI.DOUBLE],
                            [recv, (recv_counts, rdispl), MPI.DOUBLE])
        sent = int(send_counts.sum() - send_counts[self.rank]) * 8 + 8 * (self.size - 1)
        return recv, sent

    def _migrate(self, ids: np.ndarray, points: np.ndarray, radii: Optional[np.ndarray]) -> None:
        dest = self.owner(points[:, 0])
        parts = [_pack(ids[dest == q], points[dest == q], None if radii is None else radii[dest == q])
                 for q in range(self.size)]
        recv, self.bytes_migration = self._alltoallv(parts)
        self.ids, self.points, self.radii = _unpack(recv)

    def halo(self) -> Tuple[np.ndarray, np.ndarray, Optional[np.ndarray]]:
        """(ids, points, radii) of other ranks' agents within 2R (in x) of this rank's slab (within
        R_j + R̄ for agent j of a heterogeneous team; radii None otherwise)."""
        x = self.points[:, 0]
        reach = self.reach if self.radii is None else (self.radii + self.radius) * (1.0 + 1e-6)
        parts = []
        for q in range(self.size):
            if q == self.rank:
                parts.append(np.empty((0, 3 if self.radii is None else 4)))
                continue
            near = (x >= self.lo[q] - reach) & (x <= self.hi[q] + reach)
            parts.append(_pack(self.ids[near], self.points[near], None if self.radii is None else self.radii[near]))
        recv, self.bytes_halo = self._alltoallv(parts)
        return _unpack(recv)

    # -- one step
    def _local(self) -> Tuple[np.ndarray, np.ndarray, Optional[np.ndarray]]:
        hid, hpts, hradii = self.halo()
        radii = None if self.radii is None else np.concatenate([self.radii, hradii])
        return np.concatenate([self.ids, hid]), np.vstack([self.points, hpts]), radii

    def _collective(self, fn):
        """fn() on every rank; if it fails on any rank, every rank raises (no rank is left waiting in
        the next collective): the failing rank its own error, the others a ValueError naming it."""
        try:
            result, error = fn(), None
        except (ValueError, TypeError) as e:
            result, error = None, e
        errors = self.comm.allgather(None if error is None else f"{type(error).__name__}: {error}")
        if error is not None:
            raise error
        for r, failed in enumerate(errors):
            if failed is not None:
                raise ValueError(f"rank {r} failed: {failed}")
        return result

    def _moments(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(mass, centroid, polar, open) of the owned cells; open: the cell reaches its circle."""
        ids, pts, radii = self._local()
        owned = len(self.ids)

        def compute():
            if self.density is None:
                return _core.coverage_moments(pts, self.radius, self.bounds, ids, owned, self.threads, radii)
            q = _core.coverage_quadrature(pts, self.radius, self.order, self.bounds, ids, owned, self.threads,
                                          radii)
            return density_moments(self.points, q, self.density) + (q[4],)

        return self._collective(compute)

    def _total(self) -> Optional[float]:
        """Φ(Q): the environment's mass under the density (None without bounds)."""
        if self.bounds is None:
            return None
        if self._phi_total is None:
            if self.density is None:
                x, y, w, _ = _core.environment_quadrature(self.bounds, 1)
                self._phi_total = float(np.sum(w))
            else:
                x, y, w, _ = _core.environment_quadrature(self.bounds, self.order)
                self._phi_total = float(np.sum(w * _evaluate(self.density, x, y)))
        return self._phi_total

    def _global_cost(self, mass: np.ndarray, polar: np.ndarray, open_cells: np.ndarray) -> float:
        """H over every rank's cells, summed as in :func:`dvoronoi.coverage` (no R² Φ(Q) to cancel)."""
        MPI = _mpi()
        total = self._total()
        r2 = self.radius ** 2
        ri2 = r2 if self.radii is None else self.radii ** 2
        if total is None:
            return self.comm.allreduce(float(np.sum(polar - ri2 * mass)), op=MPI.SUM)
        covered = polar if self.radii is None else polar + (r2 - ri2) * mass
        polar_sum = self.comm.allreduce(math.fsum(covered), op=MPI.SUM)
        mass_sum = self.comm.allreduce(math.fsum(mass), op=MPI.SUM)
        # No agent: nothing is covered. Else U is empty exactly when no cell reaches its circle.
        count = self.comm.allreduce(len(mass), op=MPI.SUM)
        any_open = self.comm.allreduce(bool(np.any(open_cells)), op=MPI.LOR)
        uncovered = max(total - mass_sum, 0.0) if count == 0 or any_open else 0.0
        return polar_sum + self.radius ** 2 * uncovered

    def cost(self) -> float:
        """H at the current positions (collective; the same value on every rank)."""
        mass, _, polar, open_cells = self._moments()
        return self._global_cost(mass, polar, open_cells)

    def step(self) -> float:
        """One Lloyd step (collective). Returns H before the move, on every rank."""
        mass, centroid, polar, open_cells = self._moments()
        cost = self._global_cost(mass, polar, open_cells)
        moved = _core.lloyd_move(self.points, centroid, self.gain, self.bounds)
        halo_bytes = self.bytes_halo
        self._migrate(self.ids, moved, self.radii)
        self.bytes_halo = halo_bytes
        return cost

    def cells(self) -> Dict[str, np.ndarray]:
        """The owned agents' clipped cells (flat arrays, neighbours as global ids)."""
        ids, pts, radii = self._local()
        return self._collective(lambda: _core.coverage_cells(pts, self.radius, self.bounds, ids,
                                                             len(self.ids), self.threads, radii))

    def gather(self, root: int = 0) -> Optional[np.ndarray]:
        """All positions in global-id order on `root` (None elsewhere); ids must be 0..n-1."""
        got = self.comm.gather(_pack(self.ids, self.points), root=root)
        if self.rank != root:
            return None
        ids, pts, _ = _unpack(np.concatenate(got))
        out = np.empty((len(ids), 2))
        out[ids] = pts
        return out


def _scatter_input(comm: Any, points: Any, root: int, radius: Any = None) -> Tuple[np.ndarray, np.ndarray, Any]:
    """Rank `root` holds all points (and, for a heterogeneous team, the radii); every rank starts
    with a contiguous block of them (the constructor then sends each agent to its slab's owner).
    Returns (ids, points, radius): the scalar radius, or this block's radii."""
    size, rank = comm.Get_size(), comm.Get_rank()
    if rank == root:
        pts = np.asarray(points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2:
            raise ValueError(f"points must be an (n, 2) array, got shape {pts.shape}")
        bad = np.flatnonzero(~np.isfinite(pts).all(axis=1))
        if len(bad):
            raise ValueError(f"points[{bad[0]}] is not finite (NaN or inf)")
        blocks = np.array_split(np.arange(len(pts)), size)
        radii = np.asarray(radius, dtype=float) if np.ndim(radius) > 0 else None
        chunks = [(b, pts[b], radius if radii is None else radii[b]) for b in blocks]
    else:
        chunks = None
    ids, pts, r = comm.scatter(chunks, root=root)
    return ids.astype(np.int64), pts, r


def _check_on_root(comm: Any, root: int, check) -> None:
    """Run `check` on root and raise the same error on every rank (so no rank is left waiting)."""
    err = None
    if comm.Get_rank() == root:
        try:
            check()
        except (ValueError, TypeError) as e:
            err = e
    err = comm.bcast(err, root=root)
    if err is not None:
        raise err


def lloyd(points: Any, radius: Any, steps: int = 100, gain: float = 1.0, bounds: BoundsArg = None,
          density: Any = None, order: int = 8, record_every: int = 1, comm: Any = None, root: int = 0,
          workers: Optional[int] = None, *, threads: Optional[int] = None) -> Optional[Dict[str, Any]]:
    """Lloyd's algorithm on limited cells across the ranks of `comm` (collective).

    `points` (n, 2) is read on `root` only. Returns on `root` a dict with ``trajectory`` (frames, n, 2)
    (the positions every `record_every` steps and after the last, gathered to root),
    ``frame_steps``, ``cost`` (steps + 1), ``cells`` (the final :class:`CoverageCells`) and
    ``stats`` (seconds per step, halo and migration bytes sent per step, summed over ranks);
    None on other ranks. `radius` (read on root) may give one radius per agent (a heterogeneous team,
    :mod:`dvoronoi.coverage`).
    """
    MPI = _mpi()
    comm = MPI.COMM_WORLD if comm is None else comm
    team = _args.workers(workers, threads)
    radius = _radius_on_root(comm, root, radius)
    steps = _check_count(steps, "steps", 0)
    record_every = _check_count(record_every, "record_every", 1)

    def validate():
        # The single-process stepper's checks (shape, NaN, radius, bounds, inside, gain) on root.
        _core.LloydStepper(points, radius, as_bounds(bounds), _check_gain(gain), 1)

    _check_on_root(comm, root, validate)
    ids, pts, r = _scatter_input(comm, points, root, radius)
    run = DistributedLloyd(comm, ids, pts, r, gain=gain, bounds=bounds, density=density,
                           order=order, workers=team or None)
    frames: List[Optional[np.ndarray]] = [run.gather(root)]
    cost = np.empty(steps + 1)
    halo_bytes, migration_bytes = [], []
    comm.Barrier()
    t0 = time.perf_counter()
    for t in range(steps):
        cost[t] = run.step()
        halo_bytes.append(comm.allreduce(run.bytes_halo, op=MPI.SUM))
        migration_bytes.append(comm.allreduce(run.bytes_migration, op=MPI.SUM))
        if (t + 1) % record_every == 0 or t + 1 == steps:
            frames.append(run.gather(root))
    cost[steps] = run.cost()
    elapsed = time.perf_counter() - t0
    parts = comm.gather((run.ids, run.cells()), root=root)
    if comm.Get_rank() != root:
        return None
    cells = _assemble_cells(parts, run.radius, run.bounds)
    frame_steps = np.unique(np.concatenate([np.arange(0, steps + 1, record_every), [steps]])).astype(np.int64)
    return {"trajectory": np.stack([f for f in frames if f is not None]), "frame_steps": frame_steps, "cost": cost, "cells": cells,
            "stats": {"ranks": comm.Get_size(), "agents": len(cells), "steps": steps,
                      "seconds_per_step": elapsed / max(steps, 1),
                      "halo_bytes_per_step": float(np.mean(halo_bytes)) if halo_bytes else 0.0,
                      "migration_bytes_per_step": float(np.mean(migration_bytes)) if migration_bytes else 0.0}}


def _radius_on_root(comm: Any, root: int, radius: Any) -> Any:
    """The radius argument as root has it (a float, or an array of radii on root only), on every rank:
    a float, or the marker "radii" (the scattered blocks carry them)."""
    kind = err = None
    if comm.Get_rank() == root:
        try:
            radius = _radius_arg(radius)
            kind = "radii" if np.ndim(radius) > 0 else radius
        except (ValueError, TypeError) as e:
            err = e
    kind, err = comm.bcast((kind, err), root=root)
    if err is not None:
        raise err
    return radius if comm.Get_rank() == root else kind


def _assemble_cells(parts: List[Tuple[np.ndarray, Dict[str, np.ndarray]]], radius: float,
                    bounds: Optional[np.ndarray]) -> CoverageCells:
    """Per-rank cells (owned agents, any order) -> one CoverageCells in global-id order."""
    ids = np.concatenate([p[0] for p in parts])
    n = len(ids)
    order = np.empty(n, dtype=np.int64)
    order[ids] = np.arange(n)  # global id -> row in the concatenation
    cat = {k: np.concatenate([p[1][k] for p in parts]) for k in parts[0][1] if k != "radius"}
    counts = np.concatenate([np.diff(p[1]["piece_ptr"]) for p in parts])
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    ncounts = np.concatenate([np.diff(p[1]["indptr"]) for p in parts])
    nstarts = np.concatenate([[0], np.cumsum(ncounts)[:-1]])
    take = np.concatenate([np.arange(starts[r], starts[r] + counts[r]) for r in order]) if n else np.empty(0, np.int64)
    ntake = np.concatenate([np.arange(nstarts[r], nstarts[r] + ncounts[r]) for r in order]) if n else np.empty(0, np.int64)
    arrays = {"radius": radius, "points": cat["points"][order], "areas": cat["areas"][order],
              "perimeters": cat["perimeters"][order], "centroids": cat["centroids"][order],
              "piece_ptr": np.concatenate([[0], np.cumsum(counts[order])]).astype(np.int64),
              "indptr": np.concatenate([[0], np.cumsum(ncounts[order])]).astype(np.int64),
              "indices": cat["indices"][ntake].astype(np.int64)}
    for k in ("piece_neighbor", "piece_x", "piece_y", "piece_span"):
        arrays[k] = cat[k][take]
    if "radii" in cat:
        arrays["radii"] = cat["radii"][order]
    return CoverageCells(arrays, bounds)


def cells(points: Any, radius: Any, bounds: BoundsArg = None, comm: Any = None, root: int = 0,
          workers: Optional[int] = None, *, threads: Optional[int] = None) -> Optional[CoverageCells]:
    """The clipped limited cells of `points` (read on root) computed across ranks (collective);
    the assembled :class:`CoverageCells` on root, None elsewhere. ``workers``: threads per rank, None
    or -1 = all cores (``threads`` is a deprecated alias, 0 = all cores)."""
    MPI = _mpi()
    comm = MPI.COMM_WORLD if comm is None else comm
    team = _args.workers(workers, threads)
    radius = _radius_on_root(comm, root, radius)
    _check_on_root(comm, root, lambda: _core.LloydStepper(points, radius, as_bounds(bounds), 1.0, 1))
    ids, pts, r = _scatter_input(comm, points, root, radius)
    run = DistributedLloyd(comm, ids, pts, r, bounds=bounds, workers=team or None)
    parts = comm.gather((run.ids, run.cells()), root=root)
    return _assemble_cells(parts, run.radius, run.bounds) if comm.Get_rank() == root else None


# ------------------------------------------------------------------------------------------ entry
def _read_points(path: str) -> np.ndarray:
    """'x y' or 'x,y' per line, '#' comments, an optional header line; errors name file:line, and a
    coordinate must be a finite number (as the CLI's reader: NaN, inf and 1e999 are refused there,
    not later as an anonymous points[i])."""
    rows: List[Tuple[float, float]] = []
    with open(path, "rb") as f:
        raw = f.read()
    try:
        content = raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        at = raw[:e.start].count(b"\n") + 1
        raise ValueError(f"{path}:{at}: not UTF-8 text (a point file has 'x y' per line)") from None
    for lineno, line in enumerate(content.split("\n"), 1):  # lines as the CLI counts them ('\r\n' too)
        text = line.split("#", 1)[0].replace(",", " ").split()
        if not text:
            continue
        try:
            x, y = float(text[0]), float(text[1])
        except (ValueError, IndexError):
            if not rows and lineno == 1:
                continue  # a header line
            raise ValueError(f"{path}:{lineno}: expected 'x y', got {line.strip()!r}") from None
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(f"{path}:{lineno}: coordinates must be finite numbers, got {line.strip()!r}")
        rows.append((x, y))
    return np.array(rows, dtype=float).reshape(-1, 2)


def main(argv: Optional[List[str]] = None) -> int:
    """``mpirun -n K python -m dvoronoi.mpi [POINTS | --random N] -r R --steps S [--bounds ...]``."""
    MPI = _mpi()
    comm = MPI.COMM_WORLD
    ap = argparse.ArgumentParser(prog="python -m dvoronoi.mpi",
                                 description="Lloyd coverage control on limited cells across MPI ranks.")
    ap.add_argument("points", nargs="?", help="point file (x y per line); or use --random")
    ap.add_argument("--random", type=int, default=0, metavar="N",
                    help="N uniform random agents in the bounds (default box 0 0 1 1)")
    ap.add_argument("--per-rank", action="store_true",
                    help="with --random: N agents per rank in a box widened with the rank count "
                         "(weak scaling)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-r", "--radius", type=float, required=True)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--gain", type=float, default=1.0)
    ap.add_argument("--bounds", type=float, nargs=4, metavar=("XMIN", "YMIN", "XMAX", "YMAX"))
    ap.add_argument("--record-every", type=int, default=0,
                    help="gather positions every K steps (default: only first and last)")
    ap.add_argument("-o", "--output", help="write the run summary + final positions as JSON (root)")
    ap.add_argument("--threads", type=int, default=1, help="OpenMP threads per rank (default 1; 0 = all cores)")
    args = ap.parse_args(argv)
    rank, size = comm.Get_rank(), comm.Get_size()
    bounds = args.bounds
    points = None

    def read_inputs() -> None:  # on rank 0; an error reaches every rank (none is left waiting)
        nonlocal bounds, points
        if args.output and not os.path.isdir(os.path.dirname(os.path.abspath(args.output))):
            raise ValueError(f"-o/--output: the folder of {args.output!r} does not exist")
        if args.random:
            n = args.random * (size if args.per_rank else 1)
            if bounds is None:
                bounds = [0.0, 0.0, float(size) if args.per_rank else 1.0, 1.0]
            rng = np.random.default_rng(args.seed)
            points = np.column_stack([rng.uniform(bounds[0], bounds[2], n),
                                      rng.uniform(bounds[1], bounds[3], n)])
        elif args.points:
            try:
                points = _read_points(args.points)
            except OSError as e:
                raise ValueError(f"{args.points}: {e.strerror or e}") from None
        else:
            raise ValueError("give POINTS or --random N")

    try:
        _check_on_root(comm, 0, read_inputs)
        bounds = comm.bcast(bounds, root=0)
        record = args.record_every if args.record_every > 0 else max(args.steps, 1)
        out = lloyd(points, args.radius, steps=args.steps, gain=args.gain, bounds=bounds,
                    record_every=record, comm=comm, workers=args.threads or None)
    except (ValueError, TypeError) as e:  # raised on every rank alike: said once, exit 2 everywhere
        if rank == 0:
            print(f"{ap.prog}: error: {e}", file=sys.stderr)
        return 2
    if rank == 0:
        assert out is not None  # lloyd returns the result on the root rank
        s = out["stats"]
        print(f"dvoronoi.mpi: {s['agents']} agents on {s['ranks']} ranks, {s['steps']} steps: "
              f"{s['seconds_per_step'] * 1e3:.2f} ms/step, halo {s['halo_bytes_per_step'] / 1e3:.1f} kB/step, "
              f"migration {s['migration_bytes_per_step'] / 1e3:.1f} kB/step, "
              f"cost {out['cost'][0]:.9g} -> {out['cost'][-1]:.9g}")
        if args.output:
            from ._io import atomic_write_text

            doc = {"kind": "lloyd", "stats": s, "cost": out["cost"].tolist(), "radius": args.radius, "bounds": bounds,
                   "points": out["trajectory"][-1].tolist()}
            atomic_write_text(args.output, json.dumps(doc) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
