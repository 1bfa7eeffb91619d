"""Occupancy maps for tests, examples and benchmarks of the grid Voronoi diagram.

Every map is an ``(H, W)`` ``bool`` array, ``True`` = occupied, row 0 at the top (image order, as
``cv2.imread`` or a ROS ``map_server`` PGM gives it). ``size`` is an ``int`` (a square map) or an
``(H, W)`` pair. Generators with a ``seed`` draw from one ``numpy.random.default_rng(seed)`` in a fixed
order, so the same ``(size, seed)`` gives the same map on every machine; they use numpy only and make a
2048 x 2048 map in tens of milliseconds (well under a second at 4096 x 4096).

What each models:

``building(size, seed)``
    One office floor as a SLAM map shows it: outer walls on the image border, a main corridor running
    top to bottom (maps at least ~46 px wide) and cross corridors with rooms on both sides
    (double-loaded), rooms back to back between two cross corridors, some with a door between them. Walls are 1-3 px thick, drawn separately per wall. Every room has a
    door (a gap) onto its corridor; some also onto the main corridor or the next room. Door widths
    vary from 1 px (a door left ajar) through 2-3 px to wide openings. One hall (two or three rooms
    merged) holds a grid of square pillars, and a few more pillars stand in rooms: islands, not
    touching any wall. Everything free is connected.
``warehouse(size, seed)``
    Rows of shelving racks: long thin vertical blocks in one to three blocks of rows separated by
    cross aisles, a main aisle along the top and bottom walls, a staging area with pallets (small
    islands) on the left. Aisle widths vary; the first block always has aisles exactly 1, 2 and
    3 px wide, the rest are wider.
``cave(size, seed)``
    A cellular-automaton cave: random fill on a coarse grid, majority smoothing, then repeated
    doubling with smoothing (rough, rounded walls at every scale; caverns keep their proportions at
    any size). The border is solid; free space falls into several pockets that need not connect.
``rooms_with_islands(size, seed)``
    A furnished flat or lab: a jittered grid of rooms with 1-3 px walls and doors of varied width
    (every room reachable: the doors of a random spanning tree, plus some more), each room holding
    furniture as islands (rectangles, discs, L shapes, thin shelves) kept clear of walls and of
    each other.
``passages(size)``
    A test map, no randomness, size >= 64 (eight corridors of widths 1..8 alone take 36 px): a
    border wall ``T = max(2, min(H, W) // 32)`` px thick; a top hall; a gallery of eight straight
    vertical corridors, exactly 1, 2, 3, 4, 5, 6, 7 and 8 px wide from left to right, between walls
    at least 2 px thick (``max(2, min((W - 2T - 40) // 8, W // 24))``), the rest of the gallery row
    solid; a middle hall that all corridors open onto at both ends (top hall, middle hall); and
    four cells along the bottom, open to the middle hall, each with a digital wall face rising left
    to right from its floor at slope 1:1 (45 degrees), 1:2, 1:3 and 1:5 (one row up every 1, 2, 3,
    5 columns; capped at 60% of the cell's height). The staircase faces are what makes a naive
    pixel skeleton grow spurs.

Real maps: :func:`read_movingai_map` reads the MovingAI benchmark ``.map`` text format;
``tests/data/maps/`` has one such map and its provenance. :func:`resize_nearest` scales a map by
nearest neighbour (a 256 map to 2048 for benchmarks).
"""
from __future__ import annotations

import os
from typing import Any, List, Sequence, Tuple, Union

import numpy as np

__all__ = [
    "building",
    "warehouse",
    "cave",
    "rooms_with_islands",
    "passages",
    "read_movingai_map",
    "write_movingai_map",
    "resize_nearest",
]

Size = Union[int, Sequence[int]]
MOVINGAI_FREE = ".G"
MOVINGAI_BLOCKED = "@OTSW"


# ----------------------------------------------------------------------------------------- helpers
def _shape(size: Size, name: str, minimum: int = 16) -> Tuple[int, int]:
    if isinstance(size, (int, np.integer)):
        h = w = int(size)
    else:
        dims = tuple(int(s) for s in size)
        if len(dims) != 2:
            raise ValueError(f"{name}: size must be an int or an (H, W) pair, got {size!r}")
        h, w = dims
    if h < minimum or w < minimum:
        raise ValueError(f"{name}: size must be at least {minimum} x {minimum}, got {h} x {w}")
    return h, w


def _frame(occ: np.ndarray, t: int) -> None:
    occ[:t, :] = True
    occ[-t:, :] = True
    occ[:, :t] = True
    occ[:, -t:] = True


def _box3_count(g: np.ndarray) -> np.ndarray:
    """Occupied pixels in each 3 x 3 neighbourhood (the edge repeated outside), uint8."""
    p = np.pad(g.view(np.uint8), 1, mode="edge")
    r = p[:, :-2] + p[:, 1:-1] + p[:, 2:]
    return r[:-2] + r[1:-1] + r[2:]


def _island_fits(occ: np.ndarray, y0: int, y1: int, x0: int, x1: int, margin: int) -> bool:
    h, w = occ.shape
    if y0 - margin < 0 or x0 - margin < 0 or y1 + margin > h or x1 + margin > w or y1 <= y0 or x1 <= x0:
        return False
    return not occ[y0 - margin:y1 + margin, x0 - margin:x1 + margin].any()


def _door_width(rng: np.random.Generator, span: int, scale: int) -> int:
    """1, 2, 3 px often; otherwise up to ~3% of the map. Never the whole wall."""
    r = rng.random()
    if r < 0.2:
        w = 1
    elif r < 0.4:
        w = 2
    elif r < 0.55:
        w = 3
    else:
        w = int(rng.integers(4, max(5, int(0.03 * scale) + 1)))
    return max(1, min(w, span - 2 if span > 3 else span))


def _split(rng: np.random.Generator, lo: int, hi: int, n: int, jitter: float = 0.3) -> List[int]:
    """n + 1 increasing cut points from lo to hi, parts of jittered equal size."""
    f = 1.0 + jitter * rng.uniform(-1.0, 1.0, n)
    cuts = lo + np.concatenate([[0.0], np.cumsum(f) / f.sum()]) * (hi - lo)
    out = [int(round(c)) for c in cuts]
    out[0], out[-1] = lo, hi
    return out


# ---------------------------------------------------------------------------------------- building
def building(size: Size, seed: int = 0) -> np.ndarray:
    """An office floor: outer walls on the border, a main corridor, cross corridors with rooms along
    them, doors of varied width, 1-3 px walls, pillars (islands). See the module docstring."""
    H, W = _shape(size, "building")
    rng = np.random.default_rng(seed)
    s = min(H, W)
    occ = np.zeros((H, W), dtype=bool)
    t = int(rng.integers(1, 4))
    _frame(occ, t)
    y0, y1, x0, x1 = t, H - t, t, W - t

    # main corridor top to bottom (when there is room for two wings of rooms)
    wings = [(x0, x1)]
    main = None
    if x1 - x0 >= 40:
        cw = max(2, int(round(s * rng.uniform(0.02, 0.04))))
        xc = x0 + int(rng.integers(int(0.35 * (x1 - x0)), int(0.65 * (x1 - x0)) - cw))
        wv = int(rng.integers(1, 4))
        main = (xc, xc + cw, wv)
        wings = [(x0, xc - wv), (xc + cw + wv, x1)]

    # units of [rooms | corridor | rooms] stacked top to bottom, separated by back-to-back walls
    min_room = 3
    unit_target = s * rng.uniform(0.14, 0.24) + 8
    n_units = max(1, int(round((y1 - y0) / unit_target)))
    while n_units > 1 and (y1 - y0) // n_units < 2 * min_room + 10:
        n_units -= 1
    cuts = _split(rng, y0, y1, n_units, 0.25)
    bands = []      # (room rows a, room rows b, wall rows a, wall rows b): the wall faces the corridor
    corridors = []  # (row a, row b)
    separators = []  # (row a, row b) of the walls between back-to-back rooms
    for u in range(n_units):
        ua, ub = cuts[u], cuts[u + 1]
        if u > 0:
            wb = int(rng.integers(1, 4))
            for xa, xb in wings:
                occ[ua:ua + wb, xa:xb] = True
            separators.append((ua, ua + wb))
            ua += wb
        h = ub - ua
        w1, w2 = int(rng.integers(1, 4)), int(rng.integers(1, 4))
        c = max(1, int(round(s * rng.uniform(0.015, 0.035))))
        c = min(c, max(1, h - w1 - w2 - 2 * min_room))
        rest = h - c
        da = int(round(rest * rng.uniform(0.42, 0.58)))
        da = min(max(da, w1 + min_room), rest - w2 - min_room)
        ca, cb = ua + da, ua + da + c
        corridors.append((ca, cb))
        bands.append((ua, ca - w1, ca - w1, ca))
        bands.append((cb + w2, ub, cb, cb + w2))
        for xa, xb in wings:
            occ[ca - w1:ca, xa:xb] = True
            occ[cb:cb + w2, xa:xb] = True

    if main is not None:
        xc, xd, wv = main
        occ[y0:y1, xc - wv:xc] = True
        occ[y0:y1, xd:xd + wv] = True
        for ca, cb in corridors:
            occ[ca:cb, xc - wv:xd + wv] = False

    # rooms along each band of each wing
    rooms = []  # (ra, rb, xa, xb) interiors
    for wi, (xa, xb) in enumerate(wings):
        for ra, rb, wa, wb in bands:
            if rb - ra < 1:
                continue
            x = xa
            while x < xb:
                rw = max(4, int(round(s * rng.uniform(0.05, 0.12))))
                ws = int(rng.integers(1, 4))
                if xb - (x + rw) < 4 + ws:
                    rw = xb - x
                rooms.append((ra, rb, x, x + rw))
                # the door onto the corridor
                dw = _door_width(rng, rw, s)
                dx = int(rng.integers(x, x + rw - dw + 1))
                occ[wa:wb, dx:dx + dw] = False
                if x + rw < xb:
                    occ[ra:rb, x + rw:x + rw + ws] = True
                    if rng.random() < 0.25 and rb - ra >= 3:  # a door to the next room
                        dh = _door_width(rng, rb - ra, s)
                        dy = int(rng.integers(ra, rb - dh + 1))
                        occ[dy:dy + dh, x + rw:x + rw + ws] = False
                x += rw + ws
            # doors onto the main corridor from the rooms next to it
            if main is not None and rb - ra >= 3 and rng.random() < 0.4:
                xc, xd, wv = main
                dh = _door_width(rng, rb - ra, s)
                dy = int(rng.integers(ra, rb - dh + 1))
                if wi == 0:
                    occ[dy:dy + dh, xc - wv:xc] = False
                else:
                    occ[dy:dy + dh, xd:xd + wv] = False

    # doors between back-to-back rooms: always without a main corridor (they are then the only way
    # from one cross corridor to the next), else now and then
    for sa, sb in separators:
        for xa, xb in wings:
            if main is not None and rng.random() < 0.5:
                continue
            above = [(a, b) for ra, rb, a, b in rooms if rb == sa and xa <= a < xb]
            below = [(a, b) for ra, rb, a, b in rooms if ra == sb and xa <= a < xb]
            spans = [(max(a, c), min(b, d)) for a, b in above for c, d in below if min(b, d) > max(a, c)]
            if not spans:
                continue
            lo, hi = spans[int(rng.integers(len(spans)))]
            dw = _door_width(rng, hi - lo, s)
            dx = int(rng.integers(lo, hi - dw + 1))
            occ[sa:sb, dx:dx + dw] = False

    # a hall: two or three neighbouring rooms merged, with a grid of pillars
    ps = max(1, int(round(s / 256)))
    big = [i for i, (ra, rb, xa, xb) in enumerate(rooms) if rb - ra >= 3 * ps + 4]
    if big:
        i = big[int(rng.integers(len(big)))]
        ra, rb, xa, xb = rooms[i]
        j = i
        for _ in range(int(rng.integers(1, 3))):
            if j + 1 < len(rooms) and rooms[j + 1][0] == ra and rooms[j + 1][2] > xb:
                j += 1
                occ[ra:rb, xb:rooms[j][2]] = False
                xb = rooms[j][3]
        ny = 1 if rb - ra < 6 * ps + 8 else 2
        nx = max(1, min(6, (xb - xa) // (4 * ps + 6)))
        for py in range(ny):
            for px in range(nx):
                cy = ra + (rb - ra) * (2 * py + 1) // (2 * ny)
                cx = xa + (xb - xa) * (2 * px + 1) // (2 * nx)
                if _island_fits(occ, cy - ps // 2, cy - ps // 2 + ps, cx - ps // 2, cx - ps // 2 + ps, 1):
                    occ[cy - ps // 2:cy - ps // 2 + ps, cx - ps // 2:cx - ps // 2 + ps] = True
    # a few more pillars in rooms
    for _ in range(int(rng.integers(2, 6))):
        if not rooms:
            break
        ra, rb, xa, xb = rooms[int(rng.integers(len(rooms)))]
        p = int(rng.integers(ps, 2 * ps + 1))
        for _try in range(10):
            py = int(rng.integers(ra, max(ra + 1, rb - p + 1)))
            px = int(rng.integers(xa, max(xa + 1, xb - p + 1)))
            if _island_fits(occ, py, py + p, px, px + p, 2):
                occ[py:py + p, px:px + p] = True
                break
    _join_free_parts(occ)
    return occ


def _join_free_parts(occ: np.ndarray) -> None:
    """Doors (1 px) through walls of at most 8 px until the free pixels are one 4-connected part: on
    narrow maps a band of rooms can be too thin to exist, and the door meant to reach the rooms beyond
    it then has nothing to open onto. Each pass opens the shortest straight crossing from a smaller
    part into the largest one, scanning rows and columns."""
    from scipy import ndimage

    four = np.array([[0, 1, 0], [1, 1, 1], [0, 1, 0]], bool)
    for _ in range(occ.size):
        labels, n = ndimage.label(~occ, structure=four)
        if n <= 1:
            return
        main = int(np.argmax(np.bincount(labels.ravel())[1:])) + 1
        best = None  # (wall length, pixels to free)
        for grid, swap in ((labels, False), (labels.T, True)):
            for r, row in enumerate(grid):
                free = np.flatnonzero(row)
                for a, b in zip(free[:-1], free[1:]):  # wall pixels a+1 .. b-1 between two free ones
                    if 1 < b - a <= 9 and (row[a] == main) != (row[b] == main) and (best is None or b - a < best[0]):
                        cells = [(c, r) if swap else (r, c) for c in range(a + 1, b)]
                        best = (b - a, cells)
        if best is None:
            return  # no wall thin enough: leave the parts (never on the generators' maps)
        for r, c in best[1]:
            occ[r, c] = False


# --------------------------------------------------------------------------------------- warehouse
def warehouse(size: Size, seed: int = 0) -> np.ndarray:
    """Shelving racks (long thin blocks) with aisles of varied width, 1, 2 and 3 px among them;
    walls on the border; a staging area with pallets. See the module docstring."""
    H, W = _shape(size, "warehouse")
    rng = np.random.default_rng(seed)
    s = min(H, W)
    occ = np.zeros((H, W), dtype=bool)
    t = int(rng.integers(1, 4))
    _frame(occ, t)

    main = max(2, int(round(s * rng.uniform(0.04, 0.07))))     # aisles along the top and bottom walls
    stage = max(3, int(round(W * rng.uniform(0.08, 0.15))))    # staging area on the left
    side = max(2, int(round(W * rng.uniform(0.02, 0.04))))     # aisle along the right wall
    ra, rb = t + main, H - t - main
    xs, xe = t + stage, W - t - side
    n_blocks = 1 if rb - ra < 60 else int(rng.integers(2, 4))
    cross = [max(2, int(round(s * rng.uniform(0.02, 0.04)))) for _ in range(n_blocks - 1)]
    cuts = _split(rng, ra, rb - sum(cross), n_blocks, 0.2)
    rt_max = max(2, s // 128)
    a_max = max(5, int(0.03 * s))
    y = ra
    for b in range(n_blocks):
        r0, r1 = y, y + cuts[b + 1] - cuts[b]
        y = r1 + (cross[b] if b < n_blocks - 1 else 0)
        rt = int(rng.integers(2, rt_max + 1))       # rack depth: back-to-back shelves
        narrow = [1, 2, 3] if b == 0 else []
        # the narrow aisles among the first few (all of them fit even in a 32 px map)
        m = 3 + max(0, min(3, (xe - xs - 4 * rt - 6) // (rt + a_max)))
        pos = sorted(rng.choice(np.arange(m), size=len(narrow), replace=False).tolist()) if narrow else []
        order = dict(zip(pos, rng.permutation(narrow).tolist()))
        cols = np.zeros(W, dtype=bool)
        x, k = xs, 0
        while x + rt <= xe:
            cols[x:x + rt] = True
            x += rt
            a = order.get(k, 0) or int(rng.integers(4, a_max + 1))
            if k > max(pos, default=-1) and a < 4:
                a = 4
            x += a
            k += 1
        occ[r0:r1, :] |= cols[None, :]
        # breaks in some racks (a passage through the shelving)
        xs_r = np.flatnonzero(cols[1:] & ~cols[:-1]) + 1
        for xr in xs_r:
            if rng.random() < 0.15 and r1 - r0 > 12:
                gh = int(rng.integers(2, max(3, (r1 - r0) // 8)))
                gy = int(rng.integers(r0 + 3, r1 - gh - 2))
                occ[gy:gy + gh, xr:xr + rt] = False
    # pallets in the staging area
    pal = max(1, s // 100)
    for _ in range(int(rng.integers(3, 9))):
        p = int(rng.integers(pal, 2 * pal + 2))
        for _try in range(10):
            py = int(rng.integers(t + 2, max(t + 3, H - t - p - 2)))
            px = int(rng.integers(t + 2, max(t + 3, xs - p - 2)))
            if _island_fits(occ, py, py + p, px, px + p, 2):
                occ[py:py + p, px:px + p] = True
                break
    return occ


# -------------------------------------------------------------------------------------------- cave
def cave(size: Size, seed: int = 0, fill: float = 0.45) -> np.ndarray:
    """A cellular-automaton cave with a solid border; pockets of free space need not connect. See
    the module docstring."""
    H, W = _shape(size, "cave")
    rng = np.random.default_rng(seed)
    levels, bh, bw = 0, H, W
    while min(bh, bw) > 48:
        bh, bw, levels = -(-bh // 2), -(-bw // 2), levels + 1
    g = rng.random((bh, bw)) < fill
    _frame(g, 1)
    for _ in range(5):
        g = _box3_count(g) >= 5
        _frame(g, 1)
    for level in range(levels):
        g = np.repeat(np.repeat(g, 2, axis=0), 2, axis=1)
        if g.shape[0] <= 256 and g.shape[1] <= 256:   # roughen the walls at the coarse scales
            g ^= rng.integers(0, 256, size=g.shape, dtype=np.uint8) < 16
        g = _box3_count(g) >= 5
        g = _box3_count(g) >= 5
    g = np.ascontiguousarray(g[:H, :W])
    _frame(g, int(rng.integers(1, 4)))
    return g


# ------------------------------------------------------------------------------ rooms with islands
def rooms_with_islands(size: Size, seed: int = 0) -> np.ndarray:
    """A grid of rooms (1-3 px walls, doors of varied width, all rooms reachable), each furnished
    with islands clear of the walls. See the module docstring."""
    H, W = _shape(size, "rooms_with_islands")
    rng = np.random.default_rng(seed)
    s = min(H, W)
    occ = np.zeros((H, W), dtype=bool)
    t = int(rng.integers(1, 4))
    _frame(occ, t)
    ny = min(max(1, (H - 2 * t) // 12), int(rng.integers(2, 5)))
    nx = min(max(1, (W - 2 * t) // 12), int(rng.integers(2, 5)))
    ys = _split(rng, t, H - t, ny, 0.35)
    xs = _split(rng, t, W - t, nx, 0.35)
    wy = [int(rng.integers(1, 4)) for _ in range(ny + 1)]
    wx = [int(rng.integers(1, 4)) for _ in range(nx + 1)]
    for i in range(1, ny):
        occ[ys[i]:ys[i] + wy[i], :] = True
    for j in range(1, nx):
        occ[:, xs[j]:xs[j] + wx[j]] = True

    def interior(i, j):
        ra = ys[i] + (wy[i] if i > 0 else 0)
        xa = xs[j] + (wx[j] if j > 0 else 0)
        return ra, ys[i + 1], xa, xs[j + 1]

    # doors: a random spanning tree of the room grid, plus some extra
    seen = {(0, 0)}
    stack = [(0, 0)]
    tree = set()
    while stack:
        i, j = stack[-1]
        nbrs = [(i + di, j + dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= i + di < ny and 0 <= j + dj < nx and (i + di, j + dj) not in seen]
        if not nbrs:
            stack.pop()
            continue
        nb = nbrs[int(rng.integers(len(nbrs)))]
        tree.add(frozenset(((i, j), nb)))
        seen.add(nb)
        stack.append(nb)
    for i in range(ny):
        for j in range(nx):
            ra, rb, xa, xb = interior(i, j)
            if i + 1 < ny and (frozenset(((i, j), (i + 1, j))) in tree or rng.random() < 0.3):
                lo, hi = xa, min(xb, interior(i + 1, j)[3])
                lo = max(lo, interior(i + 1, j)[2])
                dw = _door_width(rng, hi - lo, s)
                dx = int(rng.integers(lo, max(lo + 1, hi - dw + 1)))
                occ[ys[i + 1]:ys[i + 1] + wy[i + 1], dx:dx + dw] = False
            if j + 1 < nx and (frozenset(((i, j), (i, j + 1))) in tree or rng.random() < 0.3):
                lo, hi = max(ra, interior(i, j + 1)[0]), min(rb, interior(i, j + 1)[1])
                dh = _door_width(rng, hi - lo, s)
                dy = int(rng.integers(lo, max(lo + 1, hi - dh + 1)))
                occ[dy:dy + dh, xs[j + 1]:xs[j + 1] + wx[j + 1]] = False

    # furniture
    for i in range(ny):
        for j in range(nx):
            ra, rb, xa, xb = interior(i, j)
            rh, rw = rb - ra, xb - xa
            if min(rh, rw) < 8:
                continue
            margin = max(1, min(rh, rw) // 24)
            for _ in range(int(rng.integers(1, 7))):
                kind = int(rng.integers(4))
                hmax = max(2, min(rh, rw) // 4)
                a = int(rng.integers(1, hmax + 1))
                b = int(rng.integers(1, hmax + 1))
                if kind == 3:   # thin shelf
                    a, b = (1 + a // 6, b * 2) if rng.random() < 0.5 else (a * 2, 1 + b // 6)
                a, b = min(a, rh - 2 * margin - 2), min(b, rw - 2 * margin - 2)
                if a < 1 or b < 1:
                    continue
                for _try in range(12):
                    py = int(rng.integers(ra + margin + 1, max(ra + margin + 2, rb - a - margin)))
                    px = int(rng.integers(xa + margin + 1, max(xa + margin + 2, xb - b - margin)))
                    if not _island_fits(occ, py, py + a, px, px + b, margin + 1):
                        continue
                    if kind == 1:   # disc
                        yy, xx = np.ogrid[:a, :b]
                        m = ((yy + 0.5 - a / 2) / (a / 2)) ** 2 + ((xx + 0.5 - b / 2) / (b / 2)) ** 2 <= 1.0
                    elif kind == 2 and min(a, b) >= 3:   # L shape
                        m = np.zeros((a, b), dtype=bool)
                        m[:, :max(1, b // 3)] = True
                        m[-max(1, a // 3):, :] = True
                    else:
                        m = np.ones((a, b), dtype=bool)
                    occ[py:py + a, px:px + b] |= m
                    break
    return occ


# ---------------------------------------------------------------------------------------- passages
def passages(size: Size) -> np.ndarray:
    """Test map: eight corridors exactly 1..8 px wide, and wall faces at slopes 1:1, 1:2, 1:3, 1:5.
    No randomness; size >= 64. The geometry is spelled out in the module docstring."""
    H, W = _shape(size, "passages", minimum=64)
    occ = np.zeros((H, W), dtype=bool)
    T = max(2, min(H, W) // 32)
    _frame(occ, T)
    Hi = H - 2 * T
    hall = max(3, Hi // 10)
    gal = max(8, int(Hi * 0.35))
    g0 = T + hall
    g1 = g0 + gal
    b0 = g1 + hall
    b1 = H - T
    # the gallery: corridors of widths 1..8 between thick walls, the rest solid
    Tw = max(2, min((W - 2 * T - 40) // 8, W // 24))
    occ[g0:g1, T:W - T] = True
    x = T + Tw
    for w in range(1, 9):
        occ[g0:g1, x:x + w] = False
        x += w + Tw
    # four bottom cells with wall faces of slope 1:k rising left to right
    Ts = T
    cw = (W - 2 * T - 3 * Ts) // 4
    ch = b1 - b0
    rmax = max(1, int(0.6 * ch))
    for c, k in enumerate((1, 2, 3, 5)):
        xa = T + c * (cw + Ts)
        xb = xa + cw if c < 3 else W - T
        if c > 0:
            occ[b0:b1, xa - Ts:xa] = True
        cols = np.arange(xa, xb)
        rise = np.minimum((cols - xa) // k, rmax)
        rows = np.arange(b0, b1)[:, None]
        occ[b0:b1, xa:xb] |= rows >= (b1 - rise)[None, :]
    return occ


# ------------------------------------------------------------------------------------- real maps
def read_movingai_map(path: Union[str, os.PathLike], free_chars: str = MOVINGAI_FREE) -> np.ndarray:
    """Read a MovingAI benchmark ``.map`` file (header ``type octile``, ``height H``, ``width W``,
    ``map``, then H lines of W characters) into an ``(H, W)`` bool array, True = blocked, row 0 the
    file's first map line (the top).

    ``.`` and ``G`` are free; ``@ O T S W`` blocked (swamp ``S`` and water ``W`` count as blocked
    here; pass ``free_chars=".GS"`` to treat swamp as free). Header keys in any case and order, each
    once; CRLF line ends and blank lines after the rows are accepted. Any other character, a missing,
    repeated or malformed header line, a row of the wrong length or a wrong number of rows raises
    ValueError naming the file and the line. The same reader as :meth:`OccupancyGrid.load` and the CLI.
    """
    from . import _core

    if not isinstance(free_chars, str) or not free_chars.isascii():
        raise TypeError(f"free_chars must be an ASCII string, got {free_chars!r}")
    try:  # the C++ reader the CLI and OccupancyGrid.load use: one set of rules and messages
        return _core._read_movingai(os.fspath(path), free_chars)
    except ValueError as e:
        raise ValueError(str(e)) from None


def write_movingai_map(path: Union[str, os.PathLike], occ: np.ndarray) -> None:
    """Write an (H, W) bool array (True = blocked) as a MovingAI ``.map`` file (``.`` free, ``@``
    blocked, LF line ends)."""
    occ = np.asarray(occ, dtype=bool)
    if occ.ndim != 2:
        raise ValueError(f"occupancy grid must be 2-D, got shape {occ.shape}")
    h, w = occ.shape
    chars = np.where(occ, ord("@"), ord(".")).astype(np.uint8)
    body = "\n".join(row.tobytes().decode("ascii") for row in chars)
    with open(os.fspath(path), "w", newline="\n") as f:
        f.write(f"type octile\nheight {h}\nwidth {w}\nmap\n{body}\n")


def resize_nearest(occ: np.ndarray, shape: Size) -> np.ndarray:
    """Nearest-neighbour resize of a 2-D map to ``shape`` (an int for a square, or (H, W)). An
    integer factor repeats every pixel factor x factor times exactly."""
    occ = np.asarray(occ)
    H, W = _shape(shape, "resize_nearest", minimum=1)
    h, w = occ.shape
    if H % h == 0 and W % w == 0:
        return np.repeat(np.repeat(occ, H // h, axis=0), W // w, axis=1)
    rows = (np.arange(H) * h) // H
    cols = (np.arange(W) * w) // W
    return occ[rows[:, None], cols[None, :]]
