"""Export: JSON (the CLI's schema, byte-identical to the CLI), GeoJSON (valid polygons approaching the
exact areas), plots (arcs drawn as arcs) and the `python -m dvoronoi demo` command."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys

import numpy as np
import pytest

import dvoronoi as dv
import dvoronoi.plotting
from conftest import random_points, write_points

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")


@pytest.fixture(scope="module")
def part():
    return dv.limited_cells(dv.datasets.intel_lab(), 3.0)


# ---------------------------------------------------------------------------- JSON


def test_json_fields_round_trip(part):
    doc = json.loads(part.to_json())
    assert doc["kind"] == "limited_partition" and doc["method"] == "auto" and doc["radius"] == 3.0
    # Doubles round-trip exactly.
    np.testing.assert_array_equal(np.array(doc["points"]), part.points)
    np.testing.assert_array_equal(doc["indptr"], part.indptr)
    np.testing.assert_array_equal(doc["indices"], part.indices)
    np.testing.assert_array_equal(doc["areas"], part.areas)
    np.testing.assert_array_equal(doc["perimeters"], part.perimeters)
    np.testing.assert_array_equal(np.array(doc["centroids"]), part.centroids)
    assert len(doc["cells"]) == len(part)
    for i, c in enumerate(doc["cells"]):
        assert c["agent"] == i
        lo, hi = part.piece_ptr[i], part.piece_ptr[i + 1]
        assert len(c["pieces"]) == hi - lo
        for k, piece in enumerate(c["pieces"]):
            assert piece["start"] == [part.piece_x[lo + k], part.piece_y[lo + k]]
            if piece["type"] == "edge":
                assert piece["neighbor"] == part.piece_neighbor[lo + k] >= 0
            else:
                assert piece["type"] == "arc" and part.piece_neighbor[lo + k] == -1
                assert piece["span"] == part.piece_span[lo + k] and piece["radius"] == 3.0
                assert piece["center"] == part.points[i].tolist()
        edges = sorted(p["neighbor"] for p in c["pieces"] if p["type"] == "edge")
        assert edges == part.neighbors(i).tolist()
    # Indentation changes the text, not the document.
    assert json.loads(part.to_json(indent=2)) == doc and "\n  " in part.to_json(indent=2)


def test_json_to_file(part, tmp_path):
    path = tmp_path / "cells.json"
    assert part.to_json(path) is None
    text = path.read_text()
    assert text.endswith("\n") and json.loads(text) == json.loads(part.to_json())


def test_cell_json(part):
    cell = part.cell(5)
    doc = json.loads(cell.to_json())
    assert doc["kind"] == "limited_cell" and doc["radius"] == 3.0
    assert doc["center"] == part.points[5].tolist()
    assert doc["neighbors"] == part.neighbors(5).tolist()
    assert doc["area"] == pytest.approx(part.areas[5], rel=1e-15)
    assert len(doc["pieces"]) == len(cell)


def test_json_equals_cli(tmp_path):
    cli = shutil.which("dvoronoi")
    if cli is None:
        pytest.skip("the dvoronoi CLI is not on the PATH (pip install . puts it there)")
    pts = random_points(31, 400)
    pfile = tmp_path / "points.txt"
    write_points(pfile, pts)
    for method in ("auto", "scan", "chords"):
        part = dv.limited_cells(pts, 0.05, method=method)
        for ext, write in ((".json", part.to_json), (".geojson", part.to_geojson)):
            out = tmp_path / f"cli{ext}"
            subprocess.run([cli, "cells", str(pfile), "--radius", "0.05", "--method", method,
                            "-q", "-o", str(out)], check=True, capture_output=True)
            mine = tmp_path / f"py{ext}"
            write(mine)
            assert mine.read_bytes() == out.read_bytes(), (method, ext)


# ---------------------------------------------------------------------------- GeoJSON


@pytest.mark.parametrize("tolerance", [None, 1e-2, 1e-5])
def test_geojson_polygons_approach_areas(part, tolerance):
    shapely = pytest.importorskip("shapely")
    doc = json.loads(part.to_geojson(tolerance=tolerance))
    tol = 3.0e-3 if tolerance is None else tolerance
    assert doc["type"] == "FeatureCollection" and len(doc["features"]) == len(part)
    for i, feature in enumerate(doc["features"]):
        assert feature["type"] == "Feature" and feature["geometry"]["type"] == "Polygon"
        assert feature["properties"]["agent"] == i
        assert feature["properties"]["neighbors"] == part.neighbors(i).tolist()
        assert feature["properties"]["area"] == part.areas[i]
        (ring,) = feature["geometry"]["coordinates"]
        assert ring[0] == ring[-1]
        poly = shapely.Polygon(ring)
        assert poly.is_valid and poly.exterior.is_ccw
        # Chords lie inside the arcs: the polygon is smaller by at most tolerance x arc length.
        lo, hi = part.piece_ptr[i], part.piece_ptr[i + 1]
        arc_length = 3.0 * float(np.sum(part.piece_span[lo:hi]))
        assert -1e-12 * part.areas[i] <= part.areas[i] - poly.area <= tol * arc_length + 1e-12
        # Every ring vertex is in the closed disk and closer to its own agent than to any other.
        xy = np.array(ring)
        d_own = np.linalg.norm(xy - part.points[i], axis=1)
        assert np.all(d_own <= 3.0 * (1 + 1e-12))
        d_all = np.linalg.norm(xy[:, None, :] - part.points[None, :, :], axis=2)
        assert np.all(d_own <= d_all.min(axis=1) + 1e-9)


def test_geojson_to_file(part, tmp_path):
    path = tmp_path / "cells.geojson"
    assert part.to_geojson(path, tolerance=0.01) is None
    assert json.loads(path.read_text()) == json.loads(part.to_geojson(tolerance=0.01))
    assert json.loads(part.cell(0).to_geojson())["geometry"]["type"] == "Polygon"


# ---------------------------------------------------------------------------- plots


def _collection(ax, gid):
    found = [c for c in ax.collections if c.get_gid() == gid]
    assert len(found) == 1, gid
    return found[0]


def test_plot_draws_arcs_as_arcs(part):
    import matplotlib.axes
    import matplotlib.pyplot as plt
    from matplotlib.path import Path

    ax = part.plot()
    try:
        assert isinstance(ax, matplotlib.axes.Axes)
        assert ax.get_aspect() == 1.0
        cells = _collection(ax, "dvoronoi-cells")
        assert len(cells.get_paths()) == len(part)
        edges = _collection(ax, "dvoronoi-edges")
        assert len(edges.get_segments()) == len(part.indices) // 2  # each shared edge once
        arcs = _collection(ax, "dvoronoi-arcs")
        arc_pieces = np.flatnonzero(part.piece_neighbor < 0)
        owner = np.searchsorted(part.piece_ptr, arc_pieces, side="right") - 1
        (path,) = arcs.get_paths()  # one compound path: MOVETO + Bezier segments per arc
        heads = np.flatnonzero(path.codes == Path.MOVETO)
        assert len(heads) == len(arc_pieces)
        assert np.all(path.codes[path.codes != Path.MOVETO] == Path.CURVE4)
        ends = np.append(heads[1:], len(path.codes))
        for h, e, piece, i in zip(heads, ends, arc_pieces, owner):
            v = path.vertices[h:e]
            assert (len(v) - 1) % 3 == 0
            assert tuple(v[0]) == (part.piece_x[piece], part.piece_y[piece])
            on_curve = v[::3]
            np.testing.assert_allclose(np.linalg.norm(on_curve - part.points[i], axis=1), 3.0, rtol=1e-12)
            # The curve between them is a circular arc, not a chord: its midpoints lie on the circle too.
            p0, p1, p2, p3 = v[0:-1:3], v[1::3], v[2::3], v[3::3]
            mid = (p0 + 3 * p1 + 3 * p2 + p3) / 8.0
            np.testing.assert_allclose(np.linalg.norm(mid - part.points[i], axis=1), 3.0, rtol=1e-7)
            # It sweeps the piece's span counter-clockwise.
            ang = np.unwrap(np.arctan2(on_curve[:, 1] - part.points[i, 1], on_curve[:, 0] - part.points[i, 0]))
            assert ang[-1] - ang[0] == pytest.approx(part.piece_span[piece], rel=1e-9)
        agents = _collection(ax, "dvoronoi-agents")
        np.testing.assert_array_equal(agents.get_offsets(), part.points)
        x0, x1 = ax.get_xlim()
        assert x0 <= part.points[:, 0].min() - 2.9 and x1 >= part.points[:, 0].max() + 2.9
    finally:
        plt.close(ax.figure)


def test_plot_into_given_axes_and_single_cell():
    import matplotlib.pyplot as plt

    from dvoronoi.plotting import plot_cell

    fig, ax = plt.subplots()
    try:
        pts = random_points(32, 30)
        assert dv.limited_cells(pts, 0.2).plot(ax=ax, facecolor="0.8", labels=True) is ax
        cell = dv.limited_cell(pts[0], pts[1:], 0.2)
        ax2 = plot_cell(cell, others=pts[1:])
        assert len(_collection(ax2, "dvoronoi-cells").get_paths()) == 1
        assert len(_collection(ax2, "dvoronoi-edges").get_segments()) == len(cell.neighbors)
        plt.close(ax2.figure)
        from matplotlib.path import Path

        part = dv.limited_cells(pts, 0.2)
        paths = dv.plotting.cell_paths(part)
        assert len(paths) == len(part)
        for i, path in enumerate(paths):
            assert path.codes[0] == Path.MOVETO and path.codes[-1] == Path.CLOSEPOLY
            lo = part.piece_ptr[i]
            assert tuple(path.vertices[0]) == (part.piece_x[lo], part.piece_y[lo])
            assert np.sum(path.codes == Path.LINETO) == np.sum(part.piece_neighbor[lo:part.piece_ptr[i + 1]] >= 0)
        with pytest.raises(TypeError, match="colour"):
            dv.limited_cells(pts, 0.2).plot(ax=ax, colour="red")
    finally:
        plt.close(fig)


# ---------------------------------------------------------------------------- demo


def test_demo_command(tmp_path):
    out = tmp_path / "demo.png"
    proc = subprocess.run([sys.executable, "-m", "dvoronoi", "demo", "--out", str(out)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "54 agents" in proc.stdout and "total cell area" in proc.stdout
    expected_total = float(np.sum(dv.limited_cells(dv.datasets.intel_lab(), 3.0).areas))
    assert f"{expected_total:.2f}" in proc.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demo.png"]


def test_demo_bad_radius(tmp_path):
    out = tmp_path / "demo.png"
    proc = subprocess.run([sys.executable, "-m", "dvoronoi", "demo", "--radius", "-1", "--out", str(out)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode != 0 and "radius" in proc.stderr
    assert not out.exists()
