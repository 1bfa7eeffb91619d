"""Exact (unlimited) Voronoi cells by Adjust-Sensing-Radius from Python: neighbour sets and hull flags
equal the CGAL oracle's on random inputs, integer grids, the degenerate corpus and the Intel lab
motes; both inner steps agree; the per-agent call agrees with the all-agents call."""
from __future__ import annotations

import numpy as np
import pytest

import dvoronoi as dv
from conftest import grid_points, neighbor_sets, random_points, read_corpus


def check(oracle, points: np.ndarray, label: str) -> None:
    exact = oracle(points, 1.0)
    want = [set(nb) for nb in exact["voronoi_neighbors"]]
    want_hull = np.asarray(exact["on_hull"], dtype=bool)
    for inner in ("auto", "scan", "evt"):
        part = dv.voronoi_cells(points, inner=inner, workers=2)
        got = neighbor_sets(part.indptr, part.indices)
        bad = [i for i in range(len(points)) if got[i] != want[i]]
        assert not bad, f"{label} [{inner}]: neighbours differ at agents {bad[:10]}"
        assert np.array_equal(part.on_hull, want_hull), f"{label} [{inner}]: hull flags differ"


@pytest.mark.parametrize("seed", range(6))
def test_random_and_grids(oracle, seed):
    check(oracle, random_points(seed, 300), f"random seed {seed}")
    check(oracle, grid_points(seed, 120, 14), f"grid seed {seed}")


def test_degenerate_corpus(oracle):
    cases = read_corpus()
    assert len(cases) > 200
    for name, _radius, pts in cases:
        check(oracle, pts, name)


def test_intel_lab(oracle):
    check(oracle, dv.datasets.intel_lab(), "intel lab")


def test_per_agent_matches_partition_and_graph_shapes():
    pts = random_points(42, 150)
    part = dv.voronoi_cells(pts)
    edges = part.delaunay_edges()
    assert edges.shape[1] == 2 and np.all(edges[:, 0] < edges[:, 1])
    assert len(edges) * 2 == len(part.indices)
    m = part.to_csr()
    assert (m != m.T).nnz == 0
    with pytest.warns(DeprecationWarning, match="to_csr"):  # the old name stays as an alias
        assert (part.delaunay_matrix() != m).nnz == 0
    for i in range(0, 150, 11):
        others = np.delete(pts, i, axis=0)
        cell = dv.voronoi_cell(pts[i], others)
        mapped = np.where(cell.neighbors < i, cell.neighbors, cell.neighbors + 1)
        assert np.array_equal(np.sort(mapped), part.neighbors(i))
        assert cell.on_hull == bool(part.on_hull[i])
        # Bounded cells: every edge ends where the next one starts.
        if not cell.on_hull:
            ends = np.array([e.end for e in cell.edges])
            starts = np.array([e.start for e in cell.edges])
            assert np.allclose(np.roll(starts, -1, axis=0), ends, rtol=0, atol=1e-12)


def test_bad_input():
    with pytest.raises(ValueError, match=r"points\[1, 0\]"):
        dv.voronoi_cells(np.array([[0.0, 0.0], [np.nan, 1.0]]))
    with pytest.raises(dv.CoincidentError, match=r"points\[0\] and points\[2\]"):
        dv.voronoi_cells(np.array([[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]]))
    with pytest.raises(ValueError, match="inner"):
        dv.voronoi_cells(np.zeros((0, 2)), inner="qhull")
    assert len(dv.voronoi_cells(np.zeros((0, 2)))) == 0
    one = dv.voronoi_cells(np.array([[3.0, 4.0]]))
    assert bool(one.on_hull[0]) and len(one.indices) == 0


def test_two_far_clusters(oracle):
    # Two clusters 1e9 apart: a sparse grid index and sensing radii that grow across the gap.
    rng = np.random.default_rng(5)
    pts = rng.uniform(0.0, 1.0, (120, 2))
    pts[60:, 0] += 1e9
    check(oracle, pts, "two far clusters")


def box_around(points: np.ndarray, margin: float, shift=(0.0, 0.0)):
    lo, hi = points.min(axis=0), points.max(axis=0)
    span = float(np.max(hi - lo)) or 1.0
    return (lo[0] - margin * span + shift[0], lo[1] - margin * span + shift[1],
            hi[0] + margin * span + shift[0], hi[1] + margin * span + shift[1])


def box_area(box) -> float:
    return (box[2] - box[0]) * (box[3] - box[1])


@pytest.mark.parametrize("seed", range(4))
def test_clipped_areas_match_cgal_and_sum_to_the_box(oracle, seed):
    # Boxes around the agents, one that cuts through them, on random points, an integer grid (exact
    # cocircularities, bisectors through box corners) and a far-offset copy.
    cases = [("random", random_points(seed, 300)), ("grid", grid_points(seed, 150, 14)),
             ("far offset", random_points(seed, 200) * 1e-3 + np.array([1e7, -3e6]))]
    for label, pts in cases:
        for box in (box_around(pts, 0.1), box_around(pts, -0.2, shift=(0.05, 0.0)), box_around(pts, 0.0)):
            want = np.asarray(oracle(pts, 1.0, box)["clipped_areas"])
            for inner in ("scan", "evt"):
                part = dv.voronoi_cells(pts, inner=inner, bounds=box, workers=2)
                scale = box_area(box)
                assert np.allclose(part.areas, want, rtol=1e-9, atol=1e-12 * scale), \
                    f"{label} {box} [{inner}]: worst {np.max(np.abs(part.areas - want)):.3g}"
                assert abs(part.areas.sum() - scale) <= 1e-9 * scale
                # The clipped polygon of cell(i) agrees with the partition's area and neighbours.
                for i in range(0, len(pts), 37):
                    c = part.cell(i)
                    assert c.clipped is not None and c.area == pytest.approx(part.areas[i], rel=1e-12, abs=1e-15 * scale)
                    sides = set(c.clipped.side_neighbors.tolist()) - {-1}
                    assert sides <= set(part.neighbors(i).tolist())


def check_side_labels(points: np.ndarray, bounds, label: str) -> int:
    """Every side of every clipped cell carries the right label: a side labelled j lies on the bisector
    of i and j (both ends equidistant from p_i and p_j), a side labelled -1 on the box's boundary, and
    a side of positive length shared by i and j is listed by both. Returns the sides checked."""
    part = dv.voronoi_cells(points, bounds=bounds)
    scale = float(max(np.ptp(points, axis=0).max(), bounds[2] - bounds[0], bounds[3] - bounds[1]))
    tol = 1e-12 * scale
    shared = {}
    checked = 0
    for i in range(len(points)):
        c = part.cell(i).clipped
        v = c.vertices
        for k, j in enumerate(c.side_neighbors.tolist()):
            a, b = v[k], v[(k + 1) % len(v)]
            where = f"{label}: cell {i} side {k} {a.tolist()}->{b.tolist()} labelled {j}"
            if j >= 0:
                for q in (a, b):
                    di, dj = np.hypot(*(q - points[i])), np.hypot(*(q - points[j]))
                    assert abs(di - dj) <= tol, f"{where}: not on the bisector of {i} and {j}"
                length = float(np.hypot(*(b - a)))
                shared[(i, j)] = shared.get((i, j), 0.0) + length
            else:
                on = [abs(a[0] - bounds[0]) <= tol and abs(b[0] - bounds[0]) <= tol,
                      abs(a[0] - bounds[2]) <= tol and abs(b[0] - bounds[2]) <= tol,
                      abs(a[1] - bounds[1]) <= tol and abs(b[1] - bounds[1]) <= tol,
                      abs(a[1] - bounds[3]) <= tol and abs(b[1] - bounds[3]) <= tol]
                assert any(on), f"{where}: not on the boundary of {bounds}"
            checked += 1
    for (i, j), length in shared.items():
        if length > tol:
            assert shared.get((j, i), 0.0) == pytest.approx(length, rel=1e-9, abs=tol), \
                f"{label}: cell {i} has a side of length {length:.3g} on the bisector with {j}, cell {j} not"
    return checked


def test_clipped_sides_labelled_when_a_vertex_lies_on_the_box():
    # Issue 20: the Voronoi vertex (70, 0) of these three agents lies on the box's bottom edge; the
    # sides leaving it along a bisector kept the label of the side before.
    pts = np.array([[55.0, 5.0], [85.0, 5.0], [65.0, 15.0]])
    box = (0.0, 0.0, 110.0, 50.0)
    part = dv.voronoi_cells(pts, bounds=box)

    def label_at(clipped, v):  # vertices are constructions (docs/guarantees.md): near, not equal
        at = np.linalg.norm(clipped.vertices - np.asarray(v), axis=1)
        assert at.min() <= 1e-12 * 110.0
        return int(clipped.side_neighbors[int(np.argmin(at))])

    assert [label_at(part.cell(i).clipped, (70.0, 0.0)) for i in range(3)] == [2, -1, 1]
    check_side_labels(pts, box, "three agents")
    # The per-agent call (neighbour ids index `others`).
    assert label_at(dv.voronoi_cell(pts[0], pts[1:], bounds=box).clipped, (70.0, 0.0)) == 1
    assert label_at(dv.voronoi_cell(pts[2], pts[:2], bounds=box).clipped, (70.0, 0.0)) == 1


@pytest.mark.parametrize("seed", range(4))
def test_clipped_side_labels_on_lattices_and_random_boxes(seed):
    rng = np.random.default_rng(seed)
    checked = 0
    # Square and hexagonal lattices in boxes whose edges pass through Voronoi vertices (half-integers),
    # through agents (integers) and between them; boxes inside and around the lattice.
    k = 6 + seed
    square = np.array([[x, y] for x in range(k) for y in range(k)], dtype=np.float64)
    hexagonal = np.array([[x + 0.5 * (y % 2), y] for x in range(k) for y in range(k)], dtype=np.float64)
    for name, pts in (("square", square), ("hexagonal", hexagonal)):
        for _ in range(12):
            lo = rng.integers(-2, k // 2, size=2) * 0.5
            hi = lo + rng.integers(2, 2 * k, size=2) * 0.5
            checked += check_side_labels(pts, (lo[0], lo[1], hi[0], hi[1]), f"{name} {lo} {hi}")
    # Random integer points (circumcentres on half-integer box edges) and random reals.
    for t in range(8):
        pts = grid_points(100 * seed + t, 40, 12)
        lo = rng.integers(-1, 4, size=2) * 0.5
        hi = rng.integers(16, 26, size=2) * 0.5
        checked += check_side_labels(pts, (lo[0], lo[1], hi[0], hi[1]), f"grid {t}")
        pts = random_points(100 * seed + t, 60) * 10.0
        checked += check_side_labels(pts, (rng.uniform(-1, 3), rng.uniform(-1, 3), rng.uniform(7, 11),
                                           rng.uniform(7, 11)), f"random {t}")
    assert checked > 1000


def test_bounded_cells_measured_and_hull_cells_not_invented():
    pts = random_points(3, 400)
    part = dv.voronoi_cells(pts)
    assert np.array_equal(np.isnan(part.areas), part.on_hull)
    # Both inner steps build the same cells (vertices too, not only neighbours).
    evt = dv.voronoi_cells(pts, inner="evt")
    assert np.allclose(part.areas, evt.areas, rtol=1e-12, atol=0, equal_nan=True)
    assert np.allclose(part.centroids, evt.centroids, rtol=0, atol=1e-12, equal_nan=True)
    box = box_around(pts, 0.5)
    clipped = dv.voronoi_cells(pts, bounds=box)
    # A bounded cell whose vertices all lie inside the box is not changed by clipping.
    inside = [i for i in range(len(pts)) if not part.on_hull[i] and np.all(
        (part.polygon(i) > [box[0], box[1]]) & (part.polygon(i) < [box[2], box[3]]))]
    assert len(inside) > 300
    inner = np.array(inside)
    assert np.allclose(part.areas[inner], clipped.areas[inner], rtol=1e-12)
    assert np.allclose(part.centroids[inner], clipped.centroids[inner], rtol=0, atol=1e-12)
    # Hull cells: rays, no finite polygon without bounds.
    i = int(np.flatnonzero(part.on_hull)[0])
    cell = part.cell(i)
    assert cell.on_hull and cell.edges[0].from_infinity and cell.edges[-1].to_infinity
    assert part.polygon(i) is None and cell.clipped is None
    assert np.isnan(cell.area)


def test_polygon_bounds_and_single_agent():
    pts = random_points(11, 250)
    hexagon = np.array([[np.cos(a), np.sin(a)] for a in np.linspace(0, 2 * np.pi, 7)[:-1]]) * 0.8 + 0.5
    area = 0.5 * abs(np.dot(hexagon[:, 0], np.roll(hexagon[:, 1], -1)) - np.dot(hexagon[:, 1], np.roll(hexagon[:, 0], -1)))
    for poly in (hexagon, hexagon[::-1]):  # either orientation
        part = dv.voronoi_cells(pts, bounds=poly)
        assert part.areas.sum() == pytest.approx(area, rel=1e-12)
        assert np.all(part.areas >= 0.0)
    # A box given as a polygon is the same region as the box.
    box = (-0.1, -0.1, 1.1, 1.1)
    as_poly = np.array([[-0.1, -0.1], [1.1, -0.1], [1.1, 1.1], [-0.1, 1.1]])
    assert np.allclose(dv.voronoi_cells(pts, bounds=box).areas, dv.voronoi_cells(pts, bounds=as_poly).areas,
                       rtol=0, atol=1e-15)
    # One agent: the same clipped cell as in the partition.
    part = dv.voronoi_cells(pts, bounds=box)
    for i in (0, 7, 100):
        cell = dv.voronoi_cell(pts[i], np.delete(pts, i, axis=0), bounds=box)
        assert cell.area == pytest.approx(part.areas[i], rel=1e-12, abs=1e-16)


def test_closed_rings_are_the_same_polygon():
    # A polygon whose last vertex repeats the first (GeoJSON, shapely) is the open polygon, for
    # voronoi_cells and voronoi_cell as for coverage.lloyd and the grid diagram. Before: voronoi_cells
    # refused it ("vertices 4 and 0 coincide") while lloyd accepted it.
    pts = random_points(3, 60)
    square = [[0, 0], [1, 0], [1, 1], [0, 1]]
    want = dv.voronoi_cells(pts, bounds=(0, 0, 1, 1))
    ring = square + [square[0]]
    got = dv.voronoi_cells(pts, bounds=ring)
    np.testing.assert_array_equal(got.areas, want.areas)
    np.testing.assert_array_equal(got.bounds, want.bounds)
    np.testing.assert_allclose(dv.voronoi_cells(pts, bounds=ring[::-1]).areas, want.areas, rtol=1e-14)
    assert dv.voronoi_cell(pts[0], pts[1:], bounds=ring).area == pytest.approx(want.areas[0], rel=1e-14)
    run = dv.coverage.lloyd(pts, 0.2, steps=3, bounds=square + [square[0]])
    np.testing.assert_array_equal(run.trajectory, dv.coverage.lloyd(pts, 0.2, steps=3, bounds=square).trajectory)


def test_bad_bounds():
    pts = random_points(1, 20)
    with pytest.raises(ValueError, match="bounds.*xmin < xmax"):
        dv.voronoi_cells(pts, bounds=(1.0, 0.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="bounds.*not convex"):
        dv.voronoi_cells(pts, bounds=[[0, 0], [1, 1], [1, 0], [0, 1]])
    with pytest.raises(ValueError, match="bounds.*finite"):
        dv.voronoi_cells(pts, bounds=(0.0, 0.0, np.inf, 1.0))
    with pytest.raises(ValueError, match="bounds"):
        dv.voronoi_cells(pts, bounds=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="bounds.*three vertices"):
        dv.voronoi_cell(pts[0], pts[1:], bounds=[[0, 0], [1, 1], [2, 2]])
    with pytest.raises(ValueError, match="method"):
        dv.voronoi_cells(pts, method="qhull")


def test_json_and_geojson_round_trip(tmp_path):
    import json
    pts = random_points(2, 60)
    part = dv.voronoi_cells(pts, bounds=(-0.5, -0.5, 1.5, 1.5))
    doc = json.loads(part.to_json())
    assert doc["indices"] == part.indices.tolist() and doc["bounds"] == part.bounds.tolist()
    assert np.allclose(doc["areas"], part.areas)
    gj = json.loads(part.to_geojson())
    assert len(gj["features"]) == 60
    for f in gj["features"]:
        ring = np.array(f["geometry"]["coordinates"][0])
        assert np.array_equal(ring[0], ring[-1])
        shoelace = 0.5 * np.sum(ring[:-1, 0] * ring[1:, 1] - ring[1:, 0] * ring[:-1, 1])
        assert shoelace == pytest.approx(f["properties"]["area"], rel=1e-12)
    unb = json.loads(dv.voronoi_cells(pts).to_geojson())
    hull = [f for f in unb["features"] if f["properties"]["on_hull"]]
    assert hull and all(f["geometry"] is None and f["properties"]["area"] is None for f in hull)


def test_every_worker_count_gives_the_same_bits():
    # Blocks of 2048 agents go to the threads as they come free; a cell's clipping order (and so its
    # area's rounding) must not depend on which agent the thread did before. Uniform and clustered
    # (many agents deferred to the triangulation pass); 60,000 agents: enough blocks to interleave.
    rng = np.random.default_rng(3)
    centres = rng.uniform(0, 1, (50, 2))
    for pts in (rng.uniform(0, 1, (60000, 2)), centres[rng.integers(0, 50, 60000)] + rng.normal(0, 0.01, (60000, 2))):
        ref = dv.voronoi_cells(pts, workers=1)
        for _ in range(3):
            part = dv.voronoi_cells(pts, workers=2)
            for name in ("areas", "centroids"):  # NaN for unbounded hull cells
                assert np.array_equal(getattr(part, name), getattr(ref, name), equal_nan=True), name
            for name in ("indptr", "indices", "on_hull"):
                assert np.array_equal(getattr(part, name), getattr(ref, name)), name
