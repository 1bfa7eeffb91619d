#!/usr/bin/env python3
"""Boundary Scan vs RCVC time against sensor density: the setup of Figure 6 of He, Feng & Ren (2018),
"Distributed Algorithm for Voronoi Partition of Wireless Sensor Networks with a Limited Sensing Range",
Section 4.1.

Paper: 500 sensors with sensing range r = 1, uniform in a square of side L = 1, 2, ..., 10 (density
rho = 500 / L^2); for each L the total time of all sensors' r/2-limited cells, averaged over 10 random
configurations, for BS and RCVC; log-log plot of time vs density. The paper's claims: RCVC takes 3-6x
BS's time at moderate density ("tens of neighbours in the sensing range"), about the same at low
density, and up to 70x at the highest density.

Here: the paper's r is the neighbourhood, so our cell radius is R = r / 2 (docs/spec.md). Both
algorithms are timed through ``dv.limited_cells(points, R, method, workers=1)`` - one call for all 500
sensors, each sensor's cell computed from the sensors within r = 2R, exactly as the paper's per-sensor
computation (the grid index that finds them is shared by both methods). ``method="scan"`` runs Boundary
Scan on every sensor (checked: ``computed_by["scan"] == 500``), ``method="chords"`` RCVC. Our default
``method="auto"`` (a certified clipping filter in front of Boundary Scan, not a published algorithm) is
timed too, for reference only (column ``time_auto_s``); it is not what the paper compares. Each time is the best of --repeat runs;
configurations are averaged. ``fixed_cost_s`` is the time of the same call with a radius so small that
every cell is a lone disk: index, input checks and result arrays, which both methods pay. Scan, Chords
and Auto must return the same neighbours (checked on every configuration).

Outputs: out/bs_vs_rcvc_density.csv and out/bs_vs_rcvc_density.png (or *_quick.* with --quick).
"""
from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchutil import best_of, git_describe  # noqa: E402

OUT = Path(__file__).resolve().parent / "out"

PAPER = {"moderate": (3.0, 6.0), "low": 1.0, "highest": 70.0}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sensors", type=int, default=500)
    ap.add_argument("--r", type=float, default=1.0, help="sensing range r of the paper (our R = r/2)")
    ap.add_argument("--sides", type=str, default="1,2,3,4,5,6,7,8,9,10", help="square sides L")
    ap.add_argument("--configs", type=int, default=10, help="random configurations per side")
    ap.add_argument("--repeat", type=int, default=3, help="timing runs per configuration (best kept)")
    ap.add_argument("--seed", type=int, default=2018)
    ap.add_argument("--out", type=Path, default=OUT, help="output folder (default tools/reproduce/out)")
    ap.add_argument("--quick", action="store_true", help="sides 1,4,10, 2 configurations, 1 run each")
    args = ap.parse_args(argv)
    if args.quick:
        args.sides, args.configs, args.repeat = "1,4,10", 2, 1
    sides = [float(s) for s in args.sides.split(",") if s.strip()]
    R = args.r / 2.0
    n = args.sensors

    import dvoronoi as dv
    from tqdm import tqdm

    rows = []
    bar = tqdm(total=len(sides) * args.configs, unit="config", desc="BS vs RCVC")
    for L in sides:
        ts, tc, ta, tf, cand, lim = [], [], [], [], [], []
        for c in range(args.configs):
            rng = np.random.default_rng([args.seed, int(round(L * 1000)), c])
            pts = rng.random((n, 2)) * L
            # Alternate the order so neither method always runs on a warm cache.
            order = ("scan", "chords", "auto") if c % 2 == 0 else ("chords", "scan", "auto")
            res = {}
            for m in order:
                res[m] = best_of(args.repeat,
                                 lambda: dv.limited_cells(pts, R, method=m, workers=1, progress=False))
            t_fixed, _ = best_of(args.repeat,
                                 lambda: dv.limited_cells(pts, 1e-9 * L, workers=1, progress=False))
            scan, chords, auto = res["scan"][1], res["chords"][1], res["auto"][1]
            for other in (chords, auto):
                if not (np.array_equal(scan.indptr, other.indptr) and np.array_equal(scan.indices, other.indices)):
                    raise SystemExit(f"L = {L}, configuration {c}: {other.method} and scan disagree on the neighbours")
            if scan.computed_by["scan"] != n or chords.computed_by["chords"] != n:
                raise SystemExit(f"L = {L}: scan / chords did not run their algorithm on every sensor")
            ts.append(res["scan"][0])
            tc.append(res["chords"][0])
            ta.append(res["auto"][0])
            tf.append(t_fixed)
            cand.append(float(np.mean(scan.candidates)))
            lim.append(len(scan.indices) / n)
            bar.update()
        ts, tc, ta, tf = np.array(ts), np.array(tc), np.array(ta), np.array(tf)
        net_s, net_c = max(ts.mean() - tf.mean(), 1e-12), max(tc.mean() - tf.mean(), 1e-12)
        rows.append({
            "L": L,
            "density": n / L**2,
            "mean_neighbors_within_r": float(np.mean(cand)),
            "time_scan_s": float(ts.mean()),
            "time_chords_s": float(tc.mean()),
            "ratio": float(tc.mean() / ts.mean()),
            "mean_limited_neighbors": float(np.mean(lim)),
            "time_scan_std_s": float(ts.std()),
            "time_chords_std_s": float(tc.std()),
            "fixed_cost_s": float(tf.mean()),
            "ratio_without_fixed_cost": float(net_c / net_s),
            "time_auto_s": float(ta.mean()),
        })
    bar.close()

    args.out.mkdir(parents=True, exist_ok=True)
    stem = "bs_vs_rcvc_density" + ("_quick" if args.quick else "")
    csv_path, png_path = args.out / f"{stem}.csv", args.out / f"{stem}.png"
    with csv_path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})

    plot(rows, png_path, n, args)

    # ---- report
    print()
    print(f"{n} sensors, r = {args.r:g} (R = {R:g}), {args.configs} configurations per side, best of "
          f"{args.repeat} runs, 1 thread, dv.limited_cells for all sensors at once")
    print(f"dvoronoi {dv.__version__}, git {git_describe()}")
    print(f"{'L':>4} {'density':>8} {'nbrs<r':>7} {'limited':>7} {'scan (ms)':>10} {'chords (ms)':>12} "
          f"{'ratio':>6} {'fixed (ms)':>10} {'ratio-fixed':>11} {'auto (ms)':>10}")
    for r in rows:
        print(f"{r['L']:4g} {r['density']:8.1f} {r['mean_neighbors_within_r']:7.1f} "
              f"{r['mean_limited_neighbors']:7.2f} {r['time_scan_s'] * 1e3:10.3f} "
              f"{r['time_chords_s'] * 1e3:12.3f} {r['ratio']:6.2f} {r['fixed_cost_s'] * 1e3:10.3f} "
              f"{r['ratio_without_fixed_cost']:11.2f} {r['time_auto_s'] * 1e3:10.3f}")
    print()
    print("Against the paper's claims (ratio = RCVC time / BS time). Density classes by the mean number")
    print("of sensors within r: low < 20, moderate 20-100 ('tens of neighbours'), high >= 100:")
    classes = {
        "low": [r for r in rows if r["mean_neighbors_within_r"] < 20.0],
        "moderate": [r for r in rows if 20.0 <= r["mean_neighbors_within_r"] < 100.0],
        "high": [r for r in rows if r["mean_neighbors_within_r"] >= 100.0],
    }
    paper_txt = {"low": "about 1x", "moderate": "3 to 6x", "high": "up to 70x at the highest density"}
    for name, sel in classes.items():
        if not sel:
            print(f"  {name:8s}: no side in this class")
            continue
        lo, hi = min(r["ratio"] for r in sel), max(r["ratio"] for r in sel)
        sides_txt = ", ".join(f"{r['L']:g}" for r in sel)
        print(f"  {name:8s}: L = {sides_txt}: ratio {lo:.2f} to {hi:.2f}; paper: {paper_txt[name]}")
    high = min(rows, key=lambda r: r["L"])
    print(f"  highest density (L = {high['L']:g}, {high['mean_neighbors_within_r']:.0f} sensors within r): "
          f"ratio {high['ratio']:.1f}; paper: up to 70x")
    print(f"wrote {csv_path}\nwrote {png_path}")
    return 0


def plot(rows, path: Path, n: int, args) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = np.array([r["density"] for r in rows])
    ts = np.array([r["time_scan_s"] for r in rows])
    tc = np.array([r["time_chords_s"] for r in rows])
    ss = np.array([r["time_scan_std_s"] for r in rows])
    sc = np.array([r["time_chords_std_s"] for r in rows])
    ratio = np.array([r["ratio"] for r in rows])
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    a.errorbar(d, ts, yerr=ss, marker="o", color="tab:blue", label="Boundary Scan (method='scan')")
    a.errorbar(d, tc, yerr=sc, marker="s", color="tab:red", label="RCVC (method='chords')")
    a.plot(d, [r["time_auto_s"] for r in rows], ls="--", color="tab:cyan", label="dvoronoi fast path (method='auto'; not in the paper)")
    a.plot(d, [r["fixed_cost_s"] for r in rows], ls=":", color="gray", label="shared fixed cost")
    a.set_xscale("log")
    a.set_yscale("log")
    a.set_xlabel(r"density $\rho = N / L^2$")
    a.set_ylabel(f"time for all {n} sensors (s)")
    a.set_title(f"{n} sensors, r = {args.r:g}, L = {min(r['L'] for r in rows):g}..{max(r['L'] for r in rows):g}")
    a.grid(True, which="both", alpha=0.3)
    a.legend(fontsize=8)
    b.plot(d, ratio, marker="o", color="k", label="measured RCVC / BS")
    b.axhspan(*PAPER["moderate"], color="tab:green", alpha=0.15, label="paper: 3-6x (moderate)")
    b.axhline(PAPER["highest"], color="tab:red", ls="--", lw=1, label="paper: up to 70x (highest)")
    b.axhline(PAPER["low"], color="gray", ls="--", lw=1, label="paper: ~1x (low)")
    b.set_xscale("log")
    b.set_yscale("log")
    b.set_xlabel(r"density $\rho = N / L^2$")
    b.set_ylabel("time ratio RCVC / BS")
    b.grid(True, which="both", alpha=0.3)
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
