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

Counts (docs/spec.md), both reported: transmissions (a broadcast - CC's location, BD07's beacon, a
route request - is one; a multi-hop message one per hop; every try counted) and link deliveries (one
per message per link that receives it: a broadcast to k neighbours makes k). The paper counts
"transmissions between two adjacent nodes" and sends locations with ``send_message(BROADCAST, ...)``;
it does not say whether a broadcast counts once or per neighbour, so both are given.

Route discovery: where GPSR cannot deliver a message addressed to a node (obstacles can leave the
Gabriel subgraph non-planar), a flood finds a route (message type "discovery"). Neither paper has it.
Every algorithm runs with it and without it (``route``: on / off) - CC's notifications and BD07's
replies alike, BD07's probes (addressed to points) go by GPSR in both. The CSV has per (range, error
rate, algorithm, route discovery) the mean, standard deviation and 95% confidence half-width of both
totals, the mean per message type, messages lost, and the fraction of CC runs whose diagram was exact
(checked against the centralised exact diagram).

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
    ap.add_argument("--ranges-list", default="", help="comma-separated ranges (overrides --ranges)")
    args = ap.parse_args(argv)

    import dvoronoi as dv
    from tqdm import tqdm

    net = dv.network
    lo, hi = (int(v) for v in args.ranges.split(":"))
    ranges = list(range(lo, hi))
    if args.ranges_list:
        ranges = [int(v) for v in args.ranges_list.split(",")]
    losses = [float(v) for v in args.losses.split(",")]
    n_net = args.networks
    suffix = ""
    if args.quick:
        n_net, ranges, suffix = 20, [14, 22, 30], "_quick"
    OUT.mkdir(exist_ok=True)
    variants = [("cc", True), ("cc", False), ("bd07", True), ("bd07", False)]
    total_runs = len(ranges) * n_net * len(losses) * len(variants)
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
            for alg, route in variants:
                done0 = bar.n

                def progress(done, total, _d0=done0):
                    bar.n = _d0 + done
                    bar.refresh()

                out = net.batch(alg, kept_pts, r, loss, kept_bars, BOX, seeds, verify=(alg == "cc"),
                                workers=args.threads or None, progress=progress, route_discovery=route)
                bar.n = done0 + n_net
                bar.refresh()
                tot = out["by_type"].sum(axis=1).astype(float)
                dlv = out["deliveries_by_type"].sum(axis=1).astype(float)
                types = (("location", "notify", "discovery") if alg == "cc"
                         else ("location", "probe", "reply", "discovery"))
                sd = (lambda v: v.std(ddof=1)) if n_net > 1 else (lambda v: 0.0)
                row = {
                    "range": r, "loss": loss, "algorithm": alg, "route_discovery": "on" if route else "off",
                    "networks": n_net, "rejected_draws": rejected,
                    "mean_transmissions": tot.mean(), "std": sd(tot), "ci95": 1.96 * sd(tot) / np.sqrt(n_net),
                    "mean_deliveries": dlv.mean(), "std_deliveries": sd(dlv),
                    "ci95_deliveries": 1.96 * sd(dlv) / np.sqrt(n_net),
                    "lost_messages": int(out["lost"].sum()),
                    "exact_fraction": float(np.mean(out["exact"])) if alg == "cc" else "",
                }
                for k, t in enumerate(types):
                    row[f"mean_{t}"] = out["by_type"][:, k].mean()
                    row[f"mean_{t}_deliveries"] = out["deliveries_by_type"][:, k].mean()
                rows.append(row)
    bar.close()
    elapsed = time.time() - t_start

    fields = ["range", "loss", "algorithm", "route_discovery", "networks", "rejected_draws",
              "mean_transmissions", "std", "ci95", "mean_deliveries", "std_deliveries", "ci95_deliveries"]
    for t in ("location", "notify", "probe", "reply", "discovery"):
        fields += [f"mean_{t}", f"mean_{t}_deliveries"]
    fields += ["lost_messages", "exact_fraction"]
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

    fig, axes = plt.subplots(2, len(losses), figsize=(5.5 * len(losses), 8.0), sharey="row", squeeze=False)
    for row_ax, (key, what) in zip(axes, (("mean_transmissions", "transmissions (a broadcast is one)"),
                                          ("mean_deliveries", "link deliveries (one per neighbour)"))):
        for ax, loss in zip(row_ax, losses):
            for (alg, route), style in zip(variants, ("o-", "o:", "s--", "s-.")):
                sel = [row for row in rows if row["loss"] == loss and row["algorithm"] == alg
                       and row["route_discovery"] == ("on" if route else "off")]
                x = [row["range"] for row in sel]
                y = np.array([row[key] for row in sel])
                ax.plot(x, y, style, label=f"{alg.upper()}, route discovery {'on' if route else 'off'}")
            ax.set_title(f"error rate {loss:.0%}")
            ax.set_xlabel("transmission range")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
        row_ax[0].set_ylabel(f"{what}\n(mean of {n_net} networks)")
    fig.suptitle(f"CC vs BD07, {args.nodes} nodes in 100x100, {args.bars} bars of length {args.bar_length:g}")
    fig.tight_layout()
    png = OUT / f"cc_vs_bd07{suffix}.png"
    fig.savefig(png, dpi=120)

    print(f"{len(ranges) * len(losses) * len(variants) * n_net} runs in {elapsed:.1f} s ({os.cpu_count()} cores); "
          f"wrote {csv_path} and {png}")

    def get(r, loss, alg, route):
        return next(x for x in rows if x["range"] == r and x["loss"] == loss and x["algorithm"] == alg
                    and x["route_discovery"] == route)

    for key, what in (("mean_transmissions", "transmissions"), ("mean_deliveries", "link deliveries")):
        for loss in losses:
            print(f"\n{what}, error rate {loss:.0%} (mean per network; CC exact = share of CC runs with the exact diagram)")
            print("| range | CC (discovery on) | CC (off) | BD07 (on) | BD07 (off) | BD07/CC (on) | BD07/CC (off) "
                  "| CC location | CC exact on / off | lost CC off / BD07 off / BD07 on |")
            print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
            for r in ranges:
                c1, c0, b1, b0 = get(r, loss, "cc", "on"), get(r, loss, "cc", "off"), get(r, loss, "bd07", "on"), get(r, loss, "bd07", "off")
                loc_key = "mean_location" if key == "mean_transmissions" else "mean_location_deliveries"
                print(f"| {r} | {c1[key]:,.0f} | {c0[key]:,.0f} | {b1[key]:,.0f} | {b0[key]:,.0f} "
                      f"| {b1[key] / c1[key]:.1f} | {b0[key] / c0[key]:.1f} | {c1[loc_key]:,.0f} "
                      f"| {c1['exact_fraction']:.1%} / {c0['exact_fraction']:.1%} "
                      f"| {c0['lost_messages']:,} / {b0['lost_messages']:,} / {b1['lost_messages']:,} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
