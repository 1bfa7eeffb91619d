"""Every result pickles and loads back to an equal result (pickle, copy.deepcopy, multiprocessing).

Equal means: every public array equal (NaN where NaN), the JSON the result writes identical, and the
methods that read the compiled result (cells, neighbours, GeoJSON, paths) answering the same.
"""
import copy
import json
import multiprocessing
import pickle

import numpy as np
import pytest

import dvoronoi as dv

RNG = np.random.default_rng(7)
P = RNG.random((40, 2))
D = np.linalg.norm(P[:, None] - P[None], axis=-1)


def _same_arrays(a, b, names):
    for name in names:
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), name


def _round_trips(r):
    yield pickle.loads(pickle.dumps(r, protocol=pickle.HIGHEST_PROTOCOL))
    yield pickle.loads(pickle.dumps(r, protocol=2))
    yield copy.deepcopy(r)


CELL_ARRAYS = ["points", "indptr", "indices", "areas", "centroids", "piece_ptr", "piece_neighbor", "piece_x",
               "piece_y", "piece_span"]


@pytest.mark.parametrize("method", ["scan", "chords"])
def test_limited_partition(method):
    r = dv.limited_cells(P, 0.2, method=method)
    for s in _round_trips(r):
        assert type(s) is type(r) and s.radius == r.radius and s.method == r.method
        assert s._core.computed_by == r._core.computed_by
        _same_arrays(r, s, CELL_ARRAYS + ["perimeters", "candidates"])
        assert s.to_json() == r.to_json() and s.to_geojson() == r.to_geojson()
        for i in (0, 17, 39):
            assert np.array_equal(s.cell(i).vertices, r.cell(i).vertices)
            assert np.array_equal(s.neighbors(i), r.neighbors(i))
    # the pickle holds the arrays once, not once more per cached view
    _ = r.areas, r.points, r.piece_x
    assert len(pickle.dumps(r)) < 1.5 * len(pickle.dumps(dv.limited_cells(P, 0.2, method=method)))


def test_limited_cell():
    c = dv.limited_cell(P[0], P[1:], 0.3)
    for s in _round_trips(c):
        for name in ("center", "vertices", "neighbors", "piece_neighbor", "piece_x", "piece_y", "piece_span", "centroid"):
            assert np.array_equal(np.asarray(getattr(s, name)), np.asarray(getattr(c, name))), name
        assert (s.area, s.perimeter, s.radius, s.candidates, len(s)) == (c.area, c.perimeter, c.radius, c.candidates, len(c))
        assert s.to_json() == c.to_json()


@pytest.mark.parametrize("bounds", [None, (0.0, 0.0, 1.0, 1.0), [[0.1, 0.0], [1.0, 0.2], [0.5, 1.0]]])
def test_voronoi_partition(bounds):
    r = dv.voronoi_cells(P, bounds=bounds)
    for s in _round_trips(r):
        _same_arrays(r, s, ["points", "indptr", "indices", "on_hull", "areas", "centroids"])
        assert s._core.computed_by == r._core.computed_by
        assert s.to_json() == r.to_json()
        for i in (0, 5, 33):
            a, b = r.cell(i), s.cell(i)
            assert np.array_equal(a.neighbors, b.neighbors) and np.array_equal(a.vertices, b.vertices)
            assert a.on_hull == b.on_hull


def test_voronoi_cell():
    for bounds in (None, (0.0, 0.0, 1.0, 1.0)):
        c = dv.voronoi_cell(P[3], np.delete(P, 3, axis=0), bounds=bounds)
        for s in _round_trips(c):
            assert np.array_equal(s.vertices, c.vertices) and np.array_equal(s.neighbors, c.neighbors)
            assert s.on_hull == c.on_hull and s.radius_steps == c.radius_steps
            assert np.array_equal(np.asarray(s.centroid), np.asarray(c.centroid), equal_nan=True)
            assert (s.clipped is None) == (c.clipped is None)
            if c.clipped is not None:
                assert np.array_equal(s.clipped.vertices, c.clipped.vertices)


def test_distance_neighbors():
    r = dv.neighbors_from_distances(D)
    for s in _round_trips(r):
        assert len(s) == len(r)
        for i in range(len(r)):
            assert np.array_equal(s.neighbors(i), r.neighbors(i))
        assert s.to_json() == r.to_json()


def test_grid_diagrams():
    doc = {"obstacles": [{"type": "polygon", "vertices": [[2, 2], [4, 2], [4, 4]]},
                         {"type": "circle", "center": [7, 7], "radius": 1}],
           "area": {"box": [0, 0, 10, 10]}}
    g = dv.grid_voronoi(doc, cells=96, diagram="labels")
    occ = np.zeros((48, 64), bool)
    occ[10:30, 20] = True
    occ[:, 0] = occ[0, :] = True
    m = dv.grid_voronoi(occ)
    def without_run_stats(text):  # a loaded labelled diagram is rebuilt: its timings are the new run's
        d = json.loads(text)
        d.pop("stats")
        return d

    for s in _round_trips(g):
        assert without_run_stats(s.to_json()) == without_run_stats(g.to_json())
        a, b = s.path((1, 1), (9, 9)), g.path((1, 1), (9, 9))
        assert np.array_equal(np.asarray(a[0] if isinstance(a, tuple) else a), np.asarray(b[0] if isinstance(b, tuple) else b))
    for s in _round_trips(m):
        assert np.array_equal(s.diagram_mask, m.diagram_mask) and s.to_json() == m.to_json()


def test_network_and_coverage_results():
    for alg in ("cc", "bd07", "bs"):
        r = dv.network.simulate(alg, P * 100, 30)
        s = pickle.loads(pickle.dumps(r))
        assert s.to_json() == r.to_json()
    lr = dv.coverage.lloyd(P, 0.3, steps=2, bounds=(0, 0, 1, 1))
    s = pickle.loads(pickle.dumps(lr))
    assert s.to_json() == lr.to_json() and np.array_equal(s.cost, lr.cost)


def _areas_sum(r):
    return float(np.sum(r.areas))


def test_results_cross_processes():
    """multiprocessing sends results back to the parent by pickling them."""
    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(1) as pool:
        r = pool.apply(dv.limited_cells, (P, 0.2))
    assert np.array_equal(r.areas, dv.limited_cells(P, 0.2).areas)


def test_bad_states_are_refused_clearly():
    r = dv.limited_cells(P, 0.2)
    core = r._core
    cls = type(core)
    bad = cls.__new__(cls)
    with pytest.raises(ValueError, match="format 99"):
        bad.__setstate__((99, {}))
    state = core.__getstate__()
    fields = dict(state[1])
    fields["areas"] = fields["areas"][:-1]
    with pytest.raises(ValueError, match="inconsistent lengths"):
        cls.__new__(cls).__setstate__((state[0], fields))
