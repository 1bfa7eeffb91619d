"""Bad input: every error has the documented type and a message naming the argument (and the index
or pair where there is one)."""
from __future__ import annotations

import json
import os
import stat
import re

import subprocess
import sys

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
    with pytest.raises(ValueError, match=rf'method must be "auto", "scan" or "chords", got "{method}"'):
        dv.limited_cells(GOOD, 1.0, method=method)
    with pytest.raises(ValueError, match="method"):
        dv.limited_cell((0.5, 0.5), GOOD, 1.0, method=method)


def test_bad_threads():
    with pytest.raises(ValueError, match="threads"), pytest.warns(DeprecationWarning):
        dv.limited_cells(GOOD, 1.0, threads=-1)


# Every function with a thread count: workers (SPEC: None or -1 = all cores, k >= 1) and the deprecated
# alias threads (0 = all cores). The count is checked before the core is called.
WORKER_CALLS = {
    "limited_cells": lambda **kw: dv.limited_cells(GOOD, 1.0, **kw),
    "voronoi_cells": lambda **kw: dv.voronoi_cells(GOOD, **kw),
    "neighbors_from_distances": lambda **kw: dv.neighbors_from_distances(np.zeros((0, 3)), **kw),
    "coverage.lloyd": lambda **kw: dv.coverage.lloyd(GOOD * 0.5 + 0.2, 0.3, steps=1, bounds=(0, 0, 1, 1), **kw),
    "coverage.step": lambda **kw: dv.coverage.step(GOOD, 0.3, **kw),
    "coverage.LloydStepper": lambda **kw: dv.coverage.LloydStepper(GOOD, 0.3, **kw),
    "network.batch": lambda **kw: dv.network.batch("cc", [GOOD * 10], 20.0, 0.0, [None], (0, 0, 10, 10), [1], **kw),
    "grid_voronoi": lambda **kw: dv.grid_voronoi({"area": {"box": [0, 0, 1, 1]}, "obstacles": []}, cells=8, **kw),
}


@pytest.mark.parametrize("call", sorted(WORKER_CALLS))
@pytest.mark.parametrize("workers", [0, -2, 2.5, 2.0, "2", True, 10**12])
def test_bad_workers(call, workers):
    # Before: threads=2.5 and "2" were accepted silently, 10**12 dumped the whole call in a pybind11
    # TypeError, and there was no workers= at all.
    with pytest.raises(ValueError, match=r"^workers must be None or -1 \(all cores\) or an integer from 1 to 2147483647, got") as err:
        WORKER_CALLS[call](workers=workers)
    assert len(str(err.value)) < 160


@pytest.mark.parametrize("call", sorted(WORKER_CALLS))
def test_good_workers_and_the_deprecated_threads(call):
    for workers in (None, -1, 1, 2, np.int64(2)):
        WORKER_CALLS[call](workers=workers)
    if call != "grid_voronoi":  # grid_voronoi never had threads
        with pytest.warns(DeprecationWarning, match="threads= is deprecated; use workers="):
            WORKER_CALLS[call](threads=0)
        for threads in (2.5, "2", -1, 10**12):
            with pytest.raises(ValueError, match=r"^threads must be 0 \(all cores\) or an integer"), \
                    pytest.warns(DeprecationWarning):
                WORKER_CALLS[call](threads=threads)
        with pytest.raises(ValueError, match="not both"):
            WORKER_CALLS[call](workers=1, threads=1)


def test_huge_worker_counts_run_and_give_the_same_answers():
    # Before: workers=100000 went to the OpenMP team as asked, and a map over 2^20 pixels or an
    # update killed the interpreter (libgomp could not start the threads). Run apart, so that a crash
    # fails this test, not the suite.
    code = """
import numpy as np, dvoronoi as dv
occ = np.zeros((1100, 1000), bool); occ[:, 500] = True; occ[300, :] = True; occ[700:710, 100:900] = True
big = dv.grid_voronoi(occ, workers=100000)
one = dv.grid_voronoi(occ, workers=1)
assert np.array_equal(big.diagram_mask, one.diagram_mask)
blob = np.zeros_like(occ); blob[::4, ::4] = True
big.set_occupied(blob); one.set_occupied(blob)
assert np.array_equal(big.diagram_mask, one.diagram_mask) and big.diagram_mask.any()
doc = {"area": {"box": [0, 0, 100, 10]}, "obstacles": [{"type": "polygon", "vertices": [[20, 2], [30, 2], [30, 8], [20, 8]]}]}
a = dv.grid_voronoi(doc, cells=3000, diagram="labels", workers=100000)
b = dv.grid_voronoi(doc, cells=3000, diagram="labels", workers=1)
assert len(a) == len(b) > 0
print("ok")
"""
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stderr[-2000:]


def LIMITED_CELLS(v):
    return dv.limited_cells(GOOD, v)


def COVERAGE_LLOYD(v):
    return dv.coverage.lloyd(GOOD, v, steps=1)


@pytest.mark.parametrize("call,name", [
    (LIMITED_CELLS, "radius"),
    (lambda v: dv.limited_cell((0.5, 0.5), GOOD, v), "radius"),
    (COVERAGE_LLOYD, "radius"),
    (lambda v: dv.network.simulate("cc", GOOD, v), "comm_range"),
    (lambda v: dv.network.simulate("bs", GOOD, 2.0, radius=v), "radius"),
    (lambda v: dv.network.simulate("cc", GOOD, 2.0, loss=v), "loss"),
])
@pytest.mark.parametrize("value", ["0.2", b"0.2", [0.2], True])
def test_reals_are_numbers_not_strings(call, name, value):
    # Before: radius="0.2" dumped the whole call (arrays included) in a pybind11 TypeError, or was
    # converted silently (network).
    if isinstance(value, list) and call in (LIMITED_CELLS, COVERAGE_LLOYD):
        # limited_cells and coverage take one radius per agent too (heterogeneous teams): here the
        # wrong count.
        with pytest.raises(ValueError, match=r"^radius must have one radius per agent: got 1 radii for"):
            call(value)
        return
    with pytest.raises(TypeError, match=rf"^{name} must be a real number, got") as err:
        call(value)
    assert len(str(err.value)) < 120


@pytest.mark.parametrize("kw,match", [
    ({"seed": 2**64}, r"^seed must be an integer from 0 to 18446744073709551615, got"),
    ({"seed": -1}, r"^seed must be an integer from 0 to"),
    ({"budget": 10**30}, r"^budget must be an integer from 1 to 9223372036854775807"),
    ({"budget": 0}, r"^budget must be an integer from 1"),
    ({"adjacency_cap": 10**30}, r"^adjacency_cap must be an integer from 0 to 2147483647"),
])
def test_network_integers_out_of_range(kw, match):
    # Before: seed=2**64 dumped the whole call (points included) in a pybind11 TypeError.
    with pytest.raises(ValueError, match=match):
        dv.network.simulate("cc", GOOD * 10, 20.0, **kw)


@pytest.mark.parametrize("kw", [{"seed": 2.5}, {"seed": "1"}, {"budget": 2.5}, {"adjacency_cap": "6"}])
def test_network_integers_are_integers(kw):
    with pytest.raises(TypeError, match=rf"^{next(iter(kw))} must be an integer, got"):
        dv.network.simulate("cc", GOOD * 10, 20.0, **kw)


@pytest.mark.parametrize("kw", [{"steps": 10**30}, {"record_every": 2**31}, {"order": 65}])
def test_lloyd_counts_beyond_the_core(kw):
    with pytest.raises(ValueError, match=rf"^{next(iter(kw))} must be an integer from"):
        dv.coverage.lloyd(GOOD, 0.3, **kw)


def test_method_and_inner_are_strings():
    with pytest.raises(TypeError, match="^method must be a string, got int"):
        dv.limited_cells(GOOD, 1.0, method=1)
    with pytest.raises(TypeError, match="^method must be a string, got int"):
        dv.limited_cell((0.5, 0.5), GOOD, 1.0, method=1)
    with pytest.raises(TypeError, match="^inner must be a string, got NoneType"):
        dv.voronoi_cells(GOOD, inner=None)


# ---------------------------------------------------------------------------- the exact range


def test_radius_range_and_measures_at_its_ends():
    # Before: R >= ~1e154 gave NaN areas (R^2 overflowed), and centroids were -inf from R ~ 1e103.
    for radius in (1e151, 1e200, 1e-151):
        with pytest.raises(ValueError, match="^radius must lie between 1e-150 and 1e150"):
            dv.limited_cells(GOOD, radius)
        with pytest.raises(ValueError, match="^radius must lie between 1e-150 and 1e150"):
            dv.limited_cell((0.5, 0.5), GOOD, radius)
    for radius in (1e-150, 1e120, 1e150):
        part = dv.limited_cells(GOOD, radius)  # alone in their disks at 1e-150, all neighbours beyond
        assert np.all(np.isfinite(part.areas)) and np.all(np.isfinite(part.centroids))
        assert np.all(np.isfinite(part.perimeters))


@pytest.mark.parametrize("k", [-1060, -1000, -900, -600, -480, -300, 300, 480, 600, 900, 1000])
def test_far_from_1_exact_or_refused(k):
    # A lattice (ties: the exact stage runs) and random agents, scaled by 2^k (exact). Before:
    # differences below ~1e-300 gave other neighbour sets, and voronoi_cells aborted the process (an
    # exception escaped the parallel loop). Now exact tests are exact at any common scale, so within
    # the radii's range [1e-150, 1e150] the answer is the unscaled one, and beyond it a ValueError.
    rng = np.random.default_rng(4)
    pts = np.vstack([np.array([(i % 6, i // 6) for i in range(36)], float), rng.random((30, 2)) * 5])
    s = 2.0 ** k
    ref = dv.voronoi_cells(pts)
    if abs(k) <= 480:
        got = dv.voronoi_cells(pts * s, workers=2)
        assert np.array_equal(got.indptr, ref.indptr) and np.array_equal(got.indices, ref.indices)
        assert np.array_equal(got.on_hull, ref.on_hull)
        ref = dv.limited_cells(pts, 1.0)
        got = dv.limited_cells(pts * s, s, workers=2)
        assert np.array_equal(got.indptr, ref.indptr) and np.array_equal(got.indices, ref.indices)
        np.testing.assert_array_equal(got.areas, ref.areas * s * s)
    else:
        with pytest.raises(ValueError, match=r"^points\[\d+\]: the nearest other agent lies (closer|farther) than "
                                             r"about 1e[-]?154: .* must lie between 1e-150 and 1e150"):
            dv.voronoi_cells(pts * s, workers=2)


def test_differences_spanning_more_than_doubles_hold_are_refused():
    # Agent 0 a few subnormal steps beside the line on which its neighbours lie 2^-30 apart: a
    # decision needs products below the smallest subnormal next to terms of 2^-60.
    tiny, h = 2.0 ** -1074, 2.0 ** -30
    pts = np.array([[3 * tiny, 0.0], [0.0, h], [0.0, -h], [-tiny, h / 2]])
    with pytest.raises(ValueError, match=r"^points\[\d\]: out of the exact range: an exact test underflowed"):
        dv.limited_cells(pts, h)


def test_coverage_radius_keeps_its_moments_finite():
    # Polar moments grow as R^4: past 1e75 they overflow. Before: lloyd without bounds at R = 1e50..1e150
    # gave NaN costs and areas, or "points[1, 0] is not finite" after the first step.
    pts = np.random.default_rng(0).random((10, 2))
    for radius in (1e76, 1e100, 1e-76):
        with pytest.raises(ValueError, match=r"^radius must lie between 1e-75 and 1e75 \(coverage"):
            dv.coverage.lloyd(pts, radius, steps=1)
    try:
        run = dv.coverage.lloyd(pts, 1e50, steps=1)
    except ValueError as e:  # the agents spread over 1e50 next to agents 1 apart: out of range
        assert re.match(r"points\[\d+\]: out of the (exact )?range", str(e)), str(e)
    else:
        assert np.all(np.isfinite(run.cost)) and np.all(np.isfinite(run.areas))


def test_chords_refuses_more_agents_within_2r_than_it_accepts():
    # Before: 2,000 agents within 2R of each other took 110 s with no bound (checkChords is quadratic).
    pts = np.random.default_rng(1).random((1100, 2))
    with pytest.raises(ValueError, match=r'^points\[\d+\]: method "chords" \(RCVC, quadratic in the agents within 2R\) '
                                         r"accepts at most 1024 agents within 2R of an agent; this one has 1099"):
        dv.limited_cells(pts, 1.0, method="chords")
    with pytest.raises(ValueError, match="accepts at most 1024"):
        dv.limited_cell((0.5, 0.5), pts, 1.0, method="chords")
    assert len(dv.limited_cells(pts, 1.0, method="scan")) == 1100


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


def test_writes_follow_links_and_keep_pipes(tmp_path):
    # Before: to_json through a link replaced the link by a file (the file it named kept its old
    # content), and a FIFO (or, run as root, /dev/null) was replaced by a regular file.
    part = dv.limited_cells(GOOD, 1.0)
    real, link = tmp_path / "real.json", tmp_path / "link.json"
    real.write_text("old")
    os.chmod(real, 0o600)
    os.symlink("real.json", link)
    part.to_json(link)
    assert link.is_symlink() and json.loads(real.read_text())
    assert os.stat(real).st_mode & 0o777 == 0o600  # a replaced file keeps its mode
    assert sorted(os.listdir(tmp_path)) == ["link.json", "real.json"]
    fifo = tmp_path / "out.json"
    os.mkfifo(fifo)
    fd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # a reader, so that the writer's open returns
    try:
        atomic_write_text(fifo, "through the pipe")
        assert os.read(fd, 100) == b"through the pipe"
    finally:
        os.close(fd)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_grid_voronoi_names_what_a_file_is_not(tmp_path):
    # Before: a JPEG said "invalid JSON: a NUL byte", a missing file gave the OS's words only.
    jpg = tmp_path / "office.jpg"
    jpg.write_bytes(b"\xff\xd8\xff\xe0\x00\x10JFIF\x00")
    with pytest.raises(ValueError, match=r"office.jpg: neither a map file nor an obstacle document.*\.pgm.*\.json"):
        dv.grid_voronoi(jpg)
    with pytest.raises(ValueError, match=r"no_such_map: cannot open file: it does not exist"):
        dv.grid_voronoi(tmp_path / "no_such_map")
    (tmp_path / "d.json").mkdir()
    with pytest.raises(ValueError, match=r"d.json: is a folder"):
        dv.grid_voronoi(tmp_path / "d.json")
    doc = tmp_path / "scene.txt"  # a document without the .json name is still read
    doc.write_text('\ufeff {"area": {"box": [0, 0, 10, 10]}, "obstacles": []}', encoding="utf-8")
    assert dv.grid_voronoi(doc, cells=16, diagram="labels").shape == (16, 16)
