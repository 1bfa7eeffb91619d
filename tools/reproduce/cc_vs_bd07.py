#!/usr/bin/env python3
"""CC vs BD07: transmissions against the communication range, the experiment of Section 4 (Figure 3)
of Núñez-Rodríguez, Xiao, Islam & Alsalih, "A Distributed Algorithm for Computing Voronoi Diagram in
the Unit Disk Graph Model".

Paper: 100 nodes uniform in a 100 x 100 square, transmission ranges 14..30, error rates 0 and 20% (a
failed transmission is repeated), 50 randomly placed opaque bars of length 5, 1000 random networks per
(range, error rate), each containing a connected subgraph of the Delaunay triangulation (Theorem 2's
condition); the average total number of transmissions of CC and BD07 (Figures 3a and 3b). Its claim:
for small ranges BD07 needs many more transmissions than CC (the sparse network makes GPSR perform
poorly), and CC is less affected by small ranges because it does not probe.

Here: the same setting through ``dv.network.batch`` (the C++ simulator, one thread per network).
Networks are drawn (points and bars) until Theorem 2's condition holds - the rejected draws are
counted - and the same 1000 networks serve both error rates (paired comparison). CC runs with both
Section 2.3 optimisations and GPSR routing, as in the paper; BD07's region is the 100 x 100 square.
Each try over a link is one transmission (a multi-hop message costs one per hop; docs/spec.md). The CSV has
the mean, standard deviation and 95% confidence half-width of the total per algorithm, the mean per
message type (CC's "discovery": route discoveries where GPSR cannot deliver, because obstacles can
leave the Gabriel subgraph non-planar; BD07's probes still go by GPSR alone, so it can lose replies),
messages lost, and the fraction of CC runs whose diagram was exact (checked against the centralised
exact diagram).

Outputs: out/cc_vs_bd07.csv and out/cc_vs_bd07.png (or *_quick.* with --quick).
"""
from __future__ import annotations

import argparse
import csv
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchutil import git_describe  # noqa: E402

OUT = Path(__file__).resolve().parent / "out"
BOX = (0.0, 0.0, 100.0, 100.0)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--networks", type=int, default=1000, help="networks per range (default 1000)")
    ap.add_argument("--ranges", default="14:31", help="ranges as START:STOP (python range), default 14:31")
    ap.add_argument("--losses", default="0,0.2", help="error rates, default 0,0.2")
    ap.add_argument("--nodes", type=int, default=100)
    ap.add_argument("--bars", type=int, default=50)
    ap.add_argument("--bar-length", type=float, default=5.0)
    ap.add_argument("--threads", type=int, default=0, help="0 = all cores")
    ap.add_argument("--seed", type=int, default=2008)
    ap.add_argument("--quick", action="store_true", help="20 networks, ranges 14, 22, 30")
    args = ap.parse_args(argv)

    import dvoronoi as dv
    from tqdm import tqdm

    net = dv.network
    lo, hi = (int(v) for v in args.ranges.split(":"))
    ranges = list(range(lo, hi))
    losses = [float(v) for v in args.losses.split(",")]
    n_net = args.networks
    suffix = ""
    if args.quick:
        n_net, ranges, suffix = 20, [14, 22, 30], "_quick"
    OUT.mkdir(exist_ok=True)
    total_runs = len(ranges) * n_net * len(losses) * 2
    bar = tqdm(total=total_runs, desc="network runs", unit="run", smoothing=0.05)
    rows = []
    t_start = time.time()
    for r in ranges:
        rng = np.random.default_rng([args.seed, r])
        # Draw networks until n_net of them satisfy Theorem 2 (checked by the first CC batch).
        kept_pts, kept_bars, rejected = [], [], 0
        while len(kept_pts) < n_net:
            need = n_net - len(kept_pts)
            draw = max(need, 64)
            cand = [rng.uniform(0, 100, (args.nodes, 2)) for _ in range(draw)]
            bars = [net.random_bars(rng, args.bars, args.bar_length, BOX) for _ in range(draw)]
            chk = net.batch("check", cand, r, 0.0, bars, BOX, list(range(draw)), workers=args.threads or None)
            bar.set_postfix_str(f"range {r}: {len(kept_pts)}/{n_net} networks drawn, {rejected} rejected")
            for k in range(draw):
                if len(kept_pts) == n_net:
                    break
                if chk["condition"][k]:
                    kept_pts.append(cand[k])
                    kept_bars.append(bars[k])
                else:
                    rejected += 1
        seeds = [int(s) for s in rng.integers(0, 2**31, n_net)]
        for loss in losses:
            for alg in ("cc", "bd07"):
                done0 = bar.n

                def progress(done, total, _d0=done0):
                    bar.n = _d0 + done
                    bar.refresh()

                out = net.batch(alg, kept_pts, r, loss, kept_bars, BOX, seeds, verify=(alg == "cc"),
                                workers=args.threads or None, progress=progress)
                bar.n = done0 + n_net
                bar.refresh()
                tot = out["by_type"].sum(axis=1).astype(float)
                types = ("location", "notify", "discovery") if alg == "cc" else ("location", "probe", "reply")
                row = {
                    "range": r, "loss": loss, "algorithm": alg, "networks": n_net, "rejected_draws": rejected,
                    "mean_transmissions": tot.mean(), "std": tot.std(ddof=1) if n_net > 1 else 0.0,
                    "ci95": 1.96 * tot.std(ddof=1) / np.sqrt(n_net) if n_net > 1 else 0.0,
                    "lost_messages": int(out["lost"].sum()),
                    "exact_fraction": float(np.mean(out["exact"])) if alg == "cc" else "",
                }
                for k, t in enumerate(types):
                    row[f"mean_{t}"] = out["by_type"][:, k].mean()
                rows.append(row)
    bar.close()
    elapsed = time.time() - t_start

    fields = ["range", "loss", "algorithm", "networks", "rejected_draws", "mean_transmissions", "std", "ci95",
              "mean_location", "mean_notify", "mean_discovery", "mean_probe", "mean_reply", "lost_messages",
              "exact_fraction"]
    csv_path = OUT / f"cc_vs_bd07{suffix}.csv"
    with open(csv_path, "w", newline="") as f:
        f.write(f"# {platform.node()} {os.cpu_count()} cores, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
                f"git {git_describe()}, {elapsed:.0f} s, seed {args.seed}\n")
        w = csv.DictWriter(f, fieldnames=fields, restval="")
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()})

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(losses), figsize=(5.5 * len(losses), 4.2), sharey=True, squeeze=False)
    for ax, loss in zip(axes[0], losses):
        for alg, style in (("cc", "o-"), ("bd07", "s--")):
            sel = [row for row in rows if row["loss"] == loss and row["algorithm"] == alg]
            x = [row["range"] for row in sel]
            y = np.array([row["mean_transmissions"] for row in sel])
            e = np.array([row["ci95"] for row in sel])
            ax.errorbar(x, y, yerr=e, fmt=style, capsize=2, label=alg.upper())
        ax.set_title(f"error rate {loss:.0%}")
        ax.set_xlabel("transmission range")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    axes[0][0].set_ylabel(f"transmissions (mean of {n_net} networks)")
    fig.suptitle(f"CC vs BD07, {args.nodes} nodes in 100x100, {args.bars} bars of length {args.bar_length:g}")
    fig.tight_layout()
    png = OUT / f"cc_vs_bd07{suffix}.png"
    fig.savefig(png, dpi=120)

    print(f"{len(ranges) * len(losses) * 2 * n_net} runs in {elapsed:.1f} s ({os.cpu_count()} cores); "
          f"wrote {csv_path} and {png}")
    print(f"{'range':>5} {'loss':>5} {'CC':>9} {'BD07':>9} {'BD07/CC':>8} {'CC exact':>8} {'rejected':>8}")
    for r in ranges:
        for loss in losses:
            cc = next(x for x in rows if x["range"] == r and x["loss"] == loss and x["algorithm"] == "cc")
            bd = next(x for x in rows if x["range"] == r and x["loss"] == loss and x["algorithm"] == "bd07")
            print(f"{r:>5} {loss:>5.2f} {cc['mean_transmissions']:>9.0f} {bd['mean_transmissions']:>9.0f} "
                  f"{bd['mean_transmissions'] / cc['mean_transmissions']:>8.2f} {cc['exact_fraction']:>8.3f} "
                  f"{cc['rejected_draws']:>8}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
