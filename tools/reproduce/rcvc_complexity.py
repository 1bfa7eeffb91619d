#!/usr/bin/env python3
"""The complexity experiment of Guruprasad & Dasgupta (IROS 2012), "Distributed Voronoi partitioning for
multi-robot systems with limited range sensors", Section VI and Fig. 8.

Paper: 25 random robots, sensor range R from 10 to 225 (their R is our cell radius R; docs/spec.md); for each
R every robot's range-constrained cell is computed and two ratios are averaged over the 25 robots:

  (a) M / (N log N), M = |P_i^{2R}| the robots within 2R (the input of RCVC), N = 25: RCVC's work
      against a full Voronoi diagram. Paper: the average reaches about 0.2 at large R; the maximum is
      below 0.3.
  (b) M' / N_i, M' = chords left after checkChords, N_i = limited (2R-limited Delaunay) neighbours:
      constructVor's work against the lower bound. Paper: the average stays below 3; the maximum is
      below 3.5.

Choices the paper leaves open, made here (all flags):
  * Region: the paper does not state it. Default a 400 x 400 square (--side): at R = 10 a robot
    almost never has another within 2R = 20; at R = 225 (2R = 450 > 400) almost all are in range.
  * log: natural log (--log e). N = 25 gives max M/(N ln N) = 24 / (25 ln 25) = 0.298 when every robot
    is in range, which matches the paper's "maximum below 0.3"; log2 would cap it at 0.207 and log10 at
    0.687 (contradicting it). The CSV also has the log2 column.
  * The paper shows one configuration; we average over --configs random configurations (the robots
    stay fixed while R grows, as in the paper) and also report the spread over configurations and the
    per-configuration maxima.
  * Robots with N_i = 0 (no limited neighbour: the cell is a full disk) have no M'/N_i; they are
    skipped in (b) and the skipped fraction is written to the CSV.

M, M' and N_i come from ``dv.limited_cell(p_i, others, R, method="chords")``: ``cell.candidates``,
``cell.chords_after_check`` and ``len(cell.neighbors)``, one call per robot and R.

Outputs: out/rcvc_complexity_side<S>.csv and .png (or *_quick.* with --quick).
"""
from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchutil import git_describe  # noqa: E402

OUT = Path(__file__).resolve().parent / "out"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--robots", type=int, default=25)
    ap.add_argument("--side", type=float, default=400.0, help="side of the square region (default 400)")
    ap.add_argument("--r-min", type=float, default=10.0)
    ap.add_argument("--r-max", type=float, default=225.0)
    ap.add_argument("--r-step", type=float, default=5.0)
    ap.add_argument("--configs", type=int, default=50, help="random configurations (default 50)")
    ap.add_argument("--log", choices=["e", "2"], default="e", help="log of N log N (default natural)")
    ap.add_argument("--seed", type=int, default=2012)
    ap.add_argument("--out", type=Path, default=OUT, help="output folder (default tools/reproduce/out)")
    ap.add_argument("--quick", action="store_true", help="5 configurations, 11 radii")
    args = ap.parse_args(argv)
    if args.quick:
        args.configs, args.r_step = 5, (args.r_max - args.r_min) / 10.0

    import dvoronoi as dv
    from tqdm import tqdm

    N = args.robots
    radii = np.arange(args.r_min, args.r_max + 1e-9, args.r_step)
    nlogn = N * (math.log(N) if args.log == "e" else math.log2(N))
    nlog2n = N * math.log2(N)
    C, K = args.configs, len(radii)
    # Per configuration and R: mean and max over robots.
    a_mean = np.zeros((C, K))
    a_max = np.zeros((C, K))
    b_mean = np.full((C, K), np.nan)
    b_max = np.full((C, K), np.nan)
    skipped = np.zeros((C, K))
    m_mean = np.zeros((C, K))
    ni_mean = np.zeros((C, K))
    mp_mean = np.zeros((C, K))

    with tqdm(total=C * K, unit="R", desc="RCVC complexity") as bar:
        for c in range(C):
            rng = np.random.default_rng([args.seed, c])
            pts = rng.random((N, 2)) * args.side
            d = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=2)
            for k, R in enumerate(radii):
                M = np.empty(N)
                Mp = np.empty(N)
                Ni = np.empty(N)
                for i in range(N):
                    others = np.delete(pts, i, axis=0)
                    cell = dv.limited_cell(pts[i], others, float(R), method="chords")
                    M[i], Mp[i], Ni[i] = cell.candidates, cell.chords_after_check, len(cell.neighbors)
                # Sanity: M is the number of robots strictly within 2R.
                expect = (d < 2.0 * R).sum(axis=1) - 1
                if not np.array_equal(M, expect):
                    raise SystemExit(f"configuration {c}, R = {R}: candidates differ from a direct count")
                a = M / nlogn
                a_mean[c, k], a_max[c, k] = a.mean(), a.max()
                m_mean[c, k], ni_mean[c, k], mp_mean[c, k] = M.mean(), Ni.mean(), Mp.mean()
                has = Ni > 0
                skipped[c, k] = 1.0 - has.mean()
                if has.any():
                    b = Mp[has] / Ni[has]
                    b_mean[c, k], b_max[c, k] = b.mean(), b.max()
                bar.update()

    def nanpct(x, q):
        return np.array([np.nanpercentile(col, q) if np.isfinite(col).any() else np.nan for col in x.T])

    with np.errstate(all="ignore"):
        b_curve = np.nanmean(b_mean, axis=0)
    rows = []
    for k, R in enumerate(radii):
        rows.append({
            "R": R,
            "mean_M": m_mean[:, k].mean(),
            "mean_limited_neighbors": ni_mean[:, k].mean(),
            "mean_M_prime": mp_mean[:, k].mean(),
            "M_over_NlogN_mean": a_mean[:, k].mean(),
            "M_over_NlogN_p10": np.percentile(a_mean[:, k], 10),
            "M_over_NlogN_p90": np.percentile(a_mean[:, k], 90),
            "M_over_NlogN_max": a_max[:, k].max(),
            "M_over_Nlog2N_mean": a_mean[:, k].mean() * nlogn / nlog2n,
            "Mp_over_Ni_mean": b_curve[k],
            "Mp_over_Ni_p10": nanpct(b_mean[:, [k]], 10)[0],
            "Mp_over_Ni_p90": nanpct(b_mean[:, [k]], 90)[0],
            "Mp_over_Ni_max": np.nanmax(b_max[:, k]) if np.isfinite(b_max[:, k]).any() else np.nan,
            "skipped_fraction_Ni0": skipped[:, k].mean(),
        })

    args.out.mkdir(parents=True, exist_ok=True)
    stem = f"rcvc_complexity_side{args.side:g}" + ("_quick" if args.quick else "")
    csv_path, png_path = args.out / f"{stem}.csv", args.out / f"{stem}.png"
    with csv_path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: f"{float(v):.6g}" for k, v in r.items()})
    logname = "ln" if args.log == "e" else "log2"
    plot(radii, rows, a_mean, b_mean, png_path, args, logname)

    # ---- report
    a_curve = a_mean.mean(axis=0)
    ka = int(np.argmax(a_curve))
    kb = int(np.nanargmax(b_curve))
    cfg_a_curve_max = a_mean.max(axis=1)             # per configuration: max over R of its average
    cfg_b_curve_max = np.nanmax(b_mean, axis=1)
    cfg_b_max = np.nanmax(b_max, axis=1)              # per configuration: max over R and robots
    print()
    print(f"{N} robots in a {args.side:g} x {args.side:g} square, R = {radii[0]:g}..{radii[-1]:g} step "
          f"{args.r_step:g}, {C} configurations, log = {logname}; dvoronoi {dv.__version__}, git {git_describe()}")
    print(f"{'R':>6} {'mean M':>7} {'M/(N' + logname + 'N)':>12} {'max':>6} {'mean Ni':>8} {'mean M1':>8} "
          f"{'M1/Ni':>6} {'max':>6} {'skip':>5}")
    for r in rows:
        print(f"{r['R']:6g} {r['mean_M']:7.2f} {r['M_over_NlogN_mean']:12.3f} {r['M_over_NlogN_max']:6.3f} "
              f"{r['mean_limited_neighbors']:8.2f} {r['mean_M_prime']:8.2f} {r['Mp_over_Ni_mean']:6.2f} "
              f"{r['Mp_over_Ni_max']:6.2f} {r['skipped_fraction_Ni0']:5.2f}")
    print("(M1 = M' = chords after checkChords; skip = fraction of robots with N_i = 0, left out of M'/N_i)")
    print()
    print("Against the paper (one configuration of 25 robots there; here the mean over configurations,")
    print("and per configuration for the maxima):")
    print(f"  (a) mean M/(N {logname} N): paper reaches about 0.2 at large R. Here max over R of the mean "
          f"curve = {a_curve[ka]:.3f} (R = {radii[ka]:g}); per configuration {np.min(cfg_a_curve_max):.3f} "
          f"to {np.max(cfg_a_curve_max):.3f}.")
    print(f"      with log2 instead: {a_curve[ka] * nlogn / nlog2n:.3f}.")
    print(f"  (a) max M/(N {logname} N): paper below 0.3. Here {a_max.max():.3f} "
          f"(bound when all {N - 1} others are in range: {(N - 1) / nlogn:.3f}).")
    print(f"  (b) mean M'/N_i: paper below 3. Here max over R of the mean curve = {b_curve[kb]:.2f} "
          f"(R = {radii[kb]:g}); per configuration the max over R of its average is below 3 in "
          f"{np.mean(cfg_b_curve_max < 3.0) * 100:.0f}% of configurations (largest {np.max(cfg_b_curve_max):.2f}).")
    print(f"  (b) max M'/N_i: paper below 3.5. Here per configuration (max over R and robots) below 3.5 in "
          f"{np.mean(cfg_b_max < 3.5) * 100:.0f}% of configurations; median {np.median(cfg_b_max):.2f}, "
          f"largest {np.max(cfg_b_max):.2f}.")
    print(f"wrote {csv_path}\nwrote {png_path}")
    return 0


def plot(radii, rows, a_mean, b_mean, path: Path, args, logname: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    col = lambda key: np.array([r[key] for r in rows], dtype=float)  # noqa: E731
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    a.fill_between(radii, col("M_over_NlogN_p10"), col("M_over_NlogN_p90"), color="tab:blue", alpha=0.2,
                   label="10-90% of configurations")
    a.plot(radii, col("M_over_NlogN_mean"), "o-", ms=3, color="tab:blue", label="mean over robots")
    a.plot(radii, col("M_over_NlogN_max"), "--", color="tab:red", label="max over robots")
    a.axhline(0.2, color="gray", ls=":", lw=1, label="paper: mean ~0.2, max < 0.3")
    a.axhline(0.3, color="gray", ls=":", lw=1)
    a.set_xlabel("sensor range R")
    a.set_ylabel(f"M / (N {logname} N)")
    a.set_title(f"(a) {args.robots} robots, {args.side:g} x {args.side:g}, {args.configs} configurations",
                fontsize=10)
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8)
    b.fill_between(radii, col("Mp_over_Ni_p10"), col("Mp_over_Ni_p90"), color="tab:blue", alpha=0.2,
                   label="10-90% of configurations")
    b.plot(radii, col("Mp_over_Ni_mean"), "o-", ms=3, color="tab:blue", label="mean over robots (N_i > 0)")
    b.plot(radii, col("Mp_over_Ni_max"), "--", color="tab:red", label="max over robots")
    b.axhline(3.0, color="gray", ls=":", lw=1, label="paper: mean < 3, max < 3.5")
    b.axhline(3.5, color="gray", ls=":", lw=1)
    b.set_xlabel("sensor range R")
    b.set_ylabel(r"$M' / N_i$")
    b.set_title("(b) chords after checkChords / limited neighbours", fontsize=10)
    b.grid(True, alpha=0.3)
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
