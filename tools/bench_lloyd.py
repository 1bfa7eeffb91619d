#!/usr/bin/env python3
"""Lloyd coverage control on limited cells: dvoronoi against the scipy + shapely loop, and MPI weak
scaling, in one run. Prints a markdown report (machine, date, load).

1. n = 1e4 agents uniform in the unit square (the environment), R = sqrt(k / (4 pi n)) (about k = 10
   agents within 2R, so cells mix edges, arcs and walls), uniform density, gain 1:
   ``dv.coverage.lloyd`` for 1e3 steps (the whole run in the compiled core, the spatial grid kept
   across steps) against the coverage loop a Python user writes today, per step: scipy.spatial.Voronoi
   of the agents (+ four far sentinels, so every region is bounded), each region a shapely Polygon
   intersected with ``Point(p).buffer(R, quad_segs=16)`` and with the box, its centroid the target.
   Two flavours of that loop: per-agent Python (the tutorial way) and shapely 2's vectorised array
   functions (the fastest it gets). The slow side runs fewer steps from the same start; ratios are
   per step. The first steps of both sides are checked to agree (centroids within the polygonal
   disk's error).
2. One ``dv.limited_cells`` call on the same swarm, to compare a Lloyd step with it.
3. A heterogeneous team on the same swarm (radii uniform in [0.5R, 1.5R], power cells clipped to the
   disks): seconds per Lloyd step against the equal-radius run, one thread, both in this process.
4. MPI weak scaling (``mpirun -n 1`` and ``-n 2``, one thread per rank): ``python -m dvoronoi.mpi``
   with N agents per rank in a box widened with the rank count (same density), seconds per step and
   the bytes each step sends (halo + migration, summed over ranks).

Benchmarks are not tests: nothing here fails on a time. The machine may be shared: the load average is
printed, and both sides of each comparison run in the same process, back to back.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_limited import cpu_model, load_average, sentinels, versions  # noqa: E402
from benchutil import best_of  # noqa: E402


# ---------------------------------------------------------------------------------- scipy + shapely
def shapely_step_loop(pts, R, box, quad_segs):
    """One Lloyd step the tutorial way: a Voronoi diagram, then one shapely cell per agent."""
    from scipy.spatial import Voronoi
    from shapely.geometry import Point, Polygon

    vor = Voronoi(np.vstack([pts, sentinels(pts)]))
    targets = np.empty_like(pts)
    for i in range(len(pts)):
        region = vor.regions[vor.point_region[i]]
        cell = Polygon(vor.vertices[region]).intersection(Point(pts[i]).buffer(R, quad_segs=quad_segs))
        cell = cell.intersection(box)
        c = cell.centroid
        targets[i] = (c.x, c.y)
    return targets


def shapely_step_vectorized(pts, R, box, quad_segs):
    """One Lloyd step with shapely 2's array functions on all agents at once."""
    import shapely
    from scipy.spatial import Voronoi

    n = len(pts)
    vor = Voronoi(np.vstack([pts, sentinels(pts)]))
    regions = [vor.regions[j] for j in vor.point_region[:n]]
    sizes = np.fromiter((len(r) + 1 for r in regions), dtype=np.int64, count=n)
    idx = np.fromiter((v for r in regions for v in (*r, r[0])), dtype=np.int64, count=int(sizes.sum()))
    polys = shapely.from_ragged_array(shapely.GeometryType.POLYGON, vor.vertices[idx],
                                      (np.concatenate([[0], np.cumsum(sizes)]), np.arange(n + 1)))
    disks = shapely.buffer(shapely.points(pts), R, quad_segs=quad_segs)
    cells = shapely.intersection(shapely.intersection(polys, disks), box)
    return shapely.get_coordinates(shapely.centroid(cells))


def baseline_run(step, pts, R, steps, box, quad_segs):
    t0 = time.perf_counter()
    p = pts.copy()
    for _ in range(steps):
        p = step(p, R, box, quad_segs)
    return (time.perf_counter() - t0) / steps, p


# ---------------------------------------------------------------------------------------------- MPI
def mpi_run(ranks: int, per_rank: int, R: float, steps: int):
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        return None
    cmd = [mpirun, "-n", str(ranks), "--oversubscribe"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    cmd += [sys.executable, "-m", "dvoronoi.mpi", "--random", str(per_rank), "--per-rank", "-r", repr(R),
            "--steps", str(steps), "--threads", "1", "--seed", "1"]
    # Ranks yield the core while they wait in a collective (the machine may be shared).
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_MCA_mpi_yield_when_idle="1")
    if not (shutil.which("ssh") or shutil.which("rsh")):
        env.setdefault("OMPI_MCA_plm_rsh_agent", "sh")  # Open MPI 4 wants one even for local ranks
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {proc.stderr[-2000:]}")
    m = re.search(r"([\d.]+) ms/step, halo ([\d.]+) kB/step, migration ([\d.]+) kB/step", proc.stdout)
    shown = " ".join("python" if c == sys.executable else os.path.basename(c) if c == mpirun else c
                     for c in cmd)
    return float(m.group(1)), float(m.group(2)), float(m.group(3)), shown


# ---------------------------------------------------------------------------------- heterogeneous team
def hetero_section(dv, pts, R, args, out) -> None:
    """Section 3: Lloyd steps of a heterogeneous team against equal radii, one thread, best of 3."""
    radii = np.random.default_rng(args.seed + 1).uniform(0.5 * R, 1.5 * R, len(pts))
    steps = max(1, min(args.steps, 20))

    def run(radius):
        return dv.coverage.lloyd(pts, radius, steps=steps, bounds=(0, 0, 1, 1), record_every=steps, workers=1,
                                 progress=False)

    eq_t, _ = best_of(3, lambda: run(R))
    het_t, het = best_of(3, lambda: run(radii))
    assert np.all(np.diff(het.cost) <= 1e-12 * abs(het.cost[0])), "cost increased"
    empty = int(np.count_nonzero(dv.coverage.LloydStepper(pts, radii, bounds=(0, 0, 1, 1)).moments()[0] == 0))
    out(f"### A heterogeneous team, n = {len(pts):,} (radii uniform in [0.5R, 1.5R]), 1 thread, {steps} steps")
    out()
    out("| radii | s / step | ratio |")
    out("|---|---:|---:|")
    out(f"| all R (Boundary Scan cells) | {eq_t / steps:.4f} | 1 |")
    out(f"| one per agent (power cells clipped to the disks) | {het_t / steps:.4f} | {het_t / eq_t:.2f} |")
    out()
    out(f"- {empty} of {len(pts):,} cells empty at the start (small disks covered by larger ones)")
    out()


# ---------------------------------------------------------------------------------------------- main
def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=10_000, help="agents (default 1e4)")
    ap.add_argument("--steps", type=int, default=1000, help="dvoronoi Lloyd steps (default 1e3)")
    ap.add_argument("--k", type=float, default=10.0, help="expected agents within 2R (default 10)")
    ap.add_argument("--loop-steps", type=int, default=2, help="steps of the per-agent shapely loop")
    ap.add_argument("--vec-steps", type=int, default=10, help="steps of the vectorised shapely loop")
    ap.add_argument("--quad-segs", type=int, default=16, help="shapely buffer segments per quarter circle")
    ap.add_argument("--threads", type=int, default=0, help="dvoronoi threads (0 = all cores)")
    ap.add_argument("--mpi-per-rank", type=int, default=10_000, help="agents per rank, weak scaling")
    ap.add_argument("--mpi-steps", type=int, default=50)
    ap.add_argument("--no-mpi", action="store_true")
    ap.add_argument("--hetero-only", action="store_true", help="only section 3 (a heterogeneous team)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", type=Path, help="also write the report to this file")
    ap.add_argument("--quick", action="store_true", help="smoke run: n 2000, 50 steps, MPI 2000/rank")
    args = ap.parse_args(argv)
    if args.quick:
        args.n, args.steps, args.loop_steps, args.vec_steps = 2000, 50, 1, 3
        args.mpi_per_rank, args.mpi_steps = 2000, 10

    import dvoronoi as dv
    from shapely.geometry import box as shapely_box

    lines = []

    def out(s=""):
        lines.append(s)
        print(s, flush=True)

    n = args.n
    R = math.sqrt(args.k / (4.0 * math.pi * n))
    rng = np.random.default_rng(args.seed)
    pts = rng.random((n, 2))
    box = shapely_box(0, 0, 1, 1)

    out("## dvoronoi Lloyd benchmark")
    out()
    out(f"- date: {_dt.datetime.now().astimezone().strftime('%Y-%m-%d %H:%M %Z')}")
    out(f"- machine: {cpu_model()}, {os.cpu_count()} logical cores, {platform.system()} "
        f"{platform.release()}; load average at start (1/5/15 min): {load_average()}")
    out(f"- {versions()}")
    out(f"- swarm: n = {n:,} uniform in the unit square (also the environment), R = {R:.5g} "
        f"(about {args.k:g} agents within 2R), uniform density, gain 1, seed {args.seed}")
    out()

    if args.hetero_only:
        hetero_section(dv, pts, R, args, out)
        if args.out:
            args.out.write_text("\n".join(lines) + "\n")
        return 0

    # ---- 1. dvoronoi, the full run
    t0, c0 = time.perf_counter(), time.process_time()
    run = dv.coverage.lloyd(pts, R, steps=args.steps, bounds=(0, 0, 1, 1), record_every=args.steps,
                            workers=args.threads or None, progress=False)
    total, cpu = time.perf_counter() - t0, time.process_time() - c0
    per_step = total / max(args.steps, 1)
    assert np.all(np.diff(run.cost) <= 1e-12 * abs(run.cost[0])), "cost increased"

    # the same on one thread (the baselines are single-threaded)
    one_steps = max(1, args.steps // 10)
    t0 = time.perf_counter()
    dv.coverage.lloyd(pts, R, steps=one_steps, bounds=(0, 0, 1, 1), record_every=one_steps, workers=1,
                      progress=False)
    per_step_1 = (time.perf_counter() - t0) / one_steps

    # ---- 2. the baselines, fewer steps from the same start; first step checked against dvoronoi
    first = dv.coverage.LloydStepper(pts, R, bounds=(0, 0, 1, 1)).moments()[1]
    vec_t, _ = baseline_run(shapely_step_vectorized, pts, R, args.vec_steps, box, args.quad_segs)
    loop_t, _ = baseline_run(shapely_step_loop, pts, R, args.loop_steps, box, args.quad_segs)
    shp_first = shapely_step_vectorized(pts, R, box, args.quad_segs)
    agree = float(np.max(np.linalg.norm(shp_first - first, axis=1))) / R

    lc_t, _ = best_of(3, lambda: dv.limited_cells(pts, R, workers=args.threads or None))

    out(f"### Lloyd steps, n = {n:,}")
    out()
    threads = args.threads or os.cpu_count()
    out(f"| method | steps timed | s / step | total for 1e3 steps (s) | dvoronoi ({threads} threads / 1 thread) faster |")
    out("|---|---:|---:|---:|---:|")
    out(f"| dvoronoi `coverage.lloyd`, {threads} threads (exact arcs, grid kept) | {args.steps} | "
        f"{per_step:.4f} | {per_step * 1000:.1f} | 1 |")
    out(f"| dvoronoi `coverage.lloyd`, 1 thread | {one_steps} | {per_step_1:.4f} | "
        f"{per_step_1 * 1000:.1f} | — |")
    out(f"| scipy Voronoi + shapely 2 vectorised (64-gon disks), 1 thread | {args.vec_steps} | {vec_t:.4f} | "
        f"{vec_t * 1000:.0f} | {vec_t / per_step:.0f}x / {vec_t / per_step_1:.0f}x |")
    out(f"| scipy Voronoi + shapely per-agent loop (64-gon disks), 1 thread | {args.loop_steps} | "
        f"{loop_t:.4f} | {loop_t * 1000:.0f} | {loop_t / per_step:.0f}x / {loop_t / per_step_1:.0f}x |")
    out()
    out(f"- the full dvoronoi run: {total:.1f} s wall, {cpu:.1f} s CPU (all threads) for {args.steps} "
        f"steps (cost {run.cost[0]:.6g} -> {run.cost[-1]:.6g}, never increasing); on a shared machine "
        "the CPU time is the steadier measure of the work")
    out(f"- one `dv.limited_cells` call on the same swarm: {lc_t * 1e3:.1f} ms; a Lloyd step (cells "
        f"clipped to the box, moments, move) is {per_step / lc_t:.2f}x that")
    out(f"- first-step targets, shapely vs dvoronoi: largest difference {agree:.2e} R (the 64-gon "
        "disk's area error, not a disagreement)")
    out()

    hetero_section(dv, pts, R, args, out)

    # ---- 4. MPI weak scaling
    out(f"### MPI weak scaling ({args.mpi_per_rank:,} agents per rank, {args.mpi_steps} steps, 1 thread "
        "per rank)")
    out()
    if args.no_mpi:
        out("(skipped: --no-mpi)")
    else:
        Rm = math.sqrt(args.k / (4.0 * math.pi * args.mpi_per_rank))
        rows = [(k, mpi_run(k, args.mpi_per_rank, Rm, args.mpi_steps)) for k in (1, 2)]
        if rows[0][1] is None:
            out("(skipped: no mpirun on the PATH)")
        else:
            out("| ranks | agents | ms / step | halo kB / step | migration kB / step | weak-scaling efficiency |")
            out("|---:|---:|---:|---:|---:|---:|")
            base = rows[0][1][0]
            for k, (ms, halo, mig, cmd) in rows:
                out(f"| {k} | {k * args.mpi_per_rank:,} | {ms:.2f} | {halo:.1f} | {mig:.2f} | "
                    f"{base / ms:.2f} |")
            out()
            out(f"- command: `{rows[1][1][3]}` (R = {Rm:.5g}, box [0, ranks] x [0, 1])")
            out("- bytes: every (id, x, y) triple is 24 bytes, plus 8 per rank pair for the counts; "
                "the halo of one slab boundary is ~2 * 2R * height * density agents each way")
    out()
    if args.out:
        args.out.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
