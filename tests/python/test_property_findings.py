"""Minimal regression tests of what the property-based tests and the reader fuzzer found (issue 20).
Each test names the property or fuzz target that found it; the inputs are the shrunk ones."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv

CORPUS = Path(__file__).resolve().parents[1] / "data" / "fuzz_corpus"


# ------------------------------------------------------------- test_voronoi_cells_dyadic_translation
@pytest.mark.parametrize("inner", ["scan", "evt"])
@pytest.mark.parametrize("offset", [1e3, 1e5, 1e7, 1e9])
def test_exact_cell_measures_do_not_depend_on_the_distance_from_the_origin(inner, offset):
    # voronoi_cells without bounds: a deferred agent's cell (cells/asr.hpp: candidate_cell) kept the
    # center of an earlier cell or the origin, so its area and centroid were summed in that frame:
    # at (1e7, 1e7) the area of agent 2 was off by 2.7e-4 relative and its centroid by 905 units, at
    # 1e9 the area by 153%. The property found it at an offset of (-221, -742): 1e-12 relative.
    pts = np.array([[4, 2], [4, 6], [9, 3], [11, 4], [13, 0], [13, 3]], dtype=float)
    ref = dv.voronoi_cells(pts, inner=inner)
    moved = dv.voronoi_cells(pts + offset, inner=inner)
    assert list(np.flatnonzero(~ref.on_hull)) == [2]
    # what is left is the rounding of the vertices, which are points of the caller's frame: a few
    # ulps of the coordinates each, times the perimeter for the area
    v = np.asarray(ref.cell(2).vertices)
    perimeter = float(np.sum(np.linalg.norm(v - np.roll(v, 1, axis=0), axis=1)))
    ulp = float(np.spacing(2 * offset))
    assert abs(moved.areas[2] - ref.areas[2]) <= 4 * ulp * perimeter
    np.testing.assert_allclose(moved.centroids[2] - offset, ref.centroids[2], rtol=0, atol=4 * ulp)


# ----------------------------------------------------------------------- fuzz target "obstacles"
def test_obstacle_file_with_bytes_outside_utf8_is_a_valueerror_naming_its_place(tmp_path):
    # The JSON parser's message quoted the bad bytes as they were; Python then raised
    # UnicodeDecodeError ("'utf-8' codec can't decode byte 0xff") instead of the ValueError.
    path = tmp_path / "map.json"
    path.write_bytes(b'{"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [1, 2], '
                     b'"name": "\xff\xfe"}]}')
    with pytest.raises(ValueError, match=r"map\.json:1:\d+: invalid JSON") as info:
        dv.grid_voronoi(str(path), cells=16)
    assert type(info.value) is ValueError and "\\xff" in str(info.value)


def test_map_yaml_lines_outside_utf8_are_a_valueerror(tmp_path):
    path = tmp_path / "map.yaml"
    path.write_bytes(b"image room.pgm \xe9\n")
    with pytest.raises(ValueError, match=r"map\.yaml:1: expected 'key: value', got 'image room\.pgm \\xe9'"):
        dv.OccupancyGrid.load(str(path))


# ------------------------------------------------------------------ fuzz target "points" (Python)
def test_mpi_point_reader_refuses_non_utf8_and_non_finite_values_naming_the_line(tmp_path):
    from dvoronoi.mpi import _read_points

    bad = tmp_path / "pts.txt"
    bad.write_bytes(b"1 2\n3 4\xe9\n")
    with pytest.raises(ValueError, match=r"pts\.txt:2: not UTF-8"):   # was UnicodeDecodeError
        _read_points(str(bad))
    for text, line in [("x y\n1 2\n1 nan\n", 3), ("1e999 0\n", 1), ("0 -inf\n", 1)]:
        bad.write_text(text)
        with pytest.raises(ValueError, match=rf"pts\.txt:{line}: coordinates must be finite"):  # was accepted
            _read_points(str(bad))
    bad.write_text("\ufeffx,y\r\n1,2\r\n3,4 # c\r\n")
    np.testing.assert_array_equal(_read_points(str(bad)), [[1, 2], [3, 4]])


# ------------------------------------------------ fuzz targets "pgm", "png", "movingai", "points"
@pytest.mark.parametrize("name,match", [
    ("pgm/regress_huge_header_p5.pgm", r"truncated PGM data \(0 of 268402689 pixels\)"),
    ("pgm/regress_huge_header_p2.pgm", r"truncated PGM data \(room for at most \d of 268402689 pixels\)"),
    ("png/regress_huge_ihdr.png", r"truncated PNG image \(16383 x 16383 pixels need at least \d+ bytes"),
    ("movingai/regress_huge_header.map", r"regress_huge_header\.map:5: expected 16383 map rows, the file has 0"),
])
def test_map_headers_claiming_more_than_the_file_holds_fail_before_allocating(name, match):
    # A few bytes of header made the readers allocate 268 MB to 2.1 GB before finding the data missing
    # (under a memory limit: MemoryError in Python, "out of memory" and status 1 from the CLI).
    import resource

    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    with pytest.raises(ValueError, match=match):
        dv.OccupancyGrid.load(str(CORPUS / name))
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before < 100_000  # KiB


def test_map_yaml_errors_name_the_yaml():
    # "missing 'image'" was reported at line 0 ("map.yaml:0: ..."); an unreadable image named only
    # the image, not the YAML that points to it.
    with pytest.raises(ValueError, match=r"missing_image\.yaml: missing 'image'"):
        dv.OccupancyGrid.load(str(CORPUS / "ros_yaml" / "missing_image.yaml"))
    with pytest.raises(ValueError, match=r"no_such_image\.yaml: image: .*nowhere\.pgm: cannot open file"):
        dv.OccupancyGrid.load(str(CORPUS / "ros_yaml" / "no_such_image.yaml"))


# ------------------------------------------------------------------ fuzz target "points" (CLI)
def test_cli_names_the_file_of_a_point_out_of_the_exact_range(tmp_path):
    # "dvoronoi: error: points[0]: out of the exact range ..." named no file (exit status 2 was right)
    import os
    import shutil
    import subprocess

    cli = os.environ.get("DVORONOI_CLI") or shutil.which("dvoronoi")
    if not cli:
        pytest.skip("no dvoronoi executable (set DVORONOI_CLI)")
    src = CORPUS / "points" / "regress_out_of_exact_range.npy"
    proc = subprocess.run([cli, "cells", str(src), "-r", "1.5", "-q", "-o", str(tmp_path / "out.json")],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert f"{src} (row 1): points[1]: out of the exact range" in proc.stderr or \
        f"{src} (row 0): points[0]: out of the exact range" in proc.stderr, proc.stderr
    text = tmp_path / "pts.txt"
    text.write_text("0 0\n5.299808824e-315 5.29462817e-315\n5.289447516e-315 0\n")
    proc = subprocess.run([cli, "cells", str(text), "-r", "1.5", "-q", "-o", str(tmp_path / "out.json")],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and f"{text}:" in proc.stderr and "out of the exact range" in proc.stderr, proc.stderr


# --------------------------------------------------------------------- fuzz target "obstacles"
@pytest.mark.parametrize("radius", [2.0**31, 1e12, 1e300])
def test_huge_circles_are_traced_quickly_and_exactly(radius):
    # The contact sampling walked the whole circle, 2 pi R / (h/2) points: R = 2^31 took about an
    # hour in a 16-cell grid (R = 1e300 overflowed the count). Now only the arc through the area.
    import time

    doc = {"area": {"polygon": [[0, 0], [8, 0], [10, 6], [4, 10], [-2, 5]]},
           "obstacles": [{"type": "circle", "center": [4, 4], "radius": radius},
                         {"type": "circle", "center": [4 + radius + 0.5, 4], "radius": radius},
                         {"type": "point", "position": [3, 3]}]}
    t0 = time.monotonic()
    gv = dv.grid_voronoi(doc, cells=32, workers=2)
    assert time.monotonic() - t0 < 5.0
    brute = dv._core._gvd_brute_force(dv.gvd.load_obstacles(doc), 32, True)[2]
    np.testing.assert_array_equal(gv.diagram_mask, brute)


def test_a_nul_byte_in_an_obstacle_file_is_a_valueerror_naming_its_place():
    # nlohmann's parser stopped at a NUL byte ('"type"\\0...' read as the string "type"), and the
    # duplicate-key walk then parsed an escaped key after it: json.exception.parse_error escaped
    # (RuntimeError; status 1 from the CLI).
    path = CORPUS / "obstacles" / "regress_nul_then_escaped_key.json"
    with pytest.raises(ValueError, match=r"regress_nul_then_escaped_key\.json:1:7: invalid JSON: a NUL byte") as info:
        dv.grid_voronoi(str(path), cells=16)
    assert type(info.value) is ValueError


def test_cli_names_the_distance_file_of_an_exact_range_error(tmp_path):
    import os
    import shutil
    import subprocess

    cli = os.environ.get("DVORONOI_CLI") or shutil.which("dvoronoi")
    if not cli:
        pytest.skip("no dvoronoi executable (set DVORONOI_CLI)")
    src = CORPUS / "distances" / "regress_out_of_exact_range.txt"
    proc = subprocess.run([cli, "neighbors-from-distances", str(src), "-o", str(tmp_path / "out.json")],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and f"{src}: distances: robot 0: out of the exact range" in proc.stderr, proc.stderr


def test_an_obstacle_file_out_of_the_exact_range_is_named(tmp_path):
    # "out of the exact range: an exact test overflowed ..." named neither the file nor anything in
    # it (Python and CLI); the loader accepts the file, the tracing's exact tests overflow.
    import os
    import shutil
    import subprocess

    src = CORPUS / "obstacles" / "regress_area_out_of_exact_range.json"
    with pytest.raises(ValueError, match=rf"{src.name}: out of the exact range"):
        dv.grid_voronoi(str(src), cells=16)
    cli = os.environ.get("DVORONOI_CLI") or shutil.which("dvoronoi")
    if cli:
        proc = subprocess.run([cli, "gvd", str(src), "--grid", "16", "-o", str(tmp_path / "o.json")],
                              capture_output=True, text=True, timeout=60)
        assert proc.returncode == 2 and f"{src}: out of the exact range" in proc.stderr, proc.stderr
