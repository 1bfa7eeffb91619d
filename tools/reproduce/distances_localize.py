#!/usr/bin/env python3
"""Elwin, Freeman & Lynch (RA-L 2017), Sections I and IV-A: the second communication round. Robots
exchange their local coordinates of their Voronoi neighbours, fit the rotation, translation and flip
between neighbouring frames, and one robot with a known pose places the team in global coordinates.
The paper describes this in two sentences and gives no figure or number for it; this script measures
what it gives under the noise of the Fig. 8 setup.

Setup as Fig. 8 (tools/reproduce/distances_distortion.py): robots uniform in a 254 cm x 254 cm square,
33 cm detection range, VORONOI-NEIGHBORS and the consistency step, then the second round
(`DistanceNeighbors.localize`). Anchor: the robot nearest the centre, given its true position, heading
and flip. Noise: exact distances; additive Gaussian noise of sigma = 0.001, 0.01, 0.1, 1 cm per
measurement direction; the XBee RSSI model of Fig. 8 (whole-dBm quantisation, spread 0, 1 and 2 dB; 2 dB is the
Fig. 8 default).

Per trial: share of robots localised (connected to the anchor through valid fits), position error
against the truth (median, 90 %, max, cm), RMS error after the best rigid motion of the whole team
(the shape error, independent of the anchor), share of valid transforms whose flip is wrong, median
fit residual, and the messages of the second round. Default: N = 200, 600, 1000, 10 trials each
(~10 s); `--trials`, `--sizes`, `--quick` (2 trials of N = 200, 600). Outputs: out/distances_localize.csv and out/distances_localize.png.
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
SIDE, RANGE = 254.0, 33.0
NOISES = [("exact", 0.0), ("additive", 0.001), ("additive", 0.01), ("additive", 0.1), ("additive", 1.0),
          ("rssi", 0.0), ("rssi", 1.0), ("rssi", 2.0)]


def mirrored(points: np.ndarray, res) -> np.ndarray:
    """Per robot: its local frame (path turning counter-clockwise) is mirrored in the true frame."""
    out = np.zeros(len(points), bool)
    for i in np.flatnonzero(res.path_length >= 2):
        p = res.path(i)
        u, w = points[p[0]] - points[i], points[p[1]] - points[i]
        out[i] = u[0] * w[1] - u[1] * w[0] < 0
    return out


def shape_error(x: np.ndarray, p: np.ndarray) -> float:
    """RMS distance after the best rigid motion (reflection allowed) of the localised robots."""
    ok = np.isfinite(x[:, 0])
    if ok.sum() < 3:
        return float("nan")
    a, b = x[ok] - x[ok].mean(0), p[ok] - p[ok].mean(0)
    u, _, vt = np.linalg.svd(a.T @ b)
    return float(np.sqrt(np.mean(np.sum((a @ (u @ vt) - b) ** 2, axis=1))))


def one_trial(n: int, seed: int, model: str, sigma: float) -> dict:
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0.0, SIDE, size=(n, 2))
    if model == "exact":
        e = dv.distances.measure(pts, radius=RANGE)
    else:
        e = dv.distances.measure(pts, radius=RANGE, model=model, sigma=sigma, seed=seed + 7)
    res = dv.neighbors_from_distances(e, workers=1)
    anchor = int(np.argmin(np.hypot(*(pts - SIDE / 2).T)))
    hand = mirrored(pts, res)
    p = res.path(anchor)
    u = pts[p[0]] - pts[anchor]
    x = res.localize(anchor, pts[anchor], float(np.arctan2(u[1], u[0])), bool(hand[anchor]))
    err = np.hypot(*(x - pts).T)
    ft = res.frame_transforms()
    rows = np.repeat(np.arange(n), np.diff(res.indptr))
    v = ft.valid
    wrong_flip = ft.flip[v] != (hand[rows[v]] != hand[res.indices[v]])
    sr = res.second_round
    fin = np.isfinite(err)
    return dict(n=n, seed=seed, model=model, sigma=sigma, localized=float(fin.mean()),
                err_median=float(np.median(err[fin])), err_p90=float(np.quantile(err[fin], 0.9)),
                err_max=float(err[fin].max()), shape_rms=shape_error(x, pts),
                valid_transforms=float(v.mean()), wrong_flips=float(wrong_flip.mean()) if v.any() else float("nan"),
                residual_median=float(np.nanmedian(ft.residual)) if v.any() else float("nan"),
                messages_per_robot=sr.messages / n, payload_per_message=sr.total_payload / max(sr.messages, 1))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--trials", type=int, default=10, help="trials per N and noise level")
    ap.add_argument("--sizes", default="200,600,1000")
    ap.add_argument("--seed", type=int, default=2017)
    ap.add_argument("--quick", action="store_true", help="2 trials of N = 200, 600")
    args = ap.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",")]
    tag = ""
    if args.quick:
        sizes, args.trials, tag = [200, 600], 2, "_quick"
    OUT.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rows = [one_trial(n, args.seed + 1000 * n + t, model, sigma)
            for n in sizes for t in range(args.trials) for model, sigma in NOISES]
    elapsed = time.perf_counter() - t0
    csv_path = OUT / f"distances_localize{tag}.csv"
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    print(f"# Elwin et al., second round: localisation from one robot's pose ({time.strftime('%Y-%m-%d')}, "
          f"commit {git_describe()})")
    print(f"N = {sizes}, {args.trials} trials per N and noise, {SIDE:g} cm square, {RANGE:g} cm range, {elapsed:.0f} s")
    print("medians over trials; errors in cm")
    print("| noise | N | localised | error median | error 90 % | error max | shape RMS | valid fits | wrong flips | residual median |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for model, sigma in NOISES:
        label = {"exact": "exact", "additive": f"additive {sigma:g} cm", "rssi": f"RSSI {sigma:g} dB"}[model]
        for n in sizes:
            sel = [r for r in rows if r["model"] == model and r["sigma"] == sigma and r["n"] == n]
            med = {k: float(np.nanmedian([r[k] for r in sel])) for k in sel[0] if isinstance(sel[0][k], float)}
            print(f"| {label} | {n} | {med['localized']:.1%} | {med['err_median']:.3g} | {med['err_p90']:.3g} | "
                  f"{med['err_max']:.3g} | {med['shape_rms']:.3g} | {med['valid_transforms']:.1%} | "
                  f"{med['wrong_flips']:.1%} | {med['residual_median']:.2g} |")
    msg = np.mean([r["messages_per_robot"] for r in rows if r["model"] == "exact"])
    pay = np.mean([r["payload_per_message"] for r in rows if r["model"] == "exact"])
    print(f"second round (exact distances): {msg:.2f} messages per robot (one per directed Voronoi edge), "
          f"{pay:.2f} entries (ID, x, y) per message")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
    for ax, model, unit in ((axes[0], "additive", "cm"), (axes[1], "rssi", "dB")):
        sigmas = sorted({s for m, s in NOISES if m == model})
        for n in sizes:
            med = [np.median([r["err_median"] for r in rows if r["model"] == model and r["sigma"] == s and r["n"] == n])
                   for s in sigmas]
            shp = [np.nanmedian([r["shape_rms"] for r in rows if r["model"] == model and r["sigma"] == s and r["n"] == n])
                   for s in sigmas]
            line, = ax.plot(sigmas, med, "o-", label=f"N = {n}: median error")
            ax.plot(sigmas, shp, "s--", color=line.get_color(), alpha=0.6, label=f"N = {n}: shape RMS")
        if model == "additive":
            ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"noise sigma ({unit})")
        ax.set_title({"additive": "additive Gaussian noise", "rssi": "XBee RSSI model (Fig. 8's noise)"}[model])
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("localisation error (cm)")
    axes[1].legend(fontsize=7)
    fig.suptitle(f"Second round: team placed from one robot's pose ({SIDE:g} cm square, {RANGE:g} cm range)")
    fig.tight_layout()
    png = OUT / f"distances_localize{tag}.png"
    fig.savefig(png, dpi=130)
    print("paper: no figure or number for the second round (Sections I and IV-A describe it; IV-A warns that noise "
          "may make it less accurate than other methods because it does not use all measurements)")
    print(f"wrote {csv_path} and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
