#!/usr/bin/env python3
"""Geodesic coverage on a map: one geodesic Lloyd step of dvoronoi against what a user would write, and
the accuracy of its distances against the exact shortest paths. Prints a markdown report.

1. Speed. A 1024 x 1024 building map (dvoronoi.occupancy_maps.building), 100 agents in free pixels,
   geodesic range 100 px, uniform density, one worker:
   - dvoronoi: ``dv.geodesic.GeodesicLloydStepper(...).step()`` (cells, centroids, paths, backtracking);
     also ``dv.coverage.geodesic_cells`` alone;
   - scipy: ``scipy.sparse.csgraph.dijkstra`` multi-source (``min_only=True``) on the 8-connected graph
     of free pixels (edge 1 or sqrt 2, ``limit`` = range), labels from its sources, then the centroids
     with numpy: the cells only, no paths (its distances are 8-connected: up to 8 % long);
   - scikit-fmm (if installed): ``skfmm.distance`` once per agent (a masked array, the range as
     ``narrow``), then the minimum over agents: the distances only.
   Ratios are per call, same process, back to back.
2. Accuracy (``--accuracy``). Small maps (corridors with a pinch point, rooms, caves, buildings,
   warehouses; 40 x 40, 1-5 agents, several seeds): relative error of the distances at pixels more
   than 3 px from the sources against tests/python/geodesic_oracle.py (Dijkstra on the visibility
   graph of the sources and the convex corners of occupied pixels), and the share of pixels whose agent
   differs. (For scale: an 8-connected pixel Dijkstra is up to 8.2 % long in open space, by geometry.)

Benchmarks are not tests: nothing here fails on a time. The load average is printed (the machine may
be shared).
"""
from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

import dvoronoi as dv
from dvoronoi import occupancy_maps as om

ROOT = Path(__file__).resolve().parent.parent


def best_of(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def pixel_graph(occ: np.ndarray):
    """The 8-connected graph of free pixels (no diagonal step through a pinch point)."""
    from scipy.sparse import coo_matrix

    H, W = occ.shape
    free = ~occ
    r, c = np.nonzero(free)
    rows, cols, w = [], [], []
    for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
        r2, c2 = r + dr, c + dc
        ok = (r2 < H) & (c2 >= 0) & (c2 < W)
        ok[ok] &= free[r2[ok], c2[ok]]
        if dr and dc:  # a diagonal step needs one of the two other pixels free
            ok[ok] &= free[r[ok], c2[ok]] | free[r2[ok], c[ok]]
        a, b = r[ok] * W + c[ok], r2[ok] * W + c2[ok]
        rows += [a, b]
        cols += [b, a]
        w += [np.full(len(a), np.hypot(dr, dc))] * 2
    return coo_matrix((np.concatenate(w), (np.concatenate(rows), np.concatenate(cols))), shape=(H * W, H * W)).tocsr()


def scipy_cells(graph, occ: np.ndarray, pix: np.ndarray, radius: float):
    """What a user writes: multi-source Dijkstra on the pixel graph, labels from its sources, centroids."""
    from scipy.sparse.csgraph import dijkstra

    H, W = occ.shape
    ids = pix[:, 0] * W + pix[:, 1]
    d, _, src = dijkstra(graph, indices=ids, min_only=True, return_predecessors=True, limit=radius)
    ok = np.isfinite(d)
    order = np.argsort(ids)
    lab = np.full(H * W, -1)
    lab[ok] = order[np.searchsorted(ids[order], src[ok])]
    r, c = np.divmod(np.flatnonzero(ok), W)
    n = len(pix)
    cnt = np.bincount(lab[ok], minlength=n)
    cx = np.bincount(lab[ok], c + 0.5, minlength=n) / np.maximum(cnt, 1)
    cy = np.bincount(lab[ok], H - r - 0.5, minlength=n) / np.maximum(cnt, 1)
    return d.reshape(H, W), lab.reshape(H, W), np.column_stack([cx, cy])


def speed(args) -> None:
    occ = om.building(args.size, seed=0)
    H, W = occ.shape
    rng = np.random.default_rng(1)
    free = np.argwhere(~occ)
    pix = free[rng.choice(len(free), args.agents, replace=False)]
    grid = dv.OccupancyGrid(occ)
    xy = grid.pixel_centers(pix)
    R = float(args.radius)
    print(f"## Speed: {H} x {W} building map, {args.agents} agents, range {R:g} px, one worker\n")
    stepper = dv.geodesic.GeodesicLloydStepper(xy, R, workers=1, environment=grid)
    stepper.step()  # warm: the workspace is allocated
    t_step = best_of(stepper.step, args.repeat)
    t_cells = best_of(lambda: dv.coverage.geodesic_cells(xy, grid, radius=R, workers=1), args.repeat)
    stepper2 = dv.geodesic.GeodesicLloydStepper(xy, R, workers=2, environment=grid)
    stepper2.step()
    t_step2 = best_of(stepper2.step, args.repeat)
    # A heterogeneous team (ranges uniform in [0.5R, 1.5R]): one range-limited wavefront per agent.
    radii = np.random.default_rng(2).uniform(0.5 * R, 1.5 * R, args.agents)
    team = dv.geodesic.GeodesicLloydStepper(xy, radii, workers=1, environment=grid)
    team.step()
    t_team = best_of(team.step, args.repeat)
    team2 = dv.geodesic.GeodesicLloydStepper(xy, radii, workers=2, environment=grid)
    team2.step()
    t_team2 = best_of(team2.step, args.repeat)
    rows = [("dvoronoi geodesic Lloyd step (1 worker)", t_step),
            ("dvoronoi geodesic Lloyd step (2 workers)", t_step2),
            ("the same, ranges uniform in [0.5R, 1.5R] (1 worker)", t_team),
            ("the same, ranges uniform in [0.5R, 1.5R] (2 workers)", t_team2),
            ("dvoronoi geodesic_cells (labels, distances, moments)", t_cells)]
    graph = pixel_graph(occ)
    t_scipy = best_of(lambda: scipy_cells(graph, occ, pix, R), args.repeat)
    rows.append(("scipy csgraph multi-source Dijkstra, 8-connected (cells only)", t_scipy))
    try:
        import skfmm
    except ImportError:
        skfmm = None
    if skfmm is not None:
        def fmm():
            best = np.full(occ.shape, np.inf)
            for r, c in pix:
                phi = np.ones(occ.shape)
                phi[r, c] = -1
                d = skfmm.distance(np.ma.MaskedArray(phi, occ), narrow=R)
                d = np.ma.filled(np.abs(d).astype(float), np.inf)
                np.minimum(best, d, out=best)
            return best
        t_fmm = best_of(fmm, 1)
        rows.append((f"scikit-fmm {skfmm.__version__}, one run per agent (distances only)", t_fmm))
    print("| what | ms | ratio to the dvoronoi step |\n| --- | ---: | ---: |")
    for name, t in rows:
        print(f"| {name} | {t * 1e3:.1f} | {t / t_step:.2f} |")
    print()


def accuracy(args) -> None:
    sys.path.insert(0, str(ROOT / "tests" / "python"))
    import geodesic_oracle as O

    def corridor():
        occ = np.zeros((20, 28), bool)
        occ[6, 3:25] = True
        occ[13, 4:] = True
        occ[6:14, 12] = True
        occ[9, 12] = False
        occ[16:18, 5:7] = True
        occ[2, 2] = occ[3, 3] = True
        return occ

    maps = {"corridors": lambda s: om.passages(64)[:40, :40] if s % 2 else corridor(),
            "rooms": lambda s: om.rooms_with_islands(40, seed=s), "cave": lambda s: om.cave(40, seed=s),
            "building": lambda s: om.building(40, seed=s), "warehouse": lambda s: om.warehouse(40, seed=s)}
    print(f"## Accuracy against exact shortest paths ({args.seeds} seeds per map kind, 40 x 40, 1-5 agents)\n")
    print("| map | pixels > 3 px | max relative error | mean | pixels whose agent differs |")
    print("| --- | ---: | ---: | ---: | ---: |")
    worst = 0.0
    for name, make in maps.items():
        mx = sm = cnt = diff = tot = 0.0
        for s in range(args.seeds):
            occ = make(s)
            n = 1 + s % 5
            rng = np.random.default_rng(s)
            H, W = occ.shape
            free = np.argwhere(~occ)
            pick = free[rng.choice(len(free), n, replace=False)]
            uw = pick[:, ::-1] + rng.uniform(0.02, 0.98, (n, 2))
            xy = np.column_stack([uw[:, 0], H - uw[:, 1]])
            exact = O.exact_distances(occ, uw)
            best = exact.min(axis=0)
            cells = dv.coverage.geodesic_cells(xy, occ)
            m = np.isfinite(best) & (best > 3)
            rel = np.abs(cells.distances[m] - best[m]) / best[m]
            mx, sm, cnt = max(mx, rel.max()), sm + rel.sum(), cnt + m.sum()
            reach = np.isfinite(best)
            diff += np.count_nonzero(cells.labels[reach] != exact.argmin(axis=0)[reach])
            tot += reach.sum()
        worst = max(worst, mx)
        print(f"| {name} | {int(cnt)} | {mx * 100:.2f} % | {sm / cnt * 100:.4f} % | {diff / tot * 100:.3f} % |")
    print(f"\nLargest relative error of dvoronoi: {worst * 100:.2f} %\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--agents", type=int, default=100)
    ap.add_argument("--radius", type=float, default=100.0)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--accuracy", action="store_true", help="also measure the error against exact paths")
    ap.add_argument("--seeds", type=int, default=16)
    args = ap.parse_args()
    load = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),) * 3
    print(f"# bench_geodesic, {_dt.datetime.now(_dt.timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.machine()}, "
          f"{os.cpu_count()} CPUs, load {load[0]:.2f}, dvoronoi {dv.__version__}, numpy {np.__version__}\n")
    speed(args)
    if args.accuracy:
        accuracy(args)


if __name__ == "__main__":
    main()
