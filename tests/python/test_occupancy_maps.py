"""dvoronoi.occupancy_maps: the generated maps (determinism, shape, border walls, free space, the
passages map's measured corridor widths and wall slopes), the MovingAI reader on the real map in
tests/data/maps and on malformed files, and the nearest-neighbour resize.

The module is numpy-only; when the installed dvoronoi predates it (a build not yet reinstalled), the
tests load it from the source tree instead so they still run.
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
MAPS = ROOT / "tests" / "data" / "maps"

try:
    from dvoronoi import occupancy_maps as om
except ImportError:  # installed package without the module: use the source file
    _spec = importlib.util.spec_from_file_location(
        "occupancy_maps", ROOT / "python" / "dvoronoi" / "occupancy_maps.py")
    om = importlib.util.module_from_spec(_spec)
    _spec.loader.exec_module(om)

SEEDED = ["building", "warehouse", "cave", "rooms_with_islands"]
SIZES = [32, 64, 257, (48, 120), (150, 40)]


def free_runs(free_row: np.ndarray) -> list:
    """Lengths of the runs of True in a 1-D bool array, left to right."""
    v = np.concatenate([[0], free_row.astype(np.int8), [0]])
    d = np.diff(v)
    return (np.flatnonzero(d == -1) - np.flatnonzero(d == 1)).tolist()


def components(free: np.ndarray) -> np.ndarray:
    ndimage = pytest.importorskip("scipy.ndimage")
    lab, n = ndimage.label(free)
    return np.bincount(lab.ravel())[1:] if n else np.zeros(0, dtype=int)


@pytest.mark.parametrize("name", SEEDED)
@pytest.mark.parametrize("size", SIZES)
def test_seeded_generators(name, size):
    f = getattr(om, name)
    a = f(size, 7)
    shape = (size, size) if isinstance(size, int) else tuple(size)
    assert a.shape == shape and a.dtype == np.bool_
    assert np.array_equal(a, f(size, 7)), "same seed, same map"
    if min(shape) >= 64:
        assert not np.array_equal(a, f(size, 8)), "another seed, another map"
    # walls on the image border
    assert a[0].all() and a[-1].all() and a[:, 0].all() and a[:, -1].all()
    free = ~a
    assert 0.15 < free.mean() < 0.995
    sizes = components(free)
    if name == "cave":  # several pockets are fine; the largest is a real cave
        assert sizes.max() >= 0.1 * free.size
    else:  # everything free is reachable
        assert len(sizes) == 1


def test_narrow_buildings_stay_connected():
    # a band of rooms too thin to exist left the rooms beyond it unreachable (13 of 210 such maps)
    for shape in ((200, 40), (300, 40), (100, 30), (64, 20), (500, 45), (40, 200), (16, 300)):
        for seed in range(30):
            assert len(components(~om.building(shape, seed))) == 1, (shape, seed)


@pytest.mark.parametrize("name", SEEDED)
def test_seeded_generators_large(name):
    a = getattr(om, name)(2048, 3)
    assert a.shape == (2048, 2048) and a.dtype == np.bool_
    assert a[0].all() and a[-1].all() and a[:, 0].all() and a[:, -1].all()
    assert 0.15 < (~a).mean() < 0.995


def test_building_has_pillars_and_thin_walls():
    a = om.building(512, 1)
    ndimage = pytest.importorskip("scipy.ndimage")
    lab, n = ndimage.label(a)
    border = set(np.unique(np.concatenate([lab[0], lab[-1], lab[:, 0], lab[:, -1]]))) - {0}
    islands = set(range(1, n + 1)) - border
    assert len(islands) >= 2, "pillars: occupied components that touch no wall"
    # every wall is 1-3 px thick: no 4 x 4 block of occupied pixels except pillars and corners
    box = np.lib.stride_tricks.sliding_window_view(a, (4, 4)).all(axis=(2, 3))
    assert box.sum() < 0.01 * a.size


def test_warehouse_has_narrow_aisles():
    for size in (32, 64, 512, 2048):
        for seed in range(3):
            a = om.warehouse(size, seed)
            widths = set()
            for row in ~a:
                widths.update(free_runs(row))
            assert {1, 2, 3} <= widths, (size, seed, sorted(widths)[:5])


@pytest.mark.parametrize("size", [64, 100, 512, (80, 200), (300, 96), 2048])
def test_passages_corridor_widths_and_slopes(size):
    a = om.passages(size)
    H, W = (size, size) if isinstance(size, int) else size
    assert a.shape == (H, W) and a.dtype == np.bool_
    assert np.array_equal(a, om.passages(size))
    T = max(2, min(H, W) // 32)
    assert a[:T].all() and a[-T:].all() and a[:, :T].all() and a[:, -T:].all()
    assert not a[T].all()
    # the gallery: rows crossing exactly eight corridors, 1, 2, ..., 8 px wide from left to right
    gallery = [r for r in range(H) if free_runs(~a[r]) == list(range(1, 9))]
    assert len(gallery) >= 0.3 * (H - 2 * T)
    assert gallery == list(range(gallery[0], gallery[-1] + 1)), "one band of straight corridors"
    # corridor walls: at least 2 px thick
    row = a[gallery[0]]
    walls = free_runs(row[T:W - T])
    assert min(walls) >= 2
    # the bottom cells' wall faces: height of the solid above the floor, column by column; the runs
    # of equal height on a ramp (one row up at each step) are 1, 2, 3 and 5 columns long
    floor = H - T - 1
    height = np.array([np.argmin(a[floor::-1, x]) for x in range(T, W - T)])
    change = np.flatnonzero(np.diff(height)) + 1
    starts = np.concatenate([[0], change])
    ends = np.concatenate([change, [len(height)]])
    vals = height[starts]
    steps = {int(ends[i] - starts[i]) for i in range(1, len(vals) - 1)
             if vals[i] - vals[i - 1] == 1 and vals[i + 1] - vals[i] == 1}
    assert steps == {1, 2, 3, 5}


def test_passages_too_small():
    with pytest.raises(ValueError, match="at least 64"):
        om.passages(48)


def test_bad_sizes():
    with pytest.raises(ValueError, match="at least"):
        om.building(8, 0)
    with pytest.raises(ValueError, match="pair"):
        om.cave((32, 32, 3), 0)


# ------------------------------------------------------------------------------ the MovingAI reader
def test_real_map_paris():
    a = om.read_movingai_map(MAPS / "Paris_1_256.map")
    assert a.shape == (256, 256) and a.dtype == np.bool_
    # 47,240 passable cells: the count the MAPF benchmark tables give for Paris_1_256
    assert int((~a).sum()) == 47240
    assert (MAPS / "Paris_1_256.map").read_bytes().count(b"\r\n") == 260  # CRLF, as published


def test_round_trip(tmp_path):
    a = om.rooms_with_islands((40, 70), 2)
    path = tmp_path / "r.map"
    om.write_movingai_map(path, a)
    assert np.array_equal(om.read_movingai_map(path), a)
    assert np.array_equal(om.read_movingai_map(str(path)), a)


def test_reader_characters(tmp_path):
    path = tmp_path / "c.map"
    path.write_text("type octile\nheight 2\nwidth 4\nmap\n.G@O\nTSW.\n")
    expect = np.array([[0, 0, 1, 1], [1, 1, 1, 0]], dtype=bool)
    assert np.array_equal(om.read_movingai_map(path), expect)
    swamp_free = om.read_movingai_map(path, free_chars=".GS")
    assert not swamp_free[1, 1] and swamp_free[1, 2]
    # header lines in another order, trailing blank lines
    path.write_text("type octile\nwidth 4\nheight 2\nmap\n.G@O\nTSW.\n\n\n")
    assert np.array_equal(om.read_movingai_map(path), expect)


@pytest.mark.parametrize("text, line, message", [
    ("type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n", 6, "unknown character 'x' in column 2"),
    ("type octile\nheight 2\nwidth 3\nmap\n...\n..\n", 6, "map row 1 has 2 characters, width is 3"),
    ("type octile\nheight 3\nwidth 3\nmap\n...\n...\n", 7, "expected 3 map rows, the file has 2"),
    ("type octile\nheight 1\nwidth 3\nmap\n...\n...\n", 6, "text after the 1 map rows"),
    ("type octile\nheight two\nwidth 3\nmap\n...\n", 2, "height must be a positive integer"),
    ("type octile\nheight 0\nwidth 3\nmap\n", 2, "height must be a positive integer"),
    ("type octile\nwidth 3\nmap\n...\n", 3, "no 'height' line"),
    ("type octile\nheight 1\nwidth 3\nsize 3\nmap\n...\n", 4, "expected 'type NAME'"),
    ("type octile\nheight 1\nwidth 3\n", 4, "header ends before the 'map' line"),
    ("type octile\nheight 1\nheight 1\nwidth 3\nmap\n...\n", 3, "'height' given twice"),
])
def test_reader_errors(tmp_path, text, line, message):
    path = tmp_path / "bad.map"
    path.write_text(text)
    with pytest.raises(ValueError) as info:
        om.read_movingai_map(path)
    assert str(info.value).startswith(f"{path}:{line}: "), str(info.value)
    assert message in str(info.value)


def test_reader_not_ascii(tmp_path):
    path = tmp_path / "bin.map"
    path.write_bytes(b"type octile\nheight 1\nwidth 2\nmap\n\xff.\n")
    with pytest.raises(ValueError, match=r"bin\.map:5: not an ASCII"):
        om.read_movingai_map(path)


def test_resize_nearest():
    a = om.read_movingai_map(MAPS / "Paris_1_256.map")
    big = om.resize_nearest(a, 2048)
    assert big.shape == (2048, 2048)
    assert np.array_equal(big[::8, ::8], a) and np.array_equal(big[7::8, 5::8], a)
    odd = om.resize_nearest(a, (300, 200))
    assert odd.shape == (300, 200) and odd[0, 0] == a[0, 0] and odd[-1, -1] == a[-1, -1]
