"""Plots (python/dvoronoi/plotting.py): defaults that work at any size, neighbour colouring, network and
CC plots cut at the data's box, wrong nodes marked, Lloyd density and trajectories, animate()'s
progress bar and file mode, and the message when matplotlib or tqdm is missing.

Everything draws with the Agg backend; inputs are small except the one 5,000-cell case.
"""
from __future__ import annotations

import os
import sys

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import network as net
from dvoronoi import plotting

from conftest import random_points

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _artist(ax, gid):
    found = [a for a in ax.get_children() if a.get_gid() == gid]
    assert len(found) == 1, (gid, len(found))
    return found[0]


def _gids(ax):
    return {a.get_gid() for a in ax.get_children() if a.get_gid()}


def _face_colors(ax, n):
    colors = _artist(ax, "dvoronoi-cells").get_facecolors()
    assert len(colors) == n
    return [tuple(c) for c in colors]


def _assert_neighbours_differ(result, colors):
    pairs = 0
    for i in range(len(result)):
        for j in result.neighbors(i):
            assert colors[i] != colors[j], f"cells {i} and {j} are neighbours with one colour"
            pairs += 1
    assert pairs > 0


# ---------------------------------------------------------------------------- neighbour colouring
def test_neighbouring_cells_get_different_face_colours():
    part = dv.limited_cells(random_points(1, 300), 0.06)
    ax = part.plot()
    colors = _face_colors(ax, len(part))
    _assert_neighbours_differ(part, colors)
    palette = {to_rgba(c, 0.55) for c in plotting.PALETTE}
    assert set(colors) <= palette and len(set(colors)) <= 6  # smallest-last greedy on a planar graph

    run = dv.coverage.lloyd(random_points(2, 40), 0.2, steps=2, bounds=(0, 0, 1, 1))
    _assert_neighbours_differ(run, _face_colors(run.plot(trajectories=False), len(run)))
    cc = net.simulate("cc", random_points(3, 40, 100.0), 30.0, bounds=(0, 0, 100, 100))
    _assert_neighbours_differ(cc, _face_colors(cc.plot(), len(cc)))


def test_neighbor_coloring_is_proper_and_small():
    part = dv.limited_cells(random_points(4, 2000), 1.0)  # a radius past the spread: Delaunay neighbours
    color = plotting.neighbor_coloring(part.indptr, part.indices)
    rows = np.repeat(np.arange(len(part)), np.diff(part.indptr))
    assert np.all(color[rows] != color[part.indices])
    assert color.min() == 0 and color.max() <= 5
    # Not symmetric, self loops and out-of-range entries are tolerated.
    c = plotting.neighbor_coloring([0, 2, 2, 3], [1, 0, 5])  # 0 -> 1, 0 -> 0, 2 -> 5 (out of range)
    assert c[0] != c[1] and c[2] == 0
    assert len(plotting.neighbor_coloring([0], [])) == 0


def test_index_colouring_and_one_facecolor_remain():
    part = dv.limited_cells(random_points(5, 30), 0.2)
    ax = part.plot(coloring="index", cmap="tab20")
    assert len(set(_face_colors(ax, len(part)))) == 20
    ax = part.plot(facecolor="0.8")
    assert len(set(map(tuple, _artist(ax, "dvoronoi-cells").get_facecolors()))) == 1
    with pytest.raises(ValueError, match="coloring"):
        part.plot(coloring="rainbow")


# ---------------------------------------------------------------------------- sizes
def test_5000_cells_thin_lines_and_no_edges_below_a_few_pixels():
    part = dv.limited_cells(random_points(6, 5000), 0.03)
    ax = part.plot()  # matplotlib's default 6.4 x 4.8 in at 100 dpi: a cell is ~5 px across
    for gid in ("dvoronoi-edges", "dvoronoi-arcs"):
        lines = _artist(ax, gid)
        assert not lines.get_visible(), f"{gid} drawn on cells a few pixels wide"
        assert np.all(lines.get_linewidths() < 0.3)
    assert np.all(_artist(ax, "dvoronoi-agents").get_sizes() < 1.0)  # marker area, points^2
    assert _artist(ax, "dvoronoi-cells").get_visible()

    # A figure big enough for the edges: they are drawn, still thinner than on a small partition.
    fig, big = plt.subplots(figsize=(15, 15), dpi=100)
    part.plot(ax=big)
    edges = _artist(big, "dvoronoi-edges")
    assert edges.get_visible() and np.all(edges.get_linewidths() < 0.8)
    small = dv.limited_cells(random_points(6, 40), 0.2).plot()
    assert _artist(small, "dvoronoi-edges").get_visible()
    assert _artist(small, "dvoronoi-edges").get_linewidths()[0] == pytest.approx(0.8)
    # An explicit width always draws the edges.
    ax = part.plot(linewidth=0.1)
    assert _artist(ax, "dvoronoi-edges").get_visible()


# ---------------------------------------------------------------------------- the data's box
def _within(ax, box, margin):
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    w, h = box[2] - box[0], box[3] - box[1]
    assert box[0] - margin * w <= x0 and x1 <= box[2] + margin * w, (ax.get_xlim(), box)
    assert box[1] - margin * h <= y0 and y1 <= box[3] + margin * h, (ax.get_ylim(), box)


def test_cc_plot_stays_within_the_data_box():
    pts = random_points(3, 40, 100.0)
    res = net.simulate("cc", pts, 30.0)
    # The case the default is for: interior cells next to the hull reach -800 (thin Delaunay triangles).
    assert res.piece_x.min() < -500
    box = np.concatenate([pts.min(axis=0), pts.max(axis=0)])
    ax = res.plot()
    _within(ax, box, 0.1)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    shown = ax.transData.transform([[x0, y0], [x1, y1]])
    for gid in ("dvoronoi-cells", "dvoronoi-edges", "dvoronoi-links", "dvoronoi-delaunay"):
        np.testing.assert_allclose(_artist(ax, gid).get_clip_box().get_points(), shown)  # cut there
    assert {"dvoronoi-links", "dvoronoi-delaunay", "dvoronoi-hull", "dvoronoi-nodes"} <= _gids(ax)
    np.testing.assert_array_equal(_artist(ax, "dvoronoi-hull").get_offsets(), pts[res.on_hull])
    # Hull cells are drawn too (from CC's neighbour order, cut at the box): every point of the box
    # lies in its nearest node's cell.
    paths = _artist(ax, "dvoronoi-cells").get_paths()
    assert len(paths) == len(pts) and res.on_hull.sum() >= 5
    probe = np.random.default_rng(0).uniform(-3, 103, (300, 2))
    nearest = np.argmin(((probe[:, None, :] - pts[None]) ** 2).sum(axis=2), axis=1)
    assert all(paths[k].contains_point(q) for q, k in zip(probe, nearest))
    assert {int(k) for k in nearest} >= {int(k) for k in np.flatnonzero(res.on_hull)}
    # clip=False shows everything; a box shows that box.
    ax = res.plot(clip=False)
    assert ax.get_xlim()[0] < -500
    ax = res.plot(clip=(20, 20, 60, 60))
    assert ax.get_xlim() == (20, 60) and ax.get_ylim() == (20, 60)
    with pytest.raises(ValueError, match="clip"):
        res.plot(clip=(1, 2, 3))


@pytest.mark.parametrize("bounds", [None, (0, 0, 1, 1)])
def test_exact_cells_plot_every_cell_cut_at_the_box(bounds):
    pts = random_points(11, 60)
    vor = dv.voronoi_cells(pts, bounds=bounds)
    ax = vor.plot(delaunay=True)
    paths = _artist(ax, "dvoronoi-cells").get_paths()
    assert len(paths) == len(pts)
    _within(ax, (0, 0, 1, 1) if bounds else np.concatenate([pts.min(axis=0), pts.max(axis=0)]), 0.1)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    probe = np.random.default_rng(1).uniform([x0, y0], [x1, y1], (300, 2))
    if bounds:
        probe = probe[np.all((probe >= 0) & (probe <= 1), axis=1)]
    nearest = np.argmin(((probe[:, None, :] - pts[None]) ** 2).sum(axis=2), axis=1)
    assert all(paths[k].contains_point(q) for q, k in zip(probe, nearest))
    _assert_neighbours_differ(vor, _face_colors(ax, len(pts)))
    np.testing.assert_array_equal(_artist(ax, "dvoronoi-hull").get_offsets(), pts[vor.on_hull])
    assert len(_artist(ax, "dvoronoi-delaunay").get_segments()) == len(vor.indices) // 2
    for few in ([[0.0, 0.0]], [[0.0, 0.0], [1.0, 0.0]], [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]):
        assert len(_artist(dv.voronoi_cells(np.array(few)).plot(), "dvoronoi-cells").get_paths()) == len(few)


def test_network_and_bounded_plots_stay_within_their_box():
    pts = random_points(3, 40, 100.0)
    for res in (net.simulate("cc", pts, 30.0, bounds=(0, 0, 100, 100)),
                net.simulate("bd07", pts, 30.0, bounds=(0, 0, 100, 100))):
        _within(res.plot(), (0, 0, 100, 100), 0.05)
    bs = net.simulate("bs", pts, 30.0)  # limited cells: the box widened by their radius
    box = np.concatenate([pts.min(axis=0) - bs.radius, pts.max(axis=0) + bs.radius])
    _within(bs.plot(), box, 0.05)
    _within(bs.plot_network(), box, 0.05)
    part = dv.limited_cells(pts, 4.0)
    _within(part.plot(), np.concatenate([pts.min(axis=0) - 4, pts.max(axis=0) + 4]), 0.01)


# ---------------------------------------------------------------------------- wrong nodes
def test_wrong_nodes_are_marked():
    rng = np.random.default_rng(3)  # two clusters farther apart than the range (test_network.py)
    pts = np.vstack([rng.uniform(0, 20, (15, 2)), rng.uniform(60, 80, (15, 2))])
    res = net.simulate("cc", pts, 15.0)
    assert len(res.wrong_nodes) > 0
    ax = res.plot()
    marks = _artist(ax, "dvoronoi-wrong-nodes")
    np.testing.assert_array_equal(marks.get_offsets(), pts[res.wrong_nodes])
    red = to_rgba("red")
    assert all(tuple(c) == red for c in marks.get_facecolors())
    nodes = _artist(ax, "dvoronoi-nodes")
    assert tuple(nodes.get_facecolors()[0]) != red
    assert marks.get_paths()[0] is not nodes.get_paths()[0]  # another marker ("X")
    assert np.all(marks.get_sizes() > nodes.get_sizes().max())
    assert "wrong nodes" in marks.get_label()
    # An exact run has nothing to mark.
    ok = net.simulate("cc", random_points(3, 40, 100.0), 30.0)
    assert ok.exact and "dvoronoi-wrong-nodes" not in _gids(ok.plot())


# ---------------------------------------------------------------------------- Lloyd
def _bump(x, y):
    return np.exp(-((x - 0.7) ** 2 + (y - 0.6) ** 2) / 0.02)


def test_lloyd_plot_shows_density_and_one_line_per_trajectory():
    run = dv.coverage.lloyd(random_points(7, 12), 0.3, steps=4, bounds=(0, 0, 1, 1), density=_bump)
    ax = run.plot()
    image = _artist(ax, "dvoronoi-density")
    assert image in ax.images
    values = np.asarray(image.get_array())
    assert values.shape[0] >= 100 and np.nanargmax(values) != 0  # the bump, not a constant
    x0, x1, y0, y1 = image.get_extent()
    assert x0 < 0.0 < 1.0 < x1 and y0 < 0.0 < 1.0 < y1
    lines = _artist(ax, "dvoronoi-trajectories").get_segments()
    assert len(lines) == len(run)
    for i, line in enumerate(lines):
        np.testing.assert_array_equal(line, run.trajectory[:, i])
    assert {"dvoronoi-bounds", "dvoronoi-cells", "dvoronoi-agents"} <= _gids(ax)

    uniform = dv.coverage.lloyd(random_points(7, 12), 0.3, steps=4, bounds=(0, 0, 1, 1))
    ax = uniform.plot()
    assert not ax.images and "dvoronoi-trajectories" in _gids(ax)
    ax = run.plot(density=False, trajectories=False)
    assert not ax.images and "dvoronoi-trajectories" not in _gids(ax)
    # In the plane (no bounds) the agents spread out: the axes hold every position of the run.
    free = dv.coverage.lloyd(random_points(7, 12) * 0.2, 0.1, steps=4)
    ax = free.plot()
    t = free.trajectory.reshape(-1, 2)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x0 < t[:, 0].min() and t[:, 0].max() < x1 and y0 < t[:, 1].min() and t[:, 1].max() < y1


def test_density_image_masks_outside_a_polygon():
    hexagon = np.array([[np.cos(a), np.sin(a)] for a in np.linspace(0, 2 * np.pi, 7)[:-1]])
    img = plotting.density_image(lambda x, y: 1.0 + x, (-1, -1, 1, 1), hexagon, pixels=50)
    assert img.shape == (50, 50)
    assert np.isnan(img[0, 0]) and np.isnan(img[-1, -1]) and img[25, 25] == pytest.approx(1.0, abs=0.05)


# ---------------------------------------------------------------------------- animate
def test_animate_writes_0644_and_reports_progress(tmp_path, capsys):
    run = dv.coverage.lloyd(random_points(8, 10), 0.2, steps=3, bounds=(0, 0, 1, 1), density=_bump)
    old = os.umask(0o022)
    try:
        seen = []
        path = tmp_path / "run.gif"
        run.animate(path, fps=5, progress=lambda done, total: seen.append((done, total)))
        assert seen == [(1, 4), (2, 4), (3, 4), (4, 4)]
        assert oct(os.stat(path).st_mode & 0o777) == oct(0o644)
        assert path.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
        pytest.importorskip("tqdm")
        capsys.readouterr()
        dv.coverage.animate(run, tmp_path / "bar.gif", progress=True, cells=False)
        assert "4/4" in capsys.readouterr().err  # tqdm writes its bar to stderr
        assert oct(os.stat(tmp_path / "bar.gif").st_mode & 0o777) == oct(0o644)
    finally:
        os.umask(old)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bar.gif", "run.gif"]  # no temp files left


# ---------------------------------------------------------------------------- optional dependencies
def _hide(monkeypatch, package):
    for name in list(sys.modules):
        if name == package or name.startswith(package + "."):
            monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, package, None)  # `import package` now raises ImportError


def test_missing_matplotlib_says_what_to_install(monkeypatch, tmp_path, capsys):
    part = dv.limited_cells(random_points(9, 10), 0.2)
    run = dv.coverage.lloyd(random_points(9, 10), 0.2, steps=1, bounds=(0, 0, 1, 1))
    res = net.simulate("cc", random_points(9, 10, 100.0), 50.0)
    _hide(monkeypatch, "matplotlib")
    for call in (part.plot, run.plot, res.plot, res.plot_network, lambda: run.animate(None),
                 lambda: plotting.cell_paths(part)):
        with pytest.raises(ImportError, match=r'pip install "dvoronoi\[plot\]"'):
            call()
    from dvoronoi.__main__ import main

    assert main(["demo", "--out", str(tmp_path / "demo.png")]) == 1
    assert 'pip install "dvoronoi[plot]"' in capsys.readouterr().err
    assert not (tmp_path / "demo.png").exists()


def test_missing_tqdm_only_matters_when_asked_for(monkeypatch, tmp_path):
    run = dv.coverage.lloyd(random_points(10, 6), 0.2, steps=1, bounds=(0, 0, 1, 1))
    _hide(monkeypatch, "tqdm")
    run.animate(tmp_path / "quiet.gif", cells=False)  # progress=None: no bar, no error
    assert (tmp_path / "quiet.gif").exists()
    with pytest.raises(ImportError, match=r"tqdm.*dvoronoi\[plot\]"):
        run.animate(tmp_path / "loud.gif", cells=False, progress=True)
    assert not (tmp_path / "loud.gif").exists()
    # The computations' own bars (progress=None shows one on big inputs) do the same.
    pts = random_points(10, 30)
    monkeypatch.setattr(dv._partition, "PROGRESS_BAR_FROM", 1)
    monkeypatch.setattr(dv.coverage, "PROGRESS_BAR_FROM", 1)
    assert len(dv.limited_cells(pts, 0.1)) == 30
    assert dv.coverage.lloyd(pts, 0.1, steps=2).steps == 2
    with pytest.raises(ImportError, match=r"tqdm.*dvoronoi\[plot\]"):
        dv.limited_cells(pts, 0.1, progress=True)
    with pytest.raises(ImportError, match=r"tqdm.*dvoronoi\[plot\]"):
        dv.coverage.lloyd(pts, 0.1, steps=2, progress=True)
