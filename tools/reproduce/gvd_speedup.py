#!/usr/bin/env python3
"""Mendes et al., Figures 5 and 6: speed-up of the grid Voronoi diagram with 1, 2, 4 and 6 workers,
for the no-communication (independent) and cooperative approaches, on the "sea of triangles" and
"mixed shapes" maps, at grids 1024, 2048 and 4096.

The paper ran one MPI process per workstation on a 6-machine cluster. Here the workers are threads
(``dv.grid_voronoi(..., workers=K, mode=...)``; ``--mpi`` runs ``mpirun -n K dvoronoi_gvd_mpi``
instead), on a machine with only 2 cores shared with other jobs: beyond 2 workers the wall-clock
speed-up cannot grow. So two speed-ups are written for each run:

- wall: T(1 worker) / T(K workers), best of --reps runs, whole call;
- work: the single worker's tracing CPU time / the busiest worker's tracing CPU time (per-thread CPU
  clocks), i.e. the speed-up the slicing would give with one free core per worker, which is what
  the paper's cluster measured. Extra work of the independent approach (each border scanned twice)
  and load imbalance between slices both show in it.

Outputs: tools/reproduce/out/gvd_speedup.csv and .png (suffix _quick with --quick). The diagram is
checked to be identical for every K and approach.
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parent / "out"
REPO = Path(__file__).resolve().parents[2]


def mpi_run(doc, grid, k, mode):
    exe = os.environ.get("DVORONOI_GVD_MPI") or str(REPO / "build" / "cpp" / "mpi" / "dvoronoi_gvd_mpi")
    flags = ["--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "map.json", Path(tmp) / "out.json"
        src.write_text(json.dumps(doc))
        t0 = time.perf_counter()
        subprocess.run(["mpirun", *flags, "-n", str(k), exe, str(src), "--grid", str(grid), "--mode", mode, "-o", str(out)],
                       check=True, capture_output=True)
        res = json.loads(out.read_text())
    st = res["stats"]
    return st["total_seconds"], st, (res["cells"]["col"], res["cells"]["row"])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--grids", default="1024,2048,4096")
    ap.add_argument("--workers", default="1,2,4,6")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--mpi", action="store_true", help="MPI ranks (mpirun) instead of threads")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    if a.quick:
        a.grids, a.reps = "256,512", 1
    import dvoronoi as dv
    from dvoronoi.gvd_maps import mixed_shapes, sea_of_triangles
    from tqdm import tqdm

    maps = {"sea of triangles": sea_of_triangles(1, per_side=20), "mixed shapes": mixed_shapes()}
    grids = [int(g) for g in a.grids.split(",")]
    workers = [int(k) for k in a.workers.split(",")]
    modes = ["independent", "cooperative"]
    rows = []
    jobs = [(m, g, mode, k) for m in maps for g in grids for mode in modes for k in workers]
    base = {}
    for name, grid, mode, k in tqdm(jobs, desc="runs"):
        doc = maps[name]
        best_wall, best_cpu, cells = np.inf, np.inf, None
        for _ in range(a.reps):
            if a.mpi:
                wall, st, cells = mpi_run(doc, grid, k, mode)
            else:
                t0 = time.perf_counter()
                r = dv.grid_voronoi(doc, cells=grid, workers=k, mode=mode)
                wall, st, cells = time.perf_counter() - t0, r.stats, (r.cells[:, 0].tolist(), r.cells[:, 1].tolist())
            best_wall = min(best_wall, wall)
            best_cpu = min(best_cpu, max(st.get("worker_cpu_seconds") or st["worker_seconds"]))
        key = (name, grid, mode)  # speed-up within each approach, as the paper's Figures 5 and 6
        if key not in base:
            base[key] = (best_wall, best_cpu, cells)
        assert cells == base[(name, grid, modes[0])][2], f"diagram differs: {name} {grid} {mode} K={k}"
        rows.append({"map": name, "grid": grid, "approach": mode, "workers": k, "wall_s": round(best_wall, 5),
                     "busiest_worker_cpu_s": round(best_cpu, 5), "wall_speedup": round(base[key][0] / best_wall, 3),
                     "work_speedup": round(base[key][1] / best_cpu, 3), "corners_labelled": st["corners_labelled"],
                     "diagram_cells": len(cells[0]), "cores": os.cpu_count(), "runner": "mpi" if a.mpi else "threads"})
    OUT.mkdir(parents=True, exist_ok=True)
    stem = "gvd_speedup" + ("_mpi" if a.mpi else "") + ("_quick" if a.quick else "")
    with open(OUT / f"{stem}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(11, 9), sharex=True, sharey=True)
    for col, mode in enumerate(modes):
        for row, metric in enumerate(["work_speedup", "wall_speedup"]):
            ax = axes[row, col]
            ax.plot(workers, workers, "k:", lw=1, label="linear")
            for name, marker in zip(maps, "os"):
                for grid, ls in zip(grids, ["-", "--", "-."]):
                    pts = [(r["workers"], r[metric]) for r in rows if r["map"] == name and r["grid"] == grid and r["approach"] == mode]
                    ax.plot(*zip(*pts), marker=marker, ls=ls, label=f"{name}, {grid}")
            title = "No communication (Fig. 5)" if mode == "independent" else "Cooperative (Fig. 6)"
            ax.set_title(f"{title}: {'work (CPU) speed-up' if row == 0 else 'wall-clock speed-up'}")
            ax.set_xlabel("workers")
            ax.set_ylabel("speed-up")
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(f"Grid Voronoi diagram speed-up ({'MPI ranks' if a.mpi else 'threads'}; this machine has "
                 f"{os.cpu_count()} cores shared with other jobs: wall-clock cannot exceed ~2)", fontsize=10)
    fig.tight_layout()
    fig.savefig(OUT / f"{stem}.png", dpi=110)
    print(f"wrote {OUT / (stem + '.csv')} and {OUT / (stem + '.png')}")
    for r in rows:
        print(f"{r['map']:>16} {r['grid']:>5} {r['approach']:>11} K={r['workers']}: wall {r['wall_s']:.3f} s "
              f"(x{r['wall_speedup']:.2f}), work x{r['work_speedup']:.2f}")


if __name__ == "__main__":
    main()
