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
    for inner in ("scan", "evt"):
        part = dv.voronoi_cells(points, inner=inner, threads=2)
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
    m = part.delaunay_matrix()
    assert (m != m.T).nnz == 0
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
