"""The standalone `dvoronoi` program, run as a user would.

The executable is $DVORONOI_CLI when that is set (e.g. a fresh CMake build:
DVORONOI_CLI=build/cpp/cli/dvoronoi pytest tests/python/test_cli.py), else `dvoronoi` on the PATH (put
there by `pip install .`). The tests are skipped only when neither exists.
"""

import csv
import json
import math
import os
import random
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parents[1] / "data"
INTEL = DATA / "intel_lab_motes.txt"
SVG_NS = "{http://www.w3.org/2000/svg}"


def _find_cli():
    env = os.environ.get("DVORONOI_CLI")
    if env:
        if not (Path(env).is_file() and os.access(env, os.X_OK)):
            raise RuntimeError(f"DVORONOI_CLI={env!r} is not an executable file")
        return env
    return shutil.which("dvoronoi")


CLI = _find_cli()
pytestmark = pytest.mark.skipif(
    CLI is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)"
)


def run(*args, stdin=None, cwd=None):
    return subprocess.run(
        [CLI, *map(str, args)],
        input=stdin,
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )


def write_points(path, pts, sep=" "):
    path.write_text("".join(f"{x!r}{sep}{y!r}\n" for x, y in pts))
    return path


def sample_points():
    """60 random points, a 4 x 4 lattice (cocircular quadruples) and one isolated agent."""
    rng = random.Random(11)
    pts = [(rng.uniform(0, 6), rng.uniform(0, 6)) for _ in range(60)]
    pts += [(20.0 + i, 20.0 + j) for i in range(4) for j in range(4)]
    pts.append((100.0, 100.0))
    return pts


@pytest.fixture
def points_file(tmp_path):
    return write_points(tmp_path / "pts.txt", sample_points())


def cells_json(points, *args):
    r = run("cells", points, *args)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def shoelace(ring):
    return 0.5 * sum(
        ring[k][0] * ring[k + 1][1] - ring[k + 1][0] * ring[k][1] for k in range(len(ring) - 1)
    )


# --- results ------------------------------------------------------------------------------------


def test_both_methods_give_the_same_neighbours_and_areas(points_file):
    scan = cells_json(points_file, "--radius", "0.9", "--method", "scan", "-q")
    chords = cells_json(points_file, "--radius", "0.9", "--method", "chords", "-q")
    auto = cells_json(points_file, "--radius", "0.9", "-q")  # the default
    assert scan["method"] == "scan" and chords["method"] == "chords" and auto["method"] == "auto"
    assert auto["indptr"] == scan["indptr"] and auto["indices"] == scan["indices"]
    assert auto["areas"] == scan["areas"]  # the filter gives Boundary Scan's cells bit for bit
    assert scan["indptr"] == chords["indptr"]
    assert scan["indices"] == chords["indices"]
    assert scan["areas"] == pytest.approx(chords["areas"], rel=1e-9)
    n = len(sample_points())
    assert len(scan["points"]) == n and scan["indptr"][-1] == len(scan["indices"])
    # Lattice agent (21, 21) is number 60 + 1*4 + 1 = 65: exactly its 4 axis neighbours.
    nb = scan["indices"][scan["indptr"][65] : scan["indptr"][66]]
    assert nb == [61, 64, 66, 69]
    # The isolated agent is a full disk.
    assert scan["areas"][-1] == pytest.approx(math.pi * 0.81, rel=1e-12)


def test_json_schema_and_pieces(points_file):
    doc = cells_json(points_file, "-r", "0.9", "-q")
    assert set(doc) == {
        "kind", "method", "radius", "points", "indptr", "indices",
        "areas", "perimeters", "centroids", "cells",
    }
    assert doc["kind"] == "limited_partition" and doc["radius"] == 0.9
    pts = sample_points()
    assert [tuple(p) for p in doc["points"]] == pts  # exact round trip of every double
    for i, cell in enumerate(doc["cells"]):
        assert cell["agent"] == i
        pieces = cell["pieces"]
        length = 0.0
        for k, pc in enumerate(pieces):
            assert pc["end"] == pieces[(k + 1) % len(pieces)]["start"]
            if pc["type"] == "edge":
                length += math.dist(pc["start"], pc["end"])
            else:
                assert pc["type"] == "arc" and pc["radius"] == 0.9
                assert list(pc["center"]) == list(pts[i])
                assert 0 < pc["span"] <= 2 * math.pi + 1e-12
                length += 0.9 * pc["span"]
        assert length == pytest.approx(doc["perimeters"][i], rel=1e-12)
        edges = sorted({pc["neighbor"] for pc in pieces if pc["type"] == "edge"})
        assert edges == doc["indices"][doc["indptr"][i] : doc["indptr"][i + 1]]


def test_stdout_and_output_file_hold_the_same_json(points_file, tmp_path):
    out = tmp_path / "cells.json"
    r = run("cells", points_file, "-r", "0.9", "-o", out, "-q")
    assert r.returncode == 0, r.stderr
    assert r.stdout == ""
    assert out.read_text() == run("cells", points_file, "-r", "0.9").stdout


def test_geojson_output(points_file, tmp_path):
    out = tmp_path / "cells.geojson"
    r = run("cells", points_file, "-r", "0.9", "-o", out, "--tolerance", "1e-4", "-q")
    assert r.returncode == 0, r.stderr
    fc = json.loads(out.read_text())
    doc = cells_json(points_file, "-r", "0.9")
    assert fc["type"] == "FeatureCollection"
    assert len(fc["features"]) == len(doc["areas"])
    for i, f in enumerate(fc["features"]):
        assert f["type"] == "Feature" and f["geometry"]["type"] == "Polygon"
        assert f["properties"]["agent"] == i
        assert f["properties"]["area"] == doc["areas"][i]
        assert f["properties"]["neighbors"] == doc["indices"][doc["indptr"][i] : doc["indptr"][i + 1]]
        ring = f["geometry"]["coordinates"][0]
        assert len(ring) >= 4 and ring[0] == ring[-1]
        area = shoelace(ring)
        assert area > 0  # counter-clockwise
        # Densified arcs lose at most (arc length x tolerance) <= (2 pi R) x 1e-4.
        assert -1e-12 <= doc["areas"][i] - area <= 2 * math.pi * 0.9 * 1e-4 + 1e-12


def test_csv_output(points_file, tmp_path):
    out = tmp_path / "cells.csv"
    assert run("cells", points_file, "-r", "0.9", "-o", out, "-q").returncode == 0
    doc = cells_json(points_file, "-r", "0.9")
    with out.open(newline="") as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == [
            "agent", "x", "y", "area", "centroid_x", "centroid_y", "perimeter", "neighbors",
        ]
        rows = list(reader)
    assert len(rows) == len(doc["areas"])
    for i, row in enumerate(rows):
        assert int(row["agent"]) == i
        assert (float(row["x"]), float(row["y"])) == tuple(doc["points"][i])
        assert float(row["area"]) == doc["areas"][i]
        assert float(row["perimeter"]) == doc["perimeters"][i]
        assert [float(row["centroid_x"]), float(row["centroid_y"])] == doc["centroids"][i]
        nb = [int(t) for t in row["neighbors"].split()]
        assert nb == doc["indices"][doc["indptr"][i] : doc["indptr"][i + 1]]


def test_svg_output(points_file, tmp_path):
    out, svg = tmp_path / "cells.json", tmp_path / "cells.svg"
    r = run("cells", points_file, "-r", "0.9", "-o", out, "--svg", svg, "-q")
    assert r.returncode == 0, r.stderr
    root = ET.parse(svg).getroot()
    assert root.tag == SVG_NS + "svg"
    n = len(sample_points())
    paths = root.findall(f".//{SVG_NS}path")
    assert len(paths) == n
    assert len(root.findall(f".//{SVG_NS}circle")) == n
    assert all(" A 0.9 0.9 0 0 0 " in p.get("d") or " A " not in p.get("d") for p in paths)
    doc = json.loads(out.read_text())
    has_arc = [any(pc["type"] == "arc" for pc in c["pieces"]) for c in doc["cells"]]
    assert [" A " in p.get("d") for p in paths] == has_arc
    assert [" L " in p.get("d") for p in paths] == [
        any(pc["type"] == "edge" for pc in c["pieces"]) for c in doc["cells"]
    ]
    # Each arc command, read as the SVG spec does (radius, large-arc 0, sweep 0), has its circle's
    # centre at the agent's dot: arcs bulge the right way after the y flip.
    dots = [(float(c.get("cx")), float(c.get("cy"))) for c in root.findall(f".//{SVG_NS}circle")]
    arcs = 0
    for i, p in enumerate(paths):
        tokens = p.get("d").split()
        k, cur = 0, None
        while k < len(tokens):
            cmd = tokens[k]
            if cmd in ("M", "L"):
                cur = (float(tokens[k + 1]), float(tokens[k + 2]))
                k += 3
            elif cmd == "A":
                r, large, sweep = float(tokens[k + 1]), tokens[k + 4], tokens[k + 5]
                end = (float(tokens[k + 6]), float(tokens[k + 7]))
                assert (large, sweep) == ("0", "0")
                mx, my = (cur[0] + end[0]) / 2, (cur[1] + end[1]) / 2
                dx, dy = end[0] - cur[0], end[1] - cur[1]
                d = math.hypot(dx, dy)
                h = math.sqrt(max(r * r - d * d / 4, 0.0))
                for c in ((mx - h * dy / d, my + h * dx / d), (mx + h * dy / d, my - h * dx / d)):
                    cross = (cur[0] - c[0]) * (end[1] - c[1]) - (cur[1] - c[1]) * (end[0] - c[0])
                    if cross < 0:  # sweep 0 = decreasing SVG angle
                        assert math.dist(c, dots[i]) < 1e-3 * 0.9, (i, c, dots[i])
                arcs += 1
                cur = end
                k += 8
            else:
                assert cmd == "Z"
                k += 1
    assert arcs >= sum(has_arc)
    x0, y0, w, h = map(float, root.get("viewBox").split())
    assert (x0, y0) == (0.0, 0.0)
    assert w >= 100 - 0 + 2 * 0.9 and h >= 100 + 2 * 0.9  # all disks, from (0, 0) to (100, 100)
    assert doc["kind"] == "limited_partition"


def test_intel_lab_file_with_columns(tmp_path):
    doc = cells_json(INTEL, "-r", "3", "--columns", "1,2", "-q")
    expected = []
    for line in INTEL.read_text().splitlines():
        line = line.split("#")[0].split()
        if line:
            expected.append([float(line[1]), float(line[2])])
    assert len(expected) == 54
    assert doc["points"] == expected
    # Without --columns the three-field lines are an error that points at the third field.
    r = run("cells", INTEL, "-r", "3", "-o", tmp_path / "x.json")
    assert r.returncode == 2
    assert f"{INTEL}:4:8:" in r.stderr and "--columns" in r.stderr
    assert not (tmp_path / "x.json").exists()


def test_header_comments_commas_and_stdin(tmp_path):
    text = "# agents\nx,y\n0,0   # first\n\n1.5, 0\n0,1.5\n"
    p = tmp_path / "h.csv"
    p.write_text(text)
    doc = cells_json(p, "-r", "1")
    assert doc["points"] == [[0, 0], [1.5, 0], [0, 1.5]]
    assert doc["indices"][doc["indptr"][0] : doc["indptr"][1]] == [1, 2]
    r = run("cells", "-", "-r", "1", stdin=text)
    assert r.returncode == 0 and json.loads(r.stdout) == doc


def test_npy_input(tmp_path):
    np = pytest.importorskip("numpy")
    pts = np.array(sample_points(), dtype=np.float64)
    np.save(tmp_path / "p64.npy", pts)
    np.save(tmp_path / "p32f.npy", np.asfortranarray(pts.astype(np.float32)))
    doc = cells_json(tmp_path / "p64.npy", "-r", "0.9")
    assert doc == cells_json(write_points(tmp_path / "p.txt", sample_points()), "-r", "0.9")
    doc32 = cells_json(tmp_path / "p32f.npy", "-r", "0.9")
    assert doc32["points"] == pts.astype(np.float32).astype(np.float64).tolist()
    np.save(tmp_path / "bad.npy", np.zeros((4, 3)))
    r = run("cells", tmp_path / "bad.npy", "-r", "1")
    assert r.returncode == 2 and "(n, 2)" in r.stderr and "bad.npy" in r.stderr


def test_empty_file_gives_empty_result(tmp_path):
    p = tmp_path / "empty.txt"
    p.write_text("# nothing here\n")
    doc = cells_json(p, "-r", "1")
    assert doc["points"] == [] and doc["cells"] == [] and doc["indptr"] == [0]


@pytest.mark.parametrize("text, header", [("hello world\n", "'hello world'"), ("x,y\n# no data yet\n", "'x,y'")])
def test_header_only_file_warns(tmp_path, text, header):
    # A file whose only content is a header line is valid and has no points (SPEC), but "hello world"
    # is more likely the wrong file: before, an empty result came out with exit 0 and not a word.
    p = tmp_path / "h.txt"
    p.write_text(text)
    r = run("cells", p, "-r", "1", "-q")
    assert r.returncode == 0 and json.loads(r.stdout)["points"] == []
    assert r.stderr == (f"dvoronoi: warning: {p}:1: {header} was read as a header line (none of its fields is "
                        "a number) and no data line follows: the file has no points\n")
    p.write_text(text + "1 2\n")  # with data after it: a header, no warning
    r = run("cells", p, "-r", "1", "-q")
    assert r.returncode == 0 and r.stderr == "" and len(json.loads(r.stdout)["points"]) == 1


# --- errors: exit code 2, FILE:LINE:COLUMN or the argument, nothing written ----------------------


def assert_fails_cleanly(r, tmp_path, *needles, before=()):
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stdout == ""
    for needle in needles:
        assert needle in r.stderr, r.stderr
    leftovers = sorted(p.name for p in tmp_path.iterdir() if p.name not in before)
    assert leftovers == [], leftovers  # no output, no temporary file


@pytest.mark.parametrize(
    "text, where, what",
    [
        ("0 0\n1 1\n2   abc\n", ":3:5:", "not a number"),
        ("0 0\n# c\n1 nan\n", ":3:3:", "not finite"),
        ("0 0\n\n inf 1\n", ":3:2:", "not finite"),
        ("0 0\n1 2 3\n", ":2:5:", "--columns"),
        ("0 0\n7\n", ":2:2:", "expected 2 fields"),
        ("0,0\n1,,2\n", ":2:3:", "empty field"),
        ("0 0\n1 1e400\n", ":2:3:", "out of the range"),
        # Control bytes in a quoted token are escaped (a NUL cut the message short before).
        ("0 0\n3 a\0b\n", ":2:3:", "y value 'a\\0b' is not a number"),
        ("0 0\n3 a\x01\x7f\\\n", ":2:3:", "y value 'a\\x01\\x7f\\\\' is not a number"),
    ],
)
def test_malformed_point_file(tmp_path, text, where, what):
    bad = tmp_path / "bad.txt"
    bad.write_text(text)
    out, svg = tmp_path / "out.json", tmp_path / "out.svg"
    r = run("cells", bad, "-r", "1", "-o", out, "--svg", svg)
    assert_fails_cleanly(r, tmp_path, f"bad.txt{where}", what, before={"bad.txt"})


def test_failure_keeps_an_existing_output_untouched(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("1 2\nx 3\n")
    out = tmp_path / "out.csv"
    out.write_text("old\n")
    r = run("cells", bad, "-r", "1", "-o", out)
    assert_fails_cleanly(r, tmp_path, "bad.txt:2:1:", before={"bad.txt", "out.csv"})
    assert out.read_text() == "old\n"


def test_coinciding_agents_name_both_lines(tmp_path):
    p = tmp_path / "dup.txt"
    p.write_text("0 0\n1 1\n2 0\n1 1\n")
    r = run("cells", p, "-r", "1", "-o", tmp_path / "o.json")
    assert_fails_cleanly(r, tmp_path, "dup.txt:4:", "line 2", "coincide", before={"dup.txt"})


@pytest.mark.parametrize("radius", ["0", "-1", "nan", "inf", "abc"])
def test_bad_radius(points_file, tmp_path, radius):
    r = run("cells", points_file, "--radius", radius, "-o", tmp_path / "o.json")
    assert_fails_cleanly(r, tmp_path, "--radius", before={"pts.txt"})


def test_unknown_output_extension_fails_before_reading(tmp_path):
    # The points file does not exist: the extension is checked first, so the message is about -o.
    r = run("cells", tmp_path / "missing.txt", "-r", "1", "-o", tmp_path / "out.txt")
    assert_fails_cleanly(r, tmp_path, "-o/--output", ".txt", ".json")


def test_missing_points_file_and_unwritable_output(points_file, tmp_path):
    r = run("cells", tmp_path / "missing.txt", "-r", "1")
    assert r.returncode == 2 and "missing.txt" in r.stderr and "cannot open" in r.stderr
    r = run("cells", points_file, "-r", "1", "-o", tmp_path / "no" / "dir.json")
    assert_fails_cleanly(r, tmp_path, "-o/--output", before={"pts.txt"})


@pytest.mark.parametrize("command", [["cells", "-r", "1"], ["voronoi"], ["lloyd", "-r", "1"]])
@pytest.mark.parametrize("value", ["-1", "2.5", "abc", "99999999999"])
def test_bad_threads_say_the_range(points_file, tmp_path, command, value):
    # Before: "--threads: Value -1 not in range 0.000000 to 1797693134862315708...(300 digits)".
    r = run(command[0], points_file, *command[1:], "--threads", value, "-o", tmp_path / "o.json")
    assert_fails_cleanly(r, tmp_path, f"--threads: must be a whole number from 0 (all cores) to 2147483647, "
                                      f"got '{value}'", before={"pts.txt"})
    assert len(r.stderr) < 200


def test_usage_errors_exit_2_and_help_exits_0(points_file):
    assert run().returncode == 2  # no subcommand
    assert run("cells", points_file).returncode == 2  # --radius missing
    r = run("cells", points_file, "-r", "1", "--method", "voronoi")
    assert r.returncode == 2 and "--method" in r.stderr
    r = run("cells", points_file, "-r", "1", "--columns", "1")
    assert r.returncode == 2 and "--columns" in r.stderr
    r = run("cells", points_file, "-r", "1", "--bogus")
    assert r.returncode == 2 and "--bogus" in r.stderr
    r = run("cells", "--help")
    assert r.returncode == 0 and "--radius" in r.stdout


def test_progress_on_large_runs_and_quiet(tmp_path):
    rng = random.Random(5)
    n = 100_000
    p = write_points(tmp_path / "big.txt", [(rng.uniform(0, 300), rng.uniform(0, 300)) for _ in range(n)])
    r = run("cells", p, "-r", "0.3", "-o", tmp_path / "big.csv")
    assert r.returncode == 0, r.stderr
    assert f"cells: {n}/{n}" in r.stderr  # stderr is a pipe here: a final line for large n
    r = run("cells", p, "-r", "0.3", "-o", tmp_path / "big2.csv", "--quiet")
    assert r.returncode == 0 and r.stderr == ""
    assert (tmp_path / "big.csv").read_text() == (tmp_path / "big2.csv").read_text()
    assert len((tmp_path / "big.csv").read_text().splitlines()) == n + 1


# --- dvoronoi voronoi --------------------------------------------------------------------------


def test_voronoi_json_equals_the_python_result(points_file):
    import numpy as np
    import dvoronoi as dv

    pts = np.array(sample_points())
    for extra, bounds in (((), None), (("--bounds", -1, -2, 110, 105), (-1, -2, 110, 105))):
        for inner in ("auto", "scan", "evt"):
            r = run("voronoi", points_file, "--inner", inner, *extra)
            assert r.returncode == 0, r.stderr
            got = json.loads(r.stdout)
            want = json.loads(dv.voronoi_cells(pts, inner=inner, bounds=bounds).to_json())
            assert got.keys() == want.keys()
            for key in ("kind", "inner", "bounds", "points", "indptr", "indices", "on_hull"):
                assert got[key] == want[key], key
            for a, b in zip(got["areas"], want["areas"]):
                assert (a is None and b is None) or math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-15)
    # With bounds every cell has an area and they tile the box.
    assert math.isclose(sum(got["areas"]), 111 * 107, rel_tol=1e-12)


def test_voronoi_geojson_csv_svg(points_file, tmp_path):
    box = ("--bounds", -1, -2, 110, 105)
    r = run("voronoi", points_file, *box, "-o", tmp_path / "v.geojson", "--svg", tmp_path / "v.svg")
    assert r.returncode == 0, r.stderr
    gj = json.loads((tmp_path / "v.geojson").read_text())
    feats = gj["features"]
    assert len(feats) == len(sample_points())
    for f in feats:
        ring = f["geometry"]["coordinates"][0]
        assert ring[0] == ring[-1]
        assert math.isclose(shoelace(ring), f["properties"]["area"], rel_tol=1e-9)
    svg = ET.parse(tmp_path / "v.svg").getroot()
    cells = [e for e in svg.iter(f"{SVG_NS}path") if e.get("id", "").startswith("cell-")]
    assert len(cells) == len(feats)
    # Without bounds: hull agents have null geometry and no area, and the SVG draws their rays.
    r = run("voronoi", points_file, "-o", tmp_path / "u.csv", "--svg", tmp_path / "u.svg")
    assert r.returncode == 0, r.stderr
    with open(tmp_path / "u.csv") as f:
        rows = list(csv.DictReader(f))
    hull = [row for row in rows if row["on_hull"] == "1"]
    assert hull and all(row["area"] == "" for row in hull)
    assert all(float(row["area"]) > 0 for row in rows if row["on_hull"] == "0")
    svg = ET.parse(tmp_path / "u.svg").getroot()
    rays = [g for g in svg.iter(f"{SVG_NS}g") if g.get("class") == "rays"]
    assert len(rays) == 1 and len(list(rays[0])) == len(hull)


@pytest.mark.parametrize("bounds, what", [((1, 0, 0, 1), "xmin < xmax"), ((0, 0, "nan", 1), "finite")])
def test_voronoi_bad_bounds_fail_before_reading(tmp_path, bounds, what):
    r = run("voronoi", tmp_path / "missing.txt", "--bounds", *bounds, "-o", tmp_path / "v.json")
    assert_fails_cleanly(r, tmp_path, "--bounds", what)


def test_voronoi_coinciding_agents_leave_no_output(tmp_path):
    pts = write_points(tmp_path / "p.txt", [(0.0, 0.0), (1.0, 1.0), (0.0, 0.0)])
    r = run("voronoi", pts, "-o", tmp_path / "v.json", "--svg", tmp_path / "v.svg")
    assert_fails_cleanly(r, tmp_path, "p.txt:3:1", "point 0 (line 1)", before=("p.txt",))
