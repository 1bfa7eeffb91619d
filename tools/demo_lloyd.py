#!/usr/bin/env python3
"""Lloyd coverage on limited cells, as pictures: 80 agents start in one corner of a hexagonal
environment and spread out under a density with a peak; writes ``lloyd.gif`` (the run) and
``lloyd.png`` (final cells + the cost per step) into OUT (default ./lloyd_demo)."""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("out", nargs="?", type=Path, default=Path("lloyd_demo"))
    ap.add_argument("--steps", type=int, default=60)
    args = ap.parse_args(argv)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import dvoronoi as dv

    hexagon = np.array([[math.cos(a), math.sin(a)] for a in np.linspace(0, 2 * math.pi, 7)[:-1]])
    rng = np.random.default_rng(2)
    start = rng.uniform(-0.45, -0.15, (80, 2))
    density = lambda x, y: 0.2 + np.exp(-((x - 0.35) ** 2 + (y - 0.2) ** 2) / (2 * 0.2 ** 2))  # noqa: E731
    run = dv.coverage.lloyd(start, 0.18, density=density, steps=args.steps, bounds=hexagon, gain=0.9)

    args.out.mkdir(parents=True, exist_ok=True)
    run.animate(args.out / "lloyd.gif", fps=12)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 5))
    run.plot(ax=a)
    a.set_title(f"after {run.steps} steps (R = {run.radius:g})")
    b.plot(run.cost)
    b.set_xlabel("step")
    b.set_ylabel("H (limited-range locational cost)")
    b.set_yscale("log")
    fig.tight_layout()
    fig.savefig(args.out / "lloyd.png", dpi=90)
    print(f"{run}; wrote {args.out / 'lloyd.gif'} and {args.out / 'lloyd.png'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
