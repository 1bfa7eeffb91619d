"""`dvoronoi neighbors-from-distances DISTFILE`, run as a user would: the same answer as the Python
API (and the exact one), JSON and CSV output, errors that name file:line:column, nothing written on
failure."""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest

import dvoronoi as dv
from conftest import random_points
from test_cli import CLI, run  # the executable and runner of the CLI tests

pytestmark = pytest.mark.skipif(CLI is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)")


def write_distances(path, points, radius=np.inf, squared=False, both=False):
    n = len(points)
    with open(path, "w") as f:
        f.write("# measured distances\ni j d\n")
        for i in range(n):
            for j in range(n) if both else range(i + 1, n):
                if i == j:
                    continue
                d2 = float(((points[i] - points[j]) ** 2).sum())
                if d2 < radius * radius:
                    f.write(f"{i} {j} {float(d2 if squared else np.sqrt(d2))!r}\n")


def test_json_equals_python_and_exact(tmp_path):
    pts = random_points(5, 80)
    path = tmp_path / "d.txt"
    write_distances(path, pts, both=True)
    proc = run("neighbors-from-distances", path, "-q")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    d = np.sqrt(((pts[:, None] - pts[None]) ** 2).sum(-1))
    res = dv.neighbors_from_distances(d)
    assert doc == json.loads(res.to_json())
    exact = dv.voronoi_cells(pts)
    for i in range(len(pts)):
        row = doc["indices"][doc["indptr"][i]:doc["indptr"][i + 1]]
        assert sorted(row) == exact.neighbors(i).tolist()
    assert doc["on_hull"] == exact.on_hull.tolist()


def test_csv_output_and_squared(tmp_path):
    pts = np.array([(x, y) for x in range(5) for y in range(4)], dtype=float)  # a lattice: degenerate
    path = tmp_path / "d.txt"
    write_distances(path, pts, squared=True)
    out = tmp_path / "out.csv"
    proc = run("neighbors-from-distances", path, "--squared", "-o", out, "-q")
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(open(out)))
    exact = dv.voronoi_cells(pts)
    assert len(rows) == len(pts)
    for i, r in enumerate(rows):
        assert int(r["robot"]) == i
        assert sorted(map(int, r["neighbors"].split())) == exact.neighbors(i).tolist()
        assert bool(int(r["on_hull"])) == bool(exact.on_hull[i])


@pytest.mark.parametrize("text,where,what", [
    ("0 1 1.0\n1 2 -1\n", ":2:5:", "must be positive"),
    ("0 1 1.0\n1 x 2.0\n", ":2:3:", "not a non-negative integer"),
    ("0 1 1.0\n1 2\n", ":2:", "expected 3 fields"),
    ("0 1 1.0\n1 0 2.0\n", ":2:1:", "differ"),
    ("0 1 1.0\n0 1 1.0\n", ":2:1:", "twice"),
    ("0 0 1.0\n", ":1:3:", "itself"),
    ("0 1 nan\n", ":1:5:", "not finite"),
])
def test_errors_name_file_line_column_and_write_nothing(tmp_path, text, where, what):
    path = tmp_path / "bad.txt"
    path.write_text(text)
    out = tmp_path / "out.json"
    proc = run("neighbors-from-distances", path, "-o", out)
    assert proc.returncode == 2
    assert f"{path}{where}" in proc.stderr and what in proc.stderr, proc.stderr
    assert not out.exists()
    assert list(tmp_path.iterdir()) == [path]  # no temporary file left behind


def test_average_and_n_and_usage_errors(tmp_path):
    path = tmp_path / "d.txt"
    path.write_text("0 1 1.0\n1 0 2.0\n1 2 1.0\n0 2 1.9\n")
    proc = run("neighbors-from-distances", path, "--average", "-n", "5", "-q")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["n"] == 5 and doc["indptr"][-1] == doc["indptr"][3]  # robots 3 and 4: nobody detected
    proc = run("neighbors-from-distances", path, "--average", "-n", "2")
    assert proc.returncode == 2 and ":3:1:" in proc.stderr
    proc = run("neighbors-from-distances", path, "-o", tmp_path / "x.geojson")
    assert proc.returncode == 2 and "GeoJSON" in proc.stderr
    proc = run("neighbors-from-distances", tmp_path / "missing.txt")
    assert proc.returncode == 2 and "missing.txt" in proc.stderr
