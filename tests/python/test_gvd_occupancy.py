"""The grid diagram on occupancy grids (dv.grid_voronoi on arrays, OccupancyGrid and map files):
the medial definition against an independent numpy oracle and the C++ brute force, invariants on
real-shaped maps, map files, updates, paths and clearance."""
import io
import json
import os
import pickle
import subprocess

import numpy as np
import pytest
from scipy import ndimage

import dvoronoi as dv
from dvoronoi import _core, occupancy_maps

CLI = os.environ.get("DVORONOI_CLI")
REST = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"  # keys map_server requires besides image, resolution, origin


def assert_is_full_build(gv, occ, workers):
    """An updated diagram equals a full build on the map it ends with."""
    full = dv.grid_voronoi(occ, workers=workers)
    assert np.array_equal(gv.grid.occupied, occ)
    assert np.array_equal(gv.diagram_mask, full.diagram_mask)
    assert np.array_equal(gv.clearance_map, full.clearance_map)


# -- an independent oracle of the definition (numpy; doubled pixel units) ------------------------

def oracle_features(occ):
    """Nearest point of the occupied squares and the outside to each pixel centre; ties to the
    smallest x, then y."""
    H, W = occ.shape
    rr, cc = np.nonzero(occ)
    sx0, sy0 = 2 * cc, 2 * (H - 1 - rr)
    fx = np.zeros((H, W), np.int64)
    fy = np.zeros((H, W), np.int64)
    for r in range(H):
        for c in range(W):
            X, Y = 2 * c + 1, 2 * (H - 1 - r) + 1
            if occ[r, c]:
                fx[r, c], fy[r, c] = X, Y
                continue
            px = np.r_[np.clip(X, sx0, sx0 + 2), 0, 2 * W, X, X]
            py = np.r_[np.clip(Y, sy0, sy0 + 2), Y, Y, 0, 2 * H]
            d = (px - X) ** 2 + (py - Y) ** 2
            k = np.flatnonzero(d == d.min())
            j = k[np.lexsort((py[k], px[k]))[0]]
            fx[r, c], fy[r, c] = px[j], py[j]
    return fx, fy


def oracle_joined(occ, a, b):
    """Are a's and b's squares joined by occupied squares meeting the box of a, b grown by 1 px?"""
    H, W = occ.shape
    pad = np.ones((H + 2, W + 2), bool)   # the outside is occupied: index (j + 1, c + 1), j from the bottom
    pad[1:-1, 1:-1] = occ[::-1]
    xlo, xhi = min(a[0], b[0]) - 2, max(a[0], b[0]) + 2
    ylo, yhi = min(a[1], b[1]) - 2, max(a[1], b[1]) + 2
    cs = [c for c in range(-1, W + 1) if 2 * c <= xhi and 2 * c + 2 >= xlo]
    js = [j for j in range(-1, H + 1) if 2 * j <= yhi and 2 * j + 2 >= ylo]
    sub = pad[js[0] + 1:js[-1] + 2, cs[0] + 1:cs[-1] + 2]
    lab, _ = ndimage.label(sub, structure=np.ones((3, 3), bool))

    def labels_at(p):
        out = set()
        for c in {(p[0] - 1) // 2, p[0] // 2} if p[0] % 2 == 0 else {p[0] // 2}:
            for j in {(p[1] - 1) // 2, p[1] // 2} if p[1] % 2 == 0 else {p[1] // 2}:
                if cs[0] <= c <= cs[-1] and js[0] <= j <= js[-1] and lab[j - js[0], c - cs[0]]:
                    out.add(lab[j - js[0], c - cs[0]])
        return out
    return bool(labels_at(a) & labels_at(b))


def oracle_medial(occ, min_separation=1.5, prune_length=8.0):
    H, W = occ.shape
    fx, fy = oracle_features(occ)
    out = np.zeros((H, W), bool)
    for r in range(H):
        for c in range(W):
            if occ[r, c]:
                continue
            p = np.array([2 * c + 1, 2 * (H - 1 - r) + 1])
            a = np.array([fx[r, c], fy[r, c]])
            for r2, c2 in ((r, c - 1), (r, c + 1), (r - 1, c), (r + 1, c)):
                if not (0 <= r2 < H and 0 <= c2 < W) or occ[r2, c2]:
                    continue
                q = np.array([2 * c2 + 1, 2 * (H - 1 - r2) + 1])
                b = np.array([fx[r2, c2], fy[r2, c2]])
                d2 = ((a - b) ** 2).sum()
                if d2 <= 4 * min_separation ** 2:
                    continue
                if ((p - b) ** 2).sum() - ((p - a) ** 2).sum() > ((q - a) ** 2).sum() - ((q - b) ** 2).sum():
                    continue
                if d2 <= 4 * prune_length ** 2 and oracle_joined(occ, a, b):
                    continue
                out[r, c] = True
    return out


def small_maps():
    rng = np.random.default_rng(3)
    maps = []
    for _ in range(6):
        H, W = rng.integers(3, 22, size=2)
        occ = np.zeros((H, W), bool)
        for _ in range(rng.integers(0, 6)):
            r, c = rng.integers(0, H), rng.integers(0, W)
            occ[r:r + rng.integers(1, 6), c:c + rng.integers(1, 6)] = True
        maps.append(occ)
    maps.append(occupancy_maps.building(20, 1))
    maps.append(occupancy_maps.cave(24, 2))
    return maps


@pytest.mark.parametrize("k", range(8))
def test_medial_equals_independent_oracle(k):
    occ = small_maps()[k]
    for prune in (0.0, 3.0, 8.0):
        gv = dv.grid_voronoi(occ, prune_length=prune, workers=1)
        assert np.array_equal(gv.diagram_mask, oracle_medial(occ, 1.5, prune))


@pytest.mark.parametrize("name", ["building", "warehouse", "cave", "rooms_with_islands"])
def test_medial_equals_brute_force_on_real_shaped_maps(name):
    occ = getattr(occupancy_maps, name)(72, 5)
    oracle = _core._medial_brute_force(occ.astype(np.uint8), 1.5, 8.0)
    for workers in (1, 2, 3, None):
        gv = dv.grid_voronoi(occ, workers=workers)
        assert np.array_equal(gv.diagram_mask, oracle)
    assert gv.diagram_mask.any()


def test_large_maps_are_read_in_and_out_alike_by_any_number_of_threads():
    # from 1 MB on, the map's copy into the core and the diagram's mask out of it are split over
    # the workers; any nonzero byte is occupied
    occ = occupancy_maps.building(1100, 3)
    raw = np.where(occ, (1 + np.arange(occ.size) % 255).reshape(occ.shape), 0).astype(np.uint8)
    one = _core._medial_build(np.ascontiguousarray(occ).view(np.uint8), 1.0, 0.0, 0.0, 1.5, 8.0, 1)
    assert 0 < one.count == one.mask.sum()
    for workers in (2, 3):
        core = _core._medial_build(raw, 1.0, 0.0, 0.0, 1.5, 8.0, workers)
        assert np.array_equal(core.occupancy, occ)
        assert np.array_equal(core.mask, one.mask)


def test_corridors_between_parts_of_one_wall_have_centrelines():
    # one wall (a comb): every corridor lies between two teeth of the same connected wall
    H, W = 40, 80
    occ = np.zeros((H, W), bool)
    occ[H - 4:, :] = True
    c = 2
    for width in range(1, 9):
        occ[8:H - 4, c:c + 2] = True      # a tooth
        c += 2 + width
    occ[8:H - 4, c:c + 2] = True
    assert ndimage.label(occ, structure=np.ones((3, 3)))[1] == 1
    gv = dv.grid_voronoi(occ)
    c = 4
    for width in range(1, 9):
        middle = c + width / 2
        # the slots end at the comb's base: the centreline stops where the two corners' bisectors meet
        for r in range(10, H - 4 - width // 2 - 2):
            on = [x for x in range(c, c + width) if gv.diagram_mask[r, x] and abs(x + 0.5 - middle) <= 1]
            if width >= 2:
                assert on, (width, r)
            else:
                assert not gv.diagram_mask[r, c]
        c += width + 2
    # the labelled (paper's) diagram has nothing inside them: one wall is one label
    labels = dv.grid_voronoi(occ, diagram="labels")
    image_row = H - 1 - labels.cells[:, 1]
    inside = (image_row > 10) & (image_row < H - 12) & (labels.cells[:, 0] > 4) & (labels.cells[:, 0] < c - 1)
    assert not inside.any()


def test_island_loops_and_disconnected_free_regions_are_found():
    occ = np.zeros((50, 70), bool)
    occ[:, 30:33] = True              # a wall splits the map: the right part never meets a map corner
    occ[20:24, 10:14] = True          # an island on the left
    occ[10:14, 50:55] = True          # and on the right
    gv = dv.grid_voronoi(occ)
    for (r, c) in ((19, 11), (9, 52)):
        free = ~occ & ~gv.diagram_mask
        lab, _ = ndimage.label(free)   # 4-connected: cannot cross an 8-connected curve
        assert lab[r, c] != lab[0, 0] and lab[r, c] != lab[0, 69] and lab[r, c] != lab[49, 69]
    assert gv.diagram_mask[:, 33:].any()


def test_coordinates_follow_the_image_and_the_origin():
    occ = np.zeros((6, 9), bool)
    occ[0, :] = True                  # the top row of the image
    gv = dv.grid_voronoi(occ, resolution=0.5, origin=(10.0, -3.0))
    assert gv.grid.extent == (10.0, 14.5, -3.0, 0.0)
    # the top row's pixels are at the top of the map
    assert gv.grid.pixel_centers([[0, 0]])[0].tolist() == [10.25, -0.25]
    assert gv.clearance_map[1, 4] == pytest.approx(0.25)   # half a pixel below the top wall
    assert gv.clearance_map[0, 4] == 0.0
    pts = gv.points
    assert np.allclose(pts, gv.grid.pixel_centers(gv.pixels))
    assert np.all(gv.clearance == gv.clearance_map[gv.diagram_mask])


def test_input_forms_and_unknown_pixels():
    rng = np.random.default_rng(0)
    occ = rng.random((30, 40)) < 0.1
    base = dv.grid_voronoi(occ).diagram_mask
    assert np.array_equal(dv.grid_voronoi(occ.astype(np.uint8)).diagram_mask, base)
    assert np.array_equal(dv.grid_voronoi(np.where(occ, 0.9, 0.1)).diagram_mask, base)
    ros = np.where(occ, 100, 0).astype(np.int8)
    assert np.array_equal(dv.grid_voronoi(ros).diagram_mask, base)
    ros[5:8, 5:8] = -1   # unknown
    unknown_occ = dv.grid_voronoi(ros)
    unknown_free = dv.grid_voronoi(ros, unknown="free")
    assert unknown_occ.grid.occupied[6, 6] and not unknown_free.grid.occupied[6, 6]
    probs = np.where(occ, 0.9, 0.1)
    probs[0, 0] = np.nan
    assert dv.grid_voronoi(probs).grid.occupied[0, 0]
    assert not dv.grid_voronoi(probs, unknown="free").grid.occupied[0, 0]
    grid = dv.OccupancyGrid(occ, resolution=0.05, origin=(1, 2, 0))
    gv = dv.grid_voronoi(grid)
    assert gv.resolution == 0.05 and gv.origin == (1.0, 2.0)


@pytest.mark.parametrize("bad, kind, match", [
    (np.zeros((3, 4, 2)), ValueError, r"2-d array"),
    (np.zeros((0, 4), bool), ValueError, r"at least one row"),
    (np.full((3, 3), 1.5), ValueError, r"occupancy\[0, 0\] = 1.5.*\[0, 1\]"),
    (np.full((3, 3), 7), ValueError, r"occupancy\[0, 0\] = 7.*0/1"),
    (np.full((3, 3), -5, np.int8), ValueError, r"-1 \(unknown\) or 0..100"),
    (np.array([["a", "b"]]), TypeError, r"dtype"),
])
def test_bad_occupancy_arrays(bad, kind, match):
    with pytest.raises(kind, match=match):
        dv.grid_voronoi(bad)


def test_bad_arguments_name_themselves():
    occ = np.zeros((10, 10), bool)
    for kwargs, match in [({"workers": 0}, "workers"), ({"workers": 2.5}, "workers"), ({"robot_radius": -1}, "robot_radius"),
                          ({"resolution": 0}, "resolution"), ({"origin": (0, 0, 1)}, "rotated"), ({"diagram": "x"}, "diagram"),
                          ({"min_separation": 0.5}, "min_separation"), ({"prune_length": -1}, "prune_length"),
                          ({"unknown": "maybe"}, "unknown"), ({"area": (0, 0, 1, 1)}, "area"), ({"cells": 10}, "cells")]:
        with pytest.raises(ValueError, match=match):
            dv.grid_voronoi(occ, **kwargs)
    with pytest.deprecated_call():
        dv.grid_voronoi([{"type": "point", "position": [1, 1]}], area=(0, 0, 2, 2), resolution=16)


# -- map files -------------------------------------------------------------------------------------

def write_pgm(path, img, binary=True):
    H, W = img.shape
    if binary:
        path.write_bytes(b"P5\n# made by the tests\n%d %d\n255\n" % (W, H) + img.astype(np.uint8).tobytes())
    else:
        path.write_text("P2\n%d %d\n255\n" % (W, H) + "\n".join(" ".join(map(str, row)) for row in img) + "\n")


def test_ros_yaml_pgm_png_and_movingai(tmp_path):
    rng = np.random.default_rng(5)
    img = np.full((30, 50), 254, np.uint8)
    img[rng.random(img.shape) < 0.15] = 0
    img[3:6, 3:6] = 205   # unknown grey (p = 0.196 .. 0.65)
    write_pgm(tmp_path / "m.pgm", img)
    (tmp_path / "m.yaml").write_text("image: m.pgm   # the image\nresolution: 0.05\norigin: [-1.0, 2.5, 0.0]\n"
                                     "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n")
    g = dv.OccupancyGrid.load(tmp_path / "m.yaml")
    expect = (img == 0) | (img == 205)
    assert np.array_equal(g.occupied, expect) and g.resolution == 0.05 and g.origin == (-1.0, 2.5)
    assert g.unknown_pixels == 9
    assert not dv.OccupancyGrid.load(tmp_path / "m.yaml", unknown="free").occupied[4, 4]
    write_pgm(tmp_path / "p2.pgm", img, binary=False)
    assert np.array_equal(dv.OccupancyGrid.load(tmp_path / "p2.pgm").occupied, expect)
    neg = dv.OccupancyGrid.load(tmp_path / "m.pgm", negate=True)
    assert np.array_equal(neg.occupied, img > 0.65 * 255)
    gv = dv.grid_voronoi(tmp_path / "m.yaml")
    assert np.array_equal(gv.diagram_mask, dv.grid_voronoi(dv.OccupancyGrid(expect, 0.05, (-1, 2.5))).diagram_mask)
    if _core._has_png:
        from PIL import Image  # a grey PNG (matplotlib writes RGBA, whose alpha map_server averages in)
        Image.fromarray(img, "L").save(tmp_path / "m.png")
        assert np.array_equal(dv.OccupancyGrid.load(tmp_path / "m.png").occupied, expect)
    rows = ["".join("@" if v else "." for v in row) for row in expect]
    rows[0] = "G" + rows[0][1:] if not expect[0, 0] else rows[0]
    (tmp_path / "m.map").write_text("type octile\nheight 30\nwidth 50\nmap\n" + "\n".join(rows) + "\n")
    assert np.array_equal(dv.OccupancyGrid.load(tmp_path / "m.map").occupied, expect)


def test_real_city_map_from_movingai():
    path = os.path.join(os.path.dirname(__file__), "..", "data", "maps", "Paris_1_256.map")
    g = dv.OccupancyGrid.load(path)
    assert g.shape == (256, 256) and int((~g.occupied).sum()) == 47240
    gv = dv.grid_voronoi(g)
    assert len(gv) > 2000
    # every free region wider than a few pixels holds diagram pixels
    lab, n = ndimage.label(~g.occupied)
    sizes = ndimage.sum(np.ones_like(lab), lab, index=np.arange(1, n + 1))
    for region in np.flatnonzero(sizes > 50) + 1:
        assert gv.diagram_mask[lab == region].any()


@pytest.mark.parametrize("name, text, match", [
    ("t.pgm", b"P5\n10 10\n255\n" + bytes(20), r"t.pgm: truncated PGM data \(20 of 100"),
    ("h.pgm", b"P5\n10", r"h.pgm: truncated PGM header"),
    ("x.pgm", b"P7\n1 1\n255\n\x00", r"x.pgm: not a PGM image"),
    ("a.yaml", b"image: a.pgm\nresolution: fast\n", r"a.yaml:2: resolution: expected a finite decimal number"),
    ("b.yaml", b"image: a.pgm\nresolution: 0.1\norigin: [1.0]\n", r"b.yaml:3: origin: expected \[x, y, yaw\]"),
    ("c.yaml", b"resolution: 0.1\n", r"c.yaml.*missing 'image'"),
    ("m.map", b"type octile\nheight 2\nwidth 3\nmap\n...\n..\n", r"m.map:6: map row 1 has 2 characters, width is 3"),
    ("n.map", b"type octile\nheight 2\nwidth 3\n", r"n.map:4: header ends before the 'map' line"),
    ("e.txt", b"", r"unknown map format"),
])
def test_bad_map_files_name_file_and_line(tmp_path, name, text, match):
    (tmp_path / name).write_bytes(text)
    with pytest.raises(ValueError, match=match):
        dv.OccupancyGrid.load(tmp_path / name)


# -- updates ---------------------------------------------------------------------------------------

def test_updates_give_the_full_build_after_random_sequences():
    rng = np.random.default_rng(11)
    for trial in range(12):
        occ = occupancy_maps.rooms_with_islands(64, trial) if trial % 2 else rng.random((48, 56)) < 0.08
        gv = dv.grid_voronoi(occ, workers=1)
        cur = occ.copy()
        for step in range(8):
            kind = rng.integers(3)
            r, c = rng.integers(0, cur.shape[0]), rng.integers(0, cur.shape[1])
            h, w = rng.integers(1, 6, size=2)
            block = [(i, j) for i in range(r, min(cur.shape[0], r + h)) for j in range(c, min(cur.shape[1], c + w))]
            as_mask = np.zeros(cur.shape, bool)
            as_mask[tuple(np.array(block).T)] = True
            pixels = as_mask if step % 2 else block  # both forms: a mask is scanned in C++
            if kind == 0:
                gv.set_occupied(pixels)
                cur[as_mask] = True
            elif kind == 1:
                gv.set_free(pixels)
                cur[as_mask] = False
            else:
                cur = cur ^ (rng.random(cur.shape) < 0.01)
                gv.update(cur)
            assert_is_full_build(gv, cur, workers=2)


def test_update_arguments_are_checked():
    gv = dv.grid_voronoi(np.zeros((10, 12), bool))
    with pytest.raises(ValueError, match=r"shape \(10, 12\)"):
        gv.update(np.zeros((10, 11), bool))
    with pytest.raises(ValueError, match=r"pixels\[1\] = \(10, 0\) is outside the 10 x 12 map"):
        gv.set_occupied([(0, 0), (10, 0)])
    with pytest.raises(ValueError, match=r"mask must have the map's shape"):
        gv.set_free(np.zeros((3, 3), bool))
    stats = gv.set_occupied(np.eye(10, 12, dtype=bool))
    assert stats["changed_pixels"] == 10


# -- paths and clearance ---------------------------------------------------------------------------

def occupied_union(occ, resolution=1.0, origin=(0.0, 0.0)):
    import shapely
    from shapely.geometry import box
    H, W = occ.shape
    x0, y0 = origin
    squares = [box(x0 + c * resolution, y0 + (H - 1 - r) * resolution, x0 + (c + 1) * resolution,
                   y0 + (H - r) * resolution) for r, c in np.argwhere(occ)]
    frame = box(x0, y0, x0 + W * resolution, y0 + H * resolution).exterior.buffer(1e-9)
    return shapely.union_all(squares + [frame])


def test_paths_keep_the_radius_and_exist_when_the_spec_promises_them():
    from shapely.geometry import LineString
    rng = np.random.default_rng(2)
    for trial in range(6):
        occ = occupancy_maps.building(64, trial) if trial % 2 else occupancy_maps.rooms_with_islands(64, trial)
        gv = dv.grid_voronoi(occ, resolution=0.1, origin=(-2.0, 1.0))
        walls = occupied_union(occ, 0.1, (-2.0, 1.0))
        cm = gv.clearance_map
        for radius in (0.0, 0.05, 0.12):
            # pixels whose centres clear r + 1 pixel, 4-connected: the continuous set {d > r + 1 px}
            # connects any two of one component, so docs/spec.md promises a path between them
            spare, _ = ndimage.label(cm > radius + 0.1)
            ok = np.argwhere(spare > 0)
            found = 0
            for k in range(8):
                a = ok[rng.integers(len(ok))]
                pool = np.argwhere(spare == spare[tuple(a)]) if k % 2 else ok   # half the pairs in one component
                b = pool[rng.integers(len(pool))]
                start, goal = gv.grid.pixel_centers([a, b])
                route = gv.path(start, goal, robot_radius=radius)
                if spare[tuple(a)] == spare[tuple(b)]:
                    assert len(route) >= 2, (trial, radius, a, b)
                if len(route):
                    found += 1
                    assert np.allclose(route[0], start) and np.allclose(route[-1], goal)
                    assert LineString(route).distance(walls) > radius
            assert found > 0


def test_no_path_through_a_door_narrower_than_the_robot():
    occ = np.zeros((30, 40), bool)
    occ[14:16, :] = True
    occ[14:16, 18:21] = False          # a door 3 pixels wide
    gv = dv.grid_voronoi(occ)
    start, goal = (20.0, 25.0), (20.0, 5.0)
    assert len(gv.path(start, goal, robot_radius=1.4)) >= 2      # the door's centre is 1.5 from the jambs
    assert len(gv.path(start, goal, robot_radius=1.5)) == 0      # not greater than 1.5: no path
    occ[14:16, 18:21] = True
    gv.update(occ)
    assert len(gv.path(start, goal, robot_radius=0.0)) == 0


def test_path_follows_the_diagram_and_refuses_bad_points():
    occ = occupancy_maps.building(96, 3)
    gv = dv.grid_voronoi(occ)
    spare, _ = ndimage.label(gv.clearance_map > 1.5 + 0.5)
    big = np.bincount(spare.ravel())[1:].argmax() + 1
    free = np.argwhere((spare == big) & (gv.clearance_map > 3))
    start, goal = gv.grid.pixel_centers([free[0], free[-1]])
    route = gv.path(start, goal, robot_radius=0.5)
    assert len(route) > 2
    # most of the route's length runs over diagram pixels (sampled along the segments)
    pts = np.concatenate([np.linspace(p, q, 20, endpoint=False) for p, q in zip(route[:-1], route[1:])])
    rc = np.stack([occ.shape[0] - 1 - np.floor(pts[:, 1]), np.floor(pts[:, 0])], axis=1).astype(int)
    near = ndimage.binary_dilation(gv.diagram_mask, iterations=1)
    assert near[rc[:, 0], rc[:, 1]].mean() > 0.6
    with pytest.raises(ValueError, match=r"start \(-5, 1\) is outside the map"):
        gv.path((-5, 1), goal)
    wall = np.argwhere(occ)[5]
    with pytest.raises(ValueError, match=r"goal .* is blocked"):
        gv.path(start, gv.grid.pixel_centers([wall])[0])


def test_clearance_at_matches_shapely():
    from shapely.geometry import Point
    occ = occupancy_maps.cave(40, 1)
    gv = dv.grid_voronoi(occ, resolution=0.5, origin=(3, 4))
    walls = occupied_union(occ, 0.5, (3, 4))
    rng = np.random.default_rng(0)
    pts = np.stack([3 + rng.random(200) * 20, 4 + rng.random(200) * 20], axis=1)
    got = gv.clearance_at(pts)
    want = np.array([0.0 if walls.contains(Point(p)) else Point(p).distance(walls) for p in pts])
    assert np.allclose(got, want, atol=1e-8)


def test_clearance_at_in_open_space_reads_far_walls_across_words():
    """Points far from sparse walls (searched 64 squares at a time): exact against every square."""
    rng = np.random.default_rng(3)
    occ = np.zeros((150, 300), bool)
    for r, c in rng.integers(0, (150, 300), (12, 2)):
        occ[r:r + 3, c:c + 2] = True
    gv = dv.grid_voronoi(occ, resolution=0.25, origin=(-7.0, 2.0))
    H, W = occ.shape
    pts = np.stack([rng.uniform(0, W, 400), rng.uniform(0, H, 400)], axis=1)  # pixel units, y up
    rows, cols = np.nonzero(occ)
    jj = H - 1 - rows
    dx = np.maximum(np.maximum(cols[None, :] - pts[:, :1], 0.0), pts[:, :1] - (cols[None, :] + 1.0))
    dy = np.maximum(np.maximum(jj[None, :] - pts[:, 1:], 0.0), pts[:, 1:] - (jj[None, :] + 1.0))
    edge = np.minimum.reduce([pts[:, 0], W - pts[:, 0], pts[:, 1], H - pts[:, 1]])
    want = 0.25 * np.minimum(np.sqrt(dx * dx + dy * dy).min(axis=1), edge)
    got = gv.clearance_at(np.asarray((-7.0, 2.0)) + 0.25 * pts)
    assert (want > 2.0).sum() > 100  # most points lie far from every wall
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)


def test_paths_along_diagonal_stretches_of_the_diagram_are_straightened():
    """A diagonal diagram line is 8-connected, the search 4-connected: the pixel path alternates
    diagram pixels and pixels beside them, and is still straightened along the diagram."""
    room = dv.grid_voronoi(np.zeros((60, 60), bool))  # its diagram: the two diagonals
    corridor = np.array([[abs((119 - r) - c) > 5 for c in range(120)] for r in range(120)])  # |y - x| <= 5 free
    band = dv.grid_voronoi(corridor, robot_radius=1.0)
    for gv, s, g in ((room, (10.5, 10.5), (49.5, 49.5)), (band, (10.5, 10.5), (109.5, 109.5))):
        for cost in (3.0, 1.0):
            route = gv.path(s, g, off_diagram_cost=cost)
            straight = float(np.hypot(*np.subtract(g, s)))
            assert gv.stats["last_path"]["length"] < 1.02 * straight and len(route) < 12, (cost, len(route))
            assert gv.clearance_at(route).min() > gv.robot_radius


# -- results: pickling, JSON, SVG, plots, CLI -----------------------------------------------------

def test_plots_of_maps_larger_than_the_axes_keep_every_diagram_line():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    occ = np.ones((1500, 1500), bool)
    rows = [60 + 140 * k + k for k in range(10)]  # ten corridors 5 px wide at different phases
    for r in rows:
        occ[r:r + 5, 20:1480] = False
    gv = dv.grid_voronoi(occ, resolution=0.1, origin=(5.0, -3.0))
    strips = np.zeros((1500, 1500), bool)  # separate walls: the labelled diagram's midlines between them
    for k in range(11):
        strips[10 + 140 * k:13 + 140 * k, 20:1480] = True
    labelled = dv.grid_voronoi(strips, diagram="labels")

    def lines(mask):  # groups of rows that are mostly diagram
        rows_on = np.flatnonzero(mask.sum(axis=1) > mask.shape[1] // 2)
        return 0 if len(rows_on) == 0 else 1 + int((np.diff(rows_on) > 1).sum())

    assert lines(gv.diagram_mask) == 10 and lines(labelled.diagram_mask) >= 10
    for result, line in ((gv, 2), (labelled, 1)):
        ax = result.plot()
        image = [a for a in ax.get_images() if a.get_gid() in ("dvoronoi-gvd-medial", "dvoronoi-gvd-cells")][0]
        shown = np.asarray(image.get_array())
        box = ax.get_window_extent()
        assert shown.shape[0] <= box.height + 1 and shown.shape[1] <= box.width + 1  # reduced to the axes
        assert lines(shown == line) == lines(result.diagram_mask)  # no line dropped
    lo, hi = gv.plot().get_xlim()
    assert (lo, hi) == pytest.approx((5.0, 155.0))
    # saved at a lower dpi, each drawing reduces for that renderer's pixels
    ax = gv.plot()
    image = [a for a in ax.get_images() if a.get_gid() == "dvoronoi-gvd-medial"][0]
    ax.figure.savefig(io.BytesIO(), dpi=40, format="png")
    shown, box = np.asarray(image.get_array()), ax.get_window_extent()
    assert shown.shape[0] <= box.height * 40 / ax.figure.dpi + 1
    plt.close("all")


def test_plots_do_not_depend_on_matplotlibs_image_origin_setting():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    occ = occupancy_maps.rooms_with_islands((40, 60), 1)
    doc = dv.obstacles_from_occupancy_grid(occ.astype(float), 0.5)
    pictures = []
    for origin in ("upper", "lower"):
        with matplotlib.rc_context({"image.origin": origin}):
            for result in (dv.grid_voronoi(occ, resolution=0.5), dv.grid_voronoi(doc, cells=60)):
                buf = io.BytesIO()
                result.plot().figure.savefig(buf, format="png")
                pictures.append(buf.getvalue())
                plt.close("all")
    assert pictures[0] == pictures[2] and pictures[1] == pictures[3]


def test_pickle_json_svg_and_plot(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    occ = occupancy_maps.rooms_with_islands(60, 4)
    gv = dv.grid_voronoi(occ, resolution=0.2, robot_radius=0.3)
    gv.set_occupied([(30, 30)])
    back = pickle.loads(pickle.dumps(gv))
    assert np.array_equal(back.diagram_mask, gv.diagram_mask) and back.robot_radius == 0.3
    doc = json.loads(gv.to_json())
    assert doc["diagram"] == "medial" and doc["map"]["rows"] == 60
    assert doc["pixels"]["row"] == gv.pixels[:, 0].tolist()
    assert np.allclose(doc["pixels"]["clearance"], gv.clearance)
    free = np.argwhere(gv.clearance_map > 1.0)
    route = gv.path(*gv.grid.pixel_centers([free[0], free[-1]]))
    svg = gv.to_svg(route=route)
    assert svg.startswith("<svg") and 'id="path"' in svg and 'id="diagram"' in svg
    gv.to_svg(tmp_path / "m.svg", route=route)
    assert (tmp_path / "m.svg").read_text() == svg
    ax = gv.plot(path=route, clearance=True)
    assert {"dvoronoi-gvd-medial", "dvoronoi-gvd-path"} <= {a.get_gid() for a in ax.get_children()}


def test_empty_diagram_is_explained():
    occ = np.zeros((9, 1), bool)
    with pytest.warns(UserWarning, match="no diagram pixel"):
        gv = dv.grid_voronoi(occ)
    assert len(gv) == 0


def test_fully_occupied_map_is_explained():
    with pytest.warns(UserWarning, match="every pixel of the 6 x 7 map is occupied") as record:
        gv = dv.grid_voronoi(np.ones((6, 7), bool))
    assert len(gv) == 0 and "unknown" not in str(record[0].message)
    ros = np.full((6, 7), -1, np.int8)  # all unknown (ROS OccupancyGrid)
    with pytest.warns(UserWarning, match="42 of them are unknown, which unknown='free' would make free"):
        dv.grid_voronoi(ros)
    gv = dv.grid_voronoi(ros, unknown="free")
    assert len(gv) > 0 and gv.grid.unknown_pixels == 42
    known = np.zeros((6, 7), np.int8)
    known[0, 0] = -1
    gv.update(known)
    assert gv.grid.unknown_pixels == 1 and dv.OccupancyGrid(known).unknown_pixels == 1
    assert dv.OccupancyGrid(np.array([[np.nan, 0.2]])).unknown_pixels == 1


def test_empty_labelled_and_document_diagrams_are_explained():
    with pytest.warns(UserWarning, match="every pixel of the 6 x 7 map is occupied"):
        assert len(dv.grid_voronoi(np.ones((6, 7), bool), diagram="labels").cells) == 0
    ring = np.zeros((20, 30), bool)
    ring[[0, -1], :] = ring[:, [0, -1]] = True  # one connected wall: the labelled diagram has nothing to split
    with pytest.warns(UserWarning, match="walls are one connected region, which the labelled diagram does not split"):
        assert len(dv.grid_voronoi(ring, diagram="labels").cells) == 0
    assert len(dv.grid_voronoi(ring)) > 0  # the medial diagram splits it
    covered = {"area": {"box": [0, 0, 10, 10]},
               "obstacles": [{"type": "polygon", "vertices": [[-1, -1], [11, -1], [11, 11], [-1, 11]]}]}
    with pytest.warns(UserWarning, match="every pixel of the document drawn on 16 x 16 pixels meets an obstacle"):
        assert len(dv.grid_voronoi(covered, cells=16, diagram="medial")) == 0
    with pytest.warns(UserWarning, match="no diagram cell: the corners of every cell share one nearest obstacle"):
        assert len(dv.grid_voronoi(covered, cells=16).cells) == 0


@pytest.mark.skipif(not CLI, reason="DVORONOI_CLI not set")
def test_cli_explains_an_empty_diagram_even_when_quiet(tmp_path):
    (tmp_path / "unknown.pgm").write_bytes(b"P5\n6 5\n255\n" + bytes([205]) * 30)  # all unknown grey
    run = subprocess.run([CLI, "gvd", str(tmp_path / "unknown.pgm"), "-o", str(tmp_path / "u.json"), "-q"],
                         capture_output=True, text=True, check=True)
    assert run.stderr == ("gvd: warning: no diagram pixel: every pixel of the 5 x 6 map is occupied (check the map's "
                          "negate and thresholds; 30 of them are unknown, which --unknown free would make free)\n")
    (tmp_path / "slit.map").write_text("type octile\nheight 3\nwidth 5\nmap\n@@@@@\n@...@\n@@@@@\n")
    run = subprocess.run([CLI, "gvd", str(tmp_path / "slit.map"), "-o", str(tmp_path / "s.json"), "-q"],
                         capture_output=True, text=True, check=True)
    assert "under 2 pixels wide" in run.stderr and "every pixel" not in run.stderr


@pytest.mark.skipif(not CLI, reason="DVORONOI_CLI not set")
def test_cli_map_files_write_the_python_json(tmp_path):
    occ = occupancy_maps.building(80, 2)
    rows = ["".join("@" if v else "." for v in row) for row in occ]
    (tmp_path / "b.map").write_text("type octile\nheight 80\nwidth 80\nmap\n" + "\n".join(rows) + "\n")
    gv = dv.grid_voronoi(tmp_path / "b.map", robot_radius=0.5)
    out = tmp_path / "b.json"
    svg = tmp_path / "b.svg"
    subprocess.run([CLI, "gvd", str(tmp_path / "b.map"), "-r", "0.5", "-o", str(out), "--svg", str(svg), "-q"], check=True)
    assert json.loads(out.read_text()) == json.loads(gv.to_json())
    assert svg.read_text() == gv.to_svg()
    bad = subprocess.run([CLI, "gvd", str(tmp_path / "nope.map")], capture_output=True, text=True)
    assert bad.returncode != 0 and "nope.map: cannot open file" in bad.stderr


# -- the review's findings -------------------------------------------------------------------------

def test_update_reads_arrays_as_the_build_did():
    ros = np.zeros((12, 14), np.int8)
    ros[3:6, 3:6] = -1
    gv = dv.grid_voronoi(ros, unknown="free")
    assert not gv.grid.occupied.any()
    gv.update(ros)
    assert not gv.grid.occupied.any()
    probs = np.full((10, 10), 0.1)
    probs[4, 4] = 0.55
    gv = dv.grid_voronoi(probs, occupied_thresh=0.5)
    gv.update(probs)
    assert gv.grid.occupied[4, 4] and gv.grid.occupied.sum() == 1


def test_yaml_brings_its_own_resolution_and_origin(tmp_path):
    write_pgm(tmp_path / "m.pgm", np.full((5, 6), 254, np.uint8))
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n" + REST)
    with pytest.raises(ValueError, match="brings its own resolution"):
        dv.OccupancyGrid.load(tmp_path / "m.yaml", resolution=0.5)
    with pytest.raises(ValueError, match="brings its own resolution"):
        dv.grid_voronoi(tmp_path / "m.yaml", origin=(1, 1))
    (tmp_path / "s.yaml").write_text("image: m.pgm\nresolution: 0.1\nmode: scale\n" + REST)
    with pytest.raises(ValueError, match=r"s.yaml:3: mode: 'scale' is not supported"):
        dv.OccupancyGrid.load(tmp_path / "s.yaml")


def test_ros_message_rows_start_at_the_bottom():
    data = np.zeros((4, 5), np.int8)
    data[0, :] = 100   # the message's first row: the map's bottom row
    g = dv.OccupancyGrid.from_ros(data.ravel().tolist(), 5, 4, 0.05, (1.0, 2.0))
    assert g.occupied[3].all() and not g.occupied[:3].any()
    with pytest.raises(ValueError, match="19 values for a 5 x 4 map"):
        dv.OccupancyGrid.from_ros(data.ravel()[:19], 5, 4, 0.05, (0, 0))


@pytest.mark.skipif(not _core._has_png, reason="built without libpng")
def test_png_colours_are_averaged_as_map_server_does(tmp_path):
    import matplotlib.image as mpimg
    # map_server's trinary mode averages every channel, alpha included: v = (R + G + B + A) / 4
    rgba = np.ones((2, 3, 4))
    rgba[0, 0, :3] = (0, 1, 0)        # opaque green: v = 1/2, occupancy 1/2: unknown
    rgba[0, 1, :3] = (1, 0, 0)        # opaque red: the same
    rgba[0, 2, 3] = 0.0               # transparent white: v = 3/4, occupancy 1/4: unknown
    rgba[1, 0, :3] = 0.0              # opaque black: v = 1/4, occupancy 3/4: occupied
    mpimg.imsave(tmp_path / "c.png", rgba)  # opaque white elsewhere: free
    g = dv.OccupancyGrid.load(tmp_path / "c.png")
    assert g.occupied.tolist() == [[True, True, True], [True, False, False]] and g.unknown_pixels == 3
    free = dv.OccupancyGrid.load(tmp_path / "c.png", unknown="free")
    assert free.occupied.tolist() == [[False, False, False], [True, False, False]]


def test_labelled_diagram_of_a_file_reads_it_as_the_medial_one(tmp_path):
    img = np.full((20, 30), 254, np.uint8)
    img[5:9, 5:9] = 205    # unknown: occupied by default
    img[12:15, 20:25] = 0
    write_pgm(tmp_path / "u.pgm", img)
    (tmp_path / "u.yaml").write_text("image: u.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n" + REST)
    doc = dv.obstacles_from_occupancy_grid(tmp_path / "u.yaml")
    assert len(doc["obstacles"]) == 2
    assert np.array_equal(dv.OccupancyGrid.load(tmp_path / "u.yaml").occupied, (img == 0) | (img == 205))


def test_movingai_unknown_character_is_an_error(tmp_path):
    (tmp_path / "x.map").write_text("type octile\nheight 1\nwidth 3\nmap\n.x.\n")
    with pytest.raises(ValueError, match=r"x.map:5: unknown character 'x' in column 2 \(free '\.G'"):
        dv.OccupancyGrid.load(tmp_path / "x.map")


def test_movingai_map_refuses_what_it_does_not_have(tmp_path):
    # no grey levels and no unknown cells: options that would do nothing are errors, not ignored
    (tmp_path / "s.map").write_text("type octile\nheight 1\nwidth 5\nmap\n.@@@.\n")
    assert dv.OccupancyGrid.load(tmp_path / "s.map").occupied.sum() == 3
    for kw in ({"negate": True}, {"occupied_thresh": 0.9}, {"free_thresh": 0.1}, {"unknown": "free"}):
        with pytest.raises(ValueError, match=r"s\.map: a MovingAI map has no grey levels and no unknown cells"):
            dv.OccupancyGrid.load(tmp_path / "s.map", **kw)
    with pytest.raises(ValueError, match="no grey levels"):
        dv.grid_voronoi(tmp_path / "s.map", occupied_thresh=0.9)
    if CLI:
        proc = subprocess.run([CLI, "gvd", str(tmp_path / "s.map"), "--unknown", "free", "-q", "-o", str(tmp_path / "o.json")],
                              capture_output=True, text=True, timeout=60)
        assert proc.returncode == 2 and "--unknown: a MovingAI map has no unknown cells" in proc.stderr, proc.stderr
        assert not (tmp_path / "o.json").exists()


@pytest.mark.skipif(not CLI, reason="DVORONOI_CLI not set")
def test_cli_refuses_obstacle_options_and_bad_resolution_for_maps(tmp_path):
    (tmp_path / "a.map").write_text("type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n")
    for args, msg in ((["--grid", "8"], "for obstacle files"), (["--resolution", "0"], "--resolution: must be a positive"),
                      (["--diagram", "labels"], 'diagram="labels"')):
        p = subprocess.run([CLI, "gvd", str(tmp_path / "a.map"), *args], capture_output=True, text=True)
        assert p.returncode == 2 and msg in p.stderr, p.stderr


def test_medial_diagram_of_an_obstacle_document():
    from shapely.geometry import LineString, Polygon
    u = [[20, 10], [80, 10], [80, 70], [60, 70], [60, 30], [40, 30], [40, 70], [20, 70]]
    doc = {"area": {"box": [0, 0, 100, 100]}, "obstacles": [{"type": "polygon", "vertices": u}]}
    gv = dv.grid_voronoi(doc, cells=200, diagram="medial", robot_radius=2.0)
    assert isinstance(gv, dv.OccupancyVoronoi) and gv.shape == (200, 200)
    assert gv.resolution == pytest.approx(0.5) and gv.origin == (0.0, 0.0)
    # the pixels meeting the U are occupied (every clearance is measured from a superset of it), and
    # the diagram is the occupancy grid's
    assert np.array_equal(gv.diagram_mask, dv.grid_voronoi(gv.grid, workers=1).diagram_mask)
    # the corridor between the arms has its centreline (x = 50) from y = 42 up to its open top
    rows = [gv.shape[0] - 1 - int(y / 0.5) for y in np.arange(42, 66, 0.5)]
    cols = [int(49.5 / 0.5), int(50.0 / 0.5)]
    assert all(gv.diagram_mask[r, cols].any() for r in rows)
    # the labelled diagram has nothing inside the U: one obstacle, one label
    labels = dv.grid_voronoi(doc, cells=200)
    inside = (labels.cells[:, 0] > 84) & (labels.cells[:, 0] < 116) & (labels.cells[:, 1] > 64) & (labels.cells[:, 1] < 136)
    assert not inside.any()
    route = gv.path((50, 60), (50, 90))
    assert len(route) >= 2 and LineString(route).distance(Polygon(u)) > 2.0


# -- the second review's findings ------------------------------------------------------------------

def test_pixel_lists_are_pairs_or_bool_masks_never_reinterpreted():
    occ = np.zeros((20, 20), bool)
    want = np.zeros_like(occ)
    want[5, 7] = want[6, 9] = want[12, 3] = True
    for pixels in (np.nonzero(want), np.argwhere(want), [tuple(p) for p in np.argwhere(want)], want):
        gv = dv.grid_voronoi(occ)
        gv.set_occupied(pixels)
        assert np.array_equal(gv.grid.occupied, want), type(pixels)
    gv = dv.grid_voronoi(occ)
    gv.set_occupied((4, 11))  # one pair
    assert np.argwhere(gv.grid.occupied).tolist() == [[4, 11]]
    with pytest.raises(ValueError, match=r"shape \(2, 3\).*np.nonzero"):
        gv.set_occupied(np.array([[1, 2, 0], [3, 4, 0]]))
    with pytest.raises(ValueError, match=r"integer mask\? pass mask.astype\(bool\)"):
        gv.set_occupied(want.astype(np.uint8))
    with pytest.raises(ValueError, match=r"two 1-d arrays of one length"):
        gv.set_free((np.array([1, 2]), np.array([3])))
    assert np.argwhere(gv.grid.occupied).tolist() == [[4, 11]]  # nothing changed by the refused calls


def test_grid_is_a_read_only_snapshot_and_grids_own_their_array():
    occ = np.zeros((30, 40), bool)
    occ[10:20, 15:18] = True
    gv = dv.grid_voronoi(occ)
    held = gv.grid
    with pytest.raises(ValueError, match="read-only"):
        held.occupied[:, 20:23] = True
    gv.set_occupied([(1, 1)])
    assert not held.occupied[1, 1] and gv.grid.occupied[1, 1]  # the snapshot keeps its map
    back = pickle.loads(pickle.dumps(gv))
    assert np.array_equal(back.diagram_mask, gv.diagram_mask) and np.array_equal(back.grid.occupied, gv.grid.occupied)
    # a grid made from the caller's array keeps its own copy; the caller's grid is never touched
    arr = occ.copy()
    g = dv.OccupancyGrid(arr, resolution=0.5)
    arr[0, 0] = True
    assert not g.occupied[0, 0]
    gv = dv.grid_voronoi(g)
    gv.set_occupied([(2, 2)])
    assert not g.occupied[2, 2] and gv.grid.occupied[2, 2]
    with pytest.raises(ValueError, match=r"resolution 1.0 and origin .* the map has 0.5"):
        gv.update(dv.OccupancyGrid(occ))
    gv.update(dv.OccupancyGrid(occ, resolution=0.5))
    assert not gv.grid.occupied[2, 2]


@pytest.mark.parametrize("kwargs, match", [
    (dict(resolution=1e308), r"resolution 1e\+308 is out of range"),
    (dict(resolution=1e-320), r"resolution 9.99.*e-321 is out of range"),
    (dict(origin=(1e308, 0.0)), r"origin \(1e\+308, 0\) lies more than 2\^40 pixels"),
    (dict(resolution=1e-9, origin=(5e3, 5.0)), r"lies more than 2\^40 pixels"),
])
def test_map_coordinates_must_tell_pixels_apart(kwargs, match):
    with pytest.raises(ValueError, match=match):
        dv.grid_voronoi(np.zeros((5, 7), bool), **kwargs)
    gv = dv.grid_voronoi(np.zeros((5, 7), bool), resolution=1e-6, origin=(1e5 * 1e-6, -3.0))  # in range
    assert np.isfinite(gv.nearest_points).all() and np.isfinite(gv.clearance_at(gv.points)).all()


def test_nested_lists_of_booleans_are_a_map_and_json_names_a_missing_folder(tmp_path):
    gv = dv.grid_voronoi([[False] * 6, [False, True, True, False, False, False], [False] * 6])
    assert gv.shape == (3, 6) and gv.grid.occupied.sum() == 2
    with pytest.raises(FileNotFoundError, match=r"nowhere.*x\.json: the folder .*nowhere does not exist"):
        gv.to_json(tmp_path / "nowhere" / "x.json")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not CLI, reason="DVORONOI_CLI not set")
def test_cli_outputs_to_one_file_by_two_names_and_bad_map_arguments(tmp_path):
    (tmp_path / "a.map").write_text("type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n")
    for svg in ("./same.json", str(tmp_path / "same.json"), "sub/../same.json"):
        (tmp_path / "sub").mkdir(exist_ok=True)
        p = subprocess.run([CLI, "gvd", "a.map", "-q", "-o", "same.json", "--svg", svg], capture_output=True, text=True,
                           cwd=tmp_path)
        assert p.returncode == 2 and "--svg: same file as -o/--output" in p.stderr, (svg, p.stderr)
        assert not (tmp_path / "same.json").exists()
    p = subprocess.run([CLI, "gvd", str(tmp_path)], capture_output=True, text=True)
    assert p.returncode == 2 and "is a folder: give a map file" in p.stderr, p.stderr
    p = subprocess.run([CLI, "gvd", "a.map", "--origin", "nan", "0", "-q"], capture_output=True, text=True, cwd=tmp_path)
    assert p.returncode == 2 and "--origin: coordinates must be finite" in p.stderr, p.stderr


# -- the third review's findings (paths, exports, arguments) ---------------------------------------

def test_path_costs_stay_in_range_and_a_start_at_the_goal_is_a_zero_length_path():
    gv = dv.grid_voronoi(np.zeros((20, 30), bool), resolution=0.5, origin=(3.0, -2.0))
    start, goal = (4.0, 1.0), (15.0, 5.0)
    assert len(gv.path(start, goal, off_diagram_cost=1e6)) >= 2  # large costs still find the path
    for bad in (1e6 * 1.01, 1e38, 0.5, float("nan"), float("inf")):
        with pytest.raises(ValueError, match=r"off_diagram_cost must be a number in \[1, 1e6\]"):
            gv.path(start, goal, off_diagram_cost=bad)
    route = gv.path(start, start)
    assert route.tolist() == [list(start), list(start)] and gv.path_length(start, start) == 0.0
    with pytest.raises(ValueError, match=r"is blocked: its clearance 1 is not greater than the robot radius 1e\+300 by more than rounding"):
        gv.path(start, goal, robot_radius=1e300)  # numbers in errors are short
    for name, kwargs in (("robot_radius", {"robot_radius": "0.3"}), ("off_diagram_cost", {"off_diagram_cost": "2"})):
        with pytest.raises(TypeError, match=f"{name} must be a real number"):
            gv.path(start, goal, **kwargs)
    with pytest.raises(TypeError, match="min_separation must be a real number"):
        dv.grid_voronoi(np.zeros((9, 9), bool), min_separation="2")
    assert gv.clearance_at((4.0, 1.0)) == pytest.approx(gv.clearance_at([(4.0, 1.0)])[0]) == 1.0


def test_routes_are_exported_only_when_finite_and_a_missing_path_has_no_length():
    occ = np.zeros((20, 30), bool)
    occ[:, 14] = True  # two rooms, no door
    gv = dv.grid_voronoi(occ)
    for bad in ([[np.inf, 0.0], [1.0, 1.0]], [[0.0, 0.0], [1.0, np.nan]]):
        with pytest.raises(ValueError, match="route: point [01] has a non-finite coordinate"):
            gv.to_svg(route=np.array(bad))
        with pytest.raises(ValueError, match="route: point [01] has a non-finite coordinate"):
            gv.to_json(route=np.array(bad))
    route = gv.path((3.5, 10.5), (25.5, 10.5))
    assert len(route) == 0 and gv.stats["last_path"]["length"] == float("inf")
    assert json.loads(gv.to_json(route=route))["path"] == {"found": False, "length": None, "points": []}
    labelled = dv.grid_voronoi({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [5, 5]}]}, cells=20)
    with pytest.raises(ValueError, match="route: point 0 has a non-finite coordinate"):
        labelled.to_svg(route=np.array([[np.nan, 1.0], [2.0, 2.0]]))


def test_arguments_the_diagram_or_input_does_not_read_are_refused():
    occ = occupancy_maps.building(40, 1)
    doc = {"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [5, 5]}]}
    for source, kwargs, match in (
            (occ, {"mode": "bogus"}, 'mode must be "cooperative" or "independent"'),
            (occ, {"visibility": "no"}, "visibility must be True or False"),
            (occ, {"mode": "independent"}, "the medial diagram does not use them"),
            (occ, {"diagram": "labels", "prune_length": 12}, 'diagram="labels" does not use them'),
            (doc, {"prune_length": 300}, 'diagram="labels" does not use them'),
            (doc, {"origin": (5, 5)}, "origin: an obstacle document's coordinates are its own"),
            (doc, {"diagram": "medial", "origin": (5, 5)}, "origin: an obstacle document's coordinates are its own"),
            (doc, {"unknown": "maybe"}, "unknown and occupied_thresh say how an occupancy array"),
            (doc, {"occupied_thresh": 7}, "unknown and occupied_thresh say how an occupancy array"),
            (doc, {"diagram": "medial", "visibility": False}, "the medial diagram does not use them"),
            (dv.OccupancyGrid(occ), {"unknown": "free"}, "an OccupancyGrid is read already"),
            (dv.OccupancyGrid(occ), {"occupied_thresh": 0.3}, "an OccupancyGrid is read already")):
        with pytest.raises((ValueError, TypeError), match=match):
            dv.grid_voronoi(source, **kwargs)
    # what each reads is still taken
    assert len(dv.grid_voronoi(occ, diagram="labels", mode="independent", visibility=False).cells) > 0
    assert len(dv.grid_voronoi(occ, diagram="labels", visibility=0).cells) > 0  # 0/1 as bools
    assert len(dv.grid_voronoi(doc, diagram="medial", cells=32, prune_length=4)) > 0


def test_pixel_centres_take_pixels_as_updates_do_and_pixels_at_inverts_them():
    grid = dv.OccupancyGrid(np.zeros((5, 7), bool), resolution=0.5, origin=(-1.0, 2.0))
    mask = np.zeros((5, 7), bool)
    mask[[0, 2, 4], [6, 1, 0]] = True
    want = grid.pixel_centers([(0, 6), (2, 1), (4, 0)])
    np.testing.assert_array_equal(want, [[2.25, 4.25], [-0.25, 3.25], [-0.75, 2.25]])
    for form in (np.nonzero(mask), np.argwhere(mask), mask):
        np.testing.assert_array_equal(grid.pixel_centers(form), want)
    np.testing.assert_array_equal(grid.pixel_centers((2, 1)), want[1:2])
    with pytest.raises(ValueError, match=r"pixels\[0\] = \(5, 0\) is outside the 5 x 7 map"):
        grid.pixel_centers([(5, 0)])
    with pytest.raises(ValueError, match=r"shape \(2, 3\)"):
        grid.pixel_centers(np.array([[0, 2, 4], [6, 1, 0]]))
    with pytest.raises(TypeError, match="integer pairs"):
        grid.pixel_centers([(0.5, 1.0)])
    np.testing.assert_array_equal(grid.pixels_at(want), np.argwhere(mask))
    # edges: left/bottom map edges and shared edges go right and down; the far edges to the last pixel
    np.testing.assert_array_equal(grid.pixels_at([(-1.0, 2.0), (2.5, 4.5), (-0.5, 3.0), (1.0 - 1e-12, 3.0)]),
                                  [[4, 0], [0, 6], [3, 1], [3, 3]])
    np.testing.assert_array_equal(grid.pixels_at((0.0, 3.5)), [[2, 2]])  # on the edge between rows 1 and 2
    odd = dv.OccupancyGrid(np.zeros((12, 32), bool), 0.1, (0.3, 0.7))  # extent (0.3, 3.5, 0.7, 1.9000000000000001)
    x0, x1, y0, y1 = odd.extent
    np.testing.assert_array_equal(odd.pixels_at([(x1, y1), (x0, y0), (x1, y0), (x0, y1)]), [[0, 31], [11, 0], [11, 31], [0, 0]])
    for bad in ((-1.0001, 3.0), (0.0, 4.50001), (np.nan, 3.0)):
        with pytest.raises(ValueError, match=r"points\[0\] = .* is outside the 5 x 7 map"):
            grid.pixels_at([bad])


def test_update_reads_arrays_by_the_rule_the_map_was_read_with(tmp_path):
    # an OccupancyGrid's threshold and unknown rule, and a YAML's own threshold, not the defaults
    probs = np.full((20, 30), 0.1)
    probs[:, 14:16] = 0.5
    probs[8:12, 14:16] = 0.1
    gv = dv.grid_voronoi(dv.OccupancyGrid(probs, occupied_thresh=0.3))
    built = gv.grid.occupied.copy()
    assert built.sum() == 32
    gv.update(probs)  # the same map: nothing changes
    assert np.array_equal(gv.grid.occupied, built) and gv.grid.occupied_thresh == 0.3
    ros = np.zeros((20, 30), np.int8)
    ros[:, 14:16] = 100
    ros[2:6, 3:8] = -1
    gv = dv.grid_voronoi(dv.OccupancyGrid(ros, unknown="free"))
    gv.update(ros)
    assert gv.grid.occupied.sum() == 40 and gv.grid.unknown == "free"
    grey = np.where(probs >= 0.5, 127, 254).astype(np.uint8)  # p = 1 - 127/255 = 0.502: occupied above 0.5
    write_pgm(tmp_path / "m.pgm", grey)
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.5\nfree_thresh: 0.196\n")
    gv = dv.grid_voronoi(tmp_path / "m.yaml")
    assert gv.grid.occupied.sum() == 32 and gv.grid.occupied_thresh == 0.5
    gv.update(np.where(probs >= 0.5, 0.51, 0.1))
    assert gv.grid.occupied.sum() == 32
    with pytest.raises(TypeError, match="new_occupancy: give an array or an OccupancyGrid"):
        gv.update(tmp_path / "m.yaml")


def test_one_diagram_shared_between_threads_stays_the_full_builds():
    # a map callback and a planner on one object: the core releases the GIL, the object's lock keeps
    # the calls apart (without it two writers left a wrong diagram or aborted the process)
    import threading

    occ = occupancy_maps.building(300, 1)
    gv = dv.grid_voronoi(occ, workers=1)
    errors = []

    def writer(seed):
        rng = np.random.default_rng(seed)
        try:
            for _ in range(25):
                m = np.zeros(occ.shape, bool)
                y, x = rng.integers(0, 200, 2)
                m[y:y + 100, x:x + 100] = True
                gv.set_occupied(m)
                gv.set_free(m & ~occ)  # each writer restores the map
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    def reader():
        try:
            for _ in range(25):
                gv.path((20.5, 20.5), (280.5, 280.5))
                gv.diagram_mask
                gv.clearance_at((150.5, 150.5))
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=writer, args=(k,)) for k in (0, 1)] + [threading.Thread(target=reader)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert_is_full_build(gv, occ, workers=1)


def test_pixel_errors_show_the_values_given():
    gv = dv.grid_voronoi(np.zeros((10, 12), bool))
    with pytest.raises(ValueError, match=r"pixels\[0\] = \(18446744073709551615, 0\) is outside the 10 x 12 map"):
        gv.set_occupied(np.array([[2 ** 64 - 1, 0]], np.uint64))
    with pytest.raises(ValueError, match=r"pixels\[1\] = \(inf, 1\.0\) is outside"):
        gv.set_free(np.array([[1.0, 1.0], [np.inf, 1.0]]))
    assert not gv.grid.occupied.any()


def test_refused_pixel_forms_name_the_argument():
    # Before: a 2-column map read an integer 0/1 mask as pairs, a ragged list gave numpy's bare
    # message, and update() named its argument `occupancy`.
    gv = dv.grid_voronoi(np.zeros((5, 2), bool))
    m = np.zeros((5, 2), int)
    m[0, 0] = 1
    with pytest.raises(ValueError, match=r"^pixels: an integer array of the map's shape \(5, 2\).*astype\(bool\)"):
        gv.set_occupied(m)
    gv.set_occupied(np.array([[0, 1], [4, 1]]))  # pairs that are not 0/1 only: read as pairs
    assert np.argwhere(gv.grid.occupied).tolist() == [[0, 1], [4, 1]]
    with pytest.raises(ValueError, match=r"^pixels must be \(row, col\) pairs"):
        gv.set_occupied([(1, 1), (3,)])
    with pytest.raises(ValueError, match=r"^new_occupancy\[0, 0\] = 1.5"):
        gv.update(np.full((5, 2), 1.5))
    assert np.argwhere(gv.grid.occupied).tolist() == [[0, 1], [4, 1]]  # nothing changed by the refused calls


def test_robot_radius_set_later_redoes_what_depends_on_it():
    # Before: robot_radius was a plain attribute; `blocked` and `blocked_mask` kept the old radius's
    # answer while paths and exports used the new one.
    occ = np.zeros((20, 30), bool)
    occ[:, 14] = True
    gv = dv.grid_voronoi(occ, robot_radius=0.5)
    assert gv.blocked.sum() == 0
    gv.robot_radius = 100.0
    fresh = dv.grid_voronoi(occ, robot_radius=100.0)
    assert np.array_equal(gv.blocked, fresh.blocked) and gv.blocked.all()
    assert np.array_equal(gv.blocked_mask, fresh.blocked_mask)
    assert json.loads(gv.to_json())["pixels"]["blocked"] == json.loads(fresh.to_json())["pixels"]["blocked"]
    for bad, err in ((-1.0, ValueError), (float("nan"), ValueError), ("1", TypeError)):
        with pytest.raises(err, match="robot_radius"):
            gv.robot_radius = bad
    assert gv.robot_radius == 100.0
    labelled = dv.grid_voronoi({"area": {"box": [0, 0, 10, 10]}, "obstacles": []}, cells=16, robot_radius=1.0,
                               diagram="labels")
    with pytest.raises(AttributeError):
        labelled.robot_radius = 2.0  # its blocked cells and graph were decided with the radius it was built for


def _exact_sq_clearance(occ, p, q):
    """Exact squared distance (pixel units, Fractions) from segment pq to the occupied squares."""
    from fractions import Fraction as F
    H, W = occ.shape
    best = None
    for r, c in np.argwhere(occ):
        x0, x1, y0, y1 = F(int(c)), F(int(c) + 1), F(H - 1 - int(r)), F(H - int(r))
        # distance from a segment to a box: minimise over the segment by sampling its critical points
        # (ends, and the parameters where it meets the box's lines or is nearest to its corners)
        px, py, qx, qy = p[0], p[1], q[0], q[1]
        dx, dy = qx - px, qy - py
        ts = {F(0), F(1)}
        for v, d, a in ((x0, dx, px), (x1, dx, px), (y0, dy, py), (y1, dy, py)):
            if d != 0:
                ts.add((v - a) / d)
        l2 = dx * dx + dy * dy
        for cx, cy in ((x0, y0), (x0, y1), (x1, y0), (x1, y1)):
            if l2 != 0:
                ts.add(((cx - px) * dx + (cy - py) * dy) / l2)
        for t in ts:
            if 0 <= t <= 1:
                x, y = px + t * dx, py + t * dy
                ex = max(x0 - x, 0, x - x1)
                ey = max(y0 - y, 0, y - y1)
                d2 = ex * ex + ey * ey
                best = d2 if best is None or d2 < best else best
    return best


def test_returned_path_segments_clear_the_radius_in_map_coordinates():
    # Before: segments were tested on rounded pixel coordinates, and returned rounded again in map
    # coordinates: with robot_radius 0 a segment could run exactly through an occupied pixel's corner,
    # and far from (0, 0) a vertex came nearer than the radius. Checked exactly (Fractions) on the
    # returned floats.
    from fractions import Fraction as F
    occ = np.zeros((6, 6), bool)
    occ[3, 3] = True
    gv = dv.grid_voronoi(occ, resolution=0.05, origin=(0.87, 8.7))
    S, G = gv.grid.pixel_centers([(3, 2), (2, 3)])  # diagonal neighbours across the corner of (3, 3)
    route = gv.path(S, G)
    assert len(route) >= 2
    to_px = lambda v: ((F(float(v[0])) - F(0.87)) / F(0.05), (F(float(v[1])) - F(8.7)) / F(0.05))  # noqa: E731
    for a, b in zip(route[:-1], route[1:]):
        assert _exact_sq_clearance(occ, to_px(a), to_px(b)) > 0
    H, W = 12, 14
    occ = np.ones((H, W), bool)
    occ[1:6, 1:4] = False
    occ[3, 4:9] = False
    occ[4:9, 8] = False
    occ[9:11, 6:12] = False  # an L-shaped corridor, one pixel wide in places
    res = 0.1
    origin = (0.0, 2.0 ** 38 * res)
    gv = dv.grid_voronoi(occ, resolution=res, origin=origin)
    r = res * (0.5 - 1e-6)
    S, G = gv.grid.pixel_centers([(3, 2), (10, 9)])
    try:
        route = gv.path(S, G, robot_radius=r)
    except ValueError as e:  # right too: the corridor clears r by less than the coordinates' rounding
        assert "by more than rounding" in str(e)
        route = np.empty((0, 2))
    to_px = lambda v: ((F(float(v[0])) - F(origin[0])) / F(res), (F(float(v[1])) - F(origin[1])) / F(res))  # noqa: E731
    for a, b in zip(route[:-1], route[1:]):
        assert _exact_sq_clearance(occ, to_px(a), to_px(b)) > (F(r) / F(res)) ** 2
    route = gv.path(S, G, robot_radius=res * 0.499)  # a gap far above rounding: found, and clear
    assert len(route) >= 2
    for a, b in zip(route[:-1], route[1:]):
        assert _exact_sq_clearance(occ, to_px(a), to_px(b)) > (F(res * 0.499) / F(res)) ** 2
