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

Here: ``dv.network.simulate("bs", points, 20, anchor_fraction=0.3)`` (C++ simulator: anchors flood
their positions with hop counts - a node passes on every improvement, in a random asynchronous order -,
then their hop sizes - passed on once -, least-squares multilateration, then one position message per
link). Our cell radius is R = r / 2 = 10 (docs/spec.md). One network (the paper's figures) is written per
node to the CSV and drawn; --networks more networks give the summary (mean position error and
transmissions per node, anchors vs normal nodes).

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
    for k in tqdm(range(n_net), desc="networks", unit="net"):
        pts = rng.uniform(0, 100, (100, 2))
        res = dv.network.simulate("bs", pts, 20.0, anchor_fraction=0.3, seed=k)
        true = dv.network.simulate("bs", pts, 20.0, seed=k)
        if first is None:
            first = (pts, res, true)
        anchor = np.zeros(100, dtype=bool)
        anchor[res.anchors] = True
        err = res.position_error
        loc = res.localized & ~anchor
        same = [set(res.neighbors(i).tolist()) == set(true.neighbors(i).tolist()) for i in range(100)]
        summary.append({
            "network": k,
            "localized_normal": int(loc.sum()), "normal": int((~anchor).sum()),
            "mean_error": float(np.mean(err[loc])) if loc.any() else float("nan"),
            "median_error": float(np.median(err[loc])) if loc.any() else float("nan"),
            "error_over_range": float(np.mean(err[loc])) / 20.0 if loc.any() else float("nan"),
            "sent_anchor": float(res.sent_per_node[anchor].mean()),
            "sent_normal": float(res.sent_per_node[~anchor].mean()),
            "received_anchor": float(res.received_per_node[anchor].mean()),
            "received_normal": float(res.received_per_node[~anchor].mean()),
            "bs_share": res.transmissions_by_type["position"] / res.total_transmissions,
            "flood": res.transmissions_by_type["anchor_flood"], "hop_size": res.transmissions_by_type["hop_size"],
            "position": res.transmissions_by_type["position"],
            "same_neighbours_fraction": float(np.mean(same)),
        })
    elapsed = time.time() - t0

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

    mean = {k: float(np.nanmean([s[k] for s in summary])) for k in summary[0] if k != "network"}
    print(f"{n_net} networks in {elapsed:.1f} s; wrote {per_node}, {summ}, {png}")
    print(f"mean position error of normal nodes {mean['mean_error']:.2f} ({mean['error_over_range']:.0%} of r); "
          f"localised {mean['localized_normal']:.1f}/{mean['normal']:.0f}")
    print(f"transmissions sent per node: anchors {mean['sent_anchor']:.0f}, normal {mean['sent_normal']:.0f}; "
          f"received: anchors {mean['received_anchor']:.0f}, normal {mean['received_normal']:.0f}")
    print(f"per network: anchor flood {mean['flood']:.0f}, hop size {mean['hop_size']:.0f}, BS positions "
          f"{mean['position']:.0f} ({mean['bs_share']:.1%} of the total); nodes whose limited neighbours are "
          f"unchanged by localisation errors: {mean['same_neighbours_fraction']:.0%}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
