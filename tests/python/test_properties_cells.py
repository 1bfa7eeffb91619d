"""Property-based tests (hypothesis) of the cell entry points: limited cells (dv.limited_cells every
method, dv.limited_cell), exact cells (dv.voronoi_cells with and without bounds, dv.voronoi_cell) and
Voronoi neighbours from distances (dv.neighbors_from_distances).

Metamorphic relations, which need no oracle: relabelling the agents permutes the answer; the eight
symmetries of the square grid (rotations by 90 degrees, mirrors) keep neighbour sets and hull flags
and map areas and centroids; scaling by 2**k keeps the combinatorics and scales lengths by 2**k and
areas by 4**k exactly (every operation scales exactly in binary floating point); a dyadic translation
keeps the combinatorics and, where cells are computed in each agent's own frame, areas and
perimeters exactly. Where the CGAL oracle is built, neighbour sets and hull flags equal its exact
answer. Inputs lie on integer grids (exact degeneracies: collinear, cocircular, agents at exactly 2R).
Profiles: see conftest.py ("ci" 200 examples per property, HYPOTHESIS_PROFILE=long 5000).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, note, strategies as st  # noqa: E402

import dvoronoi as dv  # noqa: E402
from conftest import find_oracle, run_oracle  # noqa: E402
from property_support import (  # noqa: E402
    NON_IDENTITY, csr_sets, dyadic_radius, dyadic_shift, first_difference, lattice_points, permutation,
    permuted_sets, transform_box, transform_points)


def _accepted_methods():
    methods = [None, "scan", "chords"]
    try:  # the certified fast path under its SPEC name, where this build has it
        dv.limited_cells(np.zeros((1, 2)), 1.0, method="auto")
        methods.append("auto")
    except ValueError:
        pass
    return methods


METHODS = _accepted_methods()
ORACLE = find_oracle()
needs_oracle = pytest.mark.skipif(ORACLE is None, reason="CGAL oracle dvoronoi_cgal_oracle not built")


def limited(points, radius, method):
    if method is None:
        return dv.limited_cells(points, radius, workers=1)
    return dv.limited_cells(points, radius, method=method, workers=1)


def area_tol(radius: float) -> float:
    """Rounding allowed between two computations of one cell's area (the cells are measured in the
    agent's own frame, so the error is relative to the disk)."""
    return 1e-12 * math.pi * radius * radius


# ================================================================================ limited cells
@given(data=st.data())
def test_limited_cells_permutation(data):
    pts, side = data.draw(lattice_points(1, 24))
    R = dyadic_radius(data.draw, side)
    method = data.draw(st.sampled_from(METHODS))
    perm = permutation(data.draw, len(pts))
    a = limited(pts, R, method)
    b = limited(pts[perm], R, method)
    sa, sb = csr_sets(a.indptr, a.indices), csr_sets(b.indptr, b.indices)
    want = permuted_sets(sa, perm)
    assert sb == want, first_difference(sb, want)
    # the relation is symmetric: j shapes i's cell along an edge iff i shapes j's
    assert all(i in sa[j] for i in range(len(pts)) for j in sa[i])
    np.testing.assert_allclose(b.areas, a.areas[perm], rtol=0, atol=area_tol(R))
    np.testing.assert_allclose(b.perimeters, a.perimeters[perm], rtol=0, atol=1e-12 * 2 * math.pi * R)
    np.testing.assert_allclose(b.centroids, a.centroids[perm], rtol=0, atol=1e-12 * (R + side))


@given(data=st.data())
def test_limited_cells_grid_symmetries(data):
    pts, side = data.draw(lattice_points(1, 24))
    R = dyadic_radius(data.draw, side)
    method = data.draw(st.sampled_from(METHODS))
    t = data.draw(st.sampled_from(NON_IDENTITY))
    a = limited(pts, R, method)
    b = limited(transform_points(t, pts), R, method)
    assert np.array_equal(a.indptr, b.indptr) and np.array_equal(a.indices, b.indices), \
        first_difference(csr_sets(a.indptr, a.indices), csr_sets(b.indptr, b.indices))
    np.testing.assert_allclose(b.areas, a.areas, rtol=0, atol=area_tol(R))
    np.testing.assert_allclose(b.perimeters, a.perimeters, rtol=0, atol=1e-12 * 2 * math.pi * R)
    np.testing.assert_allclose(b.centroids, transform_points(t, a.centroids), rtol=0, atol=1e-12 * (R + side))


@given(data=st.data())
def test_limited_cells_scaling_by_powers_of_two_is_exact(data):
    pts, side = data.draw(lattice_points(1, 24))
    R = dyadic_radius(data.draw, side)
    method = data.draw(st.sampled_from(METHODS))
    k = data.draw(st.integers(-20, 20))
    f = 2.0 ** k
    a = limited(pts, R, method)
    b = limited(pts * f, R * f, method)
    assert np.array_equal(a.indptr, b.indptr) and np.array_equal(a.indices, b.indices)
    # every operation scales exactly: lengths by 2**k, areas by 4**k, bit for bit
    assert np.array_equal(b.areas, a.areas * f * f), np.max(np.abs(b.areas - a.areas * f * f))
    assert np.array_equal(b.perimeters, a.perimeters * f)
    assert np.array_equal(b.centroids, a.centroids * f)


@given(data=st.data())
def test_limited_cells_dyadic_translation(data):
    pts, side = data.draw(lattice_points(1, 24))
    R = dyadic_radius(data.draw, side)
    method = data.draw(st.sampled_from(METHODS))
    shift = dyadic_shift(data.draw, side)
    a = limited(pts, R, method)
    b = limited(pts + shift, R, method)
    assert np.array_equal(a.indptr, b.indptr) and np.array_equal(a.indices, b.indices)
    # cells are computed in each agent's frame from exact differences: the same doubles
    assert np.array_equal(b.areas, a.areas)
    assert np.array_equal(b.perimeters, a.perimeters)
    scale = float(np.max(np.abs(pts + shift))) + R
    np.testing.assert_allclose(b.centroids, a.centroids + shift, rtol=0, atol=4 * np.finfo(float).eps * scale)


@given(data=st.data())
def test_limited_methods_and_the_one_agent_call_agree(data):
    pts, side = data.draw(lattice_points(1, 20))
    R = dyadic_radius(data.draw, side)
    parts = {m: limited(pts, R, m) for m in METHODS}
    ref = parts[None]
    for m, p in parts.items():
        assert np.array_equal(p.indptr, ref.indptr) and np.array_equal(p.indices, ref.indices), m
        np.testing.assert_allclose(p.areas, ref.areas, rtol=0, atol=area_tol(R))
    i = data.draw(st.integers(0, len(pts) - 1))
    method = data.draw(st.sampled_from(["scan", "chords"]))
    others = np.delete(pts, i, axis=0)
    cell = dv.limited_cell(pts[i], others, R, method=method)
    got = np.sort(np.where(cell.neighbors < i, cell.neighbors, cell.neighbors + 1))
    assert np.array_equal(got, ref.neighbors(i))
    assert abs(cell.area - ref.areas[i]) <= area_tol(R)


@needs_oracle
@given(data=st.data())
def test_limited_cells_equal_the_cgal_oracle(data):
    pts, side = data.draw(lattice_points(1, 20))
    R = dyadic_radius(data.draw, side)
    method = data.draw(st.sampled_from(METHODS))
    exact = run_oracle(ORACLE, pts, R)
    part = limited(pts, R, method)
    got = csr_sets(part.indptr, part.indices)
    want = [set(nb) for nb in exact["limited_neighbors"]]
    assert got == want, first_difference(got, want)
    np.testing.assert_allclose(part.areas, exact["limited_areas"], rtol=1e-9, atol=0)


# ================================================================================ exact cells
def _box_around(pts: np.ndarray, side: int, draw) -> tuple:
    m = side / 8.0 * draw(st.integers(1, 4))
    lo, hi = pts.min(axis=0) - m, pts.max(axis=0) + m
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _area_tol(box) -> float:
    return 1e-12 * (box[2] - box[0]) * (box[3] - box[1])


def _same_exact(a, b, perm=None):
    sa, sb = csr_sets(a.indptr, a.indices), csr_sets(b.indptr, b.indices)
    want = sa if perm is None else permuted_sets(sa, perm)
    assert sb == want, first_difference(sb, want)
    hull = a.on_hull if perm is None else a.on_hull[perm]
    assert np.array_equal(b.on_hull, hull)


@given(data=st.data())
def test_voronoi_cells_permutation(data):
    pts, side = data.draw(lattice_points(1, 24))
    inner = data.draw(st.sampled_from(["scan", "evt"]))
    box = _box_around(pts, side, data.draw) if data.draw(st.booleans()) else None
    perm = permutation(data.draw, len(pts))
    a = dv.voronoi_cells(pts, inner=inner, bounds=box, workers=1)
    b = dv.voronoi_cells(pts[perm], inner=inner, bounds=box, workers=1)
    _same_exact(a, b, perm)
    sa = csr_sets(a.indptr, a.indices)
    assert all(i in sa[j] for i in range(len(pts)) for j in sa[i])
    if box is not None:
        np.testing.assert_allclose(b.areas, a.areas[perm], rtol=0, atol=_area_tol(box))
        # the clipped cells tile the box
        assert math.isclose(float(np.sum(a.areas)), (box[2] - box[0]) * (box[3] - box[1]), rel_tol=1e-12)
    else:
        assert np.array_equal(np.isnan(b.areas), b.on_hull)
        np.testing.assert_allclose(b.areas, a.areas[perm], rtol=1e-12, atol=0, equal_nan=True)


@given(data=st.data())
def test_voronoi_cells_grid_symmetries(data):
    pts, side = data.draw(lattice_points(1, 24))
    inner = data.draw(st.sampled_from(["scan", "evt"]))
    t = data.draw(st.sampled_from(NON_IDENTITY))
    box = _box_around(pts, side, data.draw) if data.draw(st.booleans()) else None
    a = dv.voronoi_cells(pts, inner=inner, bounds=box, workers=1)
    b = dv.voronoi_cells(transform_points(t, pts), inner=inner,
                         bounds=None if box is None else transform_box(t, box), workers=1)
    _same_exact(a, b)
    if box is not None:
        np.testing.assert_allclose(b.areas, a.areas, rtol=0, atol=_area_tol(box))
        c = transform_points(t, a.centroids)
        ok = ~np.isnan(a.centroids[:, 0])
        np.testing.assert_allclose(b.centroids[ok], c[ok], rtol=0, atol=1e-12 * (box[2] - box[0] + side))
    else:
        np.testing.assert_allclose(b.areas, a.areas, rtol=1e-12, atol=0, equal_nan=True)


@given(data=st.data())
def test_voronoi_cells_scaling_by_powers_of_two(data):
    pts, side = data.draw(lattice_points(1, 24))
    inner = data.draw(st.sampled_from(["scan", "evt"]))
    box = _box_around(pts, side, data.draw) if data.draw(st.booleans()) else None
    k = data.draw(st.integers(-20, 20))
    f = 2.0 ** k
    a = dv.voronoi_cells(pts, inner=inner, bounds=box, workers=1)
    b = dv.voronoi_cells(pts * f, inner=inner, bounds=None if box is None else tuple(v * f for v in box), workers=1)
    _same_exact(a, b)
    assert np.array_equal(b.radius_steps, a.radius_steps)
    assert np.array_equal(b.areas, a.areas * f * f, equal_nan=True), np.nanmax(np.abs(b.areas - a.areas * f * f))
    assert np.array_equal(b.centroids, a.centroids * f, equal_nan=True)


@given(data=st.data())
def test_voronoi_cells_dyadic_translation(data):
    pts, side = data.draw(lattice_points(1, 24))
    inner = data.draw(st.sampled_from(["scan", "evt"]))
    box = _box_around(pts, side, data.draw) if data.draw(st.booleans()) else None
    shift = dyadic_shift(data.draw, side)
    a = dv.voronoi_cells(pts, inner=inner, bounds=box, workers=1)
    moved = None if box is None else (box[0] + shift[0], box[1] + shift[1], box[2] + shift[0], box[3] + shift[1])
    b = dv.voronoi_cells(pts + shift, inner=inner, bounds=moved, workers=1)
    _same_exact(a, b)
    if box is not None:  # clipped cells are measured in the agent's frame
        np.testing.assert_allclose(b.areas, a.areas, rtol=0, atol=_area_tol(box))
        return
    # Bounded cells: their vertices are points of the caller's frame, rounded to a few ulps of the
    # coordinates; the area moves by at most that times the perimeter, the centroid by a few ulps.
    # (Before the fix in cells/asr.hpp some cells were summed in a stale frame: errors ~ ulp * |p|^2.)
    reach = float(np.max(np.abs(np.concatenate([pts, pts + shift])))) + float(np.max(np.abs(shift)))
    assert np.array_equal(np.isnan(a.areas), np.isnan(b.areas))
    for i in np.flatnonzero(~np.isnan(a.areas)):
        v = np.asarray(a.cell(int(i)).vertices)
        ulp = float(np.spacing(2.0 * (reach + float(np.max(np.abs(v))))))  # of the largest coordinate in play
        perimeter = float(np.sum(np.linalg.norm(v - np.roll(v, 1, axis=0), axis=1)))
        assert abs(b.areas[i] - a.areas[i]) <= 4 * ulp * perimeter + 1e-14 * a.areas[i], (i, a.areas[i], b.areas[i])
        np.testing.assert_allclose(b.centroids[i], a.centroids[i] + shift, rtol=0, atol=4 * ulp)


@given(data=st.data())
def test_voronoi_cells_bounds_forms_are_one_polygon(data):
    # a box, the same box as a polygon (either orientation, any starting corner) and that polygon
    # as a closed ring (its first vertex repeated at the end) are one region: the same doubles
    pts, side = data.draw(lattice_points(1, 20))
    box = _box_around(pts, side, data.draw)
    x0, y0, x1, y1 = box
    ring = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    start = data.draw(st.integers(0, 3))
    poly = ring[start:] + ring[:start]
    if data.draw(st.booleans()):
        poly = poly[::-1]
    closed = poly + [poly[0]]
    a = dv.voronoi_cells(pts, bounds=box, workers=1)
    b = dv.voronoi_cells(pts, bounds=np.array(poly), workers=1)
    c = dv.voronoi_cells(pts, bounds=np.array(closed), workers=1)
    _same_exact(a, b)
    _same_exact(a, c)
    np.testing.assert_allclose(b.areas, a.areas, rtol=0, atol=_area_tol(box))
    assert np.array_equal(c.areas, b.areas) and np.array_equal(c.bounds, b.bounds)


@given(data=st.data())
def test_voronoi_cells_repeated_or_straight_bounds_vertex_is_the_same_polygon(data):
    # Before: a vertex repeated in place was refused ('bounds: vertices 1 and 2 coincide') while
    # obstacle documents dropped it; core/convex_ring.hpp now reads every region list one way.
    pts, side = data.draw(lattice_points(1, 12))
    x0, y0, x1, y1 = _box_around(pts, side, data.draw)
    ring = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    k = data.draw(st.integers(0, 3))
    # A repeated vertex, or the midpoint of an axis-parallel edge (exactly on it).
    extra = ring[k] if data.draw(st.booleans()) else [(ring[k][0] + ring[(k + 1) % 4][0]) / 2,
                                                      (ring[k][1] + ring[(k + 1) % 4][1]) / 2]
    spelled = ring[:k + 1] + [extra] + ring[k + 1:]
    a = dv.voronoi_cells(pts, bounds=np.array(ring), workers=1)
    b = dv.voronoi_cells(pts, bounds=np.array(spelled), workers=1)
    _same_exact(a, b)
    assert np.array_equal(a.areas, b.areas) and np.array_equal(a.bounds, b.bounds)


@given(data=st.data())
def test_voronoi_inner_steps_and_the_one_agent_call_agree(data):
    pts, side = data.draw(lattice_points(1, 20))
    box = _box_around(pts, side, data.draw) if data.draw(st.booleans()) else None
    a = dv.voronoi_cells(pts, inner="scan", bounds=box, workers=1)
    b = dv.voronoi_cells(pts, inner="evt", bounds=box, workers=1)
    _same_exact(a, b)
    i = data.draw(st.integers(0, len(pts) - 1))
    cell = dv.voronoi_cell(pts[i], np.delete(pts, i, axis=0), inner=data.draw(st.sampled_from(["scan", "evt"])),
                           bounds=box)
    got = np.sort(np.where(cell.neighbors < i, cell.neighbors, cell.neighbors + 1))
    assert np.array_equal(got, a.neighbors(i))
    assert cell.on_hull == bool(a.on_hull[i])
    if box is not None:
        assert abs(cell.area - a.areas[i]) <= _area_tol(box)


@needs_oracle
@given(data=st.data())
def test_voronoi_cells_equal_the_cgal_oracle(data):
    pts, side = data.draw(lattice_points(1, 20))
    inner = data.draw(st.sampled_from(["scan", "evt"]))
    box = _box_around(pts, side, data.draw)
    exact = run_oracle(ORACLE, pts, 1.0, box)
    part = dv.voronoi_cells(pts, inner=inner, bounds=box, workers=1)
    got = csr_sets(part.indptr, part.indices)
    want = [set(nb) for nb in exact["voronoi_neighbors"]]
    assert got == want, first_difference(got, want)
    assert np.array_equal(part.on_hull, np.asarray(exact["on_hull"], dtype=bool))
    np.testing.assert_allclose(part.areas, exact["clipped_areas"], rtol=1e-9, atol=1e-9 * (box[2] - box[0]) * (box[3] - box[1]))


# ===================================================================== neighbours from distances
def _squared_matrix(pts: np.ndarray) -> np.ndarray:
    d = pts[:, None, :] - pts[None, :, :]
    return np.sum(d * d, axis=2)  # integers: exact


def _answer(res):
    return csr_sets(res.indptr, res.indices), res.on_hull.copy()


@given(data=st.data())
def test_distances_exact_squared_equal_exact_cells(data):
    # exact squared distances (integer coordinates), every pair measured: the exact answer, lattices
    # and cocircular robots included
    pts, side = data.draw(lattice_points(1, 18, sides=(4, 8, 16, 64, 1 << 12)))
    res = dv.neighbors_from_distances(_squared_matrix(pts), squared=True, workers=1)
    vor = dv.voronoi_cells(pts, workers=1)
    got, hull = _answer(res)
    want = csr_sets(vor.indptr, vor.indices)
    assert got == want, first_difference(got, want)
    assert np.array_equal(hull, vor.on_hull)


@given(data=st.data())
def test_distances_permutation_and_scaling(data):
    pts, side = data.draw(lattice_points(1, 18, sides=(4, 8, 16, 64, 1 << 12)))
    perm = permutation(data.draw, len(pts))
    k = data.draw(st.integers(-8, 8))
    sq = _squared_matrix(pts)
    a = dv.neighbors_from_distances(sq, squared=True, workers=1)
    b = dv.neighbors_from_distances(sq[np.ix_(perm, perm)], squared=True, workers=1)
    sa, ha = _answer(a)
    sb, hb = _answer(b)
    want = permuted_sets(sa, perm)
    assert sb == want, first_difference(sb, want)
    assert np.array_equal(hb, ha[perm])
    # squared distances times 4**k: the same decisions, the same arrays (path order included)
    c = dv.neighbors_from_distances(sq * 4.0 ** k, squared=True, workers=1)
    for name in ("indptr", "indices", "on_hull", "path_length", "added", "detected"):
        assert np.array_equal(getattr(c, name), getattr(a, name)), name
    # plain distances times 2**k: one rounding of sqrt, scaled exactly
    d = np.sqrt(sq)
    e1 = dv.neighbors_from_distances(d, workers=1)
    e2 = dv.neighbors_from_distances(d * 2.0 ** k, workers=1)
    for name in ("indptr", "indices", "on_hull", "path_length"):
        assert np.array_equal(getattr(e1, name), getattr(e2, name)), name


@given(data=st.data())
def test_distances_input_forms_give_one_answer(data):
    pts, side = data.draw(lattice_points(1, 14, sides=(4, 8, 16, 64)))
    import scipy.sparse as sp

    sq = _squared_matrix(pts)
    n = len(pts)
    ref = dv.neighbors_from_distances(sq, squared=True, workers=1)
    i, j = np.nonzero(~np.eye(n, dtype=bool))
    once = i < j
    forms = {
        "edge list, both directions": np.column_stack([i, j, sq[i, j]]).astype(float),
        "edge list, once": np.column_stack([i[once], j[once], sq[i, j][once]]).astype(float),
        "tuple": (i[once], j[once], sq[i, j][once]),
        "sparse": sp.csr_matrix((sq[i, j], (i, j)), shape=(n, n)),
    }
    for name, form in forms.items():
        if name.startswith("edge list") and len(form) == 3:
            continue  # a (3, 3) array is read by the documented 3x3 rule; the tuple form covers it
        got = dv.neighbors_from_distances(form, squared=True, n=None if name == "sparse" else n, workers=1)
        for field in ("indptr", "indices", "on_hull"):
            assert np.array_equal(getattr(got, field), getattr(ref, field)), (name, field)


@given(data=st.data())
def test_distances_detection_radius_twice_the_longest_delaunay_edge(data):
    # documented: the answer is exact when every robot detects the robots within twice the longest
    # Delaunay edge (the Delaunay graph of positive-length Voronoi edges)
    pts, side = data.draw(lattice_points(3, 18, sides=(8, 16, 64, 1 << 12)))
    vor = dv.voronoi_cells(pts, workers=1)
    edges = vor.delaunay_edges()
    sq = _squared_matrix(pts)
    longest2 = float(np.max(sq[edges[:, 0], edges[:, 1]])) if len(edges) else 0.0
    keep = sq <= 4.0 * longest2
    cut = np.where(keep, sq, np.inf)
    np.fill_diagonal(cut, 0.0)
    note(f"dropped {int((~keep).sum()) // 2} of {len(pts) * (len(pts) - 1) // 2} pairs")
    res = dv.neighbors_from_distances(cut, squared=True, workers=1)
    got, hull = _answer(res)
    want = csr_sets(vor.indptr, vor.indices)
    assert got == want, first_difference(got, want)
    assert np.array_equal(hull, vor.on_hull)
