#!/usr/bin/env python3
"""Elwin, Freeman & Lynch (RA-L 2017), Section V-B / Fig. 8: Delaunay distortion delta_v against
detection distortion delta_m under the XBee RSSI noise model, with dvoronoi's distance-only Voronoi
neighbours.

Setup as in the paper: robots uniform in a 254 cm x 254 cm square; robots farther apart than 33 cm
neither sense nor talk; every detected pair measures RSSI both ways (quantised, the paper's quadratic
RSSI-to-distance fit; our noise spread `--sigma` dB, since the raw data are not published), e_ij is the
mean of the two; every robot runs VORONOI-NEIGHBORS, then the consistency step. N = 200, 300, ..., 1000.
Trials whose detection graph or computed graph is disconnected are discarded (as in the paper).

The paper ran 100 trials per N; the default here is 8 per N (72 trials, a few minutes) — `--trials`
sets it. Outputs (tools/reproduce/out/): distances_distortion.csv (one row per trial) and
distances_distortion.png (delta_v vs delta_m, with the lines delta_v/delta_m = 1, 2 and 6.5, and the
histogram of the ratio). The printed summary compares the ratio's distribution with the paper's
("bi-modal, clustered around 1 and 2, with delta_v / delta_m < 6.5").
"""
from __future__ import annotations

import argparse
import csv
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchutil import git_describe  # noqa: E402

import dvoronoi as dv  # noqa: E402

OUT = Path(__file__).resolve().parent / "out"


def one_trial(n: int, seed: int, sigma: float, side: float = 254.0):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0.0, side, size=(n, 2))
    e = dv.distances.measure(pts, model="rssi", sigma=sigma, seed=seed + 1_000_003)
    res = dv.neighbors_from_distances(e, workers=1)
    dm = dv.distances.detection_distortion(pts, e)
    dvv = dv.distances.delaunay_distortion(pts, res)
    exact = dv.voronoi_cells(pts)
    true_edges = {tuple(p) for p in exact.delaunay_edges().tolist()}
    got_edges = {tuple(p) for p in res.edges().tolist()}
    return dict(n=n, seed=seed, delta_m=dm, delta_v=dvv, ratio=dvv / dm if np.isfinite(dm) and np.isfinite(dvv) else np.inf,
                detected_mean=float(np.mean(res.detected)), true_edges=len(true_edges), computed_edges=len(got_edges),
                wrong_edges=len(got_edges - true_edges), missed_edges=len(true_edges - got_edges),
                added_by_consistency=int(res.added.sum()))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--trials", type=int, default=8, help="trials per N (paper: 100)")
    ap.add_argument("--sigma", type=float, default=2.0, help="RSSI noise spread in dB before quantisation")
    ap.add_argument("--sizes", default="200,300,400,500,600,700,800,900,1000")
    ap.add_argument("--quick", action="store_true", help="2 trials of N = 200, 600, 1000")
    ap.add_argument("--seed", type=int, default=2017)
    args = ap.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",")]
    trials = args.trials
    tag = ""
    if args.quick:
        sizes, trials, tag = [200, 600, 1000], 2, "_quick"
    from tqdm import tqdm

    OUT.mkdir(parents=True, exist_ok=True)
    rows = []
    t0 = time.perf_counter()
    jobs = [(n, args.seed + 1000 * n + t) for n in sizes for t in range(trials)]
    for n, seed in tqdm(jobs, desc="trials", unit="trial"):
        rows.append(one_trial(n, seed, args.sigma))
    elapsed = time.perf_counter() - t0
    csv_path = OUT / f"distances_distortion{tag}.csv"
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    ok = [r for r in rows if np.isfinite(r["ratio"])]
    ratio = np.array([r["ratio"] for r in ok])
    dm = np.array([r["delta_m"] for r in ok])
    dvv = np.array([r["delta_v"] for r in ok])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, hx) = plt.subplots(1, 2, figsize=(11, 4.6))
    sc = ax.scatter(dm, dvv, c=[r["n"] for r in ok], cmap="viridis", s=14)
    lim = max(dm.max(initial=1.0), 1.0) * 1.05
    xs = np.linspace(1.0, lim, 10)
    for k, style in ((1.0, "-"), (2.0, "--"), (6.5, ":")):
        ax.plot(xs, k * xs, "k" + style, lw=0.8, label=f"delta_v = {k:g} delta_m")
    ax.set_xlabel("detection distortion delta_m")
    ax.set_ylabel("Delaunay distortion delta_v")
    ax.set_title("RSSI noise, 254 x 254 cm, 33 cm range, consistency step")
    ax.legend(loc="upper left", fontsize=8)
    fig.colorbar(sc, ax=ax, label="robots N")
    hx.hist(ratio, bins=np.linspace(0.9, max(7.0, ratio.max(initial=1.0) + 0.1), 60), color="tab:blue")
    hx.axvline(6.5, color="k", ls=":", lw=0.8)
    hx.set_xlabel("delta_v / delta_m")
    hx.set_ylabel("trials")
    hx.set_title(f"{len(ok)} connected trials of {len(rows)}")
    fig.tight_layout()
    png = OUT / f"distances_distortion{tag}.png"
    fig.savefig(png, dpi=130)

    print(f"# Elwin et al. Fig. 8 reproduction ({time.strftime('%Y-%m-%d')}, commit {git_describe()})")
    print(f"N = {sizes}, {trials} trials each, RSSI sigma {args.sigma} dB, {elapsed:.0f} s")
    print(f"trials kept (both graphs connected): {len(ok)} / {len(rows)}")
    if len(ok):
        q = np.quantile(ratio, [0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0])
        print("delta_v / delta_m quantiles (0, 10, 25, 50, 75, 90, 100 %):", " ".join(f"{v:.2f}" for v in q))
        print(f"  near 1 (< 1.5): {np.mean(ratio < 1.5):.0%}   near 2 (1.5 - 2.5): {np.mean((ratio >= 1.5) & (ratio < 2.5)):.0%}"
              f"   above 2.5: {np.mean(ratio >= 2.5):.0%}   below 6.5: {np.mean(ratio < 6.5):.0%}")
        print(f"delta_m median {np.median(dm):.2f}, delta_v median {np.median(dvv):.2f}")
        print(f"wrong / missed Delaunay edges per trial (median): {np.median([r['wrong_edges'] for r in ok]):.0f} / "
              f"{np.median([r['missed_edges'] for r in ok]):.0f} of {np.median([r['true_edges'] for r in ok]):.0f}")
    print("paper: bi-modal, clustered around 1 and 2, all below 6.5 (100 trials per N)")
    print(f"wrote {csv_path} and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
