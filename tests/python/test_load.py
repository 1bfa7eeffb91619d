"""dv.load(path): every result JSON that Python or the dvoronoi CLI writes reads back.

Limited and exact partitions and network simulations come back as full result objects, rebuilt from
the inputs the file records and checked against it; the other kinds as read-only LoadedResult.
Anything else is refused with an error naming the file.
"""
from __future__ import annotations

import json
import os
import pickle
import shutil
import subprocess

import numpy as np
import pytest

import dvoronoi as dv

RNG = np.random.default_rng(22)
P = RNG.random((60, 2))


def _cli():
    env = os.environ.get("DVORONOI_CLI")
    return env if env else shutil.which("dvoronoi")


CLI = _cli()
needs_cli = pytest.mark.skipif(CLI is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)")


def run(*args):
    r = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return r


def points_file(tmp_path, pts=P):
    path = tmp_path / "pts.txt"
    path.write_text("".join(f"{float(x)!r} {float(y)!r}\n" for x, y in pts))
    return path


def same_partition(a, b, names):
    assert type(a) is type(b)
    for name in names:
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        assert x.dtype == y.dtype and np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), name
    assert json.loads(a.to_json()) == json.loads(b.to_json())


LIMITED = ["points", "indptr", "indices", "areas", "perimeters", "centroids", "piece_ptr", "piece_x", "piece_span"]
EXACT = ["points", "indptr", "indices", "on_hull", "areas", "centroids", "radius_steps", "agents_used"]


@pytest.mark.parametrize("method", ["auto", "scan", "chords"])
def test_limited_partition_from_python(tmp_path, method):
    r = dv.limited_cells(P, 0.15, method=method)
    r.to_json(tmp_path / "r.json", indent=2)
    s = dv.load(tmp_path / "r.json")
    same_partition(r, s, LIMITED)
    assert s.radius == r.radius and s.method == r.method
    assert np.array_equal(s.cell(7).vertices, r.cell(7).vertices)


@pytest.mark.parametrize("bounds", [None, (0.0, 0.0, 1.0, 1.0), [[-0.1, -0.1], [1.2, 0.0], [0.5, 1.3]]])
@pytest.mark.parametrize("inner", ["auto", "evt"])
def test_voronoi_partition_from_python(tmp_path, bounds, inner):
    r = dv.voronoi_cells(P, inner=inner, bounds=bounds)
    r.to_json(tmp_path / "v.json")
    s = dv.load(str(tmp_path / "v.json"))
    same_partition(r, s, EXACT)
    assert s.inner == r.inner


@needs_cli
def test_partitions_from_cli(tmp_path):
    pts = points_file(tmp_path)
    run("cells", pts, "-r", 0.15, "--method", "chords", "-o", tmp_path / "c.json", "-q")
    c = dv.load(tmp_path / "c.json")
    same_partition(c, dv.limited_cells(P, 0.15, method="chords"), LIMITED)
    run("voronoi", pts, "--bounds", 0, 0, 1, 1, "-o", tmp_path / "v.json", "-q")
    v = dv.load(tmp_path / "v.json")
    same_partition(v, dv.voronoi_cells(P, bounds=(0, 0, 1, 1)), EXACT)


def test_a_file_that_disagrees_with_its_inputs_is_refused(tmp_path):
    doc = json.loads(dv.limited_cells(P, 0.15).to_json())
    doc["indices"][0] = (doc["indices"][0] + 1) % len(P)
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"edited\.json.*differs at indices\[0\]"):
        dv.load(path)
    del doc["radius"]
    path.write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"edited\.json.*'radius'"):
        dv.load(path)


NETWORK = ["points", "links", "indptr", "indices", "sent", "received", "areas", "centroids", "piece_ptr",
           "piece_neighbor", "piece_x", "piece_y", "piece_span"]


@pytest.mark.parametrize("algorithm,kwargs", [
    ("cc", dict(seed=1)),
    ("cc", dict(seed=3, loss=0.2, bounds=(0, 0, 100, 100), forward=False, routing="shortest", adjacency_cap=3)),
    ("bd07", dict(route_discovery=False, verify=False, obstacles=[[20, 20, 60, 25]])),
    ("bs", dict(anchor_fraction=0.3, seed=5, dv_hop="async", anchors_relay=True)),
    ("bs", dict(radius=9.0, anchors=[0, 5, 9], budget=10**6)),
], ids=["cc", "cc-options", "bd07-options", "bs-dv-hop", "bs-anchors"])
def test_network_runs_come_back_as_full_results(tmp_path, algorithm, kwargs):
    r = dv.network.simulate(algorithm, P * 100, 30.0, **kwargs)
    r.to_json(tmp_path / "n.json")
    s = dv.load(tmp_path / "n.json")
    same_partition(r, s, NETWORK)
    assert s.to_json() == r.to_json() and s.to_geojson() == r.to_geojson()
    assert s.total_transmissions == r.total_transmissions and s.message_types == r.message_types
    assert s.cell(len(P) // 2).vertices.tolist() == r.cell(len(P) // 2).vertices.tolist()
    t = pickle.loads(pickle.dumps(s))
    assert type(t) is type(r) and t.to_json() == r.to_json()
    if algorithm == "bs":
        assert np.array_equal(s.positions, r.positions, equal_nan=True) and s.localized.tolist() == r.localized.tolist()
    else:
        assert s.condition == r.condition and s.bounds == r.bounds


def test_a_network_file_that_disagrees_with_its_run_is_refused(tmp_path):
    doc = json.loads(dv.network.simulate("cc", P * 100, 30.0, seed=1).to_json())
    path = tmp_path / "edited.json"
    doc["sent"][3][0] += 1
    path.write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"edited\.json.*differs at sent\[3\]\[0\]"):
        dv.load(path)
    doc["options"]["routing"] = "teleport"
    path.write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"edited\.json.*routing"):
        dv.load(path)
    # A file written before the options were recorded still reads back, as a read-only result.
    del doc["options"]
    path.write_text(json.dumps(doc))
    old = dv.load(path)
    assert isinstance(old, dv.LoadedResult) and old.kind == "network_cc" and old.neighbors(5).tolist() == doc[
        "indices"][doc["indptr"][5]:doc["indptr"][6]]


def _read_only_checks(loaded, kind, ref_doc):
    assert isinstance(loaded, dv.LoadedResult) and loaded.kind == kind
    assert json.loads(loaded.to_json()) == ref_doc
    with pytest.raises(AttributeError, match="read-only"):
        loaded.kind = "x"
    for name, value in ref_doc.items():  # every field is there; numeric lists as read-only arrays
        got = loaded[name]
        if name not in ("neighbors", "fields", "path"):  # names of methods/properties
            assert getattr(loaded, name) is got
        if isinstance(got, np.ndarray):
            assert not got.flags.writeable and got.tolist() == value, name
        else:
            assert got == value, name
    assert json.loads(pickle.loads(pickle.dumps(loaded)).to_json()) == ref_doc
    for name in ref_doc:  # emptying the parsed fields handed out does not change what the result writes
        if isinstance(loaded[name], (dict, list)):
            loaded[name].clear()
    assert json.loads(loaded.to_json()) == ref_doc


def test_read_only_kinds_from_python(tmp_path):
    d = np.linalg.norm(P[:, None] - P[None], axis=-1)
    run_ = dv.coverage.lloyd(P, 0.15, steps=3, bounds=(0, 0, 1, 1))
    results = {
        "limited_cell": dv.limited_cell(P[0], P[1:], 0.2),
        "distance_neighbors": dv.neighbors_from_distances(d),
        "lloyd": run_,
        "grid_voronoi": dv.grid_voronoi([{"type": "circle", "center": [30, 40], "radius": 8},
                                         {"type": "point", "position": [75, 75]}],
                                        area=(0, 0, 100, 100), cells=32),
    }
    occupied = np.zeros((30, 40), dtype=bool)
    occupied[10:20, 15:25] = True
    medial = dv.grid_voronoi(occupied, resolution=0.5)  # an occupancy grid's medial diagram
    path = tmp_path / "medial.json"
    medial.to_json(path)
    _read_only_checks(dv.load(path), "grid_voronoi", json.loads(path.read_text()))
    for kind, r in results.items():
        path = tmp_path / f"{kind}.json"
        text = r.to_json()
        path.write_text(text)
        loaded = dv.load(path)
        _read_only_checks(loaded, kind, json.loads(text))
        if kind == "lloyd":  # JSON with the agents' relation
            assert len(loaded) == len(r)
            for i in (0, 13, 59):
                assert loaded.neighbors(i).tolist() == r.neighbors(i).tolist()
            assert (loaded.to_csr() != r.to_csr()).nnz == 0
    with pytest.raises(AttributeError, match="no neighbour relation"):
        dv.load(tmp_path / "grid_voronoi.json").neighbors(0)


@needs_cli
def test_other_kinds_from_cli(tmp_path):
    pts = points_file(tmp_path)
    run("lloyd", pts, "-r", 0.15, "--steps", 3, "--bounds", 0, 0, 1, 1, "-o", tmp_path / "l.json", "-q")
    loaded = dv.load(tmp_path / "l.json")
    ref = dv.coverage.lloyd(P, 0.15, steps=3, bounds=(0, 0, 1, 1))
    assert loaded.kind == "lloyd" and np.array_equal(loaded.points, ref.points)
    assert loaded.cost.tolist() == ref.cost.tolist()
    big = points_file(tmp_path, P * 100)
    run("network", "cc", big, "--range", 30, "--seed", 1, "-o", tmp_path / "n.json", "-q")
    net = dv.load(tmp_path / "n.json")
    ref_net = dv.network.simulate("cc", P * 100, 30.0, seed=1)
    assert isinstance(net, dv.network.CcResult) and net.to_json() == ref_net.to_json()
    obstacles = tmp_path / "obstacles.json"
    obstacles.write_text(json.dumps({"area": {"box": [0, 0, 100, 100]}, "obstacles": [
        {"type": "circle", "center": [30, 40], "radius": 8}, {"type": "point", "position": [75, 75]}]}))
    run("gvd", obstacles, "--grid", 32, "-o", tmp_path / "g.json", "-q")
    g = dv.load(tmp_path / "g.json")
    assert g.kind == "grid_voronoi" and g.n_obstacles == 2 and len(g.cells["col"]) > 0


@pytest.mark.parametrize("text,message", [
    ("not json {", "not a JSON file"),
    ('{"type": "FeatureCollection", "features": []}', "GeoJSON export"),
    ('{"kind": "teapot"}', "'teapot'"),
    ("[1, 2, 3]", "not a dvoronoi result"),
])
def test_anything_else_is_refused_naming_the_file(tmp_path, text, message):
    path = tmp_path / "odd.json"
    path.write_text(text)
    with pytest.raises(ValueError, match=message) as e:
        dv.load(path)
    assert str(path) in str(e.value)
    with pytest.raises(FileNotFoundError):
        dv.load(tmp_path / "missing.json")
