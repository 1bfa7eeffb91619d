#!/usr/bin/env python3
"""Figures of docs/grid_diagram_maps.md (and the README), made from the library as it is.

    python3 tools/make_docs_figures.py            # writes docs/images/gvd_paris.png, gvd_pruning.png
    python3 tools/make_docs_figures.py --out DIR  # somewhere else

- ``gvd_paris.png``: the medial diagram of the real MovingAI city map ``tests/data/maps/Paris_1_256.map``
  for a robot of radius 1 pixel, with a path between two far-apart free points.
- ``gvd_pruning.png``: what ``min_separation`` and ``prune_length`` do, on
  ``dvoronoi.occupancy_maps.passages(96)`` (corridors 1..8 px wide, staircase walls of slope 1:1, 1:2,
  1:3, 1:5): the pair rule alone grows spurs on the staircases; a larger ``min_separation`` removes
  them and the narrow corridors' centrelines with them; the default rule keeps the corridors and drops
  the spurs.

Runs from any directory (paths are taken relative to the repository); matplotlib with the Agg backend,
one thread of work, a few seconds.
"""
from __future__ import annotations

import argparse
import os
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

import dvoronoi as dv  # noqa: E402
from dvoronoi import occupancy_maps  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
PARIS = ROOT / "tests" / "data" / "maps" / "Paris_1_256.map"
# two far-apart free points of the map's large street network (map coordinates = pixels here):
# near the lower-left corner and near the top right; both clear the robot by more than a pixel
START, GOAL = (3.5, 9.5), (225.5, 251.5)
DPI = 150


def legend_handles(path: bool = True) -> list:
    h = [Patch(color=(0.26, 0.26, 0.26), label="occupied"),
         Patch(color=(0.12, 0.47, 0.71), label="diagram"),
         Patch(color=(0.96, 0.65, 0.65), label="diagram, blocked (clearance <= robot radius)")]
    if path:
        h.append(Line2D([], [], color="#2e7d32", lw=2, marker="o", ms=5, label="path"))
    return h


def paris(out: Path) -> Path:
    grid = dv.OccupancyGrid.load(PARIS)
    gv = dv.grid_voronoi(grid, robot_radius=1.0, workers=1)
    route = gv.path(START, GOAL)
    assert len(route) >= 2, "no path between START and GOAL"
    fig, ax = plt.subplots(figsize=(7.2, 7.8))
    gv.plot(ax=ax, path=route)
    ax.set_title(f"Medial diagram of Paris_1_256 (MovingAI, 256 x 256 px), robot radius 1 px\n"
                 f"{len(gv)} diagram pixels, {int(gv.blocked.sum())} blocked; "
                 f"path {gv.stats['last_path']['length']:.0f} px with {len(route)} points", fontsize=10)
    ax.set_xlabel("x (pixels; resolution 1, origin (0, 0))", fontsize=9)
    ax.set_ylabel("y", fontsize=9)
    ax.tick_params(labelsize=8)
    ax.legend(handles=legend_handles(), loc="upper center", bbox_to_anchor=(0.5, -0.08), ncol=2, fontsize=8,
              frameon=False)
    fig.tight_layout()
    target = out / "gvd_paris.png"
    fig.savefig(target, dpi=DPI)
    plt.close(fig)
    return target


def pruning(out: Path) -> Path:
    occ = occupancy_maps.passages(96)
    panels = [
        (dict(min_separation=1.5, prune_length=0.0),
         "pair rule only\nmin_separation=1.5, prune_length=0:\nspurs on the 1:2, 1:3, 1:5 staircases"),
        (dict(min_separation=5.5, prune_length=0.0),
         "a larger separation instead\nmin_separation=5.5, prune_length=0:\n"
         "no spurs, no centreline in corridors <= 5 px"),
        (dict(min_separation=1.5, prune_length=8.0),
         "the default\nmin_separation=1.5, prune_length=8:\ncorridors >= 2 px kept, spurs dropped"),
    ]
    fig, axes = plt.subplots(1, 3, figsize=(12.6, 5.6))
    for ax, (kw, title) in zip(axes, panels):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            gv = dv.grid_voronoi(occ, workers=1, **kw)
        gv.plot(ax=ax)
        ax.set_title(title, fontsize=9, pad=14)
        ax.set_xticks([])
        ax.set_yticks([])
    # corridor widths (red, above each corridor, read off the map) and staircase slopes (white, in the floor)
    H, W = occ.shape
    gallery = np.flatnonzero(occ[:, W - 10])               # rows of the solid part right of the corridors
    g0 = int(gallery[(gallery > 5) & (gallery < H // 2)].min())
    row = occ[(g0 + H // 2) // 2]
    starts = np.flatnonzero(~row[1:] & row[:-1]) + 1
    ends = np.flatnonzero(row[1:] & ~row[:-1]) + 1
    for ax in axes:
        for a, b in zip(starts, ends):
            ax.text((a + b) / 2, H + 0.8, str(b - a), ha="center", va="bottom", fontsize=7, color="#b71c1c",
                    fontweight="bold", clip_on=False)
        T = max(2, min(H, W) // 32)                          # passages(): border and cell walls
        cw = (W - 5 * T) // 4                                 # the four bottom cells' width
        for c, k in enumerate((1, 2, 3, 5)):
            ax.text(T + c * (cw + T) + 0.75 * cw, 1.5, f"1:{k}", ha="center", va="bottom", fontsize=7, color="white")
    fig.legend(handles=legend_handles(path=False)[:2], loc="lower center", ncol=2, fontsize=8, frameon=False,
               title="dvoronoi.occupancy_maps.passages(96): corridors 1..8 px wide (red numbers: widths), staircase "
                     "walls of slope 1:1, 1:2, 1:3, 1:5 (bottom)", title_fontsize=9)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.86, bottom=0.11, wspace=0.04)
    target = out / "gvd_pruning.png"
    fig.savefig(target, dpi=DPI)
    plt.close(fig)
    return target


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "images", help="output directory")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    for make in (paris, pruning):
        target = make(args.out)
        print(f"{os.path.relpath(target)}: {target.stat().st_size / 1024:.0f} KB")


if __name__ == "__main__":
    main()
