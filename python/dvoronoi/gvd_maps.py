"""Obstacle maps for examples, tests and benchmarks of the grid Voronoi diagram: random mixes and the
paper's two arrangements ("sea of triangles", "mixed shapes"), as documents in the JSON obstacle format
that :func:`dvoronoi.grid_voronoi` and ``dvoronoi gvd`` read."""
from __future__ import annotations

import math
from typing import Any, Dict, List

import numpy as np


def ngon(c, r, n, phase):
    t = phase + 2 * math.pi * np.arange(n) / n
    return {"type": "polygon", "vertices": np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)]).tolist()}


def star(c, r, phase=0.0):
    t = phase + 2 * math.pi * np.arange(10) / 10
    rr = np.where(np.arange(10) % 2 == 1, 0.45 * r, r)
    return {"type": "polygon", "vertices": np.column_stack([c[0] + rr * np.cos(t), c[1] + rr * np.sin(t)]).tolist()}


def ell(c, s):
    x, y = c
    return {"type": "polygon", "vertices": [[x, y], [x + s, y], [x + s, y + s / 3], [x + s / 3, y + s / 3],
                                            [x + s / 3, y + s], [x, y + s]]}


def random_mixed(seed: int, count: int, size: float = 4.0, extent: float = 100.0) -> Dict[str, Any]:
    """`count` separated obstacles of mixed kinds (triangles, n-gons, circles, points, L shapes, stars)
    in the box [0, extent]^2; obstacle sizes scale with `size`."""
    rng = np.random.default_rng(seed)
    placed: List = []
    obstacles: List[Dict[str, Any]] = []
    attempts = 0
    while len(obstacles) < count and attempts < 200 * count:
        attempts += 1
        r = size * (0.4 + 0.6 * rng.random())
        c = r + 2 + (extent - 4 - 2 * r) * rng.random(2)
        if any(np.hypot(*(c - q)) <= r + rq + size / 4 for q, rq in placed):
            continue
        placed.append((c, r))
        kind = int(rng.integers(6))
        c = c.tolist()
        if kind == 0:
            obstacles.append(ngon(c, r, 3, rng.random() * 6.28))
        elif kind == 1:
            obstacles.append(ngon(c, r, int(rng.integers(4, 9)), rng.random() * 6.28))
        elif kind == 2:
            obstacles.append({"type": "circle", "center": c, "radius": r})
        elif kind == 3:
            obstacles.append({"type": "point", "position": c})
        elif kind == 4:
            obstacles.append(ell([c[0] - r / 1.5, c[1] - r / 1.5], 1.3 * r))
        else:
            obstacles.append(star(c, r, rng.random()))
    return {"area": {"box": [0.0, 0.0, extent, extent]}, "obstacles": obstacles}


def sea_of_triangles(seed: int, per_side: int = 7, extent: float = 100.0) -> Dict[str, Any]:
    """The paper's first map: a jittered lattice of small triangles."""
    rng = np.random.default_rng(seed)
    step = extent / per_side
    obstacles = []
    for a in range(per_side):
        for b in range(per_side):
            c = [(a + 0.5) * step + 0.15 * step * rng.uniform(-1, 1), (b + 0.5) * step + 0.15 * step * rng.uniform(-1, 1)]
            obstacles.append(ngon(c, 0.22 * step, 3, 3 * rng.uniform(-1, 1)))
    return {"area": {"box": [0.0, 0.0, extent, extent]}, "obstacles": obstacles}


def mixed_shapes(extent: float = 100.0) -> Dict[str, Any]:
    """The paper's second map: fewer obstacles of different kinds, circles, dots and non-convex polygons."""
    s = extent / 100.0
    obstacles = [
        ell([12 * s, 60 * s], 24 * s),
        {"type": "circle", "center": [70 * s, 72 * s], "radius": 11 * s},
        {"type": "point", "position": [45 * s, 40 * s]},
        {"type": "point", "position": [85 * s, 25 * s]},
        ngon([25 * s, 20 * s], 9 * s, 5, 0.3),
        {"type": "polygon", "vertices": [[50 * s, 80 * s], [60 * s, 95 * s], [40 * s, 95 * s]]},
        {"type": "polygon", "vertices": [[55 * s, 10 * s], [75 * s, 10 * s], [75 * s, 40 * s], [68 * s, 40 * s],
                                         [68 * s, 17 * s], [55 * s, 17 * s]]},
        {"type": "circle", "center": [40 * s, 62 * s], "radius": 4 * s},
        {"type": "segment", "vertices": [[85 * s, 45 * s], [92 * s, 60 * s]]},
        star([88 * s, 85 * s], 7 * s),
    ]
    return {"area": {"box": [0.0, 0.0, extent, extent]}, "obstacles": obstacles}
