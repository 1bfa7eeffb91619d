"""Coverage control of heterogeneous teams (one sensing radius per agent; Pimenta et al. 2008): equal
radii give the scalar run bit for bit; cells equal dv.limited_cells(points, radii) and an independent
raster of the power distance; the cost equals its definition, never increases under the step (many
seeds, hypothesis) and its gradient is 2 M_i (p_i - C_i) (finite differences); cells that miss their
agent keep every quadrature node inside; results save and reload their radii; the CLI's
--columns X,Y,R runs the same steps."""
from __future__ import annotations

import json
import math
import pickle

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import dvoronoi as dv
from dvoronoi import _core
from dvoronoi.coverage import as_bounds

HEXAGON = np.array([[math.cos(a), math.sin(a)] for a in np.linspace(0, 2 * math.pi, 7)[:-1]]) * 0.6 + 0.5
FIELDS = ("piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span", "indptr", "indices", "areas",
          "centroids", "perimeters")


def team(seed, n, lo=0.05, hi=0.25, bounds=(0, 0, 1, 1)):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 1, (n, 2))
    b = as_bounds(bounds)
    if b is not None:
        pts = pts[_core.bounds_contains(b, pts)]
    return pts, rng.uniform(lo, hi, len(pts))


def power_raster(pts, radii, box, m=1000):
    """(owner per midpoint, min(min_i pow_i, 0)) on an m x m midpoint raster of `box`: the definition."""
    x0, y0, x1, y1 = box
    xs = x0 + (np.arange(m) + 0.5) * (x1 - x0) / m
    ys = y0 + (np.arange(m) + 0.5) * (y1 - y0) / m
    X, Y = np.meshgrid(xs, ys)
    best = np.zeros_like(X)
    owner = np.full(X.shape, -1)
    for i, (p, r) in enumerate(zip(pts, radii)):
        pw = (X - p[0]) ** 2 + (Y - p[1]) ** 2 - r * r
        better = pw < best
        best[better] = pw[better]
        owner[better] = i
    return owner, best, (x1 - x0) * (y1 - y0) / m ** 2


# ------------------------------------------------------------------ equal radii: the scalar run itself
@pytest.mark.parametrize("bounds", [(0, 0, 1, 1), HEXAGON, None])
def test_equal_radii_are_the_scalar_run_bit_for_bit(bounds):
    pts, _ = team(1, 150, bounds=bounds)
    R = 0.11
    a = dv.coverage.lloyd(pts, R, steps=6, gain=0.7, bounds=bounds, progress=False)
    b = dv.coverage.lloyd(pts, np.full(len(pts), R), steps=6, gain=0.7, bounds=bounds, progress=False)
    assert np.array_equal(a.trajectory, b.trajectory) and np.array_equal(a.cost, b.cost)
    for k in FIELDS:
        assert np.array_equal(getattr(a, k), getattr(b, k)), k
    assert np.array_equal(b.radii, np.full(len(pts), R)) and "radii" not in json.loads(b.to_json())


def test_equal_radii_with_a_density_are_the_scalar_run():
    pts, _ = team(2, 80)
    f = lambda x, y: 1.0 + np.sin(3 * x) ** 2 * y  # noqa: E731
    a = dv.coverage.lloyd(pts, 0.15, density=f, steps=3, bounds=(0, 0, 1, 1), progress=False)
    b = dv.coverage.lloyd(pts, [0.15] * len(pts), density=f, steps=3, bounds=(0, 0, 1, 1), progress=False)
    assert np.array_equal(a.trajectory, b.trajectory) and np.array_equal(a.cost, b.cost)


# ------------------------------------------------------------------ cells and cost against their definitions
@pytest.mark.parametrize("seed", [3, 4, 5])
def test_unclipped_cells_are_the_heterogeneous_limited_cells(seed):
    pts, radii = team(seed, 300, bounds=None)
    cells = dv.coverage.LloydStepper(pts, radii).cells()
    part = dv.limited_cells(pts, radii)
    assert np.array_equal(cells.indptr, part.indptr) and np.array_equal(cells.indices, part.indices)
    assert np.array_equal(cells.piece_ptr, part.piece_ptr)
    for i in range(len(pts)):  # the same cycle of pieces (it may start at another piece)
        lo, hi = cells.piece_ptr[i], cells.piece_ptr[i + 1]
        mine, theirs = list(cells.piece_neighbor[lo:hi]), list(part.piece_neighbor[lo:hi])
        assert any(mine[k:] + mine[:k] == theirs for k in range(max(1, hi - lo))), i
    np.testing.assert_allclose(cells.areas, part.areas, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(cells.centroids, part.centroids, rtol=0, atol=1e-12)
    assert np.array_equal(cells.radii, radii)
    # The family really has agents outside their cells and empty cells.
    inside = [np.hypot(*(pts[i] - pts[j])) ** 2 - radii[j] ** 2 < -radii[i] ** 2
              for i in range(len(pts)) for j in range(len(pts)) if j != i]
    assert any(inside)


@pytest.mark.parametrize("bounds,seed", [((0, 0, 1, 1), 6), (HEXAGON, 7)])
def test_clipped_cells_and_cost_equal_a_raster_of_the_definition(bounds, seed):
    """Areas, centroids and H = ∫_Q min(min_i pow_i, 0) dq + R̄^2 |Q| against a 1000 x 1000 raster."""
    pts, radii = team(seed, 40, lo=0.05, hi=0.3, bounds=bounds)
    s = dv.coverage.LloydStepper(pts, radii, bounds=bounds)
    mass, cen, _ = s.moments()
    b = as_bounds(bounds)
    box = (b[:, 0].min(), b[:, 1].min(), b[:, 0].max(), b[:, 1].max())
    owner, best, cell = power_raster(pts, radii, box)
    X, Y = np.meshgrid(*(box[k] + (np.arange(1000) + 0.5) * (box[k + 2] - box[k]) / 1000 for k in (0, 1)))
    inq = _core.bounds_contains(b, np.column_stack([X.ravel(), Y.ravel()])).reshape(X.shape)
    h = 1e-3 * max(box[2] - box[0], box[3] - box[1])
    for i in range(len(pts)):
        sel = (owner == i) & inq
        assert abs(sel.sum() * cell - mass[i]) < 8 * h * 2 * math.pi * radii[i], i  # boundary pixels only
        if mass[i] > 0.01:
            c = np.array([X[sel].mean(), Y[sel].mean()])
            assert np.hypot(*(c - cen[i])) < 0.02 * radii[i], i
    rbar = radii.max()
    want = float(best[inq].sum() * cell) + rbar ** 2 * float(inq.sum() * cell)
    assert s.cost() == pytest.approx(want, rel=3e-3)


def test_plane_cost_is_the_power_cost():
    pts, radii = team(8, 60, bounds=None)
    s = dv.coverage.LloydStepper(pts, radii)
    mass, _, polar = s.moments()
    assert s.cost() == pytest.approx(float(np.sum(polar - radii ** 2 * mass)), rel=1e-13)
    owner, best, cell = power_raster(pts, radii, (-0.3, -0.3, 1.3, 1.3), m=1200)
    assert s.cost() == pytest.approx(float(best.sum() * cell), rel=2e-3)


@pytest.mark.parametrize("family", ["lattice", "nested", "tangent", "shared"])
def test_degenerate_families_are_the_heterogeneous_limited_cells(family):
    """Integer lattices with two radii (cocircular quadruples, radical axes through lattice points),
    small disks inside big ones, tangent disks and shared positions: the same relation and the same
    empty cells as dv.limited_cells(points, radii), which the CGAL oracle checks."""
    if family == "lattice":
        g = np.arange(8, dtype=float)
        pts = np.array([(x, y) for x in g for y in g])
        radii = np.where((pts.sum(axis=1) % 2) == 0, 1.0, 0.75)
    elif family == "nested":
        pts = np.array([[0.0, 0.0], [0.2, 0.1], [-0.3, 0.2], [1.5, 0.0], [1.6, 0.05]])
        radii = np.array([1.0, 0.3, 0.2, 0.6, 0.1])
    elif family == "tangent":
        pts = np.array([[0.0, 0.0], [1.5, 0.0], [1.5, 2.0], [0.0, 2.0]])
        radii = np.array([1.0, 0.5, 1.5, 1.0])  # 0-1 and 1-2 tangent, 0-3 tangent
    else:
        pts = np.array([[0.0, 0.0], [0.0, 0.0], [0.5, 0.0], [0.5, 0.0], [0.25, 0.3]])
        radii = np.array([0.4, 0.2, 0.1, 0.3, 0.25])
    cells = dv.coverage.LloydStepper(pts, radii).cells()
    part = dv.limited_cells(pts, radii)
    assert np.array_equal(cells.indptr, part.indptr) and np.array_equal(cells.indices, part.indices)
    assert np.array_equal(cells.areas == 0, part.empty)
    np.testing.assert_allclose(cells.areas, part.areas, rtol=1e-12, atol=1e-15)


def test_transformed_copies_give_the_same_cells():
    """Permuted, translated by a power of two, scaled by two, rotated by 90 degrees (exact in floating
    point): the same neighbours, areas and moments (permuted, moved, scaled)."""
    pts, radii = team(13, 120)
    s0 = dv.coverage.LloydStepper(pts, radii, bounds=(0, 0, 1, 1))
    m0, c0, j0 = s0.moments()
    nb0 = [set(s0.cells().neighbors(i)) for i in range(len(pts))]
    perm = np.random.default_rng(1).permutation(len(pts))
    inv = np.argsort(perm)
    copies = {
        "permuted": (pts[perm], radii[perm], (0, 0, 1, 1), perm, lambda c: c, 1.0),
        "translated": (pts + 1024.0, radii, (1024, 1024, 1025, 1025), np.arange(len(pts)), lambda c: c - 1024.0, 1.0),
        "scaled": (2.0 * pts, 2.0 * radii, (0, 0, 2, 2), np.arange(len(pts)), lambda c: c / 2.0, 2.0),
        "rotated": (np.column_stack([-pts[:, 1], pts[:, 0]]), radii, (-1, 0, 0, 1), np.arange(len(pts)),
                    lambda c: np.column_stack([c[:, 1], -c[:, 0]]), 1.0),
    }
    for name, (p, r, b, order, back, k) in copies.items():
        s = dv.coverage.LloydStepper(p, r, bounds=b)
        m, c, j = s.moments()
        cells = s.cells()
        rel = 1e-9 if name == "translated" else 1e-12  # coordinates near 1024 keep 10 fewer bits
        np.testing.assert_allclose(m / k ** 2, m0[order], rtol=rel, atol=1e-15, err_msg=name)
        np.testing.assert_allclose(j / k ** 4, j0[order], rtol=rel, atol=1e-15, err_msg=name)
        np.testing.assert_allclose(back(c), c0[order], rtol=0, atol=1e-9 if name == "translated" else 1e-12,
                                   err_msg=name)
        for t in range(len(p)):
            mapped = {int(order[q]) for q in cells.neighbors(t)} if name == "permuted" else set(cells.neighbors(t))
            assert mapped == nb0[order[t]], (name, t)
    assert len(inv) == len(perm)


def test_density_quadrature_of_clipped_team_cells_is_exact_for_linear_densities():
    """φ = 1 and φ = 1 + x - y/2 are integrated exactly by the cells' Gauss rules (also in cells that
    miss their agent), so the density path reproduces the closed-form moments."""
    pts, radii = team(14, 60, lo=0.05, hi=0.35, bounds=HEXAGON)
    s = dv.coverage.LloydStepper(pts, radii, bounds=HEXAGON)
    mass, cen, polar = s.moments()
    one = dv.coverage.LloydStepper(pts, radii, bounds=HEXAGON, density=lambda x, y: np.ones_like(x))
    m1, c1, j1 = one.moments()
    np.testing.assert_allclose(m1, mass, rtol=1e-12, atol=1e-16)
    np.testing.assert_allclose(j1, polar, rtol=1e-10, atol=1e-16)
    full = mass > 1e-6 * radii ** 2
    np.testing.assert_allclose(c1[full], cen[full], rtol=0, atol=1e-10)
    lin = dv.coverage.LloydStepper(pts, radii, bounds=HEXAGON, density=lambda x, y: 1 + x - y / 2)
    m2, _, _ = lin.moments()
    np.testing.assert_allclose(m2, mass * (1 + cen[:, 0] - cen[:, 1] / 2), rtol=1e-10, atol=1e-16)
    missing = [i for i in range(len(pts)) if mass[i] > 0 and any(
        np.sum((pts[i] - pts[j]) ** 2) - radii[j] ** 2 < -radii[i] ** 2 for j in range(len(pts)) if j != i)]
    assert missing  # the family has cells that miss their agent


# ------------------------------------------------------------------ the step
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10 ** 6), n=st.integers(2, 60), gain=st.floats(0.1, 1.0),
       spread=st.floats(1.0, 6.0), shape=st.sampled_from(["box", "hexagon", "plane"]))
def test_cost_never_increases_and_agents_stay_inside(seed, n, gain, spread, shape):
    bounds = {"box": (0, 0, 1, 1), "hexagon": HEXAGON, "plane": None}[shape]
    rng = np.random.default_rng(seed)
    pts, _ = team(seed, n, bounds=bounds)
    if len(pts) < 2:
        return
    radii = 0.04 * rng.uniform(1.0, spread, len(pts))
    run = dv.coverage.lloyd(pts, radii, steps=12, gain=gain, bounds=bounds, progress=False)
    scale = np.abs(run.cost).max()
    assert np.all(np.diff(run.cost) <= 1e-12 * scale), np.diff(run.cost).max()
    if bounds is not None:
        assert _core.bounds_contains(as_bounds(bounds), run.trajectory.reshape(-1, 2)).all()


def test_cost_never_increases_with_a_density():
    pts, radii = team(9, 70, lo=0.05, hi=0.3)
    f = lambda x, y: np.exp(-((x - 0.7) ** 2 + (y - 0.3) ** 2) / 0.05) + 0.1  # noqa: E731
    run = dv.coverage.lloyd(pts, radii, density=f, steps=10, bounds=(0, 0, 1, 1), progress=False)
    assert np.all(np.diff(run.cost) <= 1e-10 * run.cost[0])
    assert run.cost[-1] < 0.9 * run.cost[0]


@pytest.mark.parametrize("bounds", [(0, 0, 1, 1), None])
def test_gradient_is_twice_mass_times_offset(bounds):
    """∂H/∂p_i = 2 M_i (p_i - C_i), by central differences of the exact cost."""
    pts, radii = team(10, 25, lo=0.08, hi=0.3, bounds=bounds)
    s = dv.coverage.LloydStepper(pts, radii, bounds=bounds)
    mass, cen, _ = s.moments()
    grad = 2 * mass[:, None] * (pts - cen)
    h = 1e-6
    checked = 0
    for i in range(len(pts)):
        for k in range(2):
            fd = []
            for sgn in (1, -1):
                q = pts.copy()
                q[i, k] += sgn * h
                s.set_points(q)
                fd.append(s.cost())
            d = (fd[0] - fd[1]) / (2 * h)
            assert d == pytest.approx(grad[i, k], abs=1e-6 * max(1.0, mass[i])), (i, k)
            checked += abs(grad[i, k]) > 1e-3
    assert checked > 10  # the swarm is far from equilibrium: the gradients are not all zero


# ------------------------------------------------------------------ cells that miss their agent
def test_cell_that_misses_its_agent_is_integrated_inside_it():
    """p_1 lies in the big disk's power cell: W_1 = B(p_1, 0.5) ∩ {x >= 0.925}, a circular segment."""
    pts = np.array([[0.0, 0.0], [0.6, 0.0]])
    radii = np.array([1.0, 0.5])
    s = dv.coverage.LloydStepper(pts, radii)
    mass, cen, polar = s.moments()
    d = 0.925 - 0.6  # the radical axis x = 0.925, at d from p_1
    alpha = math.acos(d / 0.5)
    area = 0.25 * (2 * alpha - math.sin(2 * alpha)) / 2
    xbar = 0.6 + 4 * 0.5 * math.sin(alpha) ** 3 / (3 * (2 * alpha - math.sin(2 * alpha)))
    assert mass[1] == pytest.approx(area, rel=1e-13)
    assert cen[1] == pytest.approx([xbar, 0.0], abs=1e-13)
    x, y, w, ptr, _ = _core.coverage_quadrature(pts, 1.0, 8, None, None, -1, 0, radii)
    x1, y1, w1 = (a[ptr[1]:ptr[2]] for a in (x, y, w))
    assert np.all(w1 > 0) and math.fsum(w1) == pytest.approx(area, rel=1e-13)
    assert np.all(x1 >= 0.925 - 1e-12) and np.all(np.hypot(x1 - 0.6, y1) <= 0.5 + 1e-12)
    # A smooth density against an independent polar integration about p_1 (scipy).
    integrate = pytest.importorskip("scipy.integrate")
    f = lambda px, py: np.exp(px) * (1 + py * py)  # noqa: E731
    want = integrate.dblquad(lambda r, t: f(0.6 + r * math.cos(t), r * math.sin(t)) * r, -alpha, alpha,
                             lambda t: d / math.cos(t), lambda t: 0.5, epsabs=1e-14, epsrel=1e-13)[0]
    assert math.fsum(w1 * f(x1, y1)) == pytest.approx(want, rel=1e-10)
    # The step moves agent 1 onto its centroid, out of the big disk's cell.
    s.step()
    assert s.points[1] == pytest.approx([xbar, 0.0], abs=1e-13)


def test_same_position_smaller_disk_is_empty_and_stays():
    pts = np.array([[0.5, 0.5], [0.5, 0.5], [0.2, 0.3]])
    s = dv.coverage.LloydStepper(pts, [0.3, 0.1, 0.2], bounds=(0, 0, 1, 1))
    mass, cen, _ = s.moments()
    assert mass[1] == 0 and mass[0] > 0
    s.step()
    assert np.array_equal(s.points[1], [0.5, 0.5])
    with pytest.raises(ValueError, match=r"points\[0\] and points\[1\]"):
        dv.coverage.LloydStepper(pts, [0.3, 0.3, 0.2]).step()


# ------------------------------------------------------------------ results, files, errors
def test_results_save_and_reload_their_radii(tmp_path):
    pts, radii = team(11, 50)
    run = dv.coverage.lloyd(pts, radii, steps=3, bounds=(0, 0, 1, 1), progress=False)
    assert np.array_equal(run.radii, radii) and run.radius == radii.max()
    path = tmp_path / "run.json"
    run.to_json(path)
    back = dv.load(path)
    assert np.array_equal(back.radii, radii) and back.radius == radii.max()
    assert [c["radius"] for c in back.cells] == radii.tolist()
    again = pickle.loads(pickle.dumps(run))
    assert np.array_equal(again.radii, radii) and np.array_equal(again.cost, run.cost)
    # Arcs are densified on each agent's own circle.
    gj = json.loads(run.to_geojson(tolerance=1e-4))
    for i, feat in enumerate(gj["features"]):
        ring = np.array(feat["geometry"]["coordinates"][0]) if feat["geometry"]["coordinates"][0] else np.empty((0, 2))
        if len(ring):
            assert np.hypot(*(ring - run.points[i]).T).max() <= radii[i] * (1 + 1e-12), i
    assert "radii=" in repr(run)
    run.plot()


@pytest.mark.parametrize("radius,message", [
    ([0.1, 0.2], "radius"),
    ([0.1, -0.2, 0.3], "radius"),
    ([0.1, float("nan"), 0.3], "radius"),
    ([[0.1, 0.2, 0.3]], "radius"),
])
def test_bad_radii_are_named(radius, message):
    with pytest.raises(ValueError, match=message):
        dv.coverage.lloyd(np.array([[0.1, 0.1], [0.5, 0.5], [0.9, 0.2]]), radius, steps=1)


def test_cli_columns_xyr_runs_the_same_steps(tmp_path):
    from test_cli import CLI, run as cli

    if CLI is None:
        pytest.skip("no dvoronoi executable")
    pts, radii = team(12, 90)
    path = tmp_path / "team.csv"
    path.write_text("x,y,r\n" + "".join(f"{x!r},{y!r},{r!r}\n" for (x, y), r in zip(pts.tolist(), radii.tolist())))
    out = tmp_path / "run.json"
    r = cli("lloyd", path, "--columns", "x,y,r", "--steps", "7", "--gain", "0.9", "--bounds", "0", "0", "1", "1",
            "--svg-dir", tmp_path / "svg", "--svg-every", "7", "-o", out, "-t", "1", "-q")
    assert r.returncode == 0, r.stderr
    doc = json.loads(out.read_text())
    ref = dv.coverage.lloyd(pts, radii, steps=7, gain=0.9, bounds=(0, 0, 1, 1), workers=1, progress=False)
    assert doc["cost"] == ref.cost.tolist()
    assert np.array_equal(np.array(doc["points"]), ref.trajectory[-1])
    assert doc["radii"] == radii.tolist() and doc["radius"] == radii.max()
    assert sorted(p.name for p in (tmp_path / "svg").iterdir()) == ["step_000000.svg", "step_000007.svg"]
    both = cli("lloyd", path, "--columns", "x,y,r", "-r", "0.1", "--steps", "1")
    assert both.returncode != 0 and "--radius" in both.stderr


def test_animation_frames_draw_each_robot_with_its_own_radius():
    # The frames of animate() are recomputed from the trajectory: the last frame's cells are the
    # run's final cells (with one radius for all they would be the largest robot's disks).
    pytest.importorskip("matplotlib")
    from dvoronoi import plotting

    points, radii = team(3, 12, lo=0.08, hi=0.3)
    run = dv.coverage.lloyd(points, radii, steps=4, bounds=(0, 0, 1, 1), workers=1, progress=False)
    last = plotting.coverage_frame(run, len(run.trajectory) - 1)
    assert np.array_equal(last.radii, run.radii)
    assert np.allclose(last.areas, run.areas, rtol=0, atol=1e-12)
