#!/usr/bin/env python3
"""dvoronoi's range-limited cells against what a Python user does today, in one run.

Prints a markdown report (machine, date, load) for pasting in the README:

1. C++ (if built): ``bench_limited_cgal --n 1e6`` (dvoronoi vs CGAL's Delaunay_triangulation_2 plus a
   neighbour walk, same points, one process). Build it with::

       cmake -S . -B build -DDVORONOI_BUILD_BENCHMARKS=ON
       cmake --build build --target bench_limited_cgal

2. Python, n = 1e5 uniform points in the unit square, R = sqrt(k / (4 pi n)) (about k = 30 agents within
   2R): ``dv.limited_cells`` (1 thread and all cores) against scipy.spatial.Voronoi + shapely, where
   each cell polygon is intersected with ``Point(p).buffer(R, quad_segs=...)``. Unbounded Voronoi regions
   are made finite the usual way, with four far sentinel points at the corners of a big box (the
   sentinels' bisectors are far beyond R, so the clipped cells are the exact ones up to the polygonal
   disk). Two flavours: the per-cell Python loop of most tutorials (timed on a subset and extrapolated
   per agent: the output says so) and shapely 2's vectorised array functions on all agents.

3. Heterogeneous teams: the same points with radii uniform in [0.5R, 1.5R], against the equal-radius
   call on the same points (``--hetero-only`` runs just this section), 1 thread and all cores.

4. One agent's latency (a robot's control step): ``dv.limited_cell(center, others, R)`` with 30 others
   within 2R, via timeit, in microseconds; and the same cell from scipy + shapely.

Benchmarks are not tests: nothing here fails on a time. Use --quick for a small smoke run.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import platform
import subprocess
import sys
import timeit
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from benchutil import best_of, git_describe  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
DEFAULT_CPP = REPO / "build" / "tools" / "bench" / "bench_limited_cgal"


# --------------------------------------------------------------------------------------------- machine
def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def load_average() -> str:
    try:
        return " / ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def versions() -> str:
    import dvoronoi as dv
    import scipy
    import shapely

    return (f"dvoronoi {dv.__version__}, numpy {np.__version__}, scipy {scipy.__version__}, "
            f"shapely {shapely.__version__}, Python {platform.python_version()}; git {git_describe()}")


# ---------------------------------------------------------------------------------------------- timing
def uniform_points(n: int, k: float, seed: int):
    rng = np.random.default_rng(seed)
    pts = rng.random((n, 2))
    return pts, math.sqrt(k / (4.0 * math.pi * n))


def sentinels(pts: np.ndarray) -> np.ndarray:
    """Four points at the corners of a box 10x the points' extent: every real region is bounded."""
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    mid, span = (lo + hi) / 2, max(float((hi - lo).max()), 1e-12)
    d = 10.0 * span
    return mid + d * np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


# ---------------------------------------------------------------------------------- scipy + shapely
def scipy_voronoi(pts: np.ndarray):
    from scipy.spatial import Voronoi

    return Voronoi(np.vstack([pts, sentinels(pts)]))


def shapely_loop(pts, R, vor, agents, quad_segs):
    """The tutorial way: one polygon, one buffered point, one intersection per agent."""
    from shapely.geometry import Point, Polygon

    areas = np.empty(len(agents))
    cents = np.empty((len(agents), 2))
    for a, i in enumerate(agents):
        region = vor.regions[vor.point_region[i]]
        if -1 in region:  # cannot happen with the sentinels; kept as the usual guard
            raise RuntimeError(f"unbounded region for agent {i}")
        cell = Polygon(vor.vertices[region]).intersection(Point(pts[i]).buffer(R, quad_segs=quad_segs))
        areas[a] = cell.area
        c = cell.centroid
        cents[a] = (c.x, c.y)
    return areas, cents


def shapely_vectorized(pts, R, vor, quad_segs):
    """shapely 2's array API on all agents: ragged polygons, buffered points, one intersection call."""
    import shapely

    n = len(pts)
    regions = [vor.regions[j] for j in vor.point_region[:n]]
    sizes = np.fromiter((len(r) + 1 for r in regions), dtype=np.int64, count=n)  # closed rings
    idx = np.fromiter((v for r in regions for v in (*r, r[0])), dtype=np.int64, count=int(sizes.sum()))
    if (idx < 0).any():
        raise RuntimeError("unbounded region despite the sentinels")
    coords = vor.vertices[idx]
    ring_offsets = np.concatenate([[0], np.cumsum(sizes)])
    poly_offsets = np.arange(n + 1, dtype=np.int64)
    polys = shapely.from_ragged_array(shapely.GeometryType.POLYGON, coords, (ring_offsets, poly_offsets))
    disks = shapely.buffer(shapely.points(pts), R, quad_segs=quad_segs)
    cells = shapely.intersection(polys, disks)
    return shapely.area(cells), shapely.get_coordinates(shapely.centroid(cells))


# ------------------------------------------------------------------------------------------------ C++
def run_cpp(path: Path, n: int, k: float, reps: int, threads: int, seed: int):
    cmd = [str(path), "--n", str(n), "--k", str(k), "--reps", str(reps), "--threads", str(threads),
           "--seed", str(seed), "--json"]
    print(f"running {' '.join(cmd)} ...", file=sys.stderr, flush=True)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode not in (0, 2):
        raise RuntimeError(f"{path} failed ({proc.returncode}): {proc.stderr.strip()}")
    return json.loads(proc.stdout)


# ---------------------------------------------------------------------------------------------- main
def heterogeneous(dv, n: int, args, out) -> None:
    """Section 3: one radius per agent (power cells clipped to the disks) against one radius."""
    pts, R = uniform_points(n, args.k, args.seed)
    radii = R * np.random.default_rng(args.seed + 1).uniform(0.5, 1.5, n)
    out(f"### Heterogeneous teams, n = {n:,}: radii uniform in [0.5R, 1.5R]")
    out()
    out("| what | 1 thread (s) | all cores (s) |")
    out("|---|---:|---:|")
    times = {}
    for name, r in (("equal radius R", R), ("radii in [0.5R, 1.5R]", radii)):
        row = []
        for workers in (1, None):
            row.append(best_of(args.reps, lambda: dv.limited_cells(pts, r, workers=workers, progress=False))[0])
        times[name] = row
        out(f"| `limited_cells`, {name} | {row[0]:.3f} | {row[1]:.3f} |")
    eq, het = times["equal radius R"], times["radii in [0.5R, 1.5R]"]
    part = dv.limited_cells(pts, radii, progress=False)
    # The published algorithms generalised to radical axes, 1 thread (slower: --hetero-methods).
    for m in args.hetero_methods:
        t = best_of(args.reps, lambda: dv.limited_cells(pts, radii, method=m, workers=1, progress=False))[0]
        out(f"| `limited_cells`, radii in [0.5R, 1.5R], `method=\"{m}\"` | {t:.3f} | — |")
    out()
    out(f"Ratio heterogeneous / equal radius: {het[0] / eq[0]:.2f} x (1 thread), {het[1] / eq[1]:.2f} x "
        f"(all cores). Mean agents examined per cell: {part.candidates.mean():.1f}; "
        f"empty cells: {int(part.empty.sum())}; computed by: {part.computed_by}.")
    out()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=float, default=1e5, help="agents for the Python comparison (default 1e5)")
    ap.add_argument("--k", type=float, default=30.0, help="expected agents within 2R (default 30)")
    ap.add_argument("--subset", type=int, default=2000,
                    help="agents timed in the per-cell shapely loop, extrapolated to n (default 2000)")
    ap.add_argument("--quad-segs", type=int, default=16,
                    help="shapely buffer segments per quarter circle (default 16, shapely's own is 8)")
    ap.add_argument("--reps", type=int, default=3, help="runs per timing, best kept (default 3)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cpp-bench", type=Path, default=DEFAULT_CPP,
                    help=f"bench_limited_cgal program (default {DEFAULT_CPP.relative_to(REPO)})")
    ap.add_argument("--cpp-n", type=float, default=1e6, help="agents for the C++ run (default 1e6)")
    ap.add_argument("--cpp-threads", type=int, default=2, help="threads of the multi-threaded C++ run")
    ap.add_argument("--no-cpp", action="store_true", help="skip the C++ program")
    ap.add_argument("--out", type=Path, help="also write the markdown report to this file")
    ap.add_argument("--hetero-only", action="store_true",
                    help="only the heterogeneous-team comparison (section 3)")
    ap.add_argument("--hetero-methods", type=lambda v: [m for m in v.split(",") if m], default=[],
                    help="also time these methods with per-agent radii, 1 thread (e.g. scan,chords)")
    ap.add_argument("--quick", action="store_true",
                    help="small smoke run: n = 1e4, C++ n = 1e5, subset 300, 1 rep")
    args = ap.parse_args(argv)
    if args.quick:
        args.n, args.cpp_n, args.subset, args.reps = 1e4, 1e5, 300, 1
    n, cpp_n = int(args.n), int(args.cpp_n)

    import dvoronoi as dv

    lines = []

    def out(s=""):
        lines.append(s)
        print(s, flush=True)

    # Header first (machine info), then the sections as they finish.
    out("## dvoronoi benchmark")
    out()
    out(f"- date: {_dt.datetime.now().astimezone().strftime('%Y-%m-%d %H:%M %Z')}")
    out(f"- machine: {cpu_model()}, {os.cpu_count()} logical cores, {platform.system()} "
        f"{platform.release()}; load average at start (1/5/15 min): {load_average()}")
    out(f"- {versions()}")
    out(f"- points: uniform in the unit square, R = sqrt({args.k:g} / (4 pi n)), i.e. about "
        f"{args.k:g} agents within 2R; best of {args.reps} runs; seed {args.seed}")
    out()

    if args.hetero_only:
        heterogeneous(dv, n, args, out)
        if args.out:
            args.out.write_text("\n".join(lines) + "\n")
        return 0

    # ---- 1. C++
    out(f"### C++: dvoronoi vs CGAL, n = {cpp_n:,}")
    out()
    if args.no_cpp:
        out("(skipped: --no-cpp)")
    elif not args.cpp_bench.exists():
        out(f"(not built: {args.cpp_bench} does not exist. Build it with `cmake -S . -B build "
            "-DDVORONOI_BUILD_BENCHMARKS=ON && cmake --build build --target bench_limited_cgal`, "
            "or pass --cpp-bench PATH)")
    else:
        res = run_cpp(args.cpp_bench, cpp_n, args.k, args.reps, args.cpp_threads, args.seed)
        r = res["rows"][0]
        T = r["threads"]
        ns = lambda s: s * 1e9 / r["n"]  # noqa: E731
        out(f"CGAL {res['cgal_version']}, OpenMP {'on' if res['openmp'] else 'off'}, "
            f"-march=native {'on' if res['native'] else 'off'}. Per agent: {r['mean_candidates']:.1f} "
            f"agents within 2R, {r['mean_limited_neighbors']:.2f} limited neighbours, "
            f"{r['mean_delaunay_neighbors']:.2f} Delaunay neighbours.")
        out()
        out("| what | time (s) | ns / agent | ratio |")
        out("|---|---:|---:|---|")
        out(f"| CGAL Delaunay_triangulation_2 (Epick) + neighbour walk, 1 thread | {r['cgal_s']:.3f} | "
            f"{ns(r['cgal_s']):.0f} | reference |")
        out(f"| dvoronoi `limited_cells`, auto, 1 thread | {r['scan1_s']:.3f} | {ns(r['scan1_s']):.0f} | "
            f"{r['scan1_s'] / r['cgal_s']:.2f} x CGAL's time |")
        out(f"| dvoronoi `limited_cells`, auto, {T} threads | {r['scanT_s']:.3f} | {ns(r['scanT_s']):.0f} | "
            f"{r['scan1_s'] / r['scanT_s']:.2f} x speed-up over 1 thread |")
        out(f"| dvoronoi `limited_cells`, Chords (RCVC), 1 thread | {r['chords1_s']:.3f} | "
            f"{ns(r['chords1_s']):.0f} | {r['chords1_s'] / r['scan1_s']:.2f} x auto's time |")
        out()
        out("CGAL gives the unlimited Delaunay graph only; dvoronoi gives limited neighbours and every "
            "cell's exact pieces, area, perimeter and centroid. "
            f"Consistency checks (Scan = Chords = threaded; limited neighbours are Delaunay neighbours): "
            f"{'ok' if r['ok'] else 'FAILED: ' + r['problem']}.")
    out()

    # ---- 2. Python, all agents
    pts, R = uniform_points(n, args.k, args.seed)
    print(f"Python comparison, n = {n} ...", file=sys.stderr, flush=True)
    t_dv1, part = best_of(args.reps, lambda: dv.limited_cells(pts, R, workers=1, progress=False))
    t_dvall, _ = best_of(args.reps, lambda: dv.limited_cells(pts, R, workers=None, progress=False))
    t_vor, vor = best_of(args.reps, lambda: scipy_voronoi(pts))
    subset = np.random.default_rng(args.seed + 1).choice(n, size=min(args.subset, n), replace=False)
    t_loop, (loop_areas, _) = best_of(args.reps,
                                      lambda: shapely_loop(pts, R, vor, subset, args.quad_segs))
    t_loop_total = t_vor + t_loop / len(subset) * n
    t_vec, (vec_areas, vec_cents) = best_of(args.reps,
                                            lambda: shapely_vectorized(pts, R, vor, args.quad_segs))
    t_vec_total = t_vor + t_vec
    exact = np.asarray(part.areas)
    rel_area = np.abs(vec_areas - exact) / exact
    cen_err = np.linalg.norm(vec_cents - np.asarray(part.centroids), axis=1) / R
    loop_rel = np.abs(loop_areas - exact[subset]) / exact[subset]

    us = lambda s: s * 1e6 / n  # noqa: E731
    out(f"### Python: `dv.limited_cells` vs scipy.spatial.Voronoi + shapely, n = {n:,}")
    out()
    out(f"R = {R:.4g}; per agent {float(np.mean(part.candidates)):.1f} agents within 2R, "
        f"{len(part.indices) / n:.2f} limited neighbours. shapely disks: `buffer(R, quad_segs="
        f"{args.quad_segs})` ({4 * args.quad_segs}-gon).")
    out()
    out("| what | time (s) | µs / agent | vs dvoronoi 1 thread |")
    out("|---|---:|---:|---:|")
    out(f"| dvoronoi `limited_cells`, 1 thread | {t_dv1:.3f} | {us(t_dv1):.2f} | 1 |")
    out(f"| dvoronoi `limited_cells`, all {os.cpu_count()} cores | {t_dvall:.3f} | {us(t_dvall):.2f} | "
        f"{t_dvall / t_dv1:.2f} |")
    out(f"| scipy `Voronoi` alone (no clipping) | {t_vor:.3f} | {us(t_vor):.2f} | {t_vor / t_dv1:.1f} |")
    out(f"| scipy `Voronoi` + shapely, per-cell loop (**extrapolated** from {len(subset):,} agents) | "
        f"{t_loop_total:.2f} | {us(t_loop_total):.1f} | {t_loop_total / t_dv1:.0f} |")
    out(f"| scipy `Voronoi` + shapely 2 vectorised, all agents | {t_vec_total:.2f} | {us(t_vec_total):.1f} | "
        f"{t_vec_total / t_dv1:.1f} |")
    out()
    out(f"scipy + shapely give areas and centroids only (their Delaunay neighbours are not the limited "
        f"ones), from a {4 * args.quad_segs}-gon disk: area relative error vs dvoronoi's exact areas "
        f"median {np.median(rel_area):.1e}, max {rel_area.max():.1e} (loop subset max "
        f"{loop_rel.max():.1e}); centroid error max {cen_err.max():.1e} R.")
    out()

    # ---- 3. one agent's latency
    rng = np.random.default_rng(args.seed + 2)
    Rl = 1.0
    rad = 2.0 * Rl * np.sqrt(rng.random(30)) * 0.999
    ang = 2.0 * np.pi * rng.random(30)
    others = np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])
    center = np.zeros(2)
    print("one-agent latency ...", file=sys.stderr, flush=True)

    def per_call_us(stmt) -> float:
        timer = timeit.Timer(stmt)
        number, _ = timer.autorange()
        return min(timer.repeat(repeat=max(args.reps, 3), number=number)) / number * 1e6

    from scipy.spatial import Voronoi
    from shapely.geometry import Point, Polygon

    local = np.vstack([center, others])
    box = sentinels(local)

    def scipy_one():
        v = Voronoi(np.vstack([local, box]))
        region = v.regions[v.point_region[0]]
        cell = Polygon(v.vertices[region]).intersection(Point(center).buffer(Rl, quad_segs=args.quad_segs))
        return cell.area, cell.centroid

    lat_scan = per_call_us(lambda: dv.limited_cell(center, others, Rl))
    lat_chords = per_call_us(lambda: dv.limited_cell(center, others, Rl, method="chords"))
    lat_scipy = per_call_us(scipy_one)
    cell = dv.limited_cell(center, others, Rl)
    lat_area = per_call_us(lambda: dv.limited_cell(center, others, Rl).area)
    out("### One agent's cell (a robot's control step), 30 others within 2R")
    out()
    out(f"The cell has {len(cell.neighbors)} limited neighbours; timeit, best of "
        f"{max(args.reps, 3)} repeats, Python call overhead included.")
    out()
    out("| call | µs per call | vs dvoronoi auto |")
    out("|---|---:|---:|")
    out(f"| `dv.limited_cell(center, others, R)` (auto = Boundary Scan for one agent) | {lat_scan:.1f} | 1 |")
    out(f"| `dv.limited_cell(center, others, R).area` | {lat_area:.1f} | {lat_area / lat_scan:.2f} |")
    out(f"| `dv.limited_cell(..., method=\"chords\")` | {lat_chords:.1f} | {lat_chords / lat_scan:.2f} |")
    out(f"| scipy `Voronoi` of 31 (+4 sentinel) points + shapely clip of one cell | {lat_scipy:.1f} | "
        f"{lat_scipy / lat_scan:.1f} |")
    out()
    out(f"load average at end (1/5/15 min): {load_average()}")

    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("\n".join(lines) + "\n")
        print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
