#!/usr/bin/env python3
"""The grid Voronoi diagram of an occupancy map: dvoronoi against the two routes users take today,
on real-looking maps, each on one thread, in one run.

Maps (``--maps``, default ``building,paris``), each ``--size`` x ``--size`` (default 2048):
- ``building``: ``dvoronoi.occupancy_maps.building(size, seed)``, an office floor;
- ``paris``: the real city map ``tests/data/maps/Paris_1_256.map`` scaled up by nearest neighbour;
- ``warehouse``, ``cave``, ``rooms``: the other generators, on request.

Routes, all from the same ``(H, W)`` bool occupancy array (True = occupied, row 0 at the top) to an
``(H, W)`` bool diagram mask, everything in between timed (conversions included):
(a) OpenCV: ``cv2.setNumThreads(1)``; ``cv2.distanceTransformWithLabels(img, cv2.DIST_L2, 5,
    labelType=cv2.DIST_LABEL_PIXEL)`` on the free-space image (uint8, 0 at occupied pixels); the
    labels number the occupied pixels in raster order, so each label gives its pixel's
    coordinates; the diagram: free pixels whose right or lower neighbour is free and has its nearest
    occupied pixel more than one pixel away from theirs (not the same or 8-adjacent pixels). Label
    changes alone would mark nearly every free pixel along a wall (every wall pixel is its own
    label), so the same feature test as (b) is applied; the raw label-change count is reported too.
(b) scipy: ``dist, idx = scipy.ndimage.distance_transform_edt(free, return_indices=True)`` (the
    distances are the clearance map users want) and the same feature-change test on ``idx``.
(c) dvoronoi: ``dv.grid_voronoi(occ, workers=1)`` and ``workers=2``, ``.diagram_mask``; only when the
    build has the occupancy-grid API (``hasattr(dvoronoi, "OccupancyGrid")``).

Then incremental updates (``set_occupied`` / ``set_free`` of 20 square blobs of 1% of the width) against
the full build (on one worker, and on two), and what the diagram keeps in memory.

Every route runs ``--repeat`` times, interleaved (all routes see the same load); the table gives the
best and the median wall time and dvoronoi's time over each route's (best against best). Benchmarks
are not tests: nothing fails on a time.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_limited import cpu_model  # noqa: E402
from benchutil import git_describe  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PARIS = ROOT / "tests" / "data" / "maps" / "Paris_1_256.map"


def load_occupancy_maps():
    """dvoronoi.occupancy_maps, from the source tree when the installed build predates it."""
    try:
        from dvoronoi import occupancy_maps
        return occupancy_maps
    except ImportError:
        spec = importlib.util.spec_from_file_location(
            "occupancy_maps", ROOT / "python" / "dvoronoi" / "occupancy_maps.py")
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        return mod


def make_map(om, name: str, size: int, seed: int) -> np.ndarray:
    if name == "building":
        return om.building(size, seed)
    if name == "paris":
        return om.resize_nearest(om.read_movingai_map(PARIS), size)
    if name == "warehouse":
        return om.warehouse(size, seed)
    if name == "cave":
        return om.cave(size, seed)
    if name == "rooms":
        return om.rooms_with_islands(size, seed)
    raise SystemExit(f"unknown map {name!r}: building, paris, warehouse, cave, rooms")


# ----------------------------------------------------------------------------------------- routes
def feature_changes(free: np.ndarray, fy: np.ndarray, fx: np.ndarray) -> np.ndarray:
    """Free pixels whose right or lower neighbour is free and has its nearest occupied pixel (fy, fx)
    more than one pixel away from theirs (squared distance > 2: not the same, not 8-adjacent)."""
    mask = np.zeros(free.shape, dtype=bool)
    dy = fy[:, 1:] - fy[:, :-1]
    dx = fx[:, 1:] - fx[:, :-1]
    mask[:, :-1] |= (dy * dy + dx * dx > 2) & free[:, 1:] & free[:, :-1]
    dy = fy[1:, :] - fy[:-1, :]
    dx = fx[1:, :] - fx[:-1, :]
    mask[:-1, :] |= (dy * dy + dx * dx > 2) & free[1:, :] & free[:-1, :]
    return mask


def opencv_route(occ: np.ndarray) -> np.ndarray:
    import cv2

    img = (~occ).view(np.uint8)  # 1 free, 0 occupied (bool and uint8 share the layout)
    _dist, labels = cv2.distanceTransformWithLabels(img, cv2.DIST_L2, 5, labelType=cv2.DIST_LABEL_PIXEL)
    sites = np.flatnonzero(occ.ravel()).astype(np.int32)  # label k is the k-th occupied pixel, raster order
    feat = sites[labels - 1]
    fy, fx = np.divmod(feat, np.int32(occ.shape[1]))
    return feature_changes(~occ, fy, fx)


def opencv_label_changes(occ: np.ndarray) -> int:
    """Pixels marked by label changes alone (what the plain test gives with per-pixel labels)."""
    import cv2

    _dist, lab = cv2.distanceTransformWithLabels((~occ).view(np.uint8), cv2.DIST_L2, 5,
                                                 labelType=cv2.DIST_LABEL_PIXEL)
    free = ~occ
    mask = np.zeros(occ.shape, dtype=bool)
    mask[:, :-1] |= (lab[:, 1:] != lab[:, :-1]) & free[:, 1:] & free[:, :-1]
    mask[:-1, :] |= (lab[1:, :] != lab[:-1, :]) & free[1:, :] & free[:-1, :]
    return int(mask.sum())


def scipy_route(occ: np.ndarray) -> np.ndarray:
    from scipy import ndimage

    free = ~occ
    _dist, (fy, fx) = ndimage.distance_transform_edt(free, return_indices=True)
    return feature_changes(free, fy, fx)


def dvoronoi_route(occ: np.ndarray, workers: int) -> np.ndarray:
    import dvoronoi as dv

    return np.asarray(dv.grid_voronoi(occ, workers=workers).diagram_mask)


def has_dvoronoi_grid() -> bool:
    try:
        import dvoronoi
    except ImportError:
        return False
    return hasattr(dvoronoi, "OccupancyGrid")


def _wall(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


# ------------------------------------------------------------------------------------------- main
def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size", type=int, default=2048, help="map side in pixels (default 2048)")
    ap.add_argument("--repeat", type=int, default=5, help="runs of every route, interleaved (default 5)")
    ap.add_argument("--maps", default="building,paris", help="comma-separated: building, paris, warehouse, cave, rooms")
    ap.add_argument("--seed", type=int, default=1, help="seed of the generated maps")
    a = ap.parse_args()

    import cv2
    import scipy

    cv2.setNumThreads(1)
    om = load_occupancy_maps()
    with_dv = has_dvoronoi_grid()
    dv_version = "not installed"
    try:
        import dvoronoi
        dv_version = dvoronoi.__version__
    except ImportError:
        pass

    print(f"# Grid Voronoi diagram of occupancy maps: OpenCV and scipy routes{' vs dvoronoi' if with_dv else ''}"
          f" ({a.size} x {a.size}, one thread)\n")
    print(f"- machine: {cpu_model()}, {os.cpu_count()} cores, shared with other jobs "
          f"(load average at start {' / '.join(f'{x:.2f}' for x in os.getloadavg())})")
    print(f"- date: {_dt.datetime.now(_dt.timezone.utc):%Y-%m-%d %H:%M} UTC, commit {git_describe()}, "
          f"numpy {np.__version__}, scipy {scipy.__version__}, OpenCV {cv2.__version__} "
          f"(threads {cv2.getNumThreads()}), dvoronoi {dv_version}")
    print(f"- {a.repeat} interleaved runs of each route; best and median wall time\n")
    if not with_dv:
        print("dvoronoi's occupancy-grid diagram (dv.grid_voronoi(occupancy, workers=...), "
              "dvoronoi.OccupancyGrid) is not available in this build: only the OpenCV and scipy routes "
              "are timed.\n")

    routes = [("(a) OpenCV distanceTransformWithLabels + feature changes", opencv_route),
              ("(b) scipy distance_transform_edt(return_indices=True) + feature changes", scipy_route)]
    if with_dv:
        routes += [("(c) dv.grid_voronoi(occ, workers=1)", lambda m: dvoronoi_route(m, 1)),
                   ("(c) dv.grid_voronoi(occ, workers=2)", lambda m: dvoronoi_route(m, 2))]

    warm = om.building(64, 0)
    for _name, fn in routes:  # imports and first-call costs outside the timing
        fn(warm)

    rows = []
    for map_name in [m.strip() for m in a.maps.split(",") if m.strip()]:
        occ = make_map(om, map_name, a.size, a.seed)
        times = {name: [] for name, _ in routes}
        masks = {}
        for _ in range(a.repeat):
            for name, fn in routes:
                t0 = time.perf_counter()
                masks[name] = fn(occ)
                times[name].append(time.perf_counter() - t0)
        rows.append((map_name, occ, times, masks))

    print("| map | size | free | route | best | median | diagram pixels |"
          + (" dvoronoi 1 worker / route | dvoronoi 2 workers / route |" if with_dv else "")
          + "\n|---|---|---|---|---|---|---|" + ("---|---|" if with_dv else ""))
    for map_name, occ, times, masks in rows:
        h, w = occ.shape
        free = 1.0 - occ.mean()
        dv1 = min(times[routes[2][0]]) if with_dv else None
        dv2 = min(times[routes[3][0]]) if with_dv else None
        for name, _fn in routes:
            best, med = min(times[name]), statistics.median(times[name])
            ratio = f" {dv1 / best:.2f} | {dv2 / best:.2f} |" if with_dv else ""
            print(f"| {map_name} | {h} x {w} | {100 * free:.1f}% | {name} | {1e3 * best:.1f} ms | {1e3 * med:.1f} ms "
                  f"| {int(masks[name].sum())} |{ratio}")

    print("\nNotes:")
    for map_name, occ, times, masks in rows:
        import cv2
        from scipy import ndimage
        img = (~occ).view(np.uint8)
        t_cv = min(_wall(lambda: cv2.distanceTransformWithLabels(img, cv2.DIST_L2, 5, labelType=cv2.DIST_LABEL_PIXEL))
                   for _ in range(a.repeat))
        t_edt = min(_wall(lambda: ndimage.distance_transform_edt(~occ, return_indices=True)) for _ in range(a.repeat))
        print(f"- {map_name}: of the routes' best times, the transform call alone takes {1e3 * t_cv:.1f} ms (OpenCV) "
              f"and {1e3 * t_edt:.1f} ms (scipy); the rest is the feature-change test.")
        a_mask, b_mask = masks[routes[0][0]], masks[routes[1][0]]
        agree = (a_mask & b_mask).sum() / max(1, (a_mask | b_mask).sum())
        print(f"  OpenCV and scipy diagrams share {100 * agree:.1f}% of their pixels (ties between "
              f"equally near occupied pixels go different ways); label changes alone would mark "
              f"{opencv_label_changes(occ)} pixels of {int((~occ).sum())} free.")
        if with_dv:
            from scipy import ndimage
            near = ndimage.binary_dilation(b_mask, iterations=2)
            d = masks[routes[2][0]]
            print(f"  dvoronoi's diagram: {100 * near[d].mean():.1f}% of its {int(d.sum())} pixels lie within "
                  f"two pixels of scipy's; 2 workers vs 1: "
                  f"{min(times[routes[2][0]]) / min(times[routes[3][0]]):.2f}x.")

    if with_dv:
        updates(rows, a, routes)


def updates(rows, a, routes) -> None:
    """Incremental updates as ROS navigation uses them: 20 square blobs of 1% of the width put at
    random places (set_occupied), then taken away (set_free); median of --repeat rounds, against the
    full build's best time (one worker), and the same rounds on a result built with two workers."""
    import dvoronoi as dv

    print("\n## Incremental updates: 20 square blobs of 1% of the width added, then removed\n")
    print("| map | full build (best, 1 worker) | add (median) | remove (median) | add / build | remove / build "
          "| add / remove, 2 workers | pixels touched (add) |")
    print("|---|---|---|---|---|---|---|---|")
    rng = np.random.default_rng(a.seed)
    for map_name, occ, times, _masks in rows:
        h, w = occ.shape
        side = max(1, w // 100)
        gvs = {k: dv.grid_voronoi(occ, workers=k) for k in (1, 2)}
        t_add = {1: [], 2: []}
        t_rem = {1: [], 2: []}
        touched = 0
        for _ in range(a.repeat):
            blob = np.zeros_like(occ)
            for _b in range(20):
                r, c = rng.integers(0, h - side), rng.integers(0, w - side)
                blob[r:r + side, c:c + side] = True
            blob &= ~occ
            for k, gv in gvs.items():
                t0 = time.perf_counter()
                st = gv.set_occupied(blob)
                t_add[k].append(time.perf_counter() - t0)
                t0 = time.perf_counter()
                gv.set_free(blob)
                t_rem[k].append(time.perf_counter() - t0)
            touched = st["feature_changes"]
        build = min(times[routes[2][0]])
        ma, mr = statistics.median(t_add[1]), statistics.median(t_rem[1])
        ma2, mr2 = statistics.median(t_add[2]), statistics.median(t_rem[2])
        print(f"| {map_name} | {1e3 * build:.1f} ms | {1e3 * ma:.2f} ms | {1e3 * mr:.2f} ms | {ma / build:.2f} | "
              f"{mr / build:.2f} | {1e3 * ma2:.2f} / {1e3 * mr2:.2f} ms | {touched} |")
    print("\nMemory: a map's diagram keeps the occupancy (1 byte a pixel), the column pass (2), the nearest "
          "points (4), the diagram, the box-judged pixels and the occupancy as bits (1/8 each): 7.375 bytes a pixel, 124 MB for "
          "4096 x 4096 (a float64 distance map alone is 8 bytes a pixel, 134 MB; OpenCV's float32 distances "
          "+ int32 labels 8). A path search adds 5 bytes a pixel while it runs.")


if __name__ == "__main__":
    main()
