"""Bad input: every error has the documented type and a message naming the argument (and the index
or pair where there is one)."""
from __future__ import annotations

import os

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi._io import atomic_write, atomic_write_text

GOOD = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.4, 0.6]])


# ---------------------------------------------------------------------------- NaN / inf


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("row,col", [(0, 0), (3, 1), (4, 0)])
def test_nonfinite_points(value, row, col):
    pts = GOOD.copy()
    pts[row, col] = value
    with pytest.raises(ValueError, match=rf"points\[{row}, {col}\]") as err:
        dv.limited_cells(pts, 1.0)
    assert "finite" in str(err.value)
    # Any layout reports the same index.
    with pytest.raises(ValueError, match=rf"points\[{row}, {col}\]"):
        dv.limited_cells(np.asfortranarray(pts), 1.0)


@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_nonfinite_limited_cell(value):
    others = GOOD.copy()
    others[2, 1] = value
    with pytest.raises(ValueError, match=r"others\[2, 1\]"):
        dv.limited_cell((0.5, 0.5), others, 1.0)
    with pytest.raises(ValueError, match="center"):
        dv.limited_cell((value, 0.5), GOOD, 1.0)
    with pytest.raises(ValueError, match="center"):
        dv.limited_cell(np.array([0.5, value]), GOOD, 1.0)


# ---------------------------------------------------------------------------- shapes and types


@pytest.mark.parametrize("shape", [(5, 3), (5,), (5, 1), (2, 2, 2), (0, 3), (1, 5)])
def test_wrong_shape_points(shape):
    arr = np.zeros(shape)
    expected = "points must be an (n, 2) array, got shape " + str(shape).replace(",)", ",)")
    with pytest.raises(ValueError) as err:
        dv.limited_cells(arr, 1.0)
    assert str(err.value) == expected


def test_wrong_shape_others_and_center():
    with pytest.raises(ValueError, match=r"others must be an \(n, 2\) array, got shape \(4, 3\)"):
        dv.limited_cell((0, 0), np.zeros((4, 3)), 1.0)
    for center, shape in [((0.0, 0.0, 0.0), r"\(3,\)"), (np.zeros((2, 2)), r"\(2, 2\)"), ([], r"\(0,\)")]:
        with pytest.raises(ValueError, match=r"center must be a point .*got shape " + shape):
            dv.limited_cell(center, GOOD, 1.0)


def test_ragged_and_non_numeric_input():
    with pytest.raises(TypeError, match="points"):
        dv.limited_cells([[0.0, 1.0], [2.0]], 1.0)  # ragged: numpy cannot make an array
    with pytest.raises(TypeError, match="points .*dtype"):
        dv.limited_cells(np.array([["a", "b"], ["c", "d"]]), 1.0)
    with pytest.raises(TypeError, match="points .*complex"):
        dv.limited_cells(GOOD.astype(complex), 1.0)
    with pytest.raises(TypeError, match="others"):
        dv.limited_cell((0, 0), np.array([[object(), 1.0]], dtype=object), 1.0)
    with pytest.raises(TypeError, match="center"):
        dv.limited_cell(("x", "y"), GOOD, 1.0)
    with pytest.raises(TypeError):
        dv.limited_cells(GOOD, "one")


# ---------------------------------------------------------------------------- radius, method, threads


@pytest.mark.parametrize("radius", [0.0, -1.0, -0.0, np.nan, np.inf, -np.inf])
def test_bad_radius(radius):
    with pytest.raises(ValueError, match="radius must be a positive finite number"):
        dv.limited_cells(GOOD, radius)
    with pytest.raises(ValueError, match="radius must be a positive finite number"):
        dv.limited_cell((0.5, 0.5), GOOD, radius)


@pytest.mark.parametrize("method", ["fast", "", "Scan", "voronoi"])
def test_bad_method(method):
    with pytest.raises(ValueError, match=rf'method must be "scan" or "chords", got "{method}"'):
        dv.limited_cells(GOOD, 1.0, method=method)
    with pytest.raises(ValueError, match="method"):
        dv.limited_cell((0.5, 0.5), GOOD, 1.0, method=method)


def test_bad_threads():
    with pytest.raises(ValueError, match="threads"):
        dv.limited_cells(GOOD, 1.0, threads=-1)


def test_bad_tolerance():
    part = dv.limited_cells(GOOD, 1.0)
    for tol in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="tolerance"):
            part.to_geojson(tolerance=tol)


# ---------------------------------------------------------------------------- coinciding agents


def test_coinciding_agents_name_the_first_pair():
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 0.0]])
    with pytest.raises(dv.CoincidentError) as err:
        dv.limited_cells(pts, 1.0)
    assert isinstance(err.value, ValueError)
    assert "points[1] and points[3]" in str(err.value)
    assert err.value.indices == (1, 3)
    # Far apart from everything else still counts (cells undefined whatever the radius).
    far = np.vstack([GOOD, [[50.0, 50.0]], GOOD[4:5]])
    with pytest.raises(ValueError, match=r"points\[4\] and points\[6\]"):
        dv.limited_cells(far, 0.1)


def test_coinciding_agent_at_center():
    with pytest.raises(dv.CoincidentError) as err:
        dv.limited_cell(GOOD[3], GOOD, 1.0)
    msg = str(err.value)
    assert "3" in msg and "center" in msg
    assert 3 in err.value.indices


def test_coinciding_others_within_range():
    others = np.array([[0.5, 0.0], [0.0, 0.5], [0.5, 0.0]])
    with pytest.raises(dv.CoincidentError) as err:
        dv.limited_cell((0.0, 0.0), others, 1.0)
    assert err.value.indices == (0, 2)
    assert "0" in str(err.value) and "2" in str(err.value)


# ---------------------------------------------------------------------------- files


def test_failed_write_leaves_nothing(tmp_path):
    part = dv.limited_cells(GOOD, 1.0)
    with pytest.raises(OSError):
        part.to_json(tmp_path / "missing-dir" / "out.json")
    assert not (tmp_path / "missing-dir").exists()

    target = tmp_path / "keep.json"
    target.write_text("old")

    def fail(f):
        f.write(b"partial")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError, match="disk full"):
        atomic_write(target, fail)
    assert target.read_text() == "old"
    assert os.listdir(tmp_path) == ["keep.json"]  # no temporary file left behind
    atomic_write_text(target, "new")
    assert target.read_text() == "new" and os.listdir(tmp_path) == ["keep.json"]
