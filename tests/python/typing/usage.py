"""A user's typed code on dvoronoi, checked by `mypy --strict` in tests/python/test_typing.py (never run).

It touches each public entry point and result type, so a stub or annotation that is missing or wrong
shows up as a strict-mode error here, and `reveal`-style assignments pin the types users rely on.
"""
from __future__ import annotations

from typing import List, Optional

import numpy as np
import numpy.typing as npt

import dvoronoi as dv


def limited(points: npt.NDArray[np.float64]) -> float:
    part: dv.LimitedPartition = dv.limited_cells(points, 0.3, method="scan", workers=1)
    nbrs: np.ndarray = part.neighbors(0)
    cell: dv.LimitedCell = part.cell(0)
    pieces: List[dv.Piece] = cell.pieces
    kinds: List[str] = [p.kind for p in pieces]
    area: float = cell.area
    text: Optional[str] = part.to_json()
    one: dv.LimitedCell = dv.limited_cell(points[0], points[1:], 0.3)
    verts: npt.NDArray[np.float64] = one.vertices
    degree: int = len(nbrs) + len(kinds) + len(verts)
    return area + float(np.sum(part.areas)) + degree + len(text or "")


def exact(points: npt.NDArray[np.float64]) -> int:
    vor: dv.VoronoiPartition = dv.voronoi_cells(points, bounds=(0.0, 0.0, 1.0, 1.0))
    cell: dv.VoronoiCell = vor.cell(0)
    edges: List[dv.VoronoiEdge] = cell.edges
    hull: bool = cell.on_hull
    clipped: Optional[dv.ClippedCell] = cell.clipped
    polygon: Optional[np.ndarray] = vor.polygon(0)
    return len(edges) + int(hull) + (0 if clipped is None else len(clipped.vertices)) + (polygon is None)


def geo_and_files(points: npt.NDArray[np.float64], path: str) -> int:
    part = dv.limited_cells(points, 0.3)
    fc = part.__geo_interface__
    part.to_json(path)
    back = dv.load(path)
    return len(fc["features"]) + len(back)


def distances(d: npt.NDArray[np.float64]) -> int:
    nb: dv.DistanceNeighbors = dv.neighbors_from_distances(d)
    return int(nb.indptr[-1])


def version() -> str:
    v: str = dv.__version__
    return v
