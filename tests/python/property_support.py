"""Strategies, transformations and small brute-force helpers shared by the property-based tests
(test_properties_*.py). Not a test module.

Inputs are drawn on dyadic grids (integer coordinates, powers of two for scales and shifts) so that
every transformation the properties apply -- rotations by 90 degrees, mirrors, scaling by 2**k,
translation by a dyadic shift -- maps each coordinate to an exactly representable double. Lattice
inputs are also the hard ones for exact predicates: collinear triples, cocircular quadruples,
agents at exactly 2R.
"""
from __future__ import annotations

import math
from typing import Callable, Dict, List, Sequence, Tuple

import numpy as np
from hypothesis import strategies as st

# ------------------------------------------------------------------------------- transformations
#: The eight symmetries of the square grid as maps of (x, y): exact on doubles.
DIHEDRAL: Dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "identity": lambda p: p.copy(),
    "rot90": lambda p: np.column_stack([-p[:, 1], p[:, 0]]),
    "rot180": lambda p: -p,
    "rot270": lambda p: np.column_stack([p[:, 1], -p[:, 0]]),
    "mirror_x": lambda p: np.column_stack([-p[:, 0], p[:, 1]]),
    "mirror_y": lambda p: np.column_stack([p[:, 0], -p[:, 1]]),
    "transpose": lambda p: p[:, ::-1].copy(),
    "antitranspose": lambda p: np.column_stack([-p[:, 1], -p[:, 0]]),
}
NON_IDENTITY = [k for k in DIHEDRAL if k != "identity"]


def transform_points(name: str, p: np.ndarray) -> np.ndarray:
    return DIHEDRAL[name](np.asarray(p, dtype=np.float64).reshape(-1, 2))


def transform_box(name: str, box: Sequence[float]) -> Tuple[float, float, float, float]:
    """The image of the box (xmin, ymin, xmax, ymax) under a grid symmetry, as a box."""
    x0, y0, x1, y1 = box
    c = transform_points(name, np.array([[x0, y0], [x1, y1]], dtype=np.float64))
    return (float(c[:, 0].min()), float(c[:, 1].min()), float(c[:, 0].max()), float(c[:, 1].max()))


# ------------------------------------------------------------------------------------ strategies
@st.composite
def lattice_points(draw, min_n: int = 1, max_n: int = 20, sides: Sequence[int] = (4, 8, 16, 64, 1 << 20)):
    """Distinct points of a side x side integer grid (side a power of two) as an (n, 2) float array,
    with the side. Small sides give many exact degeneracies, 2**20 nearly generic positions."""
    side = draw(st.sampled_from(list(sides)))
    max_n = min(max_n, side * side)
    cells = draw(st.lists(st.tuples(st.integers(0, side - 1), st.integers(0, side - 1)),
                          min_size=min_n, max_size=max_n, unique=True))
    return np.array(cells, dtype=np.float64).reshape(-1, 2), side


def dyadic_radius(draw, side: int, lo: int = 1, hi: int = 48) -> float:
    """A cell radius side * m / 32: exact, from far below the spacing to beyond the whole set."""
    return side * draw(st.integers(lo, hi)) / 32.0


def permutation(draw, n: int) -> np.ndarray:
    return np.array(draw(st.permutations(list(range(n)))), dtype=np.int64)


def dyadic_shift(draw, side: int) -> np.ndarray:
    """A shift by multiples of 1/4 of up to 64 grid sides: every shifted coordinate and every
    difference stays exact."""
    unit = 0.25
    reach = 256 * side
    return np.array([draw(st.integers(-reach, reach)) * unit, draw(st.integers(-reach, reach)) * unit])


# --------------------------------------------------------------------------------- relations
def permuted_sets(sets: List[set], perm: np.ndarray) -> List[set]:
    """Neighbour sets of the agents ``points[perm]`` predicted from those of ``points``: new agent k
    is old agent perm[k], and old index j is new index inv[j]."""
    inv = np.empty_like(perm)
    inv[perm] = np.arange(len(perm))
    return [{int(inv[j]) for j in sets[int(perm[k])]} for k in range(len(perm))]


def csr_sets(indptr: np.ndarray, indices: np.ndarray) -> List[set]:
    return [set(indices[indptr[i]:indptr[i + 1]].tolist()) for i in range(len(indptr) - 1)]


def first_difference(a: List[set], b: List[set]) -> str:
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return f"agent {i}: {sorted(x)} != {sorted(y)}"
    return "lengths differ" if len(a) != len(b) else "equal"


# ----------------------------------------------------------- occupancy grids: nearest points
def pixel_nearest_candidates(occ: np.ndarray):
    """Brute force of the medial diagram's nearest points (docs/grid_diagram_maps.md, section 2), in
    pixel units (x right, y up, the map's lower-left corner at the origin): for every free pixel the
    squared distance from its centre to the occupied set (closed occupied squares and the outside of
    the map) and the number of distinct points of that set at that distance. Quarter-integers: exact.

    Returns (d2, ties, nearest): (H, W) arrays; ties = 0 on occupied pixels; nearest = the tie-broken
    nearest point (smallest x, then smallest y) as (H, W, 2)."""
    occ = np.asarray(occ, dtype=bool)
    H, W = occ.shape
    rr, cc = np.nonzero(~occ)
    cx = cc + 0.5
    cy = H - 1 - rr + 0.5
    cand_x = [np.zeros_like(cx), np.full_like(cx, W), cx, cx]       # the outside: the map's four sides
    cand_y = [cy, cy, np.zeros_like(cy), np.full_like(cy, H)]
    orr, occ_c = np.nonzero(occ)
    if len(orr):
        sx0, sx1 = occ_c.astype(float), occ_c + 1.0
        sy0, sy1 = (H - 1 - orr).astype(float), (H - orr).astype(float)
        px = np.clip(cx[:, None], sx0[None, :], sx1[None, :])
        py = np.clip(cy[:, None], sy0[None, :], sy1[None, :])
        allx = np.concatenate([np.stack(cand_x, 1), px], axis=1)
        ally = np.concatenate([np.stack(cand_y, 1), py], axis=1)
    else:
        allx, ally = np.stack(cand_x, 1), np.stack(cand_y, 1)
    d2 = (allx - cx[:, None]) ** 2 + (ally - cy[:, None]) ** 2
    best = d2.min(axis=1)
    d2_map = np.zeros((H, W))
    ties = np.zeros((H, W), dtype=np.int64)
    nearest = np.zeros((H, W, 2))
    # occupied pixels: F is the pixel's own centre
    orr2, occ2 = np.nonzero(occ)
    nearest[orr2, occ2, 0] = occ2 + 0.5
    nearest[orr2, occ2, 1] = H - 1 - orr2 + 0.5
    for k in range(len(rr)):
        at = d2[k] == best[k]
        pts = {(float(x), float(y)) for x, y in zip(allx[k, at], ally[k, at])}
        d2_map[rr[k], cc[k]] = best[k]
        ties[rr[k], cc[k]] = len(pts)
        nearest[rr[k], cc[k]] = min(pts)
    return d2_map, ties, nearest


def tie_free_pixels(occ: np.ndarray, ties: np.ndarray) -> np.ndarray:
    """Free pixels whose diagram membership depends on no tie: the pixel and each free 4-neighbour
    have a single nearest point (membership depends only on the nearest points of the pixel and of
    its 4-neighbours, and on the occupancy near them)."""
    occ = np.asarray(occ, dtype=bool)
    unique = (ties == 1) | occ          # occupied neighbours form no pair
    pad = np.pad(unique, 1, constant_values=True)
    ok = ~occ & (ties == 1)
    ok &= pad[:-2, 1:-1] & pad[2:, 1:-1] & pad[1:-1, :-2] & pad[1:-1, 2:]
    return ok


#: Array symmetries of an image (row 0 at the top) and the matching map of an offset (dx, dy) in
#: pixel units with y up.
ARRAY_SYMMETRIES: Dict[str, Tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray]]] = {
    "rot90": (lambda a: np.rot90(a, 1, axes=(0, 1)), lambda v: np.stack([-v[..., 1], v[..., 0]], -1)),
    "rot180": (lambda a: np.rot90(a, 2, axes=(0, 1)), lambda v: -v),
    "rot270": (lambda a: np.rot90(a, 3, axes=(0, 1)), lambda v: np.stack([v[..., 1], -v[..., 0]], -1)),
    "flipud": (lambda a: a[::-1], lambda v: np.stack([v[..., 0], -v[..., 1]], -1)),
    "fliplr": (lambda a: a[:, ::-1], lambda v: np.stack([-v[..., 0], v[..., 1]], -1)),
    "transpose": (lambda a: np.swapaxes(a, 0, 1), lambda v: np.stack([-v[..., 1], -v[..., 0]], -1)),
    "antitranspose": (lambda a: np.swapaxes(a, 0, 1)[::-1, ::-1], lambda v: np.stack([v[..., 1], v[..., 0]], -1)),
}


@st.composite
def occupancy_maps(draw, min_side: int = 4, max_side: int = 18):
    """Small occupancy grids with structure: random rectangles (walls, rooms, islands) on a random
    background noise level, sometimes a border wall."""
    H = draw(st.integers(min_side, max_side))
    W = draw(st.integers(min_side, max_side))
    occ = np.zeros((H, W), dtype=bool)
    for _ in range(draw(st.integers(0, 7))):  # walls and blocks, some carved out again (rooms, doors)
        r0 = draw(st.integers(0, H - 1))
        c0 = draw(st.integers(0, W - 1))
        h = draw(st.integers(1, max(1, H // 2)))
        w = draw(st.integers(1, max(1, W // 2)))
        occ[r0:r0 + h, c0:c0 + w] = draw(st.integers(0, 3)) > 0
    noise = draw(st.sampled_from([0, 0, 1, 2]))
    if noise:
        bits = draw(st.lists(st.booleans(), min_size=H * W, max_size=H * W))
        mask = np.array(bits, dtype=bool).reshape(H, W)
        if noise == 1:  # sparse speckles
            mask &= np.roll(mask, 1, axis=0) & np.roll(mask, 1, axis=1)
        occ |= mask
    if draw(st.booleans()):
        occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = True
    return occ


# ------------------------------------------------------------------ obstacle documents (labels)
@st.composite
def obstacle_scenes(draw, max_obstacles: int = 5):
    """An obstacle document in the square area [0, S]^2 (S = 16), on a grid of `cells` in {16, 32},
    with points, segments, circles, convex and non-convex polygons and unions at coordinates that
    are multiples of 1/4 (circles' radii too)."""
    S = 16.0
    q = lambda lo=0, hi=64: draw(st.integers(lo, hi)) / 4.0  # noqa: E731
    obstacles = []
    for _ in range(draw(st.integers(1, max_obstacles))):
        obstacles.append(_shape(draw, q, allow_union=True))
    cells = draw(st.sampled_from([16, 32]))
    return {"area": {"box": [0.0, 0.0, S, S]}, "obstacles": obstacles}, cells


def _shape(draw, q, allow_union: bool):
    kinds = ["point", "segment", "circle", "triangle", "rect", "ell"] + (["union"] if allow_union else [])
    kind = draw(st.sampled_from(kinds))
    if kind == "point":
        return {"type": "point", "position": [q(), q()]}
    if kind == "segment":
        a, b = [q(), q()], [q(), q()]
        if a == b:
            b = [a[0] + 1.0, a[1]]
        return {"type": "segment", "vertices": [a, b]}
    if kind == "circle":
        return {"type": "circle", "center": [q(), q()], "radius": draw(st.integers(1, 16)) / 4.0}
    if kind == "triangle":
        x, y = q(0, 56), q(0, 56)
        w, h = draw(st.integers(1, 8)) / 2.0, draw(st.integers(1, 8)) / 2.0
        return {"type": "polygon", "vertices": [[x, y], [x + w, y], [x + w / 2.0 if draw(st.booleans()) else x, y + h]]}
    if kind == "rect":
        x, y = q(0, 56), q(0, 56)
        w, h = draw(st.integers(1, 12)) / 2.0, draw(st.integers(1, 12)) / 2.0
        return {"type": "polygon", "vertices": [[x, y], [x + w, y], [x + w, y + h], [x, y + h]]}
    if kind == "ell":  # non-convex: split into convex parts that keep one label
        x, y = q(0, 48), q(0, 48)
        a, b = draw(st.integers(2, 8)) / 2.0, draw(st.integers(2, 8)) / 2.0
        t = draw(st.integers(1, 3)) / 2.0
        t = min(t, a / 2.0, b / 2.0)
        return {"type": "polygon", "vertices": [[x, y], [x + a, y], [x + a, y + t], [x + t, y + t], [x + t, y + b], [x, y + b]]}
    parts = [_shape(draw, q, allow_union=False) for _ in range(draw(st.integers(1, 3)))]
    return {"type": "union", "parts": parts}


def map_doc(doc, f: Callable[[np.ndarray], np.ndarray]):
    """The document with every coordinate mapped by `f` ((k, 2) -> (k, 2)); radii scaled by the
    map's scale factor (|f(1, 0) - f(0, 0)|, exact for the maps used here); polygons keep their
    vertex order (a mirror reverses the orientation, which the loader accepts)."""
    o = f(np.zeros((1, 2)))[0]
    e = f(np.array([[1.0, 0.0]]))[0] - o
    scale = float(math.hypot(e[0], e[1]))

    def pts(v):
        return f(np.asarray(v, dtype=np.float64).reshape(-1, 2)).tolist()

    def shape(s):
        t = s["type"]
        if t == "point":
            return {"type": "point", "position": pts([s["position"]])[0]}
        if t == "circle":
            return {"type": "circle", "center": pts([s["center"]])[0], "radius": s["radius"] * scale}
        if t == "union":
            return {"type": "union", "parts": [shape(p) for p in s["parts"]]}
        return {"type": t, "vertices": pts(s["vertices"])}

    area = doc["area"]
    if "box" in area:
        x0, y0, x1, y1 = area["box"]
        c = f(np.array([[x0, y0], [x1, y1]], dtype=np.float64))
        new_area = {"box": [float(c[:, 0].min()), float(c[:, 1].min()), float(c[:, 0].max()), float(c[:, 1].max())]}
    else:
        new_area = {"polygon": pts(area["polygon"])}
    return {"area": new_area, "obstacles": [shape(s) for s in doc["obstacles"]]}


def _seg_dist2(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    L = dx * dx + dy * dy
    t = np.clip(((px - ax) * dx + (py - ay) * dy) / L, 0.0, 1.0) if L > 0 else np.zeros_like(px)
    ex, ey = px - (ax + t * dx), py - (ay + t * dy)
    return ex * ex + ey * ey


def _polygon_dist2(px, py, verts):
    v = np.asarray(verts, dtype=np.float64)
    d2 = np.full(px.shape, np.inf)
    inside = np.zeros(px.shape, dtype=bool)
    k = len(v)
    for i in range(k):
        ax, ay = v[i]
        bx, by = v[(i + 1) % k]
        d2 = np.minimum(d2, _seg_dist2(px, py, ax, ay, bx, by))
        cond = (ay > py) != (by > py)
        with np.errstate(divide="ignore", invalid="ignore"):
            xcross = ax + (py - ay) * (bx - ax) / (by - ay)
        inside ^= cond & (px < xcross)
    return np.where(inside, 0.0, d2)


def shape_dist2(s, px, py):
    t = s["type"]
    if t == "point":
        x, y = s["position"]
        return (px - x) ** 2 + (py - y) ** 2
    if t == "segment":
        (ax, ay), (bx, by) = s["vertices"]
        return _seg_dist2(px, py, ax, ay, bx, by)
    if t == "circle":
        (x, y), r = s["center"], s["radius"]
        return np.maximum(0.0, np.hypot(px - x, py - y) - r) ** 2
    if t == "union":
        return np.min([shape_dist2(p, px, py) for p in s["parts"]], axis=0)
    return _polygon_dist2(px, py, s["vertices"])


def corner_ambiguity(doc, cells: int):
    """Per grid corner of the document's labelled diagram (cells along the square area's side): the
    nearest label (obstacles in order, then the area's four edges) and whether the nearest two
    labels' squared distances are within 1e-9 relative of each other (an ambiguous corner: its
    label is a tie, or so close to one that rounding decides). Arrays (cells+1, cells+1), [j, i] =
    corner (x0 + i h, y0 + j h)."""
    x0, y0, x1, y1 = doc["area"]["box"]
    h = (x1 - x0) / cells
    g = np.arange(cells + 1, dtype=np.float64)
    px, py = np.meshgrid(x0 + g * h, y0 + g * h)
    d = [shape_dist2(s, px, py) for s in doc["obstacles"]]
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    for k in range(4):
        (ax, ay), (bx, by) = corners[k], corners[(k + 1) % 4]
        d.append(_seg_dist2(px, py, ax, ay, bx, by))
    D = np.stack(d)                      # (labels, cells+1, cells+1)
    order = np.sort(D, axis=0)
    label = np.argmin(D, axis=0)
    d1, d2 = order[0], order[1]
    ambiguous = (d2 - d1) <= 1e-9 * np.maximum(1.0, d2)
    return label, ambiguous


def determined_cells(label: np.ndarray, ambiguous: np.ndarray):
    """Cells whose four corners are all unambiguous, and the diagram there (corners carry >= 2
    labels). Arrays (cells, cells), [j, i] = cell with lower-left corner (i, j)."""
    bl, br = label[:-1, :-1], label[:-1, 1:]
    tl, tr = label[1:, :-1], label[1:, 1:]
    amb = ambiguous[:-1, :-1] | ambiguous[:-1, 1:] | ambiguous[1:, :-1] | ambiguous[1:, 1:]
    mixed = (bl != br) | (bl != tl) | (bl != tr)
    return ~amb, mixed
