"""`dvoronoi gvd`: the same JSON as the Python API, SVG, a path, and errors that name the obstacle
and field or the file position, exit code 2, nothing written."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi.gvd_maps import mixed_shapes, random_mixed


def _find_cli():
    env = os.environ.get("DVORONOI_CLI")
    if env:
        return env if Path(env).is_file() else None
    return shutil.which("dvoronoi")


CLI = _find_cli()
pytestmark = pytest.mark.skipif(CLI is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)")


def run(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=120)


def test_cli_matches_python_for_every_worker_count(tmp_path):
    doc = random_mixed(3, 20)
    src = tmp_path / "map.json"
    src.write_text(json.dumps(doc))
    py = json.loads(dv.grid_voronoi(doc, cells=80, robot_radius=1.0).to_json())
    for k, mode in ((1, "cooperative"), (3, "independent"), (4, "cooperative")):
        out = tmp_path / f"o{k}.json"
        p = run("gvd", src, "--grid", 80, "--workers", k, "--mode", mode, "--robot-radius", 1.0, "-o", out, "-q")
        assert p.returncode == 0, p.stderr
        got = json.loads(out.read_text())
        assert got["cells"] == py["cells"] and got["vertices"] == py["vertices"] and got["roadmap"] == py["roadmap"]
        assert got["stats"]["workers"] == k and got["stats"]["mode"] == mode


def test_cli_svg_and_path(tmp_path):
    src = tmp_path / "map.json"
    src.write_text(json.dumps(mixed_shapes()))
    svg, out = tmp_path / "g.svg", tmp_path / "g.json"
    p = run("gvd", src, "--grid", 128, "-r", 1.5, "--path", 5, 5, 95, 95, "--svg", svg, "-o", out)
    assert p.returncode == 0, p.stderr
    assert "diagram cells" in p.stderr  # summary line
    root = ET.parse(svg).getroot()
    assert root.tag.endswith("svg")
    doc = json.loads(out.read_text())
    assert doc["path"]["found"] and doc["path"]["points"][0] == [5, 5] and doc["path"]["points"][-1] == [95, 95]
    pts = np.array(doc["path"]["points"])
    assert doc["path"]["length"] == pytest.approx(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


@pytest.mark.parametrize("text, message", [
    ('{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "circle", "center": [1, 1], "radius": 0}]}',
     r"map.json: obstacles\[0\].radius: must be a positive finite number, got 0"),
    ('{"area": {"box": [0, 0, 10, 10]},\n "obstacles": [\n  {"type": "point" "position": [1, 1]}]}', r"map.json:3:20: invalid JSON"),
    ('{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [1, 1]}, {"type": "polygon", "vertices": [[0, 0], [1, 1]]}]}',
     r"obstacles\[1\].vertices: needs at least 3 points"),
    # Before: the repeated key passed (the last one won), 1e999 failed without a place, and the NUL
    # byte cut the message at 'circ.
    ('{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [1, 1], "position": [2, 2]}]}',
     r"map.json:1:87: duplicate key 'position' in one object \(first at \S*map.json:1:67\)"),
    ('{"area": {"box": [0, 0, 10, 10]},\n "obstacles": [{"type": "circle", "center": [1, 1], "radius": -1e999}]}',
     r"map.json:2:63: number '-1e999' is beyond the range of a double"),
    ('{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "circ\\u0000le", "center": [1, 1]}]}',
     r"map.json: obstacles\[0\].type: unknown obstacle type 'circ\\0le' \(expected polygon"),
])
def test_cli_bad_input_names_the_field_and_writes_nothing(tmp_path, text, message):
    import re

    src = tmp_path / "map.json"
    src.write_text(text)
    out, svg = tmp_path / "o.json", tmp_path / "o.svg"
    p = run("gvd", src, "--grid", 16, "-o", out, "--svg", svg)
    assert p.returncode == 2
    assert re.search(message, p.stderr), p.stderr
    assert not out.exists() and not svg.exists()
    assert [f.name for f in tmp_path.iterdir()] == ["map.json"]  # no temporary files left


def test_cli_bad_arguments(tmp_path):
    src = tmp_path / "map.json"
    src.write_text(json.dumps(mixed_shapes()))
    for args, message in ((["--grid", 0], "--grid"), (["--grid", 8, "--workers", -1], "--workers"), ([], "--grid: required"),
                          (["--grid", 8, "--mode", "greedy"], "--mode"), (["--grid", 8, "-r", -1], "--robot-radius"),
                          (["--grid", 8, "-o", tmp_path / "x.csv"], "-o/--output"),
                          (["--grid", 64, "-r", 1.5, "--path", 45, 40.5, 95, 95], "--path: start")):
        p = run("gvd", src, *args)
        assert p.returncode == 2, (args, p.stderr)
        assert message in p.stderr
    p = run("gvd", tmp_path / "missing.json", "--grid", 8)
    assert p.returncode == 2 and "missing.json" in p.stderr


def test_cli_medial_diagram_of_an_obstacle_file_is_pythons(tmp_path):
    doc = mixed_shapes()
    src = tmp_path / "doc.json"
    src.write_text(json.dumps(doc))
    gv = dv.grid_voronoi(doc, cells=120, diagram="medial", robot_radius=0.2, min_separation=2, prune_length=5)
    assert len(gv) > 50
    out, svg = tmp_path / "m.json", tmp_path / "m.svg"
    r = run("gvd", src, "--grid", 120, "--diagram", "medial", "-r", 0.2, "--min-separation", 2, "--prune-length", 5,
            "-o", out, "--svg", svg)
    assert r.returncode == 0, r.stderr
    assert "obstacle file drawn on" in r.stderr
    assert json.loads(out.read_text()) == json.loads(gv.to_json())
    assert svg.read_text() == gv.to_svg()
    labels = json.loads(run("gvd", src, "--grid", 120, "-q").stdout)  # the default for obstacle files: labels
    assert "cells" in labels and "pixels" not in labels
    for args, message in ((["--diagram", "medial", "--mode", "independent"], "--diagram medial does not use them"),
                          (["--diagram", "medial", "--no-visibility"], "--diagram medial does not use them"),
                          (["--prune-length", "5"], "add --diagram medial"),
                          (["--unknown", "free"], "--resolution, --origin and --unknown are for map files"),
                          (["--origin", "1", "2"], "--resolution, --origin and --unknown are for map files"),
                          (["--diagram", "medial", "--min-separation", "40000"], "--min-separation: must be a number in [1, 32768]")):
        bad = tmp_path / "bad.json"
        r = run("gvd", src, "--grid", 120, *args, "-o", bad)
        assert r.returncode == 2 and message in r.stderr, (args, r.stderr)
        assert not bad.exists()
    # explicit defaults are not options of another input or diagram
    assert run("gvd", src, "--grid", 60, "--unknown", "occupied", "--prune-length", 8, "-q", "-o", tmp_path / "d.json").returncode == 0


def test_cli_labelled_diagram_without_path_or_cells_says_so(tmp_path):
    walls = tmp_path / "walls.json"  # two rooms: no free diagram cell joins them
    walls.write_text(json.dumps({"area": {"box": [0, 0, 10, 4]}, "obstacles": [
        {"type": "polygon", "vertices": [[4.5, -1], [5.5, -1], [5.5, 5], [4.5, 5]]}]}))
    r = run("gvd", walls, "--grid", 40, "-r", 0.6, "--path", 1, 2, 9, 2, "-q")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["path"] == {"found": False, "length": None, "points": []}
    full = tmp_path / "full.json"
    full.write_text(json.dumps({"area": {"box": [0, 0, 4, 4]}, "obstacles": [
        {"type": "polygon", "vertices": [[-1, -1], [5, -1], [5, 5], [-1, 5]]}]}))
    r = run("gvd", full, "--grid", 16, "-q")
    assert r.returncode == 0 and "gvd: warning: no diagram cell: the corners of every cell share one nearest obstacle" in r.stderr
