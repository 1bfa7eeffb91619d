"""Geodesic cells and geodesic Lloyd on occupancy grids (docs/spec.md, "Geodesic cells on maps").

The reference is tests/python/geodesic_oracle.py: exact shortest paths by Dijkstra on the visibility
graph of the sources and the convex corners of occupied pixels (shapely decides visibility).
"""
from __future__ import annotations

import json
import os
import pickle

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import _core, occupancy_maps as om

geodesic_oracle = pytest.importorskip("geodesic_oracle")
from scipy.sparse import coo_matrix  # noqa: E402
from scipy.sparse.csgraph import connected_components  # noqa: E402
from scipy import ndimage  # noqa: E402


# ----------------------------------------------------------------------------------------- maps
def corridor_map() -> np.ndarray:
    """Corridors with a one-pixel wall, a T junction, a door, a block and a pinch point (two occupied
    pixels touching diagonally at (3, 3))."""
    occ = np.zeros((20, 28), bool)
    occ[6, 3:25] = True
    occ[13, 4:] = True
    occ[6:14, 12] = True
    occ[9, 12] = False
    occ[16:18, 5:7] = True
    occ[2, 2] = occ[3, 3] = True
    return occ


MAPS = {
    "corridors": lambda s: corridor_map() if s % 2 == 0 else om.passages(64)[:32, :40],
    "rooms": lambda s: om.rooms_with_islands(32, seed=s),
    "cave": lambda s: om.cave(32, seed=s),
    "building": lambda s: om.building(32, seed=s),
    "warehouse": lambda s: om.warehouse(32, seed=s),
}


def random_agents(occ: np.ndarray, n: int, seed: int) -> np.ndarray:
    """n agents in distinct free pixels, anywhere inside them, as (x, y) map coordinates (resolution 1,
    origin 0: x = u, y = H - w)."""
    rng = np.random.default_rng(seed)
    free = np.argwhere(~occ)
    pick = free[rng.choice(len(free), n, replace=False)]
    uw = pick[:, ::-1] + rng.uniform(0.02, 0.98, (n, 2))
    return np.column_stack([uw[:, 0], occ.shape[0] - uw[:, 1]])


def to_uw(occ: np.ndarray, xy: np.ndarray) -> np.ndarray:
    return np.column_stack([xy[:, 0], occ.shape[0] - xy[:, 1]])


def pixel_of(grid: dv.OccupancyGrid, xy: np.ndarray) -> np.ndarray:
    """(row, col) of the pixels containing map points (floor, as the core)."""
    H = grid.shape[0]
    u = (xy[:, 0] - grid.origin[0]) / grid.resolution
    v = (xy[:, 1] - grid.origin[1]) / grid.resolution
    return np.column_stack([np.floor(H - v), np.floor(u)]).astype(np.int64)


# ----------------------------------------------------------------------------------------- accuracy
@pytest.mark.parametrize("name", sorted(MAPS))
@pytest.mark.parametrize("seed", range(6))
def test_distances_match_exact_shortest_paths(name, seed):
    """Never shorter than the exact shortest path (every path used is real), within 2 % of it at pixels
    more than 3 pixels from the sources (docs/geodesic_coverage.md: at most 1.6 % measured), never an
    unreachable pixel reached or the reverse, and labels equal wherever the nearest agent wins by more
    than the error allows."""
    occ = MAPS[name](seed)
    n = 1 + seed % 4
    xy = random_agents(occ, n, seed)
    exact = geodesic_oracle.exact_distances(occ, to_uw(occ, xy))
    best = exact.min(axis=0)
    cells = dv.coverage.geodesic_cells(xy, occ)
    assert np.array_equal(np.isfinite(best), np.isfinite(cells.distances))
    far = np.isfinite(best) & (best > 3)
    reach = np.isfinite(best)
    assert np.all(cells.distances[reach] >= best[reach] * (1 - 1e-12))
    rel = np.abs(cells.distances[far] - best[far]) / best[far]
    assert rel.max() <= 0.02, f"{name}/{seed}: max relative error {rel.max():.4f}"
    second = np.sort(exact, axis=0)[1] if n > 1 else np.full_like(best, np.inf)
    clear = np.isfinite(best) & (second > best * 1.05 + 0.2)
    assert np.array_equal(cells.labels[clear], exact.argmin(axis=0)[clear])


def test_open_map_is_euclidean():
    occ = np.zeros((30, 40), bool)
    xy = np.array([[7.3, 21.9]])
    cells = dv.coverage.geodesic_cells(xy, occ)
    r, c = np.mgrid[0:30, 0:40]
    euclid = np.hypot(c + 0.5 - 7.3, (30 - r - 0.5) - 21.9)
    np.testing.assert_allclose(cells.distances, euclid, rtol=0, atol=1e-12)


def test_path_around_a_wall_and_not_through_a_pinch():
    """Exact values: around a wall's end corner, and a diagonal gap between two occupied pixels that
    touch at a corner is closed."""
    occ = np.zeros((10, 10), bool)
    occ[5, 0:8] = True                      # a wall from the left edge, open at the right
    xy = np.array([[1.5, 10 - 7.5]])        # below the wall, in pixel (7, 1)
    d = dv.coverage.geodesic_cells(xy, occ).distances
    # pixel (3, 1) above the wall: around the wall's two right corners (8, 6) and (8, 5)
    expect = np.hypot(8 - 1.5, 7.5 - 6) + 1 + np.hypot(8 - 1.5, 5 - 3.5)
    assert d[3, 1] == pytest.approx(expect, rel=1e-12)
    pinch = np.zeros((4, 4), bool)
    pinch[0, 1] = pinch[1, 0] = True        # they touch at (1, 1): pixel (0, 0) is closed off
    cells = dv.coverage.geodesic_cells(np.array([[2.5, 1.5]]), pinch)
    assert cells.labels[0, 0] == -1 and np.isinf(cells.distances[0, 0])


def test_segment_test_matches_shapely():
    """The exact segment test of the core against shapely on random segments between pixel corners and
    centres (the points where paths bend and end)."""
    occ = corridor_map()
    H, W = occ.shape
    rng = np.random.default_rng(3)
    pts = np.concatenate([rng.integers(0, [W + 1, H + 1], (300, 2)).astype(float),
                          rng.integers(0, [W, H], (300, 2)) + 0.5])
    a = pts[rng.integers(0, len(pts), 1500)]
    b = a + rng.integers(-6, 7, a.shape) * rng.choice([0.5, 1.0], a.shape)
    b = np.clip(b, 0, [W, H])
    convex, pinch = geodesic_oracle.corners(occ)
    expect = geodesic_oracle.visible(geodesic_oracle.free_region(occ), pinch, a, b)
    got = np.array([_core._segment_free(occ.astype(np.uint8), *p, *q) for p, q in zip(a, b)])
    assert np.array_equal(got, expect)
    assert 100 < expect.sum() < len(expect) - 100  # both answers occur


# ----------------------------------------------------------------------------------------- cells
def cell_components(labels: np.ndarray, occ: np.ndarray) -> np.ndarray:
    """Connected components of each label (4-neighbours, and diagonal neighbours unless the two other
    pixels of their square are both occupied: a pinch point)."""
    H, W = labels.shape
    idx = np.arange(H * W).reshape(H, W)
    rows, cols = [], []

    def link(a, b, ok):
        rows.append(a[ok])
        cols.append(b[ok])

    link(idx[:, :-1], idx[:, 1:], (labels[:, :-1] == labels[:, 1:]) & (labels[:, :-1] >= 0))
    link(idx[:-1, :], idx[1:, :], (labels[:-1, :] == labels[1:, :]) & (labels[:-1, :] >= 0))
    open_ = ~(occ[:-1, 1:] & occ[1:, :-1])
    link(idx[:-1, :-1], idx[1:, 1:], (labels[:-1, :-1] == labels[1:, 1:]) & (labels[:-1, :-1] >= 0) & open_)
    open_ = ~(occ[:-1, :-1] & occ[1:, 1:])
    link(idx[:-1, 1:], idx[1:, :-1], (labels[:-1, 1:] == labels[1:, :-1]) & (labels[:-1, 1:] >= 0) & open_)
    r, c = np.concatenate(rows), np.concatenate(cols)
    g = coo_matrix((np.ones(len(r)), (r, c)), shape=(H * W, H * W))
    _, comp = connected_components(g, directed=False)
    return comp.reshape(H, W)


@pytest.mark.parametrize("name,seed", [("rooms", 4), ("cave", 5), ("building", 6)])
def test_cells_partition_reachable_free_pixels(name, seed):
    occ = MAPS[name](seed)
    xy = random_agents(occ, 6, seed)
    grid = dv.OccupancyGrid(occ)
    cells = dv.coverage.geodesic_cells(xy, grid)
    comp, _ = ndimage.label(~occ)  # free space is 4-connected (a diagonal gap is a pinch point)
    agent_px = pixel_of(grid, xy)
    reachable = np.isin(comp, comp[agent_px[:, 0], agent_px[:, 1]]) & ~occ
    assert np.array_equal(cells.labels >= 0, reachable)
    assert np.all(np.isfinite(cells.distances[reachable])) and np.all(np.isinf(cells.distances[~reachable]))
    components = cell_components(cells.labels, occ)
    for i in range(len(xy)):
        mask = cells.labels == i
        assert cells.labels[tuple(agent_px[i])] == i           # the agent's own pixel
        assert len(np.unique(components[mask])) == 1           # one piece
        assert cells.areas[i] == mask.sum()
        r, c = np.nonzero(mask)
        np.testing.assert_allclose(cells.centroids[i], [np.mean(c + 0.5), np.mean(occ.shape[0] - r - 0.5)])
    # neighbours: exactly the pairs of cells with 4-adjacent pixels, symmetric
    L = cells.labels
    pairs = set()
    for a, b in ((L[:, :-1], L[:, 1:]), (L[:-1], L[1:])):
        m = (a != b) & (a >= 0) & (b >= 0)
        pairs |= set(zip(a[m].tolist(), b[m].tolist())) | set(zip(b[m].tolist(), a[m].tolist()))
    for i in range(len(xy)):
        assert cells.neighbors(i).tolist() == sorted(j for (k, j) in pairs if k == i)


def test_ties_go_to_the_lower_index():
    occ = np.zeros((5, 9), bool)
    a, b = [1.5, 2.5], [7.5, 2.5]                     # column 4 (centre x = 4.5) is 3 from both
    assert np.all(dv.coverage.geodesic_cells(np.array([a, b]), occ).labels[:, 4] == 0)
    assert np.all(dv.coverage.geodesic_cells(np.array([b, a]), occ).labels[:, 4] == 0)


@pytest.mark.parametrize("name, seed", [("building", 3), ("rooms", 4), ("cave", 5), ("warehouse", 6)])
def test_agents_in_one_pixel_each_get_their_side(name, seed):
    # a pixel holds one label: the agent that lost its own pixel to another agent there never spread,
    # and got no cell (a corridor of 12 pixels gave areas [12, 0] instead of [1, 11])
    corridor = dv.coverage.geodesic_cells(np.array([[0.1, 0.5], [0.9, 0.5]]), np.zeros((1, 12), bool))
    assert corridor.areas.tolist() == [1.0, 11.0] and corridor.labels[0].tolist() == [0] + [1] * 11
    occ = MAPS[name](seed)
    H = occ.shape[0]
    rng = np.random.default_rng(seed)
    free = np.argwhere(~occ)
    xy = []
    for r, c in free[rng.choice(len(free), 3, replace=False)]:  # three pairs, each in one pixel
        u = rng.uniform(0.05, 0.35)
        xy += [[c + u, H - r - rng.uniform(0.2, 0.8)], [c + u + rng.uniform(0.3, 0.6), H - r - rng.uniform(0.2, 0.8)]]
    xy = np.array(xy)
    exact = geodesic_oracle.exact_distances(occ, to_uw(occ, xy))
    cells = dv.coverage.geodesic_cells(xy, occ)
    best = exact.min(axis=0)
    second = np.sort(exact, axis=0)[1]
    clear = np.isfinite(best) & (second > best * 1.05 + 0.2)  # as test_distances_match_exact_shortest_paths
    assert np.array_equal(cells.labels[clear], exact.argmin(axis=0)[clear])
    owners = set(exact.argmin(axis=0)[clear].tolist())
    assert all(cells.areas[i] > 0 for i in owners)


def test_radius_limits_the_cells():
    occ = MAPS["rooms"](1)
    xy = random_agents(occ, 4, 1)
    full = dv.coverage.geodesic_cells(xy, occ)
    lim = dv.coverage.geodesic_cells(xy, occ, radius=6.0)
    inside = lim.labels >= 0
    assert np.all(lim.distances[inside] <= 6.0) and np.all(np.isinf(lim.distances[~inside]))
    sure = full.distances <= 5.9
    assert np.array_equal(lim.labels[sure], full.labels[sure])
    np.testing.assert_allclose(lim.distances[sure], full.distances[sure], rtol=1e-12)
    assert np.count_nonzero(inside & ~sure) < np.count_nonzero(inside) // 4


def test_map_units_resolution_and_origin():
    """Resolution and origin as in the grid diagram: the same cells in pixels, map units out."""
    occ = MAPS["building"](2)
    xy = random_agents(occ, 5, 2)
    base = dv.coverage.geodesic_cells(xy, occ)
    res, origin = 0.05, (-3.0, 12.5)
    grid = dv.OccupancyGrid(occ, resolution=res, origin=origin)
    moved = dv.coverage.geodesic_cells(xy * res + origin, grid)
    assert np.array_equal(moved.labels, base.labels)
    np.testing.assert_allclose(moved.distances[base.labels >= 0], base.distances[base.labels >= 0] * res, rtol=1e-12)
    np.testing.assert_allclose(moved.areas, base.areas * res * res, rtol=1e-12)
    np.testing.assert_allclose(moved.centroids, base.centroids * res + origin, rtol=1e-12)
    np.testing.assert_allclose(moved.cost, base.cost * res ** 4, rtol=1e-9)
    # the same map as a MovingAI file and as an array with resolution= and origin=
    assert np.array_equal(dv.coverage.geodesic_cells(xy * res + origin, occ, resolution=res, origin=origin).labels,
                          base.labels)


def test_map_file_environment(tmp_path):
    occ = MAPS["cave"](3)
    path = tmp_path / "cave.map"
    om.write_movingai_map(path, occ)
    xy = random_agents(occ, 3, 3)
    assert np.array_equal(dv.coverage.geodesic_cells(xy, str(path)).labels, dv.coverage.geodesic_cells(xy, occ).labels)


def test_workers_do_not_change_the_result():
    occ = om.building(96, seed=7)
    xy = random_agents(occ, 12, 7)
    phi = lambda x, y: 1.0 + 0.02 * x  # noqa: E731
    one = dv.coverage.geodesic_cells(xy, occ, radius=30, workers=1, density=phi)
    two = dv.coverage.geodesic_cells(xy, occ, radius=30, workers=2, density=phi)
    for k in ("labels", "distances", "areas", "centroids", "masses", "mass_centroids"):
        assert np.array_equal(getattr(one, k), getattr(two, k)), k
    assert one.cost == two.cost
    r1 = dv.coverage.lloyd(xy, 30.0, steps=4, environment=occ, workers=1, density=phi)
    r2 = dv.coverage.lloyd(xy, 30.0, steps=4, environment=occ, workers=2, density=phi)
    assert np.array_equal(r1.trajectory, r2.trajectory) and np.array_equal(r1.cost, r2.cost)


def test_density_array_equals_callable_and_weights_the_centroids():
    occ = MAPS["rooms"](2)
    grid = dv.OccupancyGrid(occ, resolution=0.5)
    xy = random_agents(occ, 3, 2) * 0.5
    phi = lambda x, y: np.exp(-((x - 4.0) ** 2 + (y - 8.0) ** 2) / 20.0)  # noqa: E731
    H, W = occ.shape
    rr, cc = np.mgrid[0:H, 0:W]
    centres = grid.pixel_centers(np.column_stack([rr.ravel(), cc.ravel()]))
    arr = phi(centres[:, 0], centres[:, 1]).reshape(H, W)
    a = dv.coverage.geodesic_cells(xy, grid, density=phi)
    b = dv.coverage.geodesic_cells(xy, grid, density=arr)
    np.testing.assert_allclose(a.mass_centroids, b.mass_centroids, rtol=1e-12)
    assert a.cost == pytest.approx(b.cost, rel=1e-12)
    i = int(np.argmax(a.areas))
    m = a.labels == i
    w = arr[m]
    xs = centres[:, 0].reshape(H, W)[m]
    assert a.mass_centroids[i, 0] == pytest.approx(np.sum(w * xs) / np.sum(w), rel=1e-12)
    assert a.masses[i] == pytest.approx(np.sum(w) * 0.25, rel=1e-12)
    expect_cost = np.sum(arr[a.labels >= 0] * a.distances[a.labels >= 0] ** 2) * 0.25
    assert a.cost == pytest.approx(expect_cost, rel=1e-9)


# ----------------------------------------------------------------------------------------- Lloyd
def two_rooms() -> np.ndarray:
    occ = np.zeros((30, 50), bool)
    occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = True
    occ[:, 24:26] = True
    occ[13:16, 24:26] = False  # a door 3 px wide
    return occ


def test_lloyd_goes_around_walls_and_never_raises_the_cost():
    occ = two_rooms()
    grid = dv.OccupancyGrid(occ)
    xy = np.array([[3.5 + k, 5.5 + 2 * k] for k in range(8)])   # all in the left room
    run = dv.coverage.lloyd(xy, None, steps=40, environment=grid)
    assert np.all(np.diff(run.cost) <= 0)
    assert run.cost[-1] < 0.6 * run.cost[0]
    px = pixel_of(grid, run.trajectory.reshape(-1, 2))
    assert not occ[px[:, 0], px[:, 1]].any()                    # never on an occupied pixel
    final = pixel_of(grid, run.trajectory[-1])
    assert np.count_nonzero(final[:, 1] > 25) >= 2              # through the door into the right room
    # the recorded cost is the cost of the recorded positions
    for t in (0, 10, 40):
        assert run.cost[t] == pytest.approx(dv.coverage.geodesic_cells(run.trajectory[t], grid).cost, rel=1e-12)


@pytest.mark.parametrize("name,seed", [("building", 3), ("cave", 4), ("rooms", 5)])
def test_lloyd_with_range_and_density_cost_never_increases(name, seed):
    occ = MAPS[name](seed)
    xy = random_agents(occ, 6, seed)
    phi = np.where(occ, 0.0, 1.0 + np.linspace(0, 2, occ.shape[1])[None, :])
    stepper = dv.coverage.LloydStepper(xy, 5.0, density=phi, gain=0.8, environment=occ)
    assert isinstance(stepper, dv.geodesic.GeodesicLloydStepper)
    costs = [stepper.step() for _ in range(15)] + [stepper.cost()]
    assert np.all(np.diff(costs) <= 0) and costs[-1] < costs[0]
    px = pixel_of(stepper.grid, stepper.points)
    assert not occ[px[:, 0], px[:, 1]].any()
    cells = stepper.cells()
    assert cells.cost == pytest.approx(costs[-1], rel=1e-12)


def test_lloyd_result_surface(tmp_path):
    occ = two_rooms()
    xy = np.array([[5.5, 5.5], [10.5, 20.5], [40.5, 8.5]])
    run = dv.coverage.lloyd(xy, 12.0, steps=6, record_every=4, environment=occ)
    assert run.trajectory.shape == (3, 3, 2) and run.frame_steps.tolist() == [0, 4, 6]
    assert run.cost.shape == (7,) and run.steps == 6
    doc = json.loads(run.to_json())
    assert doc["steps"] == 6 and len(doc["cells"]) == 3 and len(doc["labels"]) == occ.shape[0]
    again = pickle.loads(pickle.dumps(run))
    assert np.array_equal(again.labels, run.labels) and np.array_equal(again.cost, run.cost)
    assert again.neighbors(0).tolist() == run.neighbors(0).tolist()
    import matplotlib

    matplotlib.use("Agg")
    ax = run.plot()
    assert ax.get_xlim() == (0.0, 50.0)


# ----------------------------------------------------------------------------------------- bad input
def test_bad_input_is_named():
    occ = two_rooms()
    good = np.array([[5.5, 5.5], [10.5, 10.5]])
    with pytest.raises(ValueError, match=r"points\[1\].*occupied"):
        dv.coverage.geodesic_cells([[5.5, 5.5], [24.5, 5.5]], occ)
    with pytest.raises(ValueError, match=r"points\[0\].*outside"):
        dv.coverage.geodesic_cells([[-1.0, 5.5]], occ)
    with pytest.raises(ValueError, match=r"points\[1\].*not finite"):
        dv.coverage.geodesic_cells([[5.5, 5.5], [np.nan, 5.5]], occ)
    with pytest.raises(ValueError, match=r"points must be an \(n, 2\)"):
        dv.coverage.geodesic_cells([1.0, 2.0, 3.0], occ)
    with pytest.raises(ValueError, match="radius"):
        dv.coverage.geodesic_cells(good, occ, radius=0)
    with pytest.raises(ValueError, match="workers"):
        dv.coverage.geodesic_cells(good, occ, workers=0)
    with pytest.raises(ValueError, match="density"):
        dv.coverage.geodesic_cells(good, occ, density=np.ones((3, 3)))
    with pytest.raises(ValueError, match="environment"):
        dv.coverage.geodesic_cells(good, None)
    with pytest.raises(ValueError, match="bounds.*environment"):
        dv.coverage.lloyd(good, 3.0, bounds=(0, 0, 50, 30), environment=occ)
    with pytest.raises(ValueError, match=r"points\[1\].*occupied"):
        dv.coverage.LloydStepper([[5.5, 5.5], [24.5, 5.5]], 3.0, environment=occ)


# ----------------------------------------------------------------------------------------- CLI
def cli_floor(tmp_path):
    """(the CLI runner, building map 5, its MovingAI file, 5 agents in it); skips without the CLI."""
    from test_cli import CLI, run

    if CLI is None:
        pytest.skip("no dvoronoi executable")
    occ = MAPS["building"](5)
    path = tmp_path / "floor.map"
    om.write_movingai_map(path, occ)
    return run, occ, path, random_agents(occ, 5, 5)


def test_cli_lloyd_on_a_map_equals_python(tmp_path):
    from test_cli import write_points

    run, occ, path, xy = cli_floor(tmp_path)
    xy = xy * 0.25 + (2.0, -1.0)
    pts = write_points(tmp_path / "agents.txt", xy.tolist())
    res = run("lloyd", pts, "-r", 3.0, "--steps", 6, "--map", path, "--resolution", 0.25, "--origin", 2.0, -1.0,
              "--trajectory", "-q", "-t", 1)
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    grid = dv.OccupancyGrid(occ, resolution=0.25, origin=(2.0, -1.0))
    py = dv.coverage.lloyd(xy, 3.0, steps=6, environment=grid, workers=1)
    assert doc["cost"] == py.cost.tolist()
    assert np.array_equal(np.array(doc["trajectory"]), py.trajectory)
    np.testing.assert_array_equal(doc["areas"], py.areas)
    bad = write_points(tmp_path / "bad.txt", [(2.0 + 0.1, -1.0 + 0.1)])  # the corner pixel is a wall
    res = run("lloyd", bad, "-r", 3.0, "--map", path, "--resolution", 0.25, "--origin", 2.0, -1.0)
    assert res.returncode == 2 and "points[0]" in res.stderr and "occupied" in res.stderr


def test_animation_is_written_whole_with_a_new_file_mode(tmp_path):
    pytest.importorskip("matplotlib")
    occ = om.building(48, seed=3)
    run = dv.coverage.lloyd(random_agents(occ, 4, 3), 12.0, steps=2, environment=occ, workers=1)
    old = os.umask(0o022)
    try:
        seen = []
        run.animate(tmp_path / "run.gif", fps=5, dpi=40, progress=lambda done, total: seen.append((done, total)))
    finally:
        os.umask(old)
    assert seen == [(k, len(run.trajectory)) for k in range(1, len(run.trajectory) + 1)]
    assert oct(os.stat(tmp_path / "run.gif").st_mode & 0o777) == oct(0o644)
    assert (tmp_path / "run.gif").read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert [p.name for p in tmp_path.iterdir()] == ["run.gif"]  # no temporary file left
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        run.animate(tmp_path / "run.png")
