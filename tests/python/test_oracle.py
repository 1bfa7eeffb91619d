"""dvoronoi against the exact CGAL oracle (tests/oracle, run as an executable): limited-neighbour sets
equal as sets, areas to 1e-9 relative, both methods; random inputs over seeds and densities, integer
grids (exact degeneracies), the degenerate corpus (tests/data/degenerate_corpus.txt) and the Intel lab
motes. With a radius larger than the point set, limited neighbours are the Voronoi neighbours."""
from __future__ import annotations

import math

import numpy as np
import pytest

import dvoronoi as dv
from conftest import CORPUS, grid_points, neighbor_sets, random_points, read_corpus

METHODS = ["auto", "scan", "chords"]
AREA_RTOL = 1e-9


def area_tolerance(area: np.ndarray) -> np.ndarray:
    """1e-9 relative: areas are measured in each agent's own frame, so they do not lose accuracy far
    from the origin (coordinates near 1e7, spacings near 1e-9)."""
    return AREA_RTOL * area


def compare(oracle, points: np.ndarray, radius: float, label: str) -> None:
    exact = oracle(points, radius)
    assert exact["n"] == len(points), label
    want = [set(nb) for nb in exact["limited_neighbors"]]
    want_areas = np.asarray(exact["limited_areas"], dtype=float)
    for method in METHODS:
        part = dv.limited_cells(points, radius, method=method)
        got = neighbor_sets(part.indptr, part.indices)
        bad = [i for i in range(len(points)) if got[i] != want[i]]
        assert not bad, (f"{label} [{method}]: limited neighbours differ at agents {bad[:10]}; "
                         f"first: got {sorted(got[bad[0]])}, exact {sorted(want[bad[0]])}")
        err = np.abs(part.areas - want_areas)
        tol = area_tolerance(want_areas)
        worst = int(np.argmax(err / tol)) if len(err) else 0
        assert np.all(err <= tol), (f"{label} [{method}]: area of agent {worst} is {part.areas[worst]!r}, "
                                    f"exact {want_areas[worst]!r}")
        if "limited_centroids" in exact and len(points):
            want_c = np.asarray(exact["limited_centroids"], dtype=float)
            cerr = np.linalg.norm(part.centroids - want_c, axis=1)
            # A centroid is a point of the caller's frame: it cannot be closer than ~ulp(|p|).
            ctol = 1e-9 * radius + 4.0 * np.finfo(float).eps * float(np.max(np.abs(points)))
            assert np.all(cerr <= ctol), f"{label} [{method}]: centroid of agent {int(np.argmax(cerr))}"


# ---------------------------------------------------------------------------- random inputs


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("n,mean_neighbours", [(30, 1.0), (200, 3.0), (500, 8.0), (300, 30.0)])
def test_random(oracle, seed, n, mean_neighbours):
    # Radius for the wanted mean number of agents within 2R in the unit square.
    radius = 0.5 * math.sqrt(mean_neighbours / (math.pi * n))
    compare(oracle, random_points(100 * seed + n, n), radius, f"random n={n} seed={seed}")


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("radius", [0.5, 1.0, 1.25, 2.5, 5.0])
def test_integer_grid(oracle, seed, radius):
    # Random nodes of an integer grid: exact cocircularities, collinearities and distances of 2R.
    compare(oracle, grid_points(seed, 120, 15), radius, f"grid seed={seed} R={radius}")


@pytest.mark.parametrize("seed", range(3))
def test_far_from_origin(oracle, seed):
    pts = random_points(seed, 200, scale=20.0) + np.array([1e7, -1e7])
    compare(oracle, pts, 1.5, f"offset 1e7 seed={seed}")


@pytest.mark.parametrize("seed", range(3))
def test_voronoi_neighbours_at_huge_radius(oracle, seed):
    pts = random_points(seed + 7, 150)
    exact = oracle(pts, 100.0)
    want = [set(nb) for nb in exact["voronoi_neighbors"]]
    assert [set(nb) for nb in exact["limited_neighbors"]] == want
    for method in METHODS:
        part = dv.limited_cells(pts, 100.0, method=method)
        assert neighbor_sets(part.indptr, part.indices) == want


# ---------------------------------------------------------------------------- named data


def _corpus_cases():
    cases = read_corpus()
    if not cases:
        return [pytest.param(None, None, None, marks=pytest.mark.skip(reason=f"{CORPUS} not found"))]
    return [pytest.param(name, radius, pts, id=name) for name, radius, pts in cases]


@pytest.mark.parametrize("name,radius,pts", _corpus_cases())
def test_degenerate_corpus(oracle, name, radius, pts):
    compare(oracle, pts, radius, f"corpus {name}")


@pytest.mark.parametrize("radius", [0.5, 1.5, 2.5, 3.0, 4.0, 10.0])
def test_intel_lab(oracle, intel, radius):
    compare(oracle, intel, radius, f"intel lab R={radius}")


@pytest.mark.parametrize("radius", [0.05, 0.3, 2.0])
def test_two_far_clusters(oracle, radius):
    # Two clusters 1e9 apart: the grid index takes its sparse (sorted-cell) path.
    rng = np.random.default_rng(11)
    pts = rng.uniform(0.0, 1.0, (200, 2))
    pts[100:, 0] += 1e9
    compare(oracle, pts, radius, f"two far clusters R={radius}")
