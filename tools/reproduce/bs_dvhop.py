#!/usr/bin/env python3
"""Distributed Boundary Scan with DV-Hop localisation: the experiment of Section 4.2 (Figures 9-12) of
He, Feng & Ren (2018), "Distributed Algorithm for Voronoi Partition of Wireless Sensor Networks with a
Limited Sensing Range".

Paper: 100 sensors uniform in 100 x 100, sensing = communication range r = 20, 30% anchors. DV-Hop
estimates the other nodes' positions (Figure 10); Boundary Scan then computes the r/2-limited cells
from true and from estimated positions (Figure 11); Figure 12 shows the messages each node sends and
receives, anchors sending fewer than normal nodes, and the Boundary Scan phase a small part of the total
("anchor nodes broadcast their information twice ... all the nodes implementing the BS algorithm just
need to transmit their positions to their neighbours once").

Here: ``dv.network.simulate("bs", points, 20, anchor_fraction=0.3)`` (C++ simulator). DV-Hop as the
paper describes it: anchors flood their positions with hop counts in breadth-first rounds, each normal
node forwarding each anchor's flood once (the first time it hears it: its minimum hop count); anchors
relay nothing ("anchor nodes will broadcast their information twice": their position and their hop
size); the hop sizes are passed on once per node; least-squares multilateration; then every node
broadcasts its position once and runs Boundary Scan. Our cell radius is R = r / 2 = 10 (docs/spec.md).
Both counts of docs/spec.md are reported: transmissions (a broadcast is one) and link deliveries (one
per neighbour that receives it; what a per-link count would call "messages").

Variants (the same networks, for the modelling choices that change the counts): ``paper`` (the above,
used for the figure), ``relay`` (anchors forward other anchors' floods too), ``async`` (anchors relay,
floods delivered in a random asynchronous order and every improvement re-flooded: what this script did
before issue 21). One network (the paper's figures) is written per node to the CSV and drawn;
--networks more networks give the summary (mean position error and counts per node, anchors vs normal
nodes).

Outputs: out/bs_dvhop.csv (per node of the first network), out/bs_dvhop_summary.csv and
out/bs_dvhop.png (or *_quick.* with --quick).
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

OUT = Path(__file__).resolve().parent / "out"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--networks", type=int, default=200, help="networks for the summary (default 200)")
    ap.add_argument("--seed", type=int, default=2018)
    ap.add_argument("--quick", action="store_true", help="20 networks")
    args = ap.parse_args(argv)

    import dvoronoi as dv
    from tqdm import tqdm

    suffix = "_quick" if args.quick else ""
    n_net = 20 if args.quick else args.networks
    OUT.mkdir(exist_ok=True)
    rng = np.random.default_rng(args.seed)
    summary = []
    first = None
    t0 = time.time()
    variants = {"paper": dict(dv_hop="sync", anchors_relay=False),
                "relay": dict(dv_hop="sync", anchors_relay=True),
                "async": dict(dv_hop="async", anchors_relay=True)}
    for k in tqdm(range(n_net), desc="networks", unit="net"):
        pts = rng.uniform(0, 100, (100, 2))
        true = dv.network.simulate("bs", pts, 20.0, seed=k)
        for variant, opts in variants.items():
            res = dv.network.simulate("bs", pts, 20.0, anchor_fraction=0.3, seed=k, **opts)
            if first is None:
                first = (pts, res, true)
            summary.append(summarise(k, variant, res, true))
    elapsed = time.time() - t0
    write_outputs(args, suffix, first, summary, n_net, elapsed, list(variants))
    return 0


def summarise(k, variant, res, true):
    """One network's numbers."""
    anchor = np.zeros(100, dtype=bool)
    anchor[res.anchors] = True
    err = res.position_error
    loc = res.localized & ~anchor
    same = [set(res.neighbors(i).tolist()) == set(true.neighbors(i).tolist()) for i in range(100)]
    tx, dl = res.transmissions_by_type, res.deliveries_by_type
    return {
        "network": k, "variant": variant,
        "localized_normal": int(loc.sum()), "normal": int((~anchor).sum()),
        "mean_error": float(np.mean(err[loc])) if loc.any() else float("nan"),
        "median_error": float(np.median(err[loc])) if loc.any() else float("nan"),
        "error_over_range": float(np.mean(err[loc])) / 20.0 if loc.any() else float("nan"),
        "sent_anchor": float(res.sent_per_node[anchor].mean()),
        "sent_normal": float(res.sent_per_node[~anchor].mean()),
        "received_anchor": float(res.received_per_node[anchor].mean()),
        "received_normal": float(res.received_per_node[~anchor].mean()),
        "bs_share": tx["position"] / res.total_transmissions,
        "flood": tx["anchor_flood"], "hop_size": tx["hop_size"], "position": tx["position"],
        "flood_deliveries": dl["anchor_flood"], "hop_size_deliveries": dl["hop_size"],
        "position_deliveries": dl["position"],
        "bs_share_deliveries": dl["position"] / res.total_deliveries,
        "same_neighbours_fraction": float(np.mean(same)),
    }


def write_outputs(args, suffix, first, summary, n_net, elapsed, variants):
    pts, res, true = first
    anchor = np.zeros(100, dtype=bool)
    anchor[res.anchors] = True
    per_node = OUT / f"bs_dvhop{suffix}.csv"
    with open(per_node, "w", newline="") as f:
        f.write(f"# seed {args.seed}, network 0, git {git_describe()}\n")
        w = csv.writer(f)
        head = ["node", "x", "y", "anchor", "est_x", "est_y", "error"]
        for t in res.dv_hop_types + res.message_types:
            head += [f"sent_{t}", f"received_{t}"]
        head += ["sent_total", "received_total", "limited_neighbors_true", "limited_neighbors_estimated"]
        w.writerow(head)
        for i in range(100):
            row = [i, f"{pts[i, 0]:.6g}", f"{pts[i, 1]:.6g}", int(anchor[i]), f"{res.positions[i, 0]:.6g}",
                   f"{res.positions[i, 1]:.6g}", f"{res.position_error[i]:.4g}"]
            for k in range(len(res.dv_hop_types)):
                row += [res.dv_hop_sent[i, k], res.dv_hop_received[i, k]]
            for k in range(len(res.message_types)):
                row += [res.sent[i, k], res.received[i, k]]
            row += [res.sent_per_node[i], res.received_per_node[i], len(true.neighbors(i)), len(res.neighbors(i))]
            w.writerow(row)
    summ = OUT / f"bs_dvhop_summary{suffix}.csv"
    with open(summ, "w", newline="") as f:
        f.write(f"# {n_net} networks, seed {args.seed}, git {git_describe()}, {elapsed:.0f} s\n")
        w = csv.DictWriter(f, fieldnames=list(summary[0]))
        w.writeheader()
        for row in summary:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()})

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(15, 9))
    ax1 = fig.add_subplot(2, 3, 1)
    res.plot_network(ax=ax1)
    ax1.scatter(pts[anchor, 0], pts[anchor, 1], marker="^", c="tab:red", s=30, zorder=5, label="anchors")
    ok = res.localized & ~anchor
    ax1.scatter(res.positions[ok, 0], res.positions[ok, 1], marker="s", c="tab:orange", s=12, zorder=4,
                label="estimates")
    for i in np.flatnonzero(ok):
        ax1.plot([pts[i, 0], res.positions[i, 0]], [pts[i, 1], res.positions[i, 1]], color="0.4", lw=0.6)
    ax1.set_title("network, anchors and DV-Hop estimates (Fig. 9-10)")
    ax1.legend(fontsize="small", loc="upper right")
    ax2 = fig.add_subplot(2, 3, 2)
    true.plot(ax=ax2, show_points=True)
    ax2.set_title("limited cells, true positions (Fig. 11a)")
    ax3 = fig.add_subplot(2, 3, 3)
    res.plot(ax=ax3)
    ax3.set_title("limited cells, estimated positions (Fig. 11b)")
    ax4 = fig.add_subplot(2, 1, 2)
    res.plot_messages(ax=ax4)
    for i in res.anchors:
        ax4.axvspan(i - 0.45, i + 0.45, color="tab:red", alpha=0.12, lw=0)
    ax4.set_title("transmissions per node (Fig. 12; anchors shaded)")
    fig.tight_layout()
    png = OUT / f"bs_dvhop{suffix}.png"
    fig.savefig(png, dpi=110)

    print(f"{n_net} networks x {len(variants)} variants in {elapsed:.1f} s; wrote {per_node}, {summ}, {png}")
    keys = [k for k in summary[0] if k not in ("network", "variant")]
    print("| quantity (mean per network) | " + " | ".join(variants) + " |")
    print("|---|" + "---:|" * len(variants))
    mean = {v: {k: float(np.nanmean([s[k] for s in summary if s["variant"] == v])) for k in keys} for v in variants}
    rows = [("position error of normal nodes (% of r)", "error_over_range", "{:.0%}"),
            ("normal nodes localised (of ~70)", "localized_normal", "{:.1f}"),
            ("transmissions sent per anchor", "sent_anchor", "{:.1f}"),
            ("transmissions sent per normal node", "sent_normal", "{:.1f}"),
            ("link deliveries received per anchor", "received_anchor", "{:.1f}"),
            ("link deliveries received per normal node", "received_normal", "{:.1f}"),
            ("anchor-flood transmissions", "flood", "{:,.0f}"),
            ("anchor-flood link deliveries", "flood_deliveries", "{:,.0f}"),
            ("hop-size transmissions", "hop_size", "{:,.0f}"),
            ("hop-size link deliveries", "hop_size_deliveries", "{:,.0f}"),
            ("BS position transmissions", "position", "{:,.0f}"),
            ("BS position link deliveries", "position_deliveries", "{:,.0f}"),
            ("BS share of transmissions", "bs_share", "{:.1%}"),
            ("BS share of link deliveries", "bs_share_deliveries", "{:.1%}"),
            ("nodes with unchanged limited neighbours", "same_neighbours_fraction", "{:.0%}")]
    for label, key, fmt in rows:
        print(f"| {label} | " + " | ".join(fmt.format(mean[v][key]) for v in variants) + " |")


if __name__ == "__main__":
    sys.exit(main())
