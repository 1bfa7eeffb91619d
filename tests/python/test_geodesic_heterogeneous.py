"""Geodesic coverage of heterogeneous teams (a geodesic range per agent): the cells are the geodesic
power cells (smallest d_g^2 - R_i^2 within range) of per-agent distance fields; equal ranges give the
scalar cells and runs exactly; the cost equals its definition, the Lloyd cost never increases, and
results do not depend on the worker count; the CLI's --columns X,Y,R runs the same steps."""
from __future__ import annotations

import json

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import occupancy_maps as om
from test_geodesic import MAPS, cli_floor, pixel_of, random_agents, two_rooms


def ranges(n, seed, lo=2.0, hi=9.0):
    return np.random.default_rng(seed + 50).uniform(lo, hi, n)


def per_agent_reference(xy, grid, radii):
    """Each agent's own range-limited field from the scalar API (one agent at a time), then the smallest
    d^2 - R^2 (ties to the lower index): the definition, from independent single-source calls."""
    H, W = grid.shape
    best = np.full((H, W), np.inf)
    owner = np.full((H, W), -1)
    dist = np.full((H, W), np.inf)
    for i, (p, r) in enumerate(zip(xy, radii)):
        d = dv.coverage.geodesic_cells(p[None, :], grid, radius=r).distances
        pw = d * d - r * r
        better = pw < best
        best[better], owner[better], dist[better] = pw[better], i, d[better]
    return owner, dist


@pytest.mark.parametrize("name,seed", [("rooms", 1), ("cave", 2), ("building", 3), ("warehouse", 4),
                                       ("corridors", 0)])
def test_cells_are_the_geodesic_power_cells(name, seed):
    occ = MAPS[name](seed)
    grid = dv.OccupancyGrid(occ)
    xy = random_agents(occ, 7, seed)
    radii = ranges(7, seed)
    cells = dv.coverage.geodesic_cells(xy, grid, radius=radii)
    owner, dist = per_agent_reference(xy, grid, radii)
    # A wavefront on its window may bend at other corners than on the whole map (both are real
    # paths), so distances agree to the wavefront's accuracy and owners wherever the powers do not
    # nearly tie.
    same = cells.labels == owner
    assert same.mean() > 0.995, same.mean()
    reached = owner >= 0
    assert np.array_equal(cells.labels >= 0, reached)
    np.testing.assert_allclose(cells.distances[same & reached], dist[same & reached], rtol=0.02, atol=1e-9)
    assert np.array_equal(cells.radii, radii) and cells.radius == radii.max()
    # cost: Σ over covered pixels of d^2 + R̄^2 - R_owner^2, R̄^2 over reachable uncovered ones
    reach = dv.coverage.geodesic_cells(xy, grid).labels >= 0
    lab = cells.labels
    want = np.sum(np.where(lab >= 0, cells.distances ** 2 + radii.max() ** 2 - radii[np.maximum(lab, 0)] ** 2,
                           0.0)) + radii.max() ** 2 * np.count_nonzero(reach & (lab < 0))
    assert cells.cost == pytest.approx(want, rel=1e-12)


def test_an_agent_can_lose_its_own_pixel():
    occ = np.zeros((20, 40), bool)
    grid = dv.OccupancyGrid(occ)
    xy = np.array([[10.5, 10.5], [14.9, 10.5]])  # radical axis 5.2 px right of agent 0, disk 1 reaches 7.4
    cells = dv.coverage.geodesic_cells(xy, grid, radius=[6.0, 3.0])
    px = pixel_of(grid, xy)
    assert cells.labels[px[1, 0], px[1, 1]] == 0   # the big range's power wins at the small agent
    assert cells.areas[1] > 0                      # which keeps a crescent beyond the radical axis
    cols = np.argwhere(cells.labels == 1)[:, 1]
    assert cols.min() > 14                         # all of it on the far side of its agent


@pytest.mark.parametrize("name,seed", [("rooms", 6), ("building", 7)])
def test_equal_ranges_are_the_scalar_call(name, seed):
    occ = MAPS[name](seed)
    xy = random_agents(occ, 6, seed)
    a = dv.coverage.geodesic_cells(xy, occ, radius=4.0)
    b = dv.coverage.geodesic_cells(xy, occ, radius=np.full(6, 4.0))
    assert np.array_equal(a.labels, b.labels) and np.array_equal(a.distances, b.distances) and a.cost == b.cost
    ra = dv.coverage.lloyd(xy, 4.0, steps=5, environment=occ)
    rb = dv.coverage.lloyd(xy, [4.0] * 6, steps=5, environment=occ)
    assert np.array_equal(ra.trajectory, rb.trajectory) and np.array_equal(ra.cost, rb.cost)


def test_workers_do_not_change_the_result():
    occ = om.building(48, seed=2)
    xy = random_agents(occ, 9, 2)
    radii = ranges(9, 2, 3.0, 12.0)
    one = dv.coverage.lloyd(xy, radii, steps=6, environment=occ, workers=1)
    two = dv.coverage.lloyd(xy, radii, steps=6, environment=occ, workers=2)
    assert np.array_equal(one.trajectory, two.trajectory) and np.array_equal(one.cost, two.cost)
    assert np.array_equal(one.labels, two.labels)


@pytest.mark.parametrize("name,seed", [("building", 3), ("cave", 4), ("rooms", 5), ("warehouse", 8)])
def test_lloyd_cost_never_increases_and_agents_stay_free(name, seed):
    occ = MAPS[name](seed)
    xy = random_agents(occ, 6, seed)
    radii = ranges(6, seed, 2.0, 10.0)
    phi = np.where(occ, 0.0, 1.0 + np.linspace(0, 2, occ.shape[1])[None, :])
    stepper = dv.coverage.LloydStepper(xy, radii, density=phi, gain=0.8, environment=occ)
    costs = [stepper.step() for _ in range(12)] + [stepper.cost()]
    assert np.all(np.diff(costs) <= 0) and costs[-1] < costs[0]
    px = pixel_of(stepper.grid, stepper.points)
    assert not occ[px[:, 0], px[:, 1]].any()
    assert stepper.cells().cost == pytest.approx(costs[-1], rel=1e-12)


def test_mixed_team_spreads_through_a_door_and_saves_its_ranges(tmp_path):
    occ = two_rooms()
    xy = np.array([[3.5 + k, 5.5 + 2 * k] for k in range(6)])
    radii = np.array([14.0, 3.0, 3.0, 6.0, 3.0, 9.0])
    run = dv.coverage.lloyd(xy, radii, steps=30, environment=occ)
    assert np.all(np.diff(run.cost) <= 0) and run.cost[-1] < 0.9 * run.cost[0]
    first = dv.coverage.geodesic_cells(run.trajectory[0], occ, radius=radii)
    assert np.count_nonzero(run.labels >= 0) > 1.3 * np.count_nonzero(first.labels >= 0)  # less overlap
    for t in (0, 15, 30):
        assert run.cost[t] == pytest.approx(
            dv.coverage.geodesic_cells(run.trajectory[t], occ, radius=radii).cost, rel=1e-12)
    doc = json.loads(run.to_json())
    assert doc["radii"] == radii.tolist() and doc["radius"] == 14.0
    assert "radii=3..14" in repr(run)
    run.plot()


def test_bad_ranges_are_named():
    occ = two_rooms()
    xy = np.array([[3.5, 5.5], [6.5, 9.5]])
    for bad in ([1.0], [1.0, -2.0], [1.0, float("inf")]):
        with pytest.raises(ValueError, match="radius"):
            dv.coverage.geodesic_cells(xy, occ, radius=bad)


def test_cli_lloyd_map_with_a_radius_column_equals_python(tmp_path):
    run, occ, path, xy = cli_floor(tmp_path)
    radii = ranges(5, 5)
    pts = tmp_path / "team.txt"
    pts.write_text("".join(f"{x!r} {y!r} {r!r}\n" for (x, y), r in zip(xy.tolist(), radii.tolist())))
    res = run("lloyd", pts, "--columns", "0,1,2", "--steps", 5, "--map", path, "--trajectory", "-q", "-t", 1)
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    py = dv.coverage.lloyd(xy, radii, steps=5, environment=dv.OccupancyGrid(occ), workers=1)
    assert doc["cost"] == py.cost.tolist()
    assert np.array_equal(np.array(doc["trajectory"]), py.trajectory)
    assert doc["radii"] == radii.tolist()
