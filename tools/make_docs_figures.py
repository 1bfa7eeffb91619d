#!/usr/bin/env python3
"""Figures of the documentation (docs/*.md and the README), made from the library as it is.

    python3 tools/make_docs_figures.py                 # writes every figure into docs/images/
    python3 tools/make_docs_figures.py --out DIR       # somewhere else
    python3 tools/make_docs_figures.py --only coverage # one figure (by its function name)

Guides (docs/limited_cells.md, heterogeneous.md, exact_cells.md, distances.md, networks.md, grid_diagram_obstacles.md,
coverage.md, mpi.md): ``limited_cells.png``, ``heterogeneous.png``, ``exact_cells.png``, ``distances.png``,
``networks.png``, ``gvd_obstacles.png``, ``coverage.png``, ``mpi_slabs.png`` (seeded random
swarms, a few seconds each); ``heterogeneous_lloyd.gif``: a mixed team's Lloyd run.

- ``gvd_paris.png``: the medial diagram of the real MovingAI city map ``tests/data/maps/Paris_1_256.map``
  for a robot of radius 1 pixel, with a path between two far-apart free points.
- ``gvd_pruning.png``: what ``min_separation`` and ``prune_length`` do, on
  ``dvoronoi.occupancy_maps.passages(96)`` (corridors 1..8 px wide, staircase walls of slope 1:1, 1:2,
  1:3, 1:5): the pair rule alone grows spurs on the staircases; a larger ``min_separation`` removes
  them and the narrow corridors' centrelines with them; the default rule keeps the corridors and drops
  the spurs.

Runs from any directory (paths are taken relative to the repository); matplotlib with the Agg backend,
one thread of work (the MPI figure draws the slabs from one process; it needs no MPI).
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
from dvoronoi import occupancy_maps, plotting  # noqa: E402

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


def _square(ax, lo=None, hi=None) -> None:
    ax.set_aspect("equal", adjustable="box")
    if lo is not None:
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
    ax.tick_params(labelsize=8)


def limited_cells(out: Path) -> Path:
    rng = np.random.default_rng(3)
    center = np.array([0.0, 0.0])
    others = rng.uniform(-1.9, 1.9, (9, 2))
    others = others[np.hypot(*others.T) > 0.6]
    cell = dv.limited_cell(center, others, radius=0.8)
    points = rng.uniform(0, 10, (160, 2))
    part = dv.limited_cells(points, radius=0.8, workers=1)
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 5.0))
    plotting.plot_cell(cell, ax=axes[0], others=others)
    axes[0].add_patch(plt.Circle(center, 0.8, fill=False, ls="--", lw=0.8, color="tab:blue"))
    axes[0].add_patch(plt.Circle(center, 2 * 0.8, fill=False, ls=":", color="0.4"))
    axes[0].set_title(f"one robot: limited_cell(center, others, radius=0.8)\n{len(cell.neighbors)} limited "
                      f"neighbours, {len(cell.pieces)} pieces (edges and arcs);\ndashed: the disk of radius R, dotted: 2R", fontsize=9)
    _square(axes[0], -2.0, 2.0)
    part.plot(ax=axes[1])
    axes[1].set_title(f"every agent: limited_cells(points, radius=0.8)\n{len(points)} agents, "
                      f"{len(part.indices) // 2} limited-neighbour pairs", fontsize=9)
    _square(axes[1], -0.9, 10.9)
    fig.tight_layout()
    return _save(fig, out / "limited_cells.png")


def heterogeneous(out: Path) -> Path:
    # A mixed team: drones (R = 1.6) and ground robots (R = 0.6); cells are power cells clipped to
    # each robot's own disk, so they tile the union of the disks.
    rng = np.random.default_rng(4)
    points = rng.uniform(0, 8, (45, 2))
    radii = np.where(rng.random(len(points)) < 0.25, 1.6, 0.6)
    part = dv.limited_cells(points, radii, workers=1)
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 5.0))
    part.plot(ax=axes[0], show_points=False)
    for p, r in zip(points, radii):
        axes[0].add_patch(plt.Circle(p, r, fill=False, ls=":", lw=0.6, color="0.45"))
    drones = radii > 1
    axes[0].scatter(*points[drones].T, marker="^", s=28, color="tab:red", zorder=3, label="drone, R = 1.6")
    axes[0].scatter(*points[~drones].T, marker="o", s=14, color="k", zorder=3, label="ground robot, R = 0.6")
    axes[0].scatter(*points[part.empty].T, marker="x", s=40, color="tab:orange", zorder=4, label="empty cell")
    axes[0].legend(loc="upper right", fontsize=7, framealpha=0.9)
    axes[0].set_title(f"limited_cells(points, radii): {len(points)} robots, {int(part.empty.sum())} empty cells\n"
                      f"cells tile the union of the disks (dotted)", fontsize=9)
    _square(axes[0], -1.7, 9.7)
    # The crescent: a small robot beside a big one keeps the part of its disk beyond the radical axis.
    pair = np.array([[0.0, 0.0], [9.5, 0.0]])
    cres = dv.limited_cells(pair, [10.0, 1.0], workers=1)
    cres.plot(ax=axes[1])
    for p, r in zip(pair, (10.0, 1.0)):
        axes[1].add_patch(plt.Circle(p, r, fill=False, ls=":", lw=0.8, color="0.45"))
    axes[1].set_title("R = 10 at (0, 0), R = 1 at (9.5, 0): the small robot's cell\n"
                      f"is a crescent (area {cres.areas[1]:.3f}) that does not contain the robot", fontsize=9)
    axes[1].set_aspect("equal", adjustable="box")
    axes[1].set_xlim(7.5, 11.0)
    axes[1].set_ylim(-1.75, 1.75)
    axes[1].tick_params(labelsize=8)
    fig.tight_layout()
    return _save(fig, out / "heterogeneous.png")


def exact_cells(out: Path) -> Path:
    rng = np.random.default_rng(5)
    points = rng.uniform(1, 9, (70, 2))
    vor = dv.voronoi_cells(points, bounds=(0, 0, 10, 10), workers=1)
    fig, ax = plt.subplots(figsize=(6.0, 6.0))
    vor.plot(ax=ax, delaunay=True)
    hull = np.flatnonzero(vor.on_hull)
    ring = next(a for a in ax.collections if a.get_gid() == "dvoronoi-hull")  # plot() circles them
    ring.set_label(f"on_hull ({len(hull)} agents: unbounded cells, clipped to the box)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.06), fontsize=8, frameon=False)
    ax.set_title("voronoi_cells(points, bounds=(0, 0, 10, 10)): exact cells and the Delaunay graph", fontsize=9)
    _square(ax, -0.3, 10.3)
    fig.tight_layout()
    return _save(fig, out / "exact_cells.png")


def distances(out: Path) -> Path:
    rng = np.random.default_rng(7)
    points = rng.uniform(0, 10, (60, 2))
    e = dv.distances.measure(points, radius=4.0, model="exact")
    res = dv.neighbors_from_distances(e)
    fig, ax = plt.subplots(figsize=(6.0, 6.0))
    res.plot(ax=ax, points=points)
    ax.set_title("neighbors_from_distances(e): Voronoi neighbours from distances only\n"
                 "(60 robots, each measuring those within 4; drawn at the true positions)", fontsize=9)
    _square(ax, -0.3, 10.3)
    fig.tight_layout()
    return _save(fig, out / "distances.png")


def networks(out: Path) -> Path:
    from dvoronoi import network
    rng = np.random.default_rng(11)
    points = rng.uniform(0, 100, (100, 2))
    bars = network.random_bars(rng, 6, 25.0, (0, 0, 100, 100))
    res = network.simulate("cc", points, comm_range=20.0, loss=0.2, obstacles=bars, seed=1)
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 5.2))
    res.plot(ax=axes[0])
    for (x0, y0, x1, y1) in bars:
        axes[0].plot([x0, x1], [y0, y1], color="k", lw=2.5)
    axes[0].set_title(f"CC over GPSR: 100 nodes, range 20, 20% loss, 6 walls (black)\n"
                      f"Theorem 2's condition: {res.condition}; nodes not exact (red crosses): {len(res.wrong_nodes)}",
                      fontsize=9)
    _square(axes[0], -2, 102)
    res.plot_messages(ax=axes[1])
    axes[1].set_title(f"messages per node ({res.total_transmissions} transmissions in all)", fontsize=9)
    fig.tight_layout()
    return _save(fig, out / "networks.png")


def gvd_obstacles(out: Path) -> Path:
    from dvoronoi.gvd_maps import mixed_shapes
    gv = dv.grid_voronoi(mixed_shapes(), cells=512, robot_radius=1.5, workers=1)
    route = gv.path((5, 5), (95, 95))
    fig, ax = plt.subplots(figsize=(6.2, 6.2))
    gv.plot(ax=ax, path=route)
    ax.set_title("grid_voronoi(mixed_shapes(), cells=512, robot_radius=1.5)\n"
                 "the paper's mixed-shapes map, its labelled diagram and a path", fontsize=9)
    ax.set_aspect("equal")
    ax.tick_params(labelsize=8)
    fig.tight_layout()
    return _save(fig, out / "gvd_obstacles.png")


def coverage(out: Path) -> Path:
    rng = np.random.default_rng(2)
    points = rng.uniform(0.0, 0.25, (40, 2))

    def density(x, y):
        return np.exp(-((x - 0.65) ** 2 + (y - 0.6) ** 2) / 0.05)

    run = dv.coverage.lloyd(points, radius=0.12, steps=60, bounds=(0, 0, 1, 1), density=density, workers=1)
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.6))
    dv.coverage.LloydStepper(points, 0.12, density=density, bounds=(0, 0, 1, 1)).cells().plot(ax=axes[0])
    axes[0].set_title("start: 40 agents in a corner, R = 0.12", fontsize=9)
    run.plot(ax=axes[1])  # the density as background, the trajectories in grey
    axes[1].set_title("after 60 Lloyd steps (grey: density and trajectories)", fontsize=9)
    for ax in axes[:2]:
        gx, gy = np.meshgrid(np.linspace(0, 1, 120), np.linspace(0, 1, 120))
        ax.contour(gx, gy, density(gx, gy), levels=4, colors="tab:orange", linewidths=0.6)
        _square(ax, -0.02, 1.02)
    axes[2].plot(np.asarray(run.cost), color="tab:blue")
    axes[2].set_xlabel("step", fontsize=9)
    axes[2].set_ylabel("coverage cost H (never increases)", fontsize=9)
    axes[2].tick_params(labelsize=8)
    axes[2].set_title("cost", fontsize=9)
    fig.tight_layout()
    return _save(fig, out / "coverage.png")


def heterogeneous_lloyd(out: Path) -> Path:
    # Coverage control of a mixed team (docs/heterogeneous.md): two drones (R = 0.3) and ten ground
    # robots (R = 0.12) start in a corner of the unit square and spread; the cost never increases.
    rng = np.random.default_rng(1)
    points = rng.uniform(0, 0.3, (12, 2))
    radii = np.array([0.3, 0.3] + [0.12] * 10)
    run = dv.coverage.lloyd(points, radii, steps=40, bounds=(0, 0, 1, 1), record_every=2, workers=1,
                            progress=False)
    run.animate(out / "heterogeneous_lloyd.gif", fps=5, dpi=70, figsize=(5.0, 5.0), progress=False)
    plt.close("all")
    return out / "heterogeneous_lloyd.gif"


def mpi_slabs(out: Path) -> Path:
    rng = np.random.default_rng(4)
    points = rng.uniform(0, 1, (300, 2))
    radius, ranks = 0.05, 3
    cells = dv.coverage.LloydStepper(points, radius, bounds=(0, 0, 1, 1)).cells()
    owner = np.minimum((points[:, 0] * ranks).astype(int), ranks - 1)
    colours = ["tab:blue", "tab:orange", "tab:green"]
    fig, ax = plt.subplots(figsize=(6.4, 6.0))
    for r in range(ranks):
        ax.axvspan(r / ranks - 2 * radius, r / ranks, color=colours[r], alpha=0.08, lw=0) if r else None
        ax.axvspan((r + 1) / ranks, (r + 1) / ranks + 2 * radius, color=colours[r], alpha=0.08, lw=0) \
            if r < ranks - 1 else None
        ax.axvline(r / ranks, color="0.3", lw=1.0) if r else None
    ax.scatter(points[:, 0], points[:, 1], s=7, c=[colours[o] for o in owner], zorder=4)
    cells.plot(ax=ax, show_points=False, facecolor="none", alpha=1.0)
    ax.set_title("dvoronoi.mpi: 3 ranks own x-slabs (colours); each also receives\n"
                 "the agents within 2R of its slab (shaded halo), R = 0.05", fontsize=9)
    _square(ax, -0.02, 1.02)
    fig.tight_layout()
    return _save(fig, out / "mpi_slabs.png")


def _save(fig, target: Path) -> Path:
    fig.savefig(target, dpi=110)
    plt.close(fig)
    return target


FIGURES = (paris, pruning, limited_cells, heterogeneous, heterogeneous_lloyd, exact_cells, distances, networks,
           gvd_obstacles, coverage, mpi_slabs)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "images", help="output directory")
    ap.add_argument("--only", action="append", choices=[f.__name__ for f in FIGURES],
                    help="make only this figure (repeatable)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    for make in FIGURES:
        if args.only and make.__name__ not in args.only:
            continue
        target = make(args.out)
        print(f"{os.path.relpath(target)}: {target.stat().st_size / 1024:.0f} KB")


if __name__ == "__main__":
    main()
