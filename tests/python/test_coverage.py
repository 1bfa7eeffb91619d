"""dv.coverage: clipped-cell moments against an independent adaptive integration (polar quad from each
agent, with the cell's extent along every ray from the bisector, disk and wall constraints -- no use of
the library's pieces), density quadrature accuracy, the cost H against a brute-force raster, Lloyd's
monotone cost, agents staying in the environment, the user-driven loop, pictures and bad input."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import _core
from dvoronoi.coverage import GridDensity, as_bounds

spatial = pytest.importorskip("scipy.spatial")


# ------------------------------------------------------------------ independent reference integrals
# Along the ray from agent i in direction theta, the clipped cell extends to
#     rho(theta) = min(R, min_j |a_j|^2 / (2 u.a_j) over u.a_j > 0, min_k h_k / (n_k.u) over n_k.u > 0)
# (bisectors, the disk, the environment's walls): the definition, nothing from the library. rho is
# analytic between the angles where two constraints tie (pairwise line intersections, line-circle
# intersections), and each smooth piece is integrated by adaptive composite Gauss-Legendre in the angle
# (and Gauss-Legendre in the radius for a density).
def _constraints(points, i, radius, bounds):
    p = points[i]
    a = np.delete(points - p, i, axis=0)
    dirs = [a]                      # ray hits bisector j where u.a_j = |a_j|^2 / (2 rho)
    offs = [(a ** 2).sum(axis=1) / 2]
    if bounds is not None:
        v = np.asarray(bounds, dtype=float)
        if np.sum(v[:, 0] * np.roll(v[:, 1], -1) - np.roll(v[:, 0], -1) * v[:, 1]) < 0:
            v = v[::-1]
        e = np.roll(v, -1, axis=0) - v
        n = np.column_stack([e[:, 1], -e[:, 0]]) / np.hypot(e[:, 0], e[:, 1])[:, None]
        dirs.append(n)
        offs.append(np.einsum("ij,ij->i", n, v - p))
    D, h = np.vstack(dirs), np.concatenate(offs)
    keep = h / np.hypot(D[:, 0], D[:, 1]) < radius  # a line at distance >= R misses the disk
    return D[keep], h[keep]


def _rho(theta, D, h, radius):
    u = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
    du = u @ D.T
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(du > 0, h / du, np.inf)
    t = np.concatenate([t, np.full(t.shape[:-1] + (1,), radius)], axis=-1)
    return t.min(axis=-1), t.argmin(axis=-1)


def reference_moments(points, i, radius, bounds, density=None):
    """(mass, centroid, polar) of agent i's clipped cell, integrated independently (see above)."""
    D, h = _constraints(points, i, radius, bounds)
    # Every angle where two constraints can tie: pairwise line intersections and line-circle ones.
    cand = []
    for k in range(len(D)):
        n2 = D[k] @ D[k]
        foot, d = h[k] * D[k] / n2, abs(h[k]) / math.sqrt(n2)
        if d < radius:
            perp = np.array([-D[k][1], D[k][0]]) / math.sqrt(n2)
            t = math.sqrt(radius * radius - d * d)
            cand += [foot + t * perp, foot - t * perp]
        for l in range(k + 1, len(D)):
            det = D[k][0] * D[l][1] - D[k][1] * D[l][0]
            if det != 0:
                cand.append(np.linalg.solve(np.array([D[k], D[l]]), np.array([h[k], h[l]])))
    ang = sorted(math.atan2(y, x) for x, y in cand)
    breaks = [-math.pi] + ang + [math.pi]
    xg, wg = np.polynomial.legendre.leggauss(24)
    p = points[i]

    def integrands(T):
        """[mass, first x, first y, polar] densities over the angles T (integrated in the radius)."""
        rho, _ = _rho(T, D, h, radius)
        c, s = np.cos(T), np.sin(T)
        if density is None:
            return np.stack([rho ** 2 / 2, rho ** 3 / 3 * c, rho ** 3 / 3 * s, rho ** 4 / 4])
        xr, wr = np.polynomial.legendre.leggauss(40)
        r = rho[:, None] * (xr + 1) / 2
        w = rho[:, None] / 2 * wr * r * density(p[0] + r * c[:, None], p[1] + r * s[:, None])
        return np.stack([w.sum(1), (w * r * c[:, None]).sum(1), (w * r * s[:, None]).sum(1),
                         (w * r * r).sum(1)])

    def gauss(a, b):
        return integrands((a + b) / 2 + (b - a) / 2 * xg) @ wg * (b - a) / 2

    def adaptive(a, b, whole, depth=0):
        """Composite Gauss-Legendre, halving until the halves agree with the whole (to 1e-15 of
        the cell's scale R^2, R^3, R^4 per radian)."""
        m = (a + b) / 2
        left, right = gauss(a, m), gauss(m, b)
        if depth >= 30 or np.all(np.abs(left + right - whole) <= tol * (b - a)):
            return left + right
        return adaptive(a, m, left, depth + 1) + adaptive(m, b, right, depth + 1)

    tol = 1e-15 * np.array([radius ** 2, radius ** 3, radius ** 3, radius ** 4])
    if density is not None:
        tol = tol * max(1e-300, float(np.max(np.abs(integrands(np.linspace(-3, 3, 7))[0]))) / radius ** 2)
    total = np.zeros(4)
    for a, b in zip(breaks[:-1], breaks[1:]):
        if b > a:
            total += adaptive(a, b, gauss(a, b))
    mass, fx, fy, polar = total
    return mass, p + np.array([fx, fy]) / mass, polar


def swarm(seed, n, side=1.0, offset=(0.0, 0.0)):
    rng = np.random.default_rng(seed)
    return rng.uniform(0, side, (n, 2)) + np.asarray(offset)


HEXAGON = np.array([[math.cos(a), math.sin(a)] for a in np.linspace(0, 2 * math.pi, 7)[:-1]]) * 0.6 + 0.5


# ------------------------------------------------------------------ uniform density
@pytest.mark.parametrize("seed,bounds,offset", [
    (1, (0, 0, 1, 1), (0, 0)),
    (2, HEXAGON, (0, 0)),
    (3, None, (0, 0)),
    (4, (1e6, -3e5, 1e6 + 1, -3e5 + 1), (1e6, -3e5)),  # far from the origin
])
def test_uniform_moments_equal_independent_integration(seed, bounds, offset):
    pts = swarm(seed, 60, offset=offset)
    b = as_bounds(bounds)
    if b is not None:
        pts = pts[_core.bounds_contains(b, pts)]
    R = 0.12
    s = dv.coverage.LloydStepper(pts, R, bounds=bounds)
    mass, cen, polar = s.moments()
    cells = s.cells()
    assert np.array_equal(cells.areas, mass)
    # Piece endpoints are rounded in the caller's frame: relative error ~ eps |p| / R far from 0.
    tol = 1e-10 + 16 * np.finfo(float).eps * float(np.max(np.abs(pts))) / R
    walls = arcs = 0
    for i in range(len(pts)):
        m, c, j = reference_moments(pts, i, R, b)
        assert mass[i] == pytest.approx(m, rel=tol)
        assert np.hypot(*(cen[i] - c)) < tol * R
        assert polar[i] == pytest.approx(j, rel=tol)
        kinds = cells.piece_neighbor[cells.piece_ptr[i]:cells.piece_ptr[i + 1]]
        walls += np.sum(kinds == -2)
        arcs += np.sum(kinds == -1)
    assert arcs > 0 and (b is None or walls > 0)  # the cases really exercise arcs and walls


def test_unclipped_cells_are_limited_cells():
    pts = swarm(5, 400, side=3.0)
    s = dv.coverage.LloydStepper(pts, 0.2)
    part = dv.limited_cells(pts, 0.2)
    cells = s.cells()
    assert np.array_equal(cells.indptr, part.indptr) and np.array_equal(cells.indices, part.indices)
    np.testing.assert_allclose(cells.areas, part.areas, rtol=1e-12)
    np.testing.assert_allclose(cells.centroids, part.centroids, rtol=0, atol=1e-12)


def test_cost_equals_brute_force_raster():
    """H = ∫_Q min(min_i |q - p_i|^2, R^2) dq, on a 1200 x 1200 midpoint raster (error ~ 1e-6)."""
    pts = swarm(6, 40)
    R = 0.15
    s = dv.coverage.LloydStepper(pts, R, bounds=(0, 0, 1, 1))
    k = 1200
    g = (np.arange(k) + 0.5) / k
    X, Y = np.meshgrid(g, g)
    d, _ = spatial.cKDTree(pts).query(np.column_stack([X.ravel(), Y.ravel()]))
    raster = float(np.mean(np.minimum(d * d, R * R)))
    assert s.cost() == pytest.approx(raster, rel=2e-5)
    # Without bounds: the sum over cells of ∫ (|q-p|^2 - R^2), i.e. H - R^2 |Q| on a Q holding all disks.
    free = dv.coverage.LloydStepper(pts, R)
    k2 = 1600
    g2 = -R + (np.arange(k2) + 0.5) / k2 * (1 + 2 * R)
    X, Y = np.meshgrid(g2, g2)
    d, _ = spatial.cKDTree(pts).query(np.column_stack([X.ravel(), Y.ravel()]))
    raster2 = float(np.mean(np.minimum(d * d, R * R) - R * R)) * (1 + 2 * R) ** 2
    assert free.cost() == pytest.approx(raster2, rel=1e-4)


# ------------------------------------------------------------------ the cost at any radius
# H = Σ_i ∫_{V_i ∩ Q} min(|q - p_i|^2, R^2) dq by the definition, nothing from the library: each
# Voronoi cell cut to Q by every bisector in exact rational arithmetic, then per fan triangle from the
# agent a closed form evaluated with 60 digits. Along the triangle's far side (distance h from the
# agent, angle phi from its foot) the ray reaches rho = h / cos(phi), and ∫_0^rho min(r^2, R^2) r dr
# is rho^4 / 4 inside the disk (|phi| <= acos(h / R)), R^4 / 4 + R^2 (rho^2 - R^2) / 2 beyond it.
def exact_voronoi_cells(points, polygon):
    from fractions import Fraction

    P = [(Fraction(float(x)), Fraction(float(y))) for x, y in points]
    Q = [(Fraction(float(x)), Fraction(float(y))) for x, y in polygon]
    cells = []
    for i, (px, py) in enumerate(P):
        poly = Q
        for j, (qx, qy) in enumerate(P):
            if j == i or not poly:
                continue
            ax, ay = qx - px, qy - py
            h = (ax * ax + ay * ay) / 2
            f = [(x - px) * ax + (y - py) * ay - h for x, y in poly]
            out = []
            for k in range(len(poly)):
                u, v, fu, fv = poly[k], poly[(k + 1) % len(poly)], f[k], f[(k + 1) % len(poly)]
                if fu <= 0:
                    out.append(u)
                if fu * fv < 0:
                    t = fu / (fu - fv)
                    out.append((u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1])))
            poly = out
        cells.append(poly)
    return cells


def exact_cost(points, cells, radius):
    import mpmath

    with mpmath.workdps(60):
        R = mpmath.mpf(float(radius))
        total = mpmath.mpf(0)
        for (px, py), poly in zip(points, cells):
            rel = [(mpmath.mpf(x.numerator) / x.denominator - mpmath.mpf(float(px)),
                    mpmath.mpf(y.numerator) / y.denominator - mpmath.mpf(float(py))) for x, y in poly]
            for k in range(len(rel)):
                (ux, uy), (vx, vy) = rel[k], rel[(k + 1) % len(rel)]
                dx, dy = vx - ux, vy - uy
                cross = ux * vy - uy * vx
                if cross == 0:
                    continue
                length = mpmath.sqrt(dx * dx + dy * dy)
                nx, ny = dy / length, -dx / length          # outward normal of the far side
                h = cross / length
                phis = [mpmath.atan2(nx * y - ny * x, nx * x + ny * y) for x, y in ((ux, uy), (vx, vy))]
                star = mpmath.acos(h / R) if h < R else mpmath.mpf(0)
                cuts = sorted({phis[0], phis[1]} | {c for c in (-star, star) if phis[0] < c < phis[1]})
                for a, b in zip(cuts[:-1], cuts[1:]):
                    if h < R and abs((a + b) / 2) <= star:  # inside the disk
                        F = lambda t: h ** 4 / 4 * (mpmath.tan(t) + mpmath.tan(t) ** 3 / 3)  # noqa: E731
                    else:
                        F = lambda t: -R ** 4 * t / 4 + R * R * h * h * mpmath.tan(t) / 2  # noqa: E731
                    total += F(b) - F(a)
        return float(total)


@pytest.mark.parametrize("bounds", [(0, 0, 1, 1), "hexagon"])
def test_cost_equals_exact_computation_at_every_radius(bounds):
    # Issue 20: H was formed as R^2 Φ(Q) + Σ (J_i - R^2 M_i), two terms that cancel: -5.28 for a true
    # 0.0129 at R = 1e6 in the unit square. And the cells' vertices came from arcs R away: 1e-7 relative
    # error in every moment at R = 1e9.
    b = as_bounds(HEXAGON if isinstance(bounds, str) else bounds)
    pts = swarm(30, 40)
    pts = pts[_core.bounds_contains(b, pts)][:30]
    cells = exact_voronoi_cells(pts, b)
    for R in (1e-3, 1e-2, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0, 10.0, 1e3, 1e5, 1e6, 1e9):
        want = exact_cost(pts, cells, R)
        s = dv.coverage.LloydStepper(pts, R, bounds=b)
        assert s.cost() == pytest.approx(want, rel=1e-13), R
        # The density path (a constant density: quadrature exact) sums the same way.
        flat = dv.coverage.LloydStepper(pts, R, bounds=b, density=lambda x, y: np.ones_like(x), order=3)
        assert flat.cost() == pytest.approx(want, rel=1e-12), R
    # Once the disks cover Q the cells are the Voronoi cells cut to Q, whatever R: the same moments.
    far = dv.coverage.LloydStepper(pts, 1e12, bounds=b).moments()
    near = dv.coverage.LloydStepper(pts, 2.0, bounds=b).moments()
    for x, y in zip(far, near):
        np.testing.assert_allclose(x, y, rtol=1e-13, atol=1e-15)


@pytest.mark.parametrize("radius", [1e5, 1e6])
def test_lloyd_cost_never_increases_for_a_large_radius(radius):
    # Issue 20: at R = 1e5 the cost rose between steps (rounding of R^2 Φ(Q) - Σ R^2 M_i).
    pts = swarm(31, 30)
    run = dv.coverage.lloyd(pts, radius, steps=30, bounds=(0, 0, 1, 1), progress=False)
    assert np.all(np.diff(run.cost) <= 0.0), np.diff(run.cost)
    assert 0 < run.cost[-1] < run.cost[0] < 0.05
    same = dv.coverage.lloyd(pts, 10.0, steps=30, bounds=(0, 0, 1, 1), progress=False)
    np.testing.assert_allclose(run.cost, same.cost, rtol=1e-12)


# ------------------------------------------------------------------ non-uniform density
def gaussian(x, y):
    return np.exp(-((x - 0.3) ** 2 + (y - 0.6) ** 2) / (2 * 0.08 ** 2)) + 0.1


def polynomial(x, y):  # degree 6 <= 2 * 6 - 2: integrated exactly at order 6
    return 1 + x + 2 * y ** 2 + 3 * (x * y) ** 3


# The stated accuracy: a Gaussian of width sigma = R/2 to 1e-9 at the default order 8 and 1e-12 at
# order 10; a polynomial of degree 6 to rounding at order 6.
@pytest.mark.parametrize("density,order,rel", [(gaussian, 8, 1e-9), (gaussian, 10, 1e-12),
                                               (polynomial, 6, 1e-12)])
def test_density_moments_equal_independent_integration(density, order, rel):
    pts = swarm(7, 30)
    R = 0.16
    s = dv.coverage.LloydStepper(pts, R, density=density, bounds=(0, 0, 1, 1), order=order)
    mass, cen, polar = s.moments()
    for i in range(len(pts)):
        m, c, j = reference_moments(pts, i, R, as_bounds((0, 0, 1, 1)), density=density)
        assert mass[i] == pytest.approx(m, rel=rel)
        assert np.hypot(*(cen[i] - c)) < rel * 10 * R
        assert polar[i] == pytest.approx(j, rel=rel * 10)


def test_density_quadrature_converges_with_order():
    pts = swarm(8, 25)
    sharp = lambda x, y: np.exp(-((x - 0.5) ** 2 + (y - 0.5) ** 2) / (2 * 0.03 ** 2))  # noqa: E731
    errs = []
    ref = None
    for order in (3, 6, 12, 24):
        m, _, _ = dv.coverage.LloydStepper(pts, 0.2, density=sharp, bounds=(0, 0, 1, 1), order=order).moments()
        if order == 24:
            ref = m
        errs.append(m)
    e = [float(np.max(np.abs(x - ref))) for x in errs[:-1]]
    assert e[0] > e[1] > e[2]
    assert e[2] < 1e-6 * float(np.max(ref))


def test_grid_density_is_bilinear_and_reproduces_linear_densities():
    lin = lambda x, y: 4.0 + 3.0 * x - 1.5 * y  # noqa: E731
    xs, ys = np.linspace(-0.5, 1.5, 7), np.linspace(-0.5, 1.5, 9)
    grid = GridDensity(lin(*np.meshgrid(xs, ys)), (-0.5, 1.5), (-0.5, 1.5))
    q = np.random.default_rng(1).uniform(-0.5, 1.5, (1000, 2))
    np.testing.assert_allclose(grid(q[:, 0], q[:, 1]), lin(q[:, 0], q[:, 1]), rtol=1e-13)
    assert grid(np.array([2.0]), np.array([0.0]))[0] == 0.0  # outside
    pts = swarm(9, 50)
    a = dv.coverage.LloydStepper(pts, 0.1, density=grid, bounds=(0, 0, 1, 1)).moments()
    b = dv.coverage.LloydStepper(pts, 0.1, density=lin, bounds=(0, 0, 1, 1)).moments()
    # Linear density: mass = ∫ lin = area * lin(centroid) exactly.
    area, cen, _ = dv.coverage.LloydStepper(pts, 0.1, bounds=(0, 0, 1, 1)).moments()
    np.testing.assert_allclose(a[0], area * lin(cen[:, 0], cen[:, 1]), rtol=1e-12)
    for x, y in zip(a, b):
        np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-15)


def test_scalar_only_density_is_called_per_node():
    pts = swarm(10, 20)
    vec = dv.coverage.LloydStepper(pts, 0.2, density=lambda x, y: np.exp(-x), bounds=(0, 0, 1, 1)).moments()
    sca = dv.coverage.LloydStepper(pts, 0.2, density=lambda x, y: math.exp(-x), bounds=(0, 0, 1, 1)).moments()
    for x, y in zip(vec, sca):
        np.testing.assert_allclose(x, y, rtol=1e-13)


# ------------------------------------------------------------------ Lloyd
@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("gain", [1.0, 0.4])
@pytest.mark.parametrize("bounds", [(0, 0, 1, 1), "hexagon", None])
def test_lloyd_cost_never_increases_and_agents_stay_inside(seed, gain, bounds):
    b = HEXAGON if isinstance(bounds, str) else bounds
    pts = swarm(seed, 80)
    if b is not None:
        pts = pts[_core.bounds_contains(as_bounds(b), pts)]
    run = dv.coverage.lloyd(pts, 0.09, steps=40, gain=gain, bounds=b, progress=False)
    scale = abs(run.cost[0])
    assert np.all(np.diff(run.cost) <= 1e-13 * scale)
    assert run.cost[-1] < run.cost[0]  # it really moved
    assert run.trajectory.shape == (41, len(pts), 2)
    if b is not None:
        for frame in run.trajectory:
            assert _core.bounds_contains(as_bounds(b), frame).all()


def test_lloyd_with_density_cost_never_increases_and_moves_towards_the_peak():
    pts = swarm(11, 60)
    run = dv.coverage.lloyd(pts, 0.1, density=gaussian, steps=25, bounds=(0, 0, 1, 1), progress=False)
    assert np.all(np.diff(run.cost) <= 1e-13 * abs(run.cost[0]))
    peak = np.array([0.3, 0.6])
    d0 = np.linalg.norm(run.trajectory[0] - peak, axis=1).mean()
    d1 = np.linalg.norm(run.trajectory[-1] - peak, axis=1).mean()
    assert d1 < d0
    assert np.all(run.masses > 0)


def test_user_loop_equals_lloyd_and_step():
    pts = swarm(12, 100)
    run = dv.coverage.lloyd(pts, 0.08, steps=10, gain=0.7, bounds=(0, 0, 1, 1), record_every=3)
    assert list(run.frame_steps) == [0, 3, 6, 9, 10]
    s = dv.coverage.LloydStepper(pts, 0.08, gain=0.7, bounds=(0, 0, 1, 1))
    frames = [s.points]
    costs = []
    for t in range(10):
        costs.append(s.step())
        frames.append(s.points)
    assert np.array_equal(np.array(costs), run.cost[:-1])
    assert np.array_equal(np.stack(frames)[[0, 3, 6, 9, 10]], run.trajectory)
    new, cost = dv.coverage.step(pts, 0.08, gain=0.7, bounds=(0, 0, 1, 1))
    assert np.array_equal(new, frames[1]) and cost == costs[0]
    # set_points: the grid follows, cells are those of a fresh stepper
    s.set_points(pts)
    assert np.array_equal(s.moments()[0], dv.coverage.LloydStepper(pts, 0.08, bounds=(0, 0, 1, 1)).moments()[0])


def test_progress_callback_sees_every_step_and_can_stop_the_run():
    seen = []
    dv.coverage.lloyd(swarm(13, 30), 0.1, steps=7, progress=lambda d, t: seen.append((d, t)))
    assert seen == [(k, 7) for k in range(1, 8)]

    def stop(done, total):
        seen.append(done)
        if done == 3:
            raise KeyboardInterrupt

    seen.clear()
    with pytest.raises(KeyboardInterrupt):
        dv.coverage.lloyd(swarm(13, 30), 0.1, steps=1000, progress=stop)
    assert seen == [1, 2, 3]


def test_result_surface_json_geojson_and_plot(tmp_path):
    run = dv.coverage.lloyd(swarm(14, 50), 0.1, steps=3, bounds=(0, 0, 1, 1))
    for i in range(len(run)):
        for j in run.neighbors(i):
            assert i in run.neighbors(j)
    doc = json.loads(run.to_json())
    assert doc["cost"] == run.cost.tolist() and len(doc["cells"]) == 50
    kinds = {p["kind"] for c in doc["cells"] for p in c["pieces"]}
    assert kinds == {"edge", "arc", "wall"}
    gj = json.loads(run.to_geojson(tolerance=1e-5))
    shapely = pytest.importorskip("shapely.geometry")
    for f, a, per in zip(gj["features"], run.areas, run.perimeters):
        poly = shapely.shape(f["geometry"])
        assert poly.is_valid
        assert a - 1e-5 * per <= poly.area <= a + 1e-12
    import matplotlib

    matplotlib.use("Agg")
    ax = run.plot()
    assert any(line.get_gid() == "dvoronoi-bounds" for line in ax.lines)


def test_animation_gif(tmp_path):
    run = dv.coverage.lloyd(swarm(15, 12), 0.15, steps=3, bounds=(0, 0, 1, 1))
    import matplotlib

    matplotlib.use("Agg")
    path = tmp_path / "run.gif"
    run.animate(path, fps=5)
    data = path.read_bytes()
    assert data[:6] in (b"GIF89a", b"GIF87a")
    from PIL import Image

    with Image.open(path) as im:
        assert im.n_frames == 4
    with pytest.raises(ValueError, match="gif or .mp4"):
        run.animate(tmp_path / "run.avi")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.gif"]


# ------------------------------------------------------------------ bad input
def test_bad_input_is_named():
    pts = swarm(16, 10)
    with pytest.raises(ValueError, match="gain"):
        dv.coverage.lloyd(pts, 0.1, gain=0.0)
    with pytest.raises(ValueError, match="gain"):
        dv.coverage.lloyd(pts, 0.1, gain=1.5)
    with pytest.raises(TypeError, match="gain"):
        dv.coverage.lloyd(pts, 0.1, gain="1")
    with pytest.raises(ValueError, match="steps"):
        dv.coverage.lloyd(pts, 0.1, steps=-1)
    with pytest.raises(ValueError, match="radius"):
        dv.coverage.lloyd(pts, -0.1)
    with pytest.raises(ValueError, match="convex"):
        dv.coverage.lloyd(pts, 0.1, bounds=[(0, 0), (1, 0), (0.5, 0.2), (1, 1), (0, 1)])
    with pytest.raises(ValueError, match="bounds"):
        dv.coverage.lloyd(pts, 0.1, bounds=(1, 0, 0, 1))
    outside = pts.copy()
    outside[4] = (2.0, 0.5)
    with pytest.raises(ValueError, match=r"points\[4\] lies outside bounds"):
        dv.coverage.lloyd(outside, 0.1, bounds=(0, 0, 1, 1))
    nan = pts.copy()
    nan[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"points\[3, 1\]"):
        dv.coverage.lloyd(nan, 0.1)
    dup = pts.copy()
    dup[7] = dup[2]
    with pytest.raises(dv.CoincidentError, match=r"points\[2\] and points\[7\]"):
        dv.coverage.lloyd(dup, 0.1, steps=1)
    with pytest.raises(TypeError, match="density"):
        dv.coverage.lloyd(pts, 0.1, density=3.0)
    with pytest.raises(ValueError, match="density must be finite and >= 0"):
        dv.coverage.lloyd(pts, 0.1, density=lambda x, y: x - 0.5, bounds=(0, 0, 1, 1))
    with pytest.raises(ValueError, match="order"):
        dv.coverage.lloyd(pts, 0.1, order=0)
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        dv.coverage.lloyd(np.zeros((3, 3)), 0.1)
    with pytest.raises(ValueError, match="values"):
        GridDensity(np.array([[1.0, -1.0], [1.0, 1.0]]), (0, 1), (0, 1))


def test_empty_and_single_agent():
    run = dv.coverage.lloyd(np.empty((0, 2)), 0.1, steps=3, bounds=(0, 0, 1, 1))
    assert run.trajectory.shape == (4, 0, 2)
    assert np.allclose(run.cost, 0.01)  # nothing covered: R^2 |Q|
    one = dv.coverage.lloyd([[0.05, 0.5]], 0.1, steps=30, bounds=(0, 0, 1, 1))
    # A lone agent at a wall moves inward, never past x = R where its disk becomes whole.
    xs = one.trajectory[:, 0, 0]
    assert np.all(np.diff(xs) > 0) and 0.099 < xs[-1] <= 0.1
    assert np.all(one.trajectory[:, 0, 1] == 0.5)
    assert math.pi * 0.01 * (1 - 1e-3) < one.areas[0] < math.pi * 0.01


def test_bounds_forms_agree():
    shapely = pytest.importorskip("shapely.geometry")
    pts = swarm(17, 40)
    ref = dv.coverage.LloydStepper(pts, 0.1, bounds=(0, 0, 1, 1)).moments()
    for b in ([(0, 0), (0, 1), (1, 1), (1, 0)],            # clockwise
              [(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)],    # closed ring
              shapely.box(0, 0, 1, 1)):
        got = dv.coverage.LloydStepper(pts, 0.1, bounds=b).moments()
        for x, y in zip(got, ref):
            np.testing.assert_allclose(x, y, rtol=1e-14, atol=1e-17)


def test_degenerate_clips_lattice_corner_edge():
    # Walls along the bisectors' lines: every cell of a unit lattice is its unit square.
    g = np.array([(i + 0.5, j + 0.5) for i in range(4) for j in range(3)], dtype=float)
    s = dv.coverage.LloydStepper(g, 0.75, bounds=(0, 0, 4, 3))
    mass, cen, polar = s.moments()
    np.testing.assert_allclose(mass, 1.0, rtol=1e-14)
    np.testing.assert_allclose(cen, g, rtol=0, atol=1e-14)
    np.testing.assert_allclose(polar, 1 / 6, rtol=1e-13)
    assert s.cost() == pytest.approx(2.0, rel=1e-13)  # everything covered: H = Σ polar
    s.step()
    assert np.max(np.abs(s.points - g)) < 1e-14  # a centroidal configuration stays put
    # R = 1/2: the walls and the bisectors are tangent to the disks: full disks, no walls.
    c = dv.coverage.LloydStepper(g, 0.5, bounds=(0, 0, 4, 3)).cells()
    np.testing.assert_allclose(c.areas, math.pi / 4, rtol=1e-14)
    assert set(c.piece_neighbor.tolist()) == {-1} and len(c.indices) == 0
    # An agent in a corner has a quarter disk, one on an edge a half disk.
    R = 0.3
    q = dv.coverage.LloydStepper([[0.0, 0.0], [0.5, 1.0]], R, bounds=(0, 0, 1, 1)).cells()
    assert q.areas[0] == pytest.approx(math.pi * R * R / 4, rel=1e-14)
    np.testing.assert_allclose(q.centroids[0], [4 * R / (3 * math.pi)] * 2, rtol=1e-13)
    assert q.areas[1] == pytest.approx(math.pi * R * R / 2, rel=1e-14)
    np.testing.assert_allclose(q.centroids[1], [0.5, 1 - 4 * R / (3 * math.pi)], rtol=1e-13)


@pytest.mark.parametrize("bounds", [(0, 0, 1, 1), "hexagon"])
def test_agents_on_the_boundary_equal_independent_integration(bounds):
    """Agents exactly on walls and at corners (cuts through the agent and through arc endpoints)."""
    b = as_bounds(HEXAGON if isinstance(bounds, str) else bounds)
    rng = np.random.default_rng(21)
    on_walls = []
    for k in range(len(b)):
        a, c = b[k], b[(k + 1) % len(b)]
        on_walls.append(a)  # the corner
        for t in rng.uniform(0.1, 0.9, 3):
            on_walls.append(a + t * (c - a))
    pts = np.vstack([np.array(on_walls), swarm(22, 25)])
    pts = pts[_core.bounds_contains(b, pts)]  # rounding may put a wall point a hair outside
    assert len(pts) >= 4 * len(b)
    R = 0.15
    mass, cen, polar = dv.coverage.LloydStepper(pts, R, bounds=b).moments()
    for i in range(len(pts)):
        m, c, j = reference_moments(pts, i, R, b)
        assert mass[i] == pytest.approx(m, rel=1e-10, abs=1e-15)
        if m > 0:
            assert np.hypot(*(cen[i] - c)) < 1e-10 * R
        assert polar[i] == pytest.approx(j, rel=1e-10, abs=1e-17)
    run = dv.coverage.lloyd(pts, R, steps=15, bounds=b)
    assert np.all(np.diff(run.cost) <= 1e-13 * run.cost[0])
    assert all(_core.bounds_contains(b, f).all() for f in run.trajectory)
