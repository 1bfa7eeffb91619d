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


# -- outputs never overwrite inputs; map files read whole or refused; inputs named for what they are --

ROOM = "type octile\nheight 8\nwidth 12\nmap\n" + "@" * 12 + "\n" + ("@" + "." * 10 + "@\n") * 6 + "@" * 12 + "\n"


def _ros_map(folder: Path) -> Path:
    grey = np.full((20, 30), 254, np.uint8)
    grey[:, 15] = 0
    (folder / "lab.pgm").write_bytes(b"P5\n30 20\n255\n" + grey.tobytes())
    (folder / "lab.yaml").write_text("image: lab.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return folder / "lab.yaml"


def test_cli_no_output_may_overwrite_an_input(tmp_path):
    # Before: each of these exited 0 and replaced the input (the map, the obstacle document, the
    # YAML's own image, the point file) with the output.
    (tmp_path / "in.map").write_text(ROOM)
    (tmp_path / "obs.json").write_text(json.dumps(mixed_shapes()))
    _ros_map(tmp_path)
    (tmp_path / "sub").mkdir()
    os.link(tmp_path / "in.map", tmp_path / "hard.svg")
    (tmp_path / "pts.csv").write_text("x,y\n1,1\n2,3\n4,1\n3,3.5\n")
    (tmp_path / "d.csv").write_text("0 1 1.5\n1 2 2.0\n0 2 2.5\n")
    (tmp_path / "poly.json").write_text("0 0\n10 0\n10 10\n0 10\n")
    frames = tmp_path / "frames"
    frames.mkdir()
    (frames / "step_000002.svg").write_text("1 1\n2 3\n4 1\n")  # a point file where a picture would go
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    cases = [
        (["gvd", "in.map", "-q", "-o", "out.json", "--svg", "in.map"], "--svg: 'in.map' is the same file as INPUT"),
        (["gvd", "in.map", "-q", "--svg", "sub/../in.map"], "--svg: 'sub/../in.map' is the same file as INPUT ('in.map')"),
        (["gvd", "in.map", "-q", "--svg", "hard.svg"], "--svg: 'hard.svg' is the same file as INPUT ('in.map')"),
        (["gvd", "obs.json", "-g", "50", "-o", "obs.json"], "-o/--output: 'obs.json' is the same file as INPUT"),
        (["gvd", "obs.json", "-g", "50", "--diagram", "medial", "-o", str(tmp_path / "obs.json")], "-o/--output: "),
        (["gvd", "lab.yaml", "-q", "--svg", "lab.pgm"], "--svg: 'lab.pgm' is the same file as the image of INPUT"),
        (["gvd", "lab.yaml", "-q", "--svg", "./sub/../lab.pgm"], "is the same file as the image of INPUT"),
        (["cells", "pts.csv", "-r", "1", "-q", "-o", "pts.csv"], "-o/--output: 'pts.csv' is the same file as POINTS"),
        (["cells", "pts.csv", "-r", "1", "-q", "--svg", "./pts.csv"], "--svg: './pts.csv' is the same file as POINTS"),
        (["voronoi", "pts.csv", "-q", "-o", "./pts.csv"], "-o/--output: './pts.csv' is the same file as POINTS"),
        (["network", "cc", "pts.csv", "-r", "3", "-q", "--svg", "pts.csv"], "--svg: 'pts.csv' is the same file as POINTS"),
        (["neighbors-from-distances", "d.csv", "-q", "-o", "d.csv"], "-o/--output: 'd.csv' is the same file as DISTFILE"),
        (["lloyd", "pts.csv", "-r", "1", "--steps", "2", "--polygon", "poly.json", "-q", "-o", "poly.json"],
         "-o/--output: 'poly.json' is the same file as --polygon"),
        (["lloyd", "frames/step_000002.svg", "-r", "1", "--steps", "2", "--bounds", "0", "0", "10", "10", "-q",
          "--svg-dir", "frames"], "--svg-dir: the picture 'frames/step_000002.svg' is the same file as POINTS"),
    ]
    for args, message in cases:
        p = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=tmp_path, timeout=120)
        assert p.returncode == 2 and message in p.stderr, (args, p.stderr)
        assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before, args  # nothing written
    # what is not an input still works: another name, and the pictures of other steps
    p = subprocess.run([CLI, "gvd", "lab.yaml", "-q", "--svg", "lab.svg", "-o", "lab.json"], capture_output=True,
                       text=True, cwd=tmp_path, timeout=120)
    assert p.returncode == 0 and (tmp_path / "lab.svg").exists() and json.loads((tmp_path / "lab.json").read_text()), p.stderr
    p = subprocess.run([CLI, "lloyd", "frames/step_000002.svg", "-r", "1", "--steps", "4", "--svg-every", "3", "--bounds",
                        "0", "0", "10", "10", "-q", "--svg-dir", "frames", "-o", "run.json"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert p.returncode == 0, p.stderr  # steps 0, 3 and 4 are drawn
    assert sorted(f.name for f in frames.iterdir()) == ["step_000000.svg", "step_000002.svg", "step_000003.svg",
                                                        "step_000004.svg"]
    assert (frames / "step_000002.svg").read_text() == "1 1\n2 3\n4 1\n"


def test_cli_svg_to_stdout_is_refused(tmp_path):
    # Before: `--svg -` wrote a file named '-' while `-o -` means stdout.
    (tmp_path / "room.map").write_text(ROOM)
    (tmp_path / "pts.csv").write_text("1 1\n2 3\n4 1\n")
    for args in (["gvd", "room.map", "-q", "-o", "out.json", "--svg", "-"], ["cells", "pts.csv", "-r", "1", "-q", "--svg", "-"],
                 ["voronoi", "pts.csv", "-q", "--svg", "-"], ["network", "cc", "pts.csv", "-r", "3", "-q", "--svg", "-"]):
        p = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=tmp_path, timeout=120)
        assert p.returncode == 2 and "--svg: '-' (stdout) is for -o/--output's JSON" in p.stderr, (args, p.stderr)
        assert sorted(f.name for f in tmp_path.iterdir()) == ["pts.csv", "room.map"], args


def test_cli_pgm_raster_must_match_its_header(tmp_path):
    # Before: a raster longer than W x H was read sheared (its extra pixels dropped) and samples above
    # the maximum grey value were clipped, both with exit code 0.
    img = np.full((20, 31), 254, np.uint8)
    img[:, 15] = 0
    cases = [
        (b"P5\n30 20\n255\n" + img.tobytes(), "shear.pgm: the PGM raster is longer than its header's 30 x 20 pixels (20 bytes after"),
        (b"P5\r\n3 1\r\n255\r\n\xfe\x00\xfe", "the header ends in CR LF, but one whitespace character ends a P5 header"),
        (b"P5\n3 1\n100\n\x00\x96\x00", "shear.pgm: PGM pixel value 150 exceeds the maximum grey value 100 (row 0, column 1)"),
        (b"P2\n3 1\n100\n0 150 999\n", "shear.pgm:4:3: PGM pixel value '150' exceeds the maximum grey value 100 (row 0, column 1)"),
        (b"P2\n2 2\n255\n0 1\n2 3 # four values\n4\n", "shear.pgm:6:1: the PGM raster is longer than its header's 2 x 2 pixels ('4' after"),
    ]
    for data, message in cases:
        (tmp_path / "shear.pgm").write_bytes(data)
        p = run("gvd", tmp_path / "shear.pgm", "-q", "-o", tmp_path / "out.json")
        assert p.returncode == 2 and message in p.stderr, (data[:20], p.stderr)
        assert not (tmp_path / "out.json").exists()
    # exact rasters (comments after a plain one, the maximum itself) are read
    for data in (b"P2\n2 1\n100\n0 100\n# end\n", b"P5\n2 1\n100\n\x00\x64"):
        (tmp_path / "ok.pgm").write_bytes(data)
        p = run("gvd", tmp_path / "ok.pgm", "-q")
        assert p.returncode == 0 and json.loads(p.stdout)["map"]["cols"] == 2, p.stderr


def test_cli_inputs_named_for_what_they_are(tmp_path):
    # Before: a JPEG, a missing file and a folder named like a map got "--grid: required" or a
    # truncated header; now the first word is about the file.
    import cv2

    cv2.imwrite(str(tmp_path / "office.jpg"), np.full((20, 20), 254, np.uint8))
    for name in ("dir.pgm", "d.yaml", "d.map", "d.png", "plain"):
        (tmp_path / name).mkdir()
    cases = [(["office.jpg"], "office.jpg: neither a map file nor an obstacle document (not JSON): maps are read from "
                              ".yaml/.yml (map_server), .pgm, .png and .map (MovingAI) files"),
             (["no_such_map"], "no_such_map: cannot open file: it does not exist"),
             (["no_such_map.json", "--grid", "8"], "no_such_map.json: cannot open file: it does not exist"),
             (["nope.pgm"], "nope.pgm: cannot open file: it does not exist")]
    cases += [([name], f"'{name}' is a folder: give a map file") for name in ("dir.pgm", "d.yaml", "d.map", "d.png", "plain")]
    for args, message in cases:
        p = subprocess.run([CLI, "gvd", *args, "-q"], capture_output=True, text=True, cwd=tmp_path, timeout=120)
        assert p.returncode == 2 and message in p.stderr and "--grid: required" not in p.stderr, (args, p.stderr)
    # a JSON obstacle document under another name is still one
    (tmp_path / "obstacles.txt").write_text("\ufeff  " + json.dumps(mixed_shapes()), encoding="utf-8")
    p = subprocess.run([CLI, "gvd", "obstacles.txt", "-q"], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert p.returncode == 2 and "--grid: required" in p.stderr, p.stderr
    # a YAML whose image is a folder says so
    (tmp_path / "lab.yaml").write_text("image: dir.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
                                       "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    p = subprocess.run([CLI, "gvd", "lab.yaml", "-q"], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert p.returncode == 2 and "lab.yaml: image: dir.pgm: is a folder, not a file" in p.stderr, p.stderr


def test_cli_resolution_bounds_are_printed_so_that_they_are_accepted(tmp_path):
    # Before: --resolution 2.2e-308 failed with "must lie in [2.2e-308, 4e295]".
    import re

    (tmp_path / "m.pgm").write_bytes(b"P5\n3 3\n255\n" + bytes([254, 254, 254, 254, 0, 254, 254, 254, 254]))
    for bad in ("2.2e-308", "1e-310", "4.1e295"):
        p = run("gvd", tmp_path / "m.pgm", "--resolution", bad, "-q")
        assert p.returncode == 2, p.stderr
        m = re.search(r"--resolution: must lie in \[(\S+), (\S+)\]", p.stderr)
        assert m, p.stderr
        for end in m.groups():
            ok = run("gvd", tmp_path / "m.pgm", "--resolution", end, "-q")
            assert ok.returncode == 0 and json.loads(ok.stdout)["map"]["resolution"] == float(end), (end, ok.stderr)
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 2.2e-308\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    p = run("gvd", tmp_path / "m.yaml", "-q")
    assert p.returncode == 2 and "m.yaml:2: resolution: must lie in [2.2250738585072014e-308, " in p.stderr, p.stderr
