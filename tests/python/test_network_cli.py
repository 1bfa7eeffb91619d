"""`dvoronoi network cc|bd07|bs` run as a user would: the same answer and counts as the Python API,
CSV per node, an SVG picture, errors that name the argument or file:line:column and leave no output."""
from __future__ import annotations

import csv
import json
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import dvoronoi as dv


def _find_cli():
    env = os.environ.get("DVORONOI_CLI")
    if env:
        return env
    return shutil.which("dvoronoi")


CLI = _find_cli()
pytestmark = pytest.mark.skipif(CLI is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)")


def run(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.fixture
def network_files(tmp_path):
    rng = np.random.default_rng(21)
    pts = rng.uniform(0, 100, (70, 2))
    bars = dv.network.random_bars(rng, 15, 5.0, (0, 0, 100, 100))
    p = tmp_path / "nodes.txt"
    p.write_text("".join(f"{float(x)!r} {float(y)!r}\n" for x, y in pts))
    o = tmp_path / "bars.txt"
    o.write_text("# x0 y0 x1 y1\n" + "".join(" ".join(repr(float(v)) for v in b) + "\n" for b in bars))
    return pts, bars, p, o


def test_cc_matches_python_api(network_files, tmp_path):
    pts, bars, p, o = network_files
    out, svg = tmp_path / "cc.json", tmp_path / "cc.svg"
    r = run("network", "cc", p, "--range", 25, "--loss", 0.2, "--seed", 4, "--obstacles", o,
            "--bounds", 0, 0, 100, 100, "-o", out, "--svg", svg)
    assert r.returncode == 0, r.stderr
    doc = json.loads(out.read_text())
    py = dv.network.simulate("cc", pts, 25.0, loss=0.2, seed=4, obstacles=bars, bounds=(0, 0, 100, 100))
    assert doc["kind"] == "network_cc"
    assert doc["indices"] == py.indices.tolist() and doc["indptr"] == py.indptr.tolist()
    assert doc["sent"] == py.sent.tolist() and doc["total_transmissions"] == py.total_transmissions
    assert doc["condition"] == py.condition and doc["wrong_nodes"] == py.wrong_nodes.tolist()
    assert np.allclose(doc["areas"], py.areas)
    root = ET.parse(svg).getroot()
    assert root.tag.endswith("svg") and len(list(root.iter("{http://www.w3.org/2000/svg}circle"))) == 70


def test_bd07_and_bs_csv(network_files, tmp_path):
    pts, _, p, _ = network_files
    out = tmp_path / "bd.csv"
    r = run("network", "bd07", p, "--range", 30, "--bounds", 0, 0, 100, 100, "-o", out, "-q")
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader(out.open()))
    py = dv.network.simulate("bd07", pts, 30.0, bounds=(0, 0, 100, 100))
    assert len(rows) == 70
    # the columns of every CSV writer: 'agent' and the neighbour list (space-separated, ascending)
    assert [int(x["agent"]) for x in rows] == list(range(70))
    assert [[int(v) for v in x["neighbors"].split()] for x in rows] == [py.neighbors(i).tolist() for i in range(70)]
    # the older comma-separated --bounds is still read
    old = tmp_path / "bd_old.csv"
    assert run("network", "bd07", p, "--range", 30, "--bounds", "0,0,100,100", "-o", old, "-q").returncode == 0
    assert old.read_text() == out.read_text()
    assert [int(x["sent_probe"]) for x in rows] == py.sent[:, 1].tolist()
    assert sum(float(x["area"]) for x in rows) == pytest.approx(1e4, rel=1e-9)
    r = run("network", "bs", p, "--range", 20, "--anchor-fraction", 0.3, "-q")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["dv_hop_types"] == ["anchor_flood", "hop_size"] and len(doc["anchors"]) == 21
    r = run("network", "bs", p, "--range", 20, "-q")
    doc = json.loads(r.stdout)
    ref = dv.limited_cells(pts, 10.0)
    assert doc["indices"] == ref.indices.tolist()


def test_errors_name_the_argument_and_write_nothing(network_files, tmp_path):
    _, _, p, o = network_files
    out = tmp_path / "never.json"
    r = run("network", "cc", p, "--range", -3, "-o", out)
    assert r.returncode == 2 and "--range" in r.stderr and not out.exists()
    r = run("network", "cc", p, "--range", 20, "--loss", 1.5, "-o", out)
    assert r.returncode == 2 and "--loss" in r.stderr and not out.exists()
    r = run("network", "flood", p, "--range", 20)
    assert r.returncode == 2
    bad = tmp_path / "bad_bars.txt"
    bad.write_text("1 2 3 4\n5 6 x 8\n")
    r = run("network", "cc", p, "--range", 20, "--obstacles", bad, "-o", out)
    assert r.returncode == 2 and f"{bad}:2:" in r.stderr and not out.exists()
    for bounds in (["0,0,-1"], [0, 0, -1], [0, 0, "x", 1], [1, 0, 0, 1]):
        r = run("network", "bd07", p, "--range", 20, "--bounds", *bounds, "-o", out)
        assert r.returncode == 2 and "--bounds" in r.stderr and not out.exists(), bounds
    r = run("network", "bd07", p, "--range", 20, "--budget", 10, "-o", out)
    assert r.returncode == 1 and "budget" in r.stderr and not out.exists()
    geo = tmp_path / "never.geojson"
    r = run("network", "bs", p, "--range", 20, "--tolerance", -1, "-o", geo)
    assert r.returncode == 2 and "--tolerance" in r.stderr and not geo.exists()
    r = run("network", "bs", p, "--range", 20, "-o", tmp_path / "never.txt")
    assert r.returncode == 2 and "-o/--output" in r.stderr and ".geojson" in r.stderr


@pytest.mark.parametrize("cli_args, kwargs", [
    (["cc", "--range", 25, "--loss", 0.2, "--seed", 4, "--obstacles", "OBS", "--bounds", 0, 0, 100, 100],
     dict(algorithm="cc", comm_range=25.0, loss=0.2, seed=4, obstacles="OBS", bounds=(0, 0, 100, 100))),
    (["cc", "--range", 30, "--no-forward", "--routing", "shortest"],
     dict(algorithm="cc", comm_range=30.0, forward=False, routing="shortest")),
    (["bd07", "--range", 30, "--seed", 2, "--no-route-discovery", "--obstacles", "OBS"],
     dict(algorithm="bd07", comm_range=30.0, seed=2, route_discovery=False, obstacles="OBS")),
    (["bs", "--range", 20, "--anchor-fraction", 0.3, "--seed", 5, "--dv-hop-async"],
     dict(algorithm="bs", comm_range=20.0, anchor_fraction=0.3, seed=5, dv_hop="async")),
    (["bs", "--range", 25, "--radius", 9, "--loss", 0.1, "--obstacles", "OBS"],
     dict(algorithm="bs", comm_range=25.0, radius=9.0, loss=0.1, obstacles="OBS")),
], ids=["cc-bounds-obstacles", "cc-unbounded", "bd07-default-region", "bs-dv-hop", "bs-radius"])
def test_cli_and_python_write_the_same_document(network_files, tmp_path, cli_args, kwargs):
    # One run, one writer (io/network_json.hpp): the CLI's -o file and Python's to_json(path) are the
    # same bytes for the same run (anchors picked by anchor_fraction included).
    pts, bars, p, o = network_files
    out = tmp_path / "cli.json"
    r = run("network", cli_args[0], p, *[o if a == "OBS" else a for a in cli_args[1:]], "-o", out, "-q")
    assert r.returncode == 0, r.stderr
    kwargs = {k: (bars if v == "OBS" else v) for k, v in kwargs.items()}
    py = dv.network.simulate(points=pts, **kwargs)
    py.to_json(tmp_path / "py.json")
    assert (tmp_path / "py.json").read_text() == out.read_text()
    assert out.read_text() == py.to_json() + "\n"
    doc = json.loads(out.read_text())
    assert doc["kind"] == f"network_{cli_args[0]}" and doc["total_transmissions"] == py.total_transmissions
    # dv.load runs the recorded simulation again: the full result, the same document.
    loaded = dv.load(out)
    assert type(loaded) is type(py) and loaded.to_json() == py.to_json()
    # The cells' GeoJSON has one writer too (io/network_geojson.hpp).
    geo = tmp_path / "cli.geojson"
    r = run("network", cli_args[0], p, *[o if a == "OBS" else a for a in cli_args[1:]], "-o", geo, "-q")
    assert r.returncode == 0, r.stderr
    py.to_geojson(tmp_path / "py.geojson")
    assert (tmp_path / "py.geojson").read_text() == geo.read_text() == py.to_geojson() + "\n"
    assert json.loads(geo.read_text())["type"] == "FeatureCollection"
