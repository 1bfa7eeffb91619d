#!/usr/bin/env python3
"""Figures of docs/geodesic_coverage.md, made from the library as it is.

    python3 tools/make_geodesic_figures.py             # docs/images/geodesic_cells.png, geodesic_lloyd.gif
    python3 tools/make_geodesic_figures.py --out DIR

- ``geodesic_cells.png``: left, the geodesic cells of 24 agents on a 160 x 160 office floor
  (``dvoronoi.occupancy_maps.building(96, seed=3)``) with a range of 40 px, the distance field as
  contours; right, the same agents after 60 geodesic Lloyd steps.
- ``geodesic_lloyd.gif``: the 60 steps, every third step a frame: the team starts packed in one corner
  and spreads through the doors into the rooms.

Matplotlib with the Agg backend; a few seconds.
"""
from __future__ import annotations

import argparse
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import dvoronoi as dv  # noqa: E402
from dvoronoi import occupancy_maps  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def team():
    """The floor and 24 agents packed into free pixels near its lower-left corner (map units = pixels)."""
    occ = occupancy_maps.building(96, seed=3)
    grid = dv.OccupancyGrid(occ)
    free = np.argwhere(~occ)
    H = occ.shape[0]
    near = free[np.argsort(np.hypot(free[:, 0] - (H - 8), free[:, 1] - 8), kind="stable")[:120]]
    rng = np.random.default_rng(0)
    pick = near[rng.choice(len(near), 16, replace=False)]
    return grid, grid.pixel_centers(pick)


def figures(out: Path) -> None:
    grid, start = team()
    run = dv.coverage.lloyd(start, None, steps=60, record_every=3, environment=grid, workers=1)
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.6))
    first = dv.coverage.geodesic_cells(start, grid)
    for ax, cells, title in ((axes[0], first, "start: geodesic cells"),
                             (axes[1], run, f"after {run.steps} Lloyd steps")):
        cells.plot(ax=ax, point_size=10)
        d = np.where(np.isfinite(cells.distances), cells.distances, np.nan)
        ax.contour(d, levels=np.arange(5, 120, 5), extent=grid.extent, origin="upper", colors="k",
                   linewidths=0.3, alpha=0.5)
        ax.set_title(f"{title}\nH = {cells.cost if not hasattr(cells, 'steps') else run.cost[-1]:.4g}")
        ax.set_axis_off()
    fig.tight_layout()
    fig.savefig(out / "geodesic_cells.png", dpi=100)
    plt.close(fig)
    run.animate(out / "geodesic_lloyd.gif", fps=6, dpi=60, figsize=(5, 5))
    for name in ("geodesic_cells.png", "geodesic_lloyd.gif"):
        p = out / name
        print(f"{os.path.relpath(p)}: {p.stat().st_size / 1024:.0f} KB")
    print(f"cost {run.cost[0]:.5g} -> {run.cost[-1]:.5g}, never increasing: {bool(np.all(np.diff(run.cost) <= 0))}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "images", help="output directory")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    figures(args.out)


if __name__ == "__main__":
    main()
