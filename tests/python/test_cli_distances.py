"""`dvoronoi neighbors-from-distances DISTFILE`, run as a user would: the same answer as the Python
API (and the exact one), JSON and CSV output, errors that name file:line:column, nothing written on
failure."""
from __future__ import annotations

import csv
import json
import resource
import subprocess
import time

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


def run_limited(*args, memory=1 << 30, timeout=60):
    """Runs the CLI with its address space capped (a run that sized memory by the largest robot ID
    fails instead of exhausting the machine's memory)."""
    def cap():
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=timeout, preexec_fn=cap)


def test_large_robot_ids_are_ids_not_sizes(tmp_path):
    # Issue 20: the one-line file below made the CLI allocate for 2e9 + 1 robots.
    path = tmp_path / "d.txt"
    path.write_text("0 2000000000 1\n")
    start = time.monotonic()
    proc = run_limited("neighbors-from-distances", path, "-q")
    assert proc.returncode == 0, proc.stderr
    assert time.monotonic() - start < 30
    doc = json.loads(proc.stdout)
    assert doc["n"] == 2 and doc["ids"] == [0, 2000000000]
    assert doc["indptr"] == [0, 1, 2] and doc["indices"] == [2000000000, 0]
    out = tmp_path / "out.csv"
    proc = run_limited("neighbors-from-distances", path, "-q", "-o", out)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(open(out)))
    assert [(r["robot"], r["neighbors"]) for r in rows] == [("0", "2000000000"), ("2000000000", "0")]


def write_id_distances(path, points, ids, radius=np.inf, squared=False):
    """write_distances with robot i named ids[i], lines in a shuffled order."""
    lines = []
    for i in range(len(points)):
        for j in range(i + 1, len(points)):
            d2 = float(((points[i] - points[j]) ** 2).sum())
            if d2 < radius * radius:
                lines.append(f"{ids[i]} {ids[j]} {float(d2 if squared else np.sqrt(d2))!r}\n")
    np.random.default_rng(3).shuffle(lines)
    path.write_text("".join(lines))


@pytest.mark.parametrize("squared", [False, True])
def test_serial_number_ids_give_the_renumbered_relation(tmp_path, squared):
    # Robots named by serial numbers (not in the order of their rows) answer as the same file
    # renumbered 0..n-1 in ascending ID order, with every robot mapped back to its ID.
    rng = np.random.default_rng(7)
    n = 60
    pts = np.array([(x, y) for x in range(6) for y in range(5)] + [tuple(p) for p in rng.integers(0, 40, (n, 2))],
                   dtype=float)
    pts = np.unique(pts, axis=0)
    rng.shuffle(pts)
    n = len(pts)
    ids = np.unique(rng.integers(1_000_000, 9_000_000_000_000, 2 * n))[:n]
    ids[:3] = [1_000_003, 1_000_017, 1_000_018]
    ids = rng.permutation(ids)  # robot i of `pts` is ids[i]; the file's order is not the ID order
    order = np.argsort(ids)     # the renumbering: ascending ID
    flags = ["--squared"] if squared else []
    write_id_distances(tmp_path / "ids.txt", pts, ids, radius=12.0, squared=squared)
    write_id_distances(tmp_path / "plain.txt", pts[order], np.arange(n), radius=12.0, squared=squared)
    by_id = json.loads(run("neighbors-from-distances", tmp_path / "ids.txt", "-q", *flags).stdout)
    plain = json.loads(run("neighbors-from-distances", tmp_path / "plain.txt", "-q", *flags).stdout)
    assert "ids" not in plain  # IDs exactly 0..n-1: the output as before
    assert by_id["ids"] == sorted(ids.tolist())
    sorted_ids = np.array(by_id["ids"])
    for key in ("n", "indptr", "on_hull", "path_length", "added", "detected", "consistency", "squared"):
        assert by_id[key] == plain[key], key
    assert by_id["indices"] == sorted_ids[plain["indices"]].tolist()  # same order along each path
    # The CSV names robots and neighbours by ID, rows in ascending ID order.
    proc = run("neighbors-from-distances", tmp_path / "ids.txt", "-q", "-o", tmp_path / "ids.csv", *flags)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(open(tmp_path / "ids.csv")))
    assert [int(r["robot"]) for r in rows] == by_id["ids"]
    for k, r in enumerate(rows):
        row = by_id["indices"][by_id["indptr"][k]:by_id["indptr"][k + 1]]
        assert list(map(int, r["neighbors"].split())) == row
    # With every pair measured and exact squared distances, the relation is the exact Voronoi relation
    # of the robots' positions, by ID.
    if not squared:
        return
    write_id_distances(tmp_path / "all.txt", pts, ids, squared=True)
    by_id = json.loads(run("neighbors-from-distances", tmp_path / "all.txt", "-q", "--squared").stdout)
    exact = dv.voronoi_cells(pts)
    position = {int(ids[i]): i for i in range(n)}
    for k, robot in enumerate(by_id["ids"]):
        row = by_id["indices"][by_id["indptr"][k]:by_id["indptr"][k + 1]]
        assert sorted(position[j] for j in row) == exact.neighbors(position[robot]).tolist()


def test_id_errors_name_robots_by_id(tmp_path):
    path = tmp_path / "d.txt"
    path.write_text("1000003 1000017 1.0\n1000017 1000003 2.0\n")
    proc = run("neighbors-from-distances", path)
    assert proc.returncode == 2 and ":2:1:" in proc.stderr and "(1000003, 1000017)" in proc.stderr, proc.stderr
