"""The Python API: shapes, dtypes, memory layouts, small cases, consistency between the entry points
and the two methods, invariance under exact transformations, and measures against shapely."""
from __future__ import annotations

import gc
import math

import numpy as np
import pytest

import dvoronoi as dv
from conftest import (densified_disk, disk_deficit, grid_points, neighbor_sets, random_points)

METHODS = ["auto", "scan", "chords"]


def dyadic_points(seed: int, n: int, bits: int = 20) -> np.ndarray:
    """Random points whose coordinates are multiples of 2^-bits in [0, 1): translations by powers of
    two up to 2^(52 - bits) and power-of-two scalings are exact on them."""
    rng = np.random.default_rng(seed)
    return rng.integers(0, 2 ** bits, size=(n, 2)).astype(np.float64) / 2.0 ** bits


# ---------------------------------------------------------------------------- package surface


def test_package_exports():
    assert set(dv.__all__) >= {"limited_cell", "limited_cells", "LimitedCell", "LimitedPartition",
                               "__version__"}
    for name in dv.__all__:
        assert hasattr(dv, name), name
    assert isinstance(dv.__version__, str) and dv.__version__[0].isdigit()
    assert issubclass(dv.CoincidentError, ValueError)


def test_intel_lab_dataset():
    pts = dv.datasets.intel_lab()
    assert pts.shape == (54, 2) and pts.dtype == np.float64 and pts.flags.c_contiguous
    assert tuple(pts[0]) == (21.5, 23.0)  # mote 1
    assert np.all(np.isfinite(pts))
    assert len({tuple(p) for p in pts}) == 54  # distinct positions


# ---------------------------------------------------------------------------- shapes and dtypes


@pytest.mark.parametrize("method", METHODS)
def test_partition_arrays(method):
    pts = random_points(1, 300)
    part = dv.limited_cells(pts, 0.05, method=method)
    n = len(part)
    assert n == 300 and part.method == method and part.radius == 0.05
    for name in ("indptr", "indices", "candidates", "piece_ptr", "piece_neighbor"):
        assert getattr(part, name).dtype == np.int64, name
    for name in ("areas", "perimeters", "centroids", "points", "piece_x", "piece_y", "piece_span"):
        assert getattr(part, name).dtype == np.float64, name
    assert part.points.shape == (n, 2) and part.centroids.shape == (n, 2)
    assert part.areas.shape == part.perimeters.shape == part.candidates.shape == (n,)
    np.testing.assert_array_equal(part.points, pts)
    # CSR: scipy's layout, ascending rows, symmetric relation, no self loops.
    ip, ix = part.indptr, part.indices
    assert ip.shape == (n + 1,) and ip[0] == 0 and ip[-1] == len(ix) and np.all(np.diff(ip) >= 0)
    sets = neighbor_sets(ip, ix)
    for i in range(n):
        row = part.neighbors(i)
        assert row.dtype == np.int64 and np.all(np.diff(row) > 0)
        assert i not in sets[i]
        for j in sets[i]:
            assert i in sets[j]
    # Pieces: every limited neighbour is one edge piece; arcs have spans in (0, 2 pi].
    pp = part.piece_ptr
    assert pp.shape == (n + 1,) and pp[0] == 0 and pp[-1] == len(part.piece_x)
    assert np.all(np.diff(pp) >= 1)
    arc = part.piece_neighbor < 0
    assert np.all(part.piece_span[arc] > 0) and np.all(part.piece_span[arc] <= 2 * np.pi)
    assert np.all(part.piece_span[~arc] == 0)
    for i in range(n):
        edges = part.piece_neighbor[pp[i]:pp[i + 1]]
        assert sorted(edges[edges >= 0].tolist()) == sorted(sets[i])
    assert np.all(part.areas > 0) and np.all(part.areas <= np.pi * 0.05 ** 2 * (1 + 1e-12))
    assert np.all(part.candidates >= np.diff(ip))


def test_arrays_are_readonly_views_that_keep_the_result_alive():
    pts = random_points(2, 100)
    part = dv.limited_cells(pts, 0.1)
    areas, indices, centroids = part.areas, part.indices, part.centroids
    expected = (areas.copy(), indices.copy(), centroids.copy())
    for a in (areas, indices, centroids, part.points, part.neighbors(3)):
        assert not a.flags.writeable and not a.flags.owndata and a.base is not None
        with pytest.raises(ValueError):
            a[0] = 0
    # Repeated access hands out the same memory (no copy per access).
    assert part._core.areas.ctypes.data == areas.ctypes.data
    del part
    gc.collect()
    np.testing.assert_array_equal(areas, expected[0])
    np.testing.assert_array_equal(indices, expected[1])
    np.testing.assert_array_equal(centroids, expected[2])


def test_to_csr_matches_neighbors():
    pts = random_points(3, 200)
    part = dv.limited_cells(pts, 0.06)
    csr = part.to_csr()
    assert csr.shape == (200, 200) and csr.nnz == len(part.indices)
    assert (csr != csr.T).nnz == 0
    for i in range(200):
        np.testing.assert_array_equal(csr[i].indices, part.neighbors(i))


# ---------------------------------------------------------------------------- memory layouts


def test_any_layout_equals_c_contiguous():
    pts = random_points(4, 150)
    ref = dv.limited_cells(pts, 0.08)
    wide = np.zeros((150, 5))
    wide[:, 0], wide[:, 3] = pts[:, 0], pts[:, 1]
    tall = np.zeros((300, 2))
    tall[::2] = pts
    layouts = {
        "fortran": np.asfortranarray(pts),
        "column-strided": wide[:, ::3],
        "row-strided": tall[::2],
        "transposed": np.ascontiguousarray(pts.T).T,
        "list": pts.tolist(),
        "tuple of tuples": tuple(map(tuple, pts.tolist())),
        "big-endian": pts.astype(">f8"),
    }
    for name, arr in layouts.items():
        got = dv.limited_cells(arr, 0.08)
        np.testing.assert_array_equal(got.indptr, ref.indptr, err_msg=name)
        np.testing.assert_array_equal(got.indices, ref.indices, err_msg=name)
        np.testing.assert_array_equal(got.areas, ref.areas, err_msg=name)
        np.testing.assert_array_equal(got.points, pts, err_msg=name)


def test_reversed_rows_are_a_permutation():
    pts = random_points(5, 120)
    ref = dv.limited_cells(pts, 0.09)
    rev = dv.limited_cells(pts[::-1], 0.09)  # negative stride
    n = len(pts)
    for k in range(n):
        assert {n - 1 - j for j in rev.neighbors(k)} == set(ref.neighbors(n - 1 - k).tolist())
    np.testing.assert_allclose(rev.areas[::-1], ref.areas, rtol=1e-13)


def test_integer_and_float32_input_is_converted():
    ipts = grid_points(6, 60, 12)
    np.testing.assert_array_equal(dv.limited_cells(ipts.astype(np.int64), 1.5).indices,
                                  dv.limited_cells(ipts, 1.5).indices)
    np.testing.assert_array_equal(dv.limited_cells(ipts.astype(np.int32), 1.5).areas,
                                  dv.limited_cells(ipts, 1.5).areas)
    f32 = random_points(7, 50).astype(np.float32)
    np.testing.assert_array_equal(dv.limited_cells(f32, 0.2).areas,
                                  dv.limited_cells(f32.astype(np.float64), 0.2).areas)


def test_limited_cell_any_layout():
    rng = np.random.default_rng(8)
    others = rng.uniform(-1, 1, size=(30, 2))
    ref = dv.limited_cell(np.zeros(2), others, 0.7)
    wide = np.zeros((30, 4))
    wide[:, 1], wide[:, 2] = others[:, 0], others[:, 1]
    centers = [(0.0, 0.0), [0, 0], np.zeros((1, 2)), np.zeros(4)[::2], np.zeros(2, dtype=np.int32)]
    for center in centers:
        for arr in (np.asfortranarray(others), wide[:, 1:3], others.tolist(), others.astype(">f8")):
            got = dv.limited_cell(center, arr, 0.7)
            np.testing.assert_array_equal(got.neighbors, ref.neighbors)
            assert got.area == ref.area
            np.testing.assert_array_equal(got.vertices, ref.vertices)


# ---------------------------------------------------------------------------- small cases


@pytest.mark.parametrize("empty", [np.empty((0, 2)), [], np.empty((0, 2), dtype=np.int64)])
def test_empty_input(empty):
    part = dv.limited_cells(empty, 1.0)
    assert len(part) == 0
    np.testing.assert_array_equal(part.indptr, [0])
    assert part.indices.shape == (0,) and part.areas.shape == (0,) and part.centroids.shape == (0, 2)
    assert part.points.shape == (0, 2)
    assert part.to_csr().shape == (0, 0)
    with pytest.raises(IndexError):
        part.cell(0)
    cell = dv.limited_cell((1.0, 2.0), empty, 0.5)
    assert cell.is_full_disk and cell.neighbors.shape == (0,)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("center,radius", [((0.0, 0.0), 1.0), ((1e7, -3e6), 0.25), ((1e-9, 2e-9), 1e-9)])
def test_one_agent_is_a_full_disk(method, center, radius):
    part = dv.limited_cells(np.array([center]), radius, method=method)
    assert len(part) == 1 and len(part.indices) == 0
    assert part.areas[0] == pytest.approx(math.pi * radius ** 2, rel=1e-14)
    assert part.perimeters[0] == pytest.approx(2 * math.pi * radius, rel=1e-14)
    np.testing.assert_allclose(part.centroids[0], center, rtol=0, atol=1e-12 * radius + 1e-16 * abs(max(center)))
    cell = part.cell(0)
    assert cell.is_full_disk and len(cell) == 1 and cell.vertices.shape == (0, 2)
    (piece,) = cell.pieces
    assert piece.kind == "arc" and piece.neighbor == -1 and piece.span == pytest.approx(2 * math.pi)


def test_tangent_disks_are_not_neighbours():
    # Square lattice, spacing 1: at R = 0.5 the disks touch (bisector at distance exactly R).
    pts = grid_points(9, 25, 5)[np.lexsort(grid_points(9, 25, 5).T)]
    part = dv.limited_cells(pts, 0.5)
    assert len(part.indices) == 0
    np.testing.assert_allclose(part.areas, math.pi / 4, rtol=1e-14)
    # Just above: 4-neighbourhood on the lattice, never the diagonals (cells touch in a point).
    part = dv.limited_cells(pts, 0.5 + 2 ** -20)
    for i in range(len(pts)):
        for j in part.neighbors(i):
            assert np.sum(np.abs(pts[i] - pts[j])) == 1.0
    assert len(part.indices) == 2 * 40  # 5x5 lattice has 40 unit edges
    part = dv.limited_cells(pts, 5.0)  # whole Voronoi cells (squares) inside the disks
    assert len(part.indices) == 2 * 40
    interior = [i for i in range(25) if 0 < pts[i, 0] < 4 and 0 < pts[i, 1] < 4]
    np.testing.assert_allclose(part.areas[interior], 1.0, rtol=1e-13)


def test_cell_object():
    pts = dv.datasets.intel_lab()
    part = dv.limited_cells(pts, 3.0)
    cell = part.cell(0)
    assert isinstance(cell, dv.LimitedCell)
    np.testing.assert_array_equal(cell.center, pts[0])
    assert cell.radius == 3.0 and len(cell.pieces) == len(cell) == part.piece_ptr[1] - part.piece_ptr[0]
    np.testing.assert_array_equal(cell.neighbors, part.neighbors(0))
    assert cell.area == pytest.approx(part.areas[0], rel=1e-15)
    np.testing.assert_allclose(cell.centroid, part.centroids[0], rtol=1e-15)
    assert cell.perimeter == pytest.approx(part.perimeters[0], rel=1e-15)
    verts = cell.vertices
    assert verts.shape == (len(cell), 2)
    for k, piece in enumerate(cell.pieces):
        assert piece.start == tuple(verts[k]) and piece.end == tuple(verts[(k + 1) % len(cell)])
        assert (piece.kind == "arc") == piece.is_arc == (piece.neighbor == -1)
        if piece.is_arc:
            for end in (piece.start, piece.end):
                assert math.hypot(end[0] - pts[0, 0], end[1] - pts[0, 1]) == pytest.approx(3.0, rel=1e-12)
    # Counter-clockwise: the polygon of the vertices has positive signed area.
    x, y = verts[:, 0], verts[:, 1]
    assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0
    assert "LimitedCell(" in repr(cell) and "LimitedPartition(n=54" in repr(part)


def test_index_errors():
    part = dv.limited_cells(random_points(10, 10), 0.3)
    for bad in (10, -1, 100):
        with pytest.raises(IndexError, match="out of range"):
            part.cell(bad)
        with pytest.raises(IndexError, match="out of range"):
            part.neighbors(bad)
    assert part.neighbors(np.int64(9)).dtype == np.int64


# ---------------------------------------------------------------------------- consistency


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("seed,n,radius", [(11, 80, 0.08), (12, 200, 0.15), (13, 50, 2.0)])
def test_limited_cell_equals_partition_cell(method, seed, n, radius):
    pts = random_points(seed, n)
    part = dv.limited_cells(pts, radius, method=method)
    for i in range(n):
        others = np.delete(pts, i, axis=0)
        cell = dv.limited_cell(pts[i], others, radius, method=method)
        mapped = np.where(cell.neighbors < i, cell.neighbors, cell.neighbors + 1)
        np.testing.assert_array_equal(mapped, part.neighbors(i))
        assert cell.area == pytest.approx(part.areas[i], rel=1e-12)
        np.testing.assert_allclose(cell.centroid, part.centroids[i], rtol=1e-12)
        ref = part.cell(i)
        assert len(cell) == len(ref)
        np.testing.assert_allclose(cell.vertices, ref.vertices, rtol=1e-12, atol=1e-15)
        nb = cell.piece_neighbor
        np.testing.assert_array_equal(np.where(nb < 0, nb, np.where(nb < i, nb, nb + 1)), ref.piece_neighbor)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("kind", ["uniform", "grid", "clustered"])
def test_scan_equals_chords(seed, kind):
    if kind == "uniform":
        pts, radius = random_points(seed, 400), 0.04 + 0.02 * seed
    elif kind == "grid":
        pts, radius = grid_points(seed, 150, 16), [0.5, 1.0, 1.5, 2.0, 2.5, 0.75][seed]
    else:
        rng = np.random.default_rng(seed)
        centres = rng.uniform(0, 1, size=(5, 2))
        pts = (centres[rng.integers(0, 5, 300)] + rng.normal(0, 0.02, size=(300, 2)))
        radius = 0.01 * (seed + 1)
    scan = dv.limited_cells(pts, radius, method="scan")
    chords = dv.limited_cells(pts, radius, method="chords")
    np.testing.assert_array_equal(scan.indptr, chords.indptr)
    np.testing.assert_array_equal(scan.indices, chords.indices)
    np.testing.assert_allclose(scan.areas, chords.areas, rtol=1e-11)
    np.testing.assert_allclose(scan.centroids, chords.centroids, rtol=1e-11, atol=1e-14)


def test_threads_do_not_change_the_result():
    pts = random_points(14, 20000)
    one = dv.limited_cells(pts, 0.006, workers=1)
    two = dv.limited_cells(pts, 0.006, workers=2)
    every = dv.limited_cells(pts, 0.006)
    for other in (two, every):
        # Threads write their pieces to their own columns, merged afterwards: every array must match.
        for name in ("indptr", "indices", "areas", "perimeters", "centroids", "candidates",
                     "piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span"):
            np.testing.assert_array_equal(getattr(one, name), getattr(other, name), err_msg=name)


def test_progress_callback():
    pts = random_points(15, 10000)
    calls = []
    part = dv.limited_cells(pts, 0.01, progress=lambda done, total: calls.append((done, total)))
    assert len(part) == 10000
    assert calls and calls[-1] == (10000, 10000)
    assert all(total == 10000 for _, total in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_progress_callback_exception_propagates():
    def boom(done, total):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        dv.limited_cells(random_points(16, 5000), 0.01, progress=boom)


def test_progress_bar(capsys):
    dv.limited_cells(random_points(17, 3000), 0.01, progress=True)
    assert "limited cells" in capsys.readouterr().err
    dv.limited_cells(random_points(17, 3000), 0.01, progress=False)
    dv.limited_cells(random_points(17, 3000), 0.01)  # small n: no bar by default
    assert "limited cells" not in capsys.readouterr().err


# ---------------------------------------------------------------------------- invariance


def _transforms(pts, radius):
    s = 2.0 ** 10
    return {
        "translate": (pts + np.array([2.0 ** 12, -(2.0 ** 9)]), radius, 1.0),
        "rotate90": (np.column_stack([-pts[:, 1], pts[:, 0]]), radius, 1.0),
        "mirror": (np.column_stack([-pts[:, 0], pts[:, 1]]), radius, 1.0),
        "scale-up": (pts * s, radius * s, s * s),
        "scale-down": (pts / s, radius / s, 1.0 / (s * s)),
    }


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", ["dyadic", "grid-1.0", "grid-1.5", "grid-2.5"])
def test_invariance(method, case):
    if case == "dyadic":
        pts, radius = dyadic_points(18, 300), 0.05
    else:
        pts, radius = grid_points(19, 120, 14) / 4.0, float(case.split("-")[1]) / 4.0
    ref = dv.limited_cells(pts, radius, method=method)
    ref_sets = neighbor_sets(ref.indptr, ref.indices)
    for name, (tp, tr, area_scale) in _transforms(pts, radius).items():
        got = dv.limited_cells(tp, tr, method=method)
        assert neighbor_sets(got.indptr, got.indices) == ref_sets, name
        np.testing.assert_allclose(got.areas, ref.areas * area_scale, rtol=1e-9, err_msg=name)
    perm = np.random.default_rng(20).permutation(len(pts))
    got = dv.limited_cells(pts[perm], radius, method=method)
    for k in range(len(pts)):
        assert {int(perm[j]) for j in got.neighbors(k)} == ref_sets[perm[k]]
    np.testing.assert_allclose(got.areas, ref.areas[perm], rtol=1e-12)


# ---------------------------------------------------------------------------- measures vs shapely


def _shapely_cell(pts, i, radius, k):
    """V_i ∩ (inscribed k-gon of the disk), from half-planes, independently of dvoronoi."""
    import shapely

    poly = densified_disk(pts[i], radius, k)
    p = pts[i]
    for j in range(len(pts)):
        if j == i:
            continue
        d = pts[j] - p
        dist = math.hypot(*d)
        if dist >= 2 * radius:
            continue
        u = d / dist
        v = np.array([-u[1], u[0]])
        m = 0.5 * (p + pts[j])
        big = 4.0 * radius
        half = shapely.Polygon([m + big * v, m - big * v, m - big * v - big * u, m + big * v - big * u])
        poly = poly.intersection(half)
    return poly


@pytest.mark.parametrize("seed,n,radius", [(21, 60, 0.12), (22, 150, 0.07), (23, 20, 0.5)])
def test_measures_against_shapely(seed, n, radius):
    pytest.importorskip("shapely")
    k = 4096
    deficit = disk_deficit(radius, k)  # area of disk minus inscribed k-gon
    eps = 1e-12 * math.pi * radius ** 2
    pts = random_points(seed, n)
    part = dv.limited_cells(pts, radius)
    for i in range(n):
        poly = _shapely_cell(pts, i, radius, k)
        area = part.areas[i]
        # The k-gon lies inside the disk, so the exact area is larger by at most `deficit`.
        assert -eps <= area - poly.area <= deficit + eps, i
        # Moments relative to the agent differ by at most deficit * R: centroid bound 2 R deficit / A.
        c = np.array([poly.centroid.x, poly.centroid.y])
        assert np.linalg.norm(part.centroids[i] - c) <= 2 * radius * deficit / area + 1e-12 * radius, i
        # Perimeter: the polygon is a convex subset within Hausdorff distance h = R (1 - cos(pi/k))
        # of the convex cell, so its perimeter is smaller by at most 2 pi h.
        h = radius * (1 - math.cos(math.pi / k))
        assert poly.length <= part.perimeters[i] * (1 + 1e-12)
        assert part.perimeters[i] - poly.length <= 2 * math.pi * h + 1e-12 * radius


@pytest.mark.parametrize("seed,n,radius", [(24, 100, 0.08), (25, 300, 0.03), (26, 40, 0.3)])
def test_areas_sum_to_union_of_disks(seed, n, radius):
    shapely = pytest.importorskip("shapely")
    k = 2048
    pts = random_points(seed, n)
    part = dv.limited_cells(pts, radius)
    union = shapely.union_all([densified_disk(p, radius, k) for p in pts]).area
    total = float(np.sum(part.areas))
    # Union of inscribed k-gons <= union of disks <= it + n * deficit.
    assert union - 1e-12 * total <= total <= union + n * disk_deficit(radius, k) + 1e-12 * total


def test_methods_name_what_runs():
    # "auto" (default) is the certified filter with Boundary Scan behind it; "scan" runs Boundary Scan
    # on every agent, "chords" RCVC; computed_by counts which algorithm computed each cell.
    uniform = random_points(7, 2000)
    lattice = grid_points(0, 400, 20)
    for pts, radius in ((uniform, 0.03), (lattice, 0.75)):
        n = len(pts)
        auto = dv.limited_cells(pts, radius)
        scan = dv.limited_cells(pts, radius, method="scan")
        chords = dv.limited_cells(pts, radius, method="chords")
        assert auto.method == "auto"
        assert scan.computed_by == {"clip": 0, "scan": n, "chords": 0, "power": 0}
        assert chords.computed_by == {"clip": 0, "scan": 0, "chords": n, "power": 0}
        assert auto.computed_by["clip"] + auto.computed_by["scan"] == n and auto.computed_by["chords"] == 0
        for other in (scan, chords):
            np.testing.assert_array_equal(auto.indptr, other.indptr)
            np.testing.assert_array_equal(auto.indices, other.indices)
        np.testing.assert_array_equal(auto.areas, scan.areas)
    assert dv.limited_cells(uniform, 0.03).computed_by["clip"] == len(uniform)  # the filter never gives up here
    vor = {inner: dv.voronoi_cells(uniform, inner=inner, workers=2) for inner in ("auto", "scan", "evt")}
    assert vor["scan"].computed_by == {"one_shot": 0, "deferred": 0, "asr": len(uniform)}
    assert vor["auto"].computed_by["one_shot"] > len(uniform) // 2 and vor["auto"].inner == "auto"
    for inner in ("scan", "evt"):
        np.testing.assert_array_equal(vor[inner].indices, vor["auto"].indices)
        np.testing.assert_array_equal(vor[inner].on_hull, vor["auto"].on_hull)
