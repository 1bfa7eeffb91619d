"""Heterogeneous teams (docs/heterogeneous.md): one radius per agent, power cells clipped to the disks."""
import json
import math
import pickle

import numpy as np
import pytest

import dvoronoi as dv


def union_area(points, radii):
    """Area of the union of the disks, independently of any diagram: Green's theorem on the union's
    boundary, the arcs of each circle that no other disk covers (covered angle intervals from the
    circle-circle intersections, in closed form). Exact up to rounding (about 1e-13 relative)."""
    total = 0.0
    n = len(points)
    for i in range(n):
        (cx, cy), r = points[i], radii[i]
        cover = []
        hidden = False
        for j in range(n):
            if j == i:
                continue
            dx, dy = points[j][0] - cx, points[j][1] - cy
            d, R = math.hypot(dx, dy), radii[j]
            if d >= r + R or d + R <= r:
                continue  # apart, or j inside i: nothing of i's circle covered
            if d + r <= R:
                hidden = True  # i inside j
                break
            theta = math.atan2(dy, dx)
            half = math.acos(max(-1.0, min(1.0, (r * r + d * d - R * R) / (2 * r * d))))
            a, b = (theta - half) % (2 * math.pi), (theta + half) % (2 * math.pi)
            cover += [(a, b)] if a <= b else [(a, 2 * math.pi), (0.0, b)]
        if hidden:
            continue
        cover.sort()
        free, at = [], 0.0
        for a, b in cover:
            if a > at:
                free.append((at, a))
            at = max(at, b)
        if at < 2 * math.pi:
            free.append((at, 2 * math.pi))
        for a, b in free:  # 1/2 the integral of x dy - y dx over the arc
            total += 0.5 * (r * r * (b - a) + r * (cx * (math.sin(b) - math.sin(a)) + cy * (math.cos(a) - math.cos(b))))
    return total


def team(n, seed, R=0.05):
    rng = np.random.default_rng(seed)
    return rng.random((n, 2)), R * (0.5 + rng.random(n))


def neighbor_sets(part):
    return [set(part.neighbors(i).tolist()) for i in range(len(part))]


def test_equal_radii_are_the_scalar_call_bit_for_bit():
    pts, _ = team(500, 1)
    a = dv.limited_cells(pts, 0.04)
    b = dv.limited_cells(pts, np.full(len(pts), 0.04))
    for name in ("indptr", "indices", "areas", "perimeters", "centroids", "piece_ptr", "piece_neighbor", "piece_x",
                 "piece_y", "piece_span"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert a.to_json() == b.to_json()
    assert b.computed_by["power"] == 0 and not b.empty.any()
    assert np.array_equal(b.radii, np.full(len(pts), 0.04))
    c1 = dv.limited_cell(pts[0], pts[1:], 0.04)
    c2 = dv.limited_cell(pts[0], pts[1:], 0.04, other_radii=np.full(len(pts) - 1, 0.04))
    assert c1.area == c2.area and np.array_equal(c1.vertices, c2.vertices)


@pytest.mark.parametrize("seed", range(4))
def test_areas_sum_to_the_union_of_the_disks(seed):
    pts, radii = team(300, seed, R=0.06 if seed < 2 else 0.15)
    part = dv.limited_cells(pts, radii)
    ran = part.computed_by
    assert ran["clip"] + ran["power"] == len(pts) and ran["scan"] == ran["chords"] == 0
    assert ran["clip"] > 0.9 * len(pts)  # the certified fast path decides nearly every cell
    assert part.areas.sum() == pytest.approx(union_area(pts, radii), rel=1e-9)
    assert np.all(part.areas <= np.pi * radii**2 * (1 + 1e-12))


def test_union_with_nested_tangent_and_coinciding_disks():
    pts = np.array([[0, 0], [0.5, 0], [3, 0], [3, 0], [0, -3], [9.5, 0], [2.5, 2]], float)
    radii = np.array([2.0, 1.0, 1.0, 0.5, 1.0, 1.0, 1.5])
    part = dv.limited_cells(pts, radii)
    assert part.empty.tolist() == [False, True, False, True, False, False, False]
    assert part.areas.sum() == pytest.approx(union_area(pts, radii), rel=1e-12)
    for i in np.flatnonzero(part.empty):
        assert part.areas[i] == 0 and len(part.neighbors(i)) == 0 and len(part.cell(i).pieces) == 0
        assert np.array_equal(part.centroids[i], pts[i])
    assert len(part.neighbors(4)) == 0  # tangent to disk 0: no edge of positive length


def test_crescent_the_agent_outside_its_cell():
    # The example: R = 10 at the origin, R = 1 at (9.5, 0).
    part = dv.limited_cells([[0, 0], [9.5, 0]], [10.0, 1.0])
    h = (9.5**2 + 100 - 1) / 19 - 9.5  # the radical axis, from p_1
    assert part.areas[1] == pytest.approx(math.acos(h) - h * math.sqrt(1 - h * h), rel=1e-12)
    assert part.centroids[1, 0] > 9.5 + h  # beyond the radical axis, away from the agent
    cell = part.cell(1)
    assert cell.radius == 1.0 and cell.neighbors.tolist() == [0]
    one = dv.limited_cell([9.5, 0], [[0, 0]], 1.0, other_radii=[10.0])
    assert one.area == pytest.approx(part.areas[1], rel=1e-12)


def test_neighbours_are_symmetric_and_invariant():
    pts, radii = team(400, 7)
    base = neighbor_sets(dv.limited_cells(pts, radii))
    for i, s in enumerate(base):
        assert all(i in base[j] for j in s)
    perm = np.random.default_rng(3).permutation(len(pts))
    inv = np.argsort(perm)
    moved = [
        (pts[perm], radii[perm], True),
        (pts[perm] @ np.array([[0, 1], [-1, 0]]), radii[perm], True),  # rotation by 90 degrees
        (pts[perm] * 8.0, radii[perm] * 8.0, True),
        (pts[perm] * 2.0**-5, radii[perm] * 2.0**-5, True),
        # Translation: coordinates on the grid 2^-40 stay exact under +4, -8.
        (np.round(pts[perm] * 2.0**40) * 2.0**-40 + np.array([4.0, -8.0]), radii[perm], True),
    ]
    grid = np.round(pts * 2.0**40) * 2.0**-40
    grid_base = neighbor_sets(dv.limited_cells(grid, radii))
    for k, (p, r, _) in enumerate(moved):
        got = neighbor_sets(dv.limited_cells(p, r))
        mapped = [{int(perm[j]) for j in got[inv[i]]} for i in range(len(pts))]
        assert mapped == (grid_base if k == len(moved) - 1 else base)


def test_bad_radii_name_the_argument():
    pts = np.zeros((3, 2)) + np.arange(3)[:, None]
    with pytest.raises(ValueError, match="radius"):
        dv.limited_cells(pts, [1.0, 2.0])
    with pytest.raises(ValueError, match=r"radius\[1\]"):
        dv.limited_cells(pts, [1.0, -2.0, 1.0])
    with pytest.raises(ValueError, match=r"radius\[2\]"):
        dv.limited_cells(pts, [1.0, 2.0, np.nan])
    with pytest.raises(ValueError, match="radius"):
        dv.limited_cells(pts, np.ones((3, 1)))
    with pytest.raises(ValueError, match="radius"):
        dv.limited_cells(pts, ["a", "b", "c"])
    with pytest.raises(ValueError, match="other_radii"):
        dv.limited_cell([0, 0], pts, 1.0, other_radii=[1.0])
    with pytest.raises(ValueError, match="method"):
        dv.limited_cells(pts, [1.0, 2.0, 1.0], method="clip")
    with pytest.raises(dv.CoincidentError, match="points\\[1\\] and points\\[2\\]"):
        dv.limited_cells([[0, 0], [1, 1], [1, 1]], [1.0, 2.0, 2.0])
    dv.limited_cells([[0, 0], [1, 1], [1, 1]], [1.0, 2.0, 3.0])  # same place, different radii: allowed


def test_pickle_and_json_keep_the_radii():
    pts, radii = team(200, 11)
    part = dv.limited_cells(pts, radii)
    back = pickle.loads(pickle.dumps(part))
    assert np.array_equal(back.radii, radii) and back.computed_by == part.computed_by
    assert np.array_equal(back.empty, part.empty) and back.cell(5).radius == radii[5]
    doc = json.loads(part.to_json())
    assert doc["radii"] == radii.tolist() and doc["radius"] == radii.max()


def _cli():
    import os
    import shutil
    return os.environ.get("DVORONOI_CLI") or shutil.which("dvoronoi")


@pytest.mark.skipif(_cli() is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)")
def test_cli_reads_a_radius_column(tmp_path):
    import subprocess
    pts, radii = team(60, 4)
    f = tmp_path / "team.csv"
    f.write_text("x,y,r\n" + "".join(f"{float(x)!r},{float(y)!r},{float(r)!r}\n" for (x, y), r in zip(pts, radii)))
    out = subprocess.run([_cli(), "cells", str(f), "--columns", "x,y,r", "-q"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == dv.limited_cells(pts, radii).to_json()
    both = subprocess.run([_cli(), "cells", str(f), "--columns", "x,y,r", "-r", "1", "-q"], capture_output=True, text=True)
    assert both.returncode != 0 and "--radius" in both.stderr
    f.write_text("0 0 1\n1 0 -1\n")
    bad = subprocess.run([_cli(), "cells", str(f), "--columns", "0,1,2", "-q"], capture_output=True, text=True)
    assert bad.returncode != 0 and f"{f}:2:5: radius must be positive" in bad.stderr


def test_empty_cells_export():
    part = dv.limited_cells([[0, 0], [0, 0], [1, 0]], [1.0, 2.0, 1.0])
    assert part.empty.tolist() == [True, False, True]
    features = json.loads(part.to_geojson())["features"]
    assert features[0]["geometry"] == {"coordinates": [], "type": "Polygon"}
    assert len(features[1]["geometry"]["coordinates"][0]) > 3
    cell = dv.limited_cell([0, 0], [[0, 0], [1, 0]], 1.0, other_radii=[2.0, 1.0])
    assert cell.area == 0 and len(cell.pieces) == 0 and len(cell.neighbors) == 0
    assert json.loads(cell.to_geojson())["geometry"]["coordinates"] == []
