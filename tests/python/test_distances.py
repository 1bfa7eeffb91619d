"""Voronoi neighbours from distances only (Elwin, Freeman & Lynch): neighbour sets and hull flags equal
the CGAL oracle's on random, lattice, cocircular and real (Intel lab) positions when the detection
radius is at least twice the longest Delaunay edge; the per-robot guarantee under a smaller radius;
Delaunay-path order; input forms; consistency under noise; noise models; distortion on hand-checked
graphs; local regions; bad input."""
from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import scipy.sparse as sp

import dvoronoi as dv
from conftest import grid_points, neighbor_sets, random_points, read_corpus


# ------------------------------------------------------------------------------------------ helpers
def dense_distances(points: np.ndarray, radius: float = np.inf, squared: bool = False) -> np.ndarray:
    diff = points[:, None, :] - points[None, :, :]
    d2 = (diff ** 2).sum(axis=2)
    out = d2 if squared else np.sqrt(d2)
    out = np.where(d2 < radius * radius, out, np.inf)
    np.fill_diagonal(out, 0.0)
    return out


def longest_delaunay_edge(points: np.ndarray, want: list) -> float:
    return max((np.hypot(*(points[i] - points[j])) for i, nb in enumerate(want) for j in nb), default=0.0)


def check_against_oracle(oracle, points, label, *, radius=None, squared=False, form="dense"):
    exact = oracle(points, 1.0)
    want = [set(nb) for nb in exact["voronoi_neighbors"]]
    want_hull = np.asarray(exact["on_hull"], dtype=bool)
    if radius is None:  # twice the longest Delaunay edge (plus a hair: detection is strict)
        radius = 2.0 * longest_delaunay_edge(points, want) * (1 + 1e-9) + 1e-300
    d = dense_distances(points, radius, squared)
    if form == "sparse":
        d = sp.csr_matrix(np.where(np.isinf(d), 0.0, d))
    elif form == "edges":
        i, j = np.nonzero(np.triu(np.isfinite(d), 1))
        d = np.column_stack([i, j, d[i, j]])
    res = dv.neighbors_from_distances(d, squared=squared, n=len(points) if form == "edges" else None)
    got = neighbor_sets(res.indptr, res.indices)
    bad = [i for i in range(len(points)) if got[i] != want[i]]
    assert not bad, f"{label}: neighbours differ at robots {bad[:10]}: {[(got[i], want[i]) for i in bad[:3]]}"
    assert np.array_equal(res.on_hull, want_hull), f"{label}: hull flags differ at {np.flatnonzero(res.on_hull != want_hull)[:10]}"
    assert res.added.sum() == 0, f"{label}: exact distances needed the consistency step"
    return res, want


def squared_distances_exact(points: np.ndarray) -> bool:
    """Every pairwise dx^2 + dy^2 is exactly a double (so squared=True inputs are exact)."""
    fr = [(Fraction(float(x)), Fraction(float(y))) for x, y in points]
    for a in range(len(fr)):
        for b in range(a + 1, len(fr)):
            dx, dy = fr[a][0] - fr[b][0], fr[a][1] - fr[b][1]
            v = dx * dx + dy * dy
            if Fraction(float(v)) != v:
                return False
    return True


# ----------------------------------------------------------------------------- exact distances
@pytest.mark.parametrize("seed", range(5))
def test_random_positions_equal_oracle(oracle, seed):
    pts = random_points(seed, 250, scale=10.0 ** (seed - 2))  # scales 1e-2 .. 1e2
    res, want = check_against_oracle(oracle, pts, f"random seed {seed}")
    # Delaunay-path order: consecutive neighbours are mutual Voronoi neighbours (cyclically inside).
    for i in range(len(pts)):
        path = res.path(i).tolist()
        pairs = list(zip(path, path[1:])) + ([] if res.on_hull[i] else [(path[-1], path[0])])
        assert all(b in want[a] for a, b in pairs), f"robot {i}: path {path} is not a Delaunay path"
        if res.on_hull[i]:
            assert len(path) >= 1
        else:
            assert len(path) >= 3


@pytest.mark.parametrize("form", ["dense", "sparse", "edges"])
def test_input_forms_and_squared(oracle, form):
    pts = random_points(7, 150)
    check_against_oracle(oracle, pts, f"random as {form}", form=form)
    check_against_oracle(oracle, pts, f"random squared as {form}", form=form, squared=True)


@pytest.mark.parametrize("seed", range(4))
def test_lattices_with_exact_squared_distances(oracle, seed):
    # Integer grids: many collinear triples and cocircular quadruples; squared distances are exact.
    pts = grid_points(seed, 90, 12)
    check_against_oracle(oracle, pts, f"grid seed {seed}", squared=True)
    full = np.array([(x, y) for x in range(9) for y in range(8)], dtype=float)
    check_against_oracle(oracle, full, "full 9x8 lattice", squared=True)
    # Transformed copies (rotation by 90 degrees, translation by a power of two, permutation).
    rot = np.column_stack([-pts[:, 1], pts[:, 0]]) + 1024.0
    check_against_oracle(oracle, rot, f"grid seed {seed} rotated+translated", squared=True)
    perm = np.random.default_rng(seed).permutation(len(pts))
    check_against_oracle(oracle, pts[perm], f"grid seed {seed} permuted", squared=True)


def test_degenerate_corpus_where_squared_distances_are_exact(oracle):
    cases = [(name, pts) for name, _r, pts in read_corpus() if len(pts) <= 60]
    checked = 0
    for name, pts in cases:
        if len(pts) < 2 or not squared_distances_exact(pts):
            continue
        check_against_oracle(oracle, pts, name, radius=np.inf, squared=True)
        checked += 1
    assert checked >= 20, f"only {checked} corpus cases have exact squared distances"


def test_intel_lab_motes(oracle):
    # The motes sit on a half-metre grid with whole rows collinear (on the hull, too): their squared
    # distances are exact, so the answer is exact. Distances rounded to double would perturb those
    # collinear rows (documented: exact zeros are not kept through a square root).
    pts = dv.datasets.intel_lab()
    assert squared_distances_exact(pts)
    check_against_oracle(oracle, pts, "intel lab", squared=True)
    check_against_oracle(oracle, pts, "intel lab, all detected", squared=True, radius=np.inf)


def test_smaller_radius_guarantee(oracle):
    """Under a smaller detection radius R, robot i's answer is still exact when R is at least twice
    the longest edge of its Delaunay star (edges i-j and j-k of the Delaunay triangles at i), and every
    answer only names detected robots."""
    pts = random_points(3, 500, scale=10.0)
    exact = oracle(pts, 1.0)
    want = [set(nb) for nb in exact["voronoi_neighbors"]]
    hull = np.asarray(exact["on_hull"], dtype=bool)
    radius = 2.0
    d = dense_distances(pts, radius)
    res = dv.neighbors_from_distances(d, consistency=False)
    covered = wrong_elsewhere = 0
    for i in range(len(pts)):
        star = [np.hypot(*(pts[i] - pts[j])) for j in want[i]]
        star += [np.hypot(*(pts[j] - pts[k])) for j in want[i] for k in want[i] if k in want[j]]
        got = set(res.neighbors(i).tolist())
        assert all(d[i, j] < np.inf for j in got), f"robot {i} names an undetected robot"
        if 2.0 * max(star) <= radius:
            covered += 1
            assert got == want[i], f"robot {i}: {got} != {want[i]}"
            assert res.on_hull[i] == hull[i]
        elif got != want[i] or res.on_hull[i] != hull[i]:
            wrong_elsewhere += 1
    assert covered > 250, covered
    assert wrong_elsewhere > 0, covered  # the radius is small enough for the guarantee to matter


# ----------------------------------------------------------------------------------------- noise
@pytest.mark.parametrize("model,sigma", [("additive", 0.03), ("multiplicative", 0.05), ("rssi", 2.0)])
def test_noisy_runs_are_symmetric_after_consistency(model, sigma):
    pts = random_points(11, 400, scale=254.0 if model == "rssi" else 5.0)
    radius = 33.0 if model == "rssi" else 1.0
    e = dv.distances.measure(pts, radius, model=model, sigma=sigma, seed=5)
    raw = dv.neighbors_from_distances(e, consistency=False)
    fixed = dv.neighbors_from_distances(e)
    m = fixed.to_csr()
    assert (m != m.T).nnz == 0
    raw_m = raw.to_csr()
    # The step only adds: every robot's own answer is kept, in path order, at the front of its row.
    for i in range(len(pts)):
        assert np.array_equal(fixed.path(i), raw.neighbors(i))
    assert fixed.added.sum() == (raw_m.T - raw_m.multiply(raw_m.T)).nnz
    if model == "rssi":  # quantised RSSI is noisy enough to break symmetry before the step
        assert (raw_m != raw_m.T).nnz > 0


def test_noise_models_are_seeded_and_shaped():
    pts = random_points(2, 300, scale=254.0)
    a = dv.distances.measure(pts, model="rssi", seed=9)
    b = dv.distances.measure(pts, model="rssi", seed=9)
    c = dv.distances.measure(pts, model="rssi", seed=10)
    assert (a != b).nnz == 0 and (a != c).nnz > 0
    # Detection: exactly the pairs closer than 33 cm.
    i, j = a.nonzero()
    assert np.all(np.hypot(*(pts[i] - pts[j]).T) < 33.0)
    full = dense_distances(pts)
    assert a.nnz == int(((full < 33.0) & (full > 0)).sum())
    # Quantised RSSI: each e_ij is the mean of two values of the fit at whole dBm.
    levels = dv.distances.rssi_to_distance(np.arange(20, 70))
    pair_means = np.add.outer(levels, levels).ravel() / 2
    assert np.all(np.min(np.abs(a.data[:, None] - pair_means[None, :]), axis=1) < 1e-9)
    # The fit's inverse is its inverse, and exact measurements are exact.
    x = np.linspace(30, 69, 40)
    assert np.allclose(dv.distances.distance_to_rssi(dv.distances.rssi_to_distance(x)), x)
    ex = dv.distances.measure(pts, 20.0, model="exact")
    i, j = ex.nonzero()
    assert np.allclose(ex.data, np.hypot(*(pts[i] - pts[j]).T), rtol=0, atol=1e-12)
    add = dv.distances.measure(pts, 20.0, model="additive", sigma=0.5, seed=1)
    assert (add != add.T).nnz == 0
    assert 0.2 < np.std(add.data - ex.data) < 0.5  # mean of two N(0, 0.5^2): std 0.35
    with pytest.raises(ValueError, match="model"):
        dv.distances.measure(pts, 20.0, model="laser")


# ------------------------------------------------------------------------------------ distortion
def test_distortion_hand_checked():
    # Triangle with unit edges vs one edge measured 0.5 (the paper's single-edge example): d/e = 2.
    tri = np.array([[0, 1, 1], [1, 0, 1], [1, 1, 0]], dtype=float)
    short = tri.copy()
    short[0, 1] = short[1, 0] = 0.5
    assert dv.distances.distortion(tri, short) == pytest.approx(2.0)
    assert dv.distances.distortion(short, tri) == pytest.approx(2.0)
    # One edge measured 1.5 too long: the shortest path goes around (length 2 > 1.5): 1.5.
    longer = tri.copy()
    longer[0, 1] = longer[1, 0] = 1.5
    assert dv.distances.distortion(tri, longer) == pytest.approx(1.5)
    # Path 0-1-2 with weights (1, 1) vs (1, 2): distances (1, 1, 2) vs (1, 2, 3): ratios 1, 2, 1.5.
    p1 = sp.csr_matrix(([1.0, 1.0, 1.0, 1.0], ([0, 1, 1, 2], [1, 0, 2, 1])), shape=(3, 3))
    p2 = sp.csr_matrix(([1.0, 1.0, 2.0, 2.0], ([0, 1, 1, 2], [1, 0, 2, 1])), shape=(3, 3))
    assert dv.distances.distortion(p1, p2) == pytest.approx(2.0)
    # Uniform scaling has distortion 1; a disconnected graph has none (inf).
    assert dv.distances.distortion(p1, 3.0 * p1) == pytest.approx(1.0)
    cut = sp.csr_matrix(([1.0, 1.0], ([0, 1], [1, 0])), shape=(3, 3))
    assert dv.distances.distortion(p1, cut) == np.inf
    with pytest.raises(ValueError, match="sizes"):
        dv.distances.distortion(p1, tri[:2, :2])


def test_distortions_of_exact_measurements_are_one():
    pts = random_points(4, 200, scale=254.0)
    e = dv.distances.measure(pts, 1e9, model="exact")  # every pair detected: every Delaunay edge
    res = dv.neighbors_from_distances(e)
    assert dv.distances.detection_distortion(pts, e) == pytest.approx(1.0)
    assert dv.distances.delaunay_distortion(pts, res) == pytest.approx(1.0)
    # One wrong measurement on a detection edge: delta_m >= its own ratio.
    e2 = e.tolil()
    i, j = 0, int(e[0].indices[0])
    e2[i, j] = e2[j, i] = e[i, j] * 1.3
    # A direct edge measured 1.3 x too long can only lengthen paths by up to 1.3 x: 1 < delta_m <= 1.3.
    dm = dv.distances.detection_distortion(pts, e2.tocsr())
    assert 1.0 < dm <= 1.3 + 1e-12


# ----------------------------------------------------------------------------------- local region
def test_local_regions_match_true_cells():
    pts = random_points(6, 120, scale=10.0)
    res = dv.neighbors_from_distances(dense_distances(pts))
    checked = 0
    for i in range(0, len(pts), 5):
        reg = res.region(i)
        assert np.array_equal(reg.neighbors, res.path(i))
        assert np.allclose(np.hypot(*reg.positions.T), np.hypot(*(pts[reg.neighbors] - pts[i]).T))
        if not reg.bounded:
            assert res.on_hull[i] and reg.area == np.inf
            continue
        others = np.delete(pts, i, axis=0)
        cell = dv.voronoi_cell(pts[i], others)
        v = np.array([e.start for e in cell.edges])
        true_area = abs(np.dot(v[:, 0], np.roll(v[:, 1], -1)) - np.dot(v[:, 1], np.roll(v[:, 0], -1))) / 2
        assert reg.area == pytest.approx(true_area, rel=1e-9)
        # Vertex distances to the robot are invariant under the unknown rotation/reflection.
        assert np.allclose(np.sort(np.hypot(*reg.vertices.T)), np.sort(np.hypot(*(v - pts[i]).T)), rtol=1e-9)
        checked += 1
    assert checked >= 10


# ------------------------------------------------------------------------------------- API surface
def test_result_surface_json_and_single_robot():
    pts = random_points(8, 60)
    res = dv.neighbors_from_distances(dense_distances(pts))
    assert isinstance(res, dv.distances.DistanceNeighbors) and isinstance(res, dv._result.Result)
    assert res.neighbors(3).dtype == np.int64
    import json
    doc = json.loads(res.to_json())
    assert doc["kind"] == "distance_neighbors" and doc["indices"] == res.indices.tolist()
    assert doc["on_hull"] == res.on_hull.tolist()
    order, hull = dv._core.voronoi_neighbors_of(res.graph, 3)
    assert np.array_equal(order, res.path(3)) and hull == res.on_hull[3]
    with pytest.raises(IndexError):
        res.neighbors(60)
    import matplotlib
    matplotlib.use("Agg")
    ax = res.plot()
    assert len(ax.collections) >= 2
    # Degenerate sizes: no robot, one robot, two robots.
    assert len(dv.neighbors_from_distances(np.zeros((0, 0)))) == 0
    one = dv.neighbors_from_distances(np.zeros((1, 1)))
    assert one.neighbors(0).tolist() == [] and one.on_hull[0]
    two = dv.neighbors_from_distances(np.array([[0, 2.0], [2.0, 0]]))
    assert two.neighbors(0).tolist() == [1] and two.neighbors(1).tolist() == [0] and two.on_hull.all()


def test_predicates_exposed():
    assert dv.distances.circumradius(3, 4, 5) == pytest.approx(2.5)
    assert dv.distances.signed_circumradius(3, 4, 6) < 0
    assert dv.distances.obtuse(3, 4, 6) and not dv.distances.obtuse(3, 4, 5)
    assert dv.distances.opposite_sides(1, 1, 2, 1, 2, 4, squared=True) == -1


def test_bad_input_names_the_entry():
    with pytest.raises(ValueError, match=r"distances must be an \(n, n\) matrix.*rows have different lengths"):
        dv.neighbors_from_distances([[0, 1], [1, 0, 2]])
    d = dense_distances(random_points(1, 6))
    bad = d.copy()
    bad[1, 4] = bad[4, 1] = -1.0
    with pytest.raises(ValueError, match=r"distances\[1, 4\]"):
        dv.neighbors_from_distances(bad)
    bad = d.copy()
    bad[2, 3] = np.nan
    with pytest.raises(ValueError, match=r"distances\[2, 3\] is NaN"):
        dv.neighbors_from_distances(bad)
    bad = d.copy()
    bad[0, 5] += 0.1
    with pytest.raises(ValueError, match=r"differ"):
        dv.neighbors_from_distances(bad)
    avg = dv.neighbors_from_distances(bad, symmetrize=True)  # averaging is the paper's e_ij
    assert len(avg) == 6
    bad = d.copy()
    bad[0, 5] = np.inf
    with pytest.raises(ValueError, match=r"distances\[0, 5\] = inf but distances\[5, 0\]"):
        dv.neighbors_from_distances(bad)
    bad = d.copy()
    bad[3, 3] = 1.0
    with pytest.raises(ValueError, match=r"distances\[3, 3\] must be 0"):
        dv.neighbors_from_distances(bad)
    bad = d.copy()
    bad[1, 2] = bad[2, 1] = 0.0
    with pytest.raises(ValueError, match="coinciding"):
        dv.neighbors_from_distances(bad)
    with pytest.raises(ValueError, match=r"edges\[1\]"):
        dv.neighbors_from_distances(np.array([[0, 1, 1.0], [1, 2, -2.0], [0, 2, 1.5], [2, 3, 1.0]]))
    with pytest.raises(ValueError, match="integers"):
        dv.neighbors_from_distances(np.array([[0, 1.5, 1.0], [1, 2, 2.0], [0, 2, 1.5], [2, 3, 1.0]]))
    with pytest.raises(ValueError, match="out of range"):
        dv.neighbors_from_distances((np.array([0, 1]), np.array([1, 7]), np.array([1.0, 1.0])), n=3)
    with pytest.raises(ValueError, match="shape"):
        dv.neighbors_from_distances(np.zeros((4, 5)))
    with pytest.raises(TypeError):
        dv.neighbors_from_distances(np.array([["a", "b"], ["c", "d"]]))


def test_three_row_edge_list_is_not_a_matrix():
    # A (3, 3) array is both an (m, 3) edge list with m = 3 and a square matrix. The documented rule:
    # a matrix when its diagonal is all 0 or inf (as every distance matrix's is), else an edge list.
    # Before: three measurements of a triangle were read as a 3 x 3 matrix and refused
    # ("distances[1, 1] must be 0"), whatever the order of their rows.
    tri = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    want = dv.neighbors_from_distances(dense_distances(tri))
    for edges in ([[0, 1, 1.0], [0, 2, 1.0], [1, 2, 2**0.5]],
                  [[1, 0, 1.0], [2, 0, 1.0], [2, 1, 2**0.5]],
                  [[0, 1, 1.0], [1, 2, 2**0.5], [0, 2, 1.0]]):
        got = dv.neighbors_from_distances(np.array(edges))
        assert [sorted(got.neighbors(i)) for i in range(3)] == [sorted(want.neighbors(i)) for i in range(3)]
        assert got.on_hull.tolist() == want.on_hull.tolist()
    # A bad edge list of three rows says how it was read, and how to say it otherwise.
    with pytest.raises(ValueError, match=r"edges\[1\].*\[a \(3, 3\) array is read as an edge list .* unless its "
                                         r"diagonal is all 0 or inf.*pass \(rows, cols, values\)"):
        dv.neighbors_from_distances(np.array([[0, 1, 1.0], [0, 2, -1.0], [1, 2, 2.0]]))
    with pytest.raises(ValueError, match=r"integers.*\[a \(3, 3\) array is read as an edge list"):
        dv.neighbors_from_distances(np.array([[0, 1.5, 1.0], [0, 2, 1.0], [1, 2, 2.0]]))
    # A matrix with a zero diagonal stays a matrix, and its own errors say so.
    bad = dense_distances(tri)
    bad[0, 1] += 0.1
    with pytest.raises(ValueError, match=r"distances\[\d, \d\].*differ"):
        dv.neighbors_from_distances(bad)


def test_serial_number_indices_are_refused_not_allocated():
    # Before: one row '0 2000000000 1' sized the team by the largest index (2e9 robots: memory
    # exhausted). Now a clear error with the renumbering; the renumbered list gives the two robots.
    edges = np.array([[0, 2_000_000_000, 1.0]])
    with pytest.raises(ValueError, match=r"indices go up to 2000000000 but only 2 robots appear.*np.unique"):
        dv.neighbors_from_distances(edges)
    ids, inv = np.unique(edges[:, :2], return_inverse=True)
    renumbered = edges.copy()
    renumbered[:, :2] = inv.reshape(-1, 2)
    r = dv.neighbors_from_distances(renumbered)
    assert len(r) == 2 and ids.tolist() == [0, 2_000_000_000]
    assert r.neighbors(0).tolist() == [1] and r.neighbors(1).tolist() == [0]
    # Gaps of a few missing robots are still positions (isolated robots), as documented.
    small = dv.neighbors_from_distances(np.array([[0, 5, 1.0], [5, 9, 1.0]]))
    assert len(small) == 10 and small.neighbors(3).tolist() == []
