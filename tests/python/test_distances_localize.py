"""Elwin, Freeman & Lynch's second communication round: each robot fits the rigid motion (rotation,
translation, flip) from each Voronoi neighbour's local frame to its own, and the team is placed in
global coordinates from one robot's pose. With exact distances the placement reproduces the true
positions up to rounding (random points, lattices, points given in rotated, reflected and translated
frames); transforms invert each other and carry a neighbour's coordinates onto the robot's own;
robots not connected to the anchor are NaN; with noisy distances the error is first-order in the
noise."""
from __future__ import annotations

import numpy as np
import pytest

import dvoronoi as dv
from conftest import grid_points, random_points

# Exact distances: positions agree with the truth to this fraction of the team's diameter (rounding
# accumulates along the chain of transforms; observed ~1e-13).
REL_TOL = 1e-9


def dense_distances(points: np.ndarray, radius: float = np.inf, squared: bool = False) -> np.ndarray:
    d2 = ((points[:, None, :] - points[None, :, :]) ** 2).sum(axis=2)
    out = np.where(d2 < radius * radius, d2 if squared else np.sqrt(d2), np.inf)
    np.fill_diagonal(out, 0.0)
    return out


def true_pose(points: np.ndarray, res, anchor: int):
    """The anchor's true heading (direction of its first path neighbour) and flip (its path turns
    clockwise in the true frame, so its counter-clockwise local frame is mirrored)."""
    p = res.path(anchor)
    u, w = points[p[0]] - points[anchor], points[p[1]] - points[anchor]
    return float(np.arctan2(u[1], u[0])), bool(u[0] * w[1] - u[1] * w[0] < 0)


def diameter(points: np.ndarray) -> float:
    return float(np.hypot(*np.ptp(points, axis=0)))


def localize_truly(points, res, anchor=0):
    heading, flip = true_pose(points, res, anchor)
    return res.localize(anchor, points[anchor], heading, flip), flip


def local_frame_handedness(points, res, i) -> bool:
    """True when robot i's local frame (path turning counter-clockwise) is mirrored in the true one."""
    return true_pose(points, res, i)[1]


# ------------------------------------------------------------------------------------- exact input
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_localize_reproduces_random_positions(seed):
    pts = random_points(seed, 150, scale=50.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    for anchor in (0, 77):
        got, _ = localize_truly(pts, res, anchor)
        assert np.all(np.isfinite(got))
        assert np.max(np.hypot(*(got - pts).T)) <= REL_TOL * diameter(pts)


def test_localize_on_lattices_with_exact_squared_distances():
    for seed, n, side in ((3, 60, 9), (4, 120, 14)):
        pts = grid_points(seed, n, side)
        res = dv.neighbors_from_distances(dense_distances(pts, squared=True), squared=True)
        got, _ = localize_truly(pts, res, 0)
        assert np.max(np.hypot(*(got - pts).T)) <= REL_TOL * diameter(pts)
    full = np.array([(x, y) for x in range(8) for y in range(8)], float)  # every robot cocircular with 3 others
    res = dv.neighbors_from_distances(dense_distances(full, squared=True), squared=True)
    got, _ = localize_truly(full, res, 27)
    assert np.max(np.hypot(*(got - full).T)) <= REL_TOL * diameter(full)
    # There two neighbours share no neighbour (the diagonals are not Voronoi edges): only i and j are
    # common, and a measured distance between robots only one of them places decides the flip.
    ft = res.frame_transforms()
    rows = np.repeat(np.arange(len(full)), np.diff(res.indptr))
    assert ft.valid.all() and (ft.common == 2).all()
    hand = np.array([local_frame_handedness(full, res, i) for i in range(len(full))])
    assert np.array_equal(ft.flip, hand[rows] != hand[res.indices])


@pytest.mark.parametrize("mirror", [False, True])
@pytest.mark.parametrize("angle", [0.0, 0.7, np.pi / 2, 2.5])
def test_points_in_rotated_reflected_translated_frames(mirror, angle):
    base = random_points(5, 80, scale=20.0)
    c, s = np.cos(angle), np.sin(angle)
    m = np.array([[c, -s], [s, c]]) @ (np.diag([1.0, -1.0]) if mirror else np.eye(2))
    pts = base @ m.T + np.array([2.0 ** 20, -3.0 ** 9])
    res = dv.neighbors_from_distances(dense_distances(pts))
    got, flip = localize_truly(pts, res, 0)
    assert np.max(np.hypot(*(got - pts).T)) <= REL_TOL * diameter(pts)
    # The same measurements anchored in the mirrored world need the opposite flip, and give it.
    _, flip_base = localize_truly(base, dv.neighbors_from_distances(dense_distances(base)), 0)
    assert flip == (flip_base != mirror)
    # A wrong flip at the anchor mirrors the whole team about the anchor's heading line.
    heading, _ = true_pose(pts, res, 0)
    wrong = res.localize(0, pts[0], heading, not flip)
    assert np.max(np.hypot(*(wrong - pts).T)) > 0.01 * diameter(pts)


def test_reflected_team_needs_flip():
    pts = random_points(6, 100, scale=10.0)
    mirrored = pts * np.array([-1.0, 1.0])
    res = dv.neighbors_from_distances(dense_distances(pts))
    flips = [localize_truly(p, res, 0)[1] for p in (pts, mirrored)]
    assert flips[0] != flips[1]
    for p in (pts, mirrored):
        got, _ = localize_truly(p, res, 0)
        assert np.max(np.hypot(*(got - p).T)) <= REL_TOL * diameter(p)


# ------------------------------------------------------------------------------------- transforms
def test_transforms_carry_neighbour_frames_and_invert():
    pts = random_points(7, 120, scale=30.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    regions = [res.region(i) for i in range(len(pts))]
    local = [dict(zip(r.neighbors.tolist(), r.positions)) | {r.robot: np.zeros(2)} for r in regions]
    scale = diameter(pts)
    checked = 0
    for i in range(0, len(pts), 3):
        for j in res.neighbors(i).tolist():
            t = res.frame_transform(i, j)
            assert t.valid and t.robot == i and t.neighbor == j
            assert np.allclose(t.rotation.T @ t.rotation, np.eye(2), atol=1e-12)
            assert np.isclose(np.linalg.det(t.rotation), -1.0 if t.flip else 1.0)
            # The flip is exactly "the two robots' local frames have opposite handedness in truth".
            assert t.flip == (local_frame_handedness(pts, res, i) != local_frame_handedness(pts, res, j))
            # The common robots: i, j and at least one robot that neighbours both (a Delaunay triangle).
            assert {i, j} <= set(t.common.tolist()) and len(t.common) >= 3
            assert set(t.common.tolist()) <= set(local[i]) & set(local[j])
            assert t.residual <= 1e-12 * scale
            # It carries j's coordinates of every robot j places that i also places onto i's own.
            shared = sorted(set(local[i]) & set(local[j]))
            assert np.allclose(t.apply(np.array([local[j][k] for k in shared])),
                               np.array([local[i][k] for k in shared]), atol=1e-11 * scale)
            # (i, j) composed with (j, i) is the identity.
            back = res.frame_transform(j, i)
            assert np.allclose(t.rotation @ back.rotation, np.eye(2), atol=1e-12)
            assert np.allclose(t.rotation @ back.translation + t.translation, 0.0, atol=1e-11 * scale)
            checked += 1
    assert checked > 100
    all_t = res.frame_transforms()
    assert all_t.rotation.shape == (len(res.indices), 2, 2) and all_t.valid.all()
    k = int(res.indptr[5]) + 1
    one = res.frame_transform(5, int(res.indices[k]))
    assert np.array_equal(all_t.rotation[k], one.rotation) and np.array_equal(all_t.translation[k], one.translation)


def test_two_hop_places_neighbours_of_neighbours():
    pts = random_points(14, 120, scale=30.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    for i in range(0, 120, 11):
        robots, xy = res.two_hop(i)
        nb = set(res.neighbors(i).tolist())
        want = nb | {i} | {k for j in nb for k in res.neighbors(j).tolist()}
        assert robots.tolist() == sorted(want)
        # i's frame mapped to the truth with i's true pose gives the true positions.
        heading, flip = true_pose(pts, res, i)
        z = xy[:, 0] + 1j * xy[:, 1]
        g = np.exp(1j * heading) * (np.conj(z) if flip else z) + complex(*pts[i])
        assert np.max(np.abs(g - (pts[robots, 0] + 1j * pts[robots, 1]))) <= REL_TOL * diameter(pts)
        own = dict(zip(res.region(i).neighbors.tolist(), res.region(i).positions))
        at = {r: k for k, r in enumerate(robots.tolist())}
        assert all(np.allclose(xy[at[j]], own[j], rtol=0, atol=1e-12 * 30.0) for j in nb)  # i's own coordinates
        assert np.array_equal(xy[at[i]], [0.0, 0.0])


def test_local_coordinates_match_regions():
    """The second round sends exactly the coordinates region(i) reports (one convention)."""
    pts = random_points(8, 90, scale=10.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    fr = res._frames
    for i in range(0, 90, 7):
        lo, hi = fr.tab_ptr[i], fr.tab_ptr[i + 1]
        table = dict(zip(fr.tab_member[lo:hi].tolist(), fr.tab_z[lo:hi]))
        reg = res.region(i)
        assert table[i] == 0
        got = np.array([[table[k].real, table[k].imag] for k in reg.neighbors.tolist()])
        assert np.allclose(got, reg.positions, rtol=0, atol=1e-12 * 10.0)


# ------------------------------------------------------------------------------ components, errors
def test_robots_not_connected_to_the_anchor_are_nan():
    a = random_points(9, 40, scale=10.0)
    b = random_points(10, 30, scale=10.0) + np.array([100.0, 0.0])
    pts = np.vstack([a, b, [[50.0, 50.0]]])
    res = dv.neighbors_from_distances(dense_distances(pts, radius=30.0))
    got, _ = localize_truly(pts, res, 0)
    assert np.max(np.hypot(*(got[:40] - pts[:40]).T)) <= REL_TOL * diameter(a)
    assert np.isnan(got[40:]).all()
    other, _ = localize_truly(pts, res, 45)
    assert np.isnan(other[:40]).all() and np.isnan(other[70]).all()
    assert np.max(np.hypot(*(other[40:70] - pts[40:70]).T)) <= REL_TOL * diameter(b)
    alone = res.localize(70, (1.0, 2.0), 0.0)
    assert alone[70].tolist() == [1.0, 2.0] and np.isnan(alone[:70]).all()


def test_bad_arguments():
    pts = random_points(11, 30, scale=10.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    stranger = next(j for j in range(30) if j != 0 and j not in res.neighbors(0))
    with pytest.raises(ValueError, match="not Voronoi neighbours"):
        res.frame_transform(0, stranger)
    with pytest.raises(IndexError):
        res.localize(30)
    with pytest.raises(ValueError, match="position"):
        res.localize(0, (np.nan, 0.0))
    with pytest.raises(ValueError, match="heading"):
        res.localize(0, (0.0, 0.0), np.inf)


# ------------------------------------------------------------------------------------------ noise
def test_noise_error_is_first_order_in_the_noise():
    """Scaling one draw of noise by s scales the localisation error by s while the neighbour relation
    stays the exact one; the error stays within a bound proportional to the noise."""
    pts = random_points(12, 150, scale=10.0)
    d = dense_distances(pts)
    exact = dv.neighbors_from_distances(d)
    z = np.triu(np.random.default_rng(12).normal(size=d.shape), 1)
    z = z + z.T
    ratios = []
    for s in (1e-9, 1e-8, 1e-7, 1e-6):
        res = dv.neighbors_from_distances(d + s * z)
        assert np.array_equal(res.indices, exact.indices)
        got, _ = localize_truly(pts, res, 0)
        err = np.max(np.hypot(*(got - pts).T))
        assert 0 < err
        ratios.append(err / s)
        # Noisy fits have a residual, of the order of the noise.
        assert 0 < np.nanmax(res.frame_transforms().residual) < 100 * s
    ratios = np.array(ratios)
    assert ratios.max() <= 1.1 * ratios.min(), ratios           # linear: smooth, no jumps
    assert ratios.max() <= 1e3 * diameter(pts), ratios          # ... and bounded


# ----------------------------------------------------------------------------------- message counts
def test_second_round_counts():
    pts = random_points(13, 70, scale=10.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    sr = res.second_round
    deg = np.diff(res.indptr)
    assert sr.messages == len(res.indices) == sr.total_transmissions == sr.total_deliveries
    assert np.array_equal(sr.sent, deg) and np.array_equal(sr.payload, res.path_length)
    assert sr.total_payload == int(np.dot(deg, res.path_length))
    assert sr.broadcasts == 70
    # Without the consistency step the relation may be one-sided: a robot receives from those whose
    # row names it.
    noisy = dv.distances.measure(pts, radius=4.0, model="additive", sigma=0.3, seed=3)
    raw = dv.neighbors_from_distances(noisy, consistency=False)
    sr = raw.second_round
    assert sr.total_deliveries == sr.messages == len(raw.indices)
    assert np.array_equal(sr.received, np.bincount(raw.indices, minlength=70))
