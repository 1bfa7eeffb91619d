"""Mendes et al., Figures 5 and 6: speed-up of the grid Voronoi diagram with 1, 2, 4 and 6 workers,
for the no-communication (independent) and cooperative approaches, on the "sea of triangles" and
"mixed shapes" maps, at grids 1024, 2048 and 4096.

The paper ran one MPI process per workstation on a cluster and plotted measured speed-ups (its
text gives no numbers: near-linear on the sea of triangles, lower on mixed shapes, the cooperative
approach slightly ahead in most cases, the no-communication one faster in two 2-processor runs of
mixed shapes below the largest grid). This machine has 2 cores, so three things are reported, each
under its own name:

- measured: wall-clock time per call with 1 and 2 workers, as threads
  (``dv.grid_voronoi(..., workers=K, mode=...)``) and as MPI ranks (``mpirun -n K
  dvoronoi_gvd_mpi``, the program's own total time, without mpirun's start-up); each threads figure
  is the median over --reps batches of calls that last at least --min-time seconds, each MPI
  figure the median over --reps launches; speed-up = T(1) / T(2) of the same runner;
- checked: 4 and 6 workers run by oversubscription (threads and ranks) only to assert that the
  diagram is identical for every K, approach and runner; their times mean nothing here;
- model (K = 1, 2, 4, 6): the distance evaluations each worker made (``worker_evaluations``, counted
  exactly, the work the paper's cost consists of), speed-up = all evaluations of one worker / those
  of the busiest of K. It assumes one free core per worker and free communication: a model, not a
  measurement.

Outputs: tools/reproduce/out/gvd_speedup.csv and .png (suffix _quick with --quick).
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

OUT = Path(__file__).resolve().parent / "out"
REPO = Path(__file__).resolve().parents[2]


def mpi_run(doc, grid, k, mode):
    exe = os.environ.get("DVORONOI_GVD_MPI") or str(REPO / "build" / "cpp" / "mpi" / "dvoronoi_gvd_mpi")
    flags = ["--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "map.json", Path(tmp) / "out.json"
        src.write_text(json.dumps(doc))
        subprocess.run(["mpirun", *flags, "-n", str(k), exe, str(src), "--grid", str(grid), "--mode", mode, "-o", str(out)],
                       check=True, capture_output=True)
        res = json.loads(out.read_text())
    st = res["stats"]
    return st["total_seconds"], st, (res["cells"]["col"], res["cells"]["row"])


def thread_run(doc, grid, k, mode):
    import dvoronoi as dv
    t0 = time.perf_counter()
    r = dv.grid_voronoi(doc, cells=grid, workers=k, mode=mode)
    return time.perf_counter() - t0, r.stats, (r.cells[:, 0].tolist(), r.cells[:, 1].tolist())


def thread_time(doc, grid, k, mode, reps, min_time):
    """Median over `reps` batches of the time per call, each batch lasting at least min_time."""
    per_call = []
    for _ in range(reps):
        calls, t0 = 0, time.perf_counter()
        while True:
            thread_run(doc, grid, k, mode)
            calls += 1
            if time.perf_counter() - t0 >= min_time:
                break
        per_call.append((time.perf_counter() - t0) / calls)
    return statistics.median(per_call)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--grids", default="1024,2048,4096")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--min-time", type=float, default=0.3, help="seconds per batch of thread calls (default 0.3)")
    ap.add_argument("--no-mpi", action="store_true", help="threads only (no mpirun)")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    if a.quick:
        a.grids, a.reps, a.min_time = "256,512", 1, 0.05
    from dvoronoi.gvd_maps import mixed_shapes, sea_of_triangles
    from tqdm import tqdm

    maps = {"sea of triangles": sea_of_triangles(1, per_side=20), "mixed shapes": mixed_shapes()}
    grids = [int(g) for g in a.grids.split(",")]
    modes = ["independent", "cooperative"]
    model_k, measured_k = [1, 2, 4, 6], [1, 2]
    runners = ["threads"] + ([] if a.no_mpi else ["mpi"])
    rows = []
    jobs = [(m, g, mode) for m in maps for g in grids for mode in modes]
    reference = {}
    for name, grid, mode in tqdm(jobs, desc="map, grid, approach"):
        doc = maps[name]
        ref = reference.setdefault((name, grid), thread_run(doc, grid, 1, "cooperative")[2])
        evals, cells_per_k = {}, {}
        for runner in runners:  # checked: every K, oversubscribed beyond the cores, same diagram
            for k in model_k:
                _, st, cells = (thread_run if runner == "threads" else mpi_run)(doc, grid, k, mode)
                assert cells == ref, f"diagram differs: {name} {grid} {mode} K={k} ({runner})"
                if runner == "threads":
                    evals[k] = [int(e) for e in st["worker_evaluations"]]
                    cells_per_k[k] = len(cells[0])
        wall = {}
        for runner in runners:  # measured: the cores this machine has
            for k in measured_k:
                if runner == "threads":
                    wall[runner, k] = thread_time(doc, grid, k, mode, a.reps, a.min_time)
                else:
                    wall[runner, k] = statistics.median(mpi_run(doc, grid, k, mode)[0] for _ in range(a.reps))
        total1 = sum(evals[1])
        for k in model_k:
            row = {"map": name, "grid": grid, "approach": mode, "workers": k,
                   "model_speedup": round(total1 / max(evals[k]), 3), "busiest_worker_evaluations": max(evals[k]),
                   "all_evaluations": sum(evals[k]), "diagram_cells": cells_per_k[k]}
            for runner in ("threads", "mpi"):
                t = wall.get((runner, k))
                row[f"{runner}_wall_s"] = "" if t is None else round(t, 5)
                row[f"{runner}_speedup"] = "" if t is None else round(wall[runner, 1] / t, 3)
            rows.append(row)
    OUT.mkdir(parents=True, exist_ok=True)
    stem = "gvd_speedup" + ("_quick" if a.quick else "")
    with open(OUT / f"{stem}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    for ax, mode in zip(axes, modes):
        ax.plot(model_k, model_k, "k:", lw=1, label="linear")
        for (name, color) in zip(maps, ["tab:blue", "tab:orange"]):
            for grid, ls in zip(grids, ["-", "--", "-."]):
                sel = [r for r in rows if r["map"] == name and r["grid"] == grid and r["approach"] == mode]
                ax.plot([r["workers"] for r in sel], [r["model_speedup"] for r in sel], color=color, ls=ls,
                        marker="o", ms=3, label=f"model: {name}, {grid}")
                for runner, marker in (("threads", "^"), ("mpi", "s")):
                    got = [(r["workers"], r[f"{runner}_speedup"]) for r in sel if r[f"{runner}_speedup"] != ""]
                    if got:
                        ax.plot(*zip(*got), color=color, ls="none", marker=marker, ms=6, mfc="none",
                                label=f"measured ({runner}): {name}, {grid}" if grid == grids[-1] else None)
        title = "No communication (Fig. 5)" if mode == "independent" else "Cooperative (Fig. 6)"
        ax.set_title(f"{title}\nlines: work model; open markers: measured wall clock (2 cores)")
        ax.set_xlabel("workers")
        ax.set_ylabel("speed-up")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(OUT / f"{stem}.png", dpi=110)
    print(f"wrote {OUT / (stem + '.csv')} and {OUT / (stem + '.png')}")
    for r in rows:
        meas = "  ".join(f"{x} {r[x + '_wall_s'] * 1e3:.1f} ms (x{r[x + '_speedup']:.2f})" for x in ("threads", "mpi")
                         if r[x + "_wall_s"] != "")
        print(f"{r['map']:>16} {r['grid']:>5} {r['approach']:>11} K={r['workers']}: model x{r['model_speedup']:.2f}  {meas}")


if __name__ == "__main__":
    main()
