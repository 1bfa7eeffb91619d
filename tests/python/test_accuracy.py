"""Accurate constructions (docs/guarantees.md, "Constructions"; issue 20, item 5): every vertex, arc
span, area, centroid and perimeter that limited_cells (both methods) and voronoi_cells report is
within 2^-40 D of the exact value for the input doubles (areas 2^-40 D^2; D = the cell's diameter;
points in the caller's frame also carry their own rounding, half an ulp).

The reference is computed here from dvoronoi's own combinatorics (exact predicates, compared with
CGAL in test_oracle.py), checked against every agent's half-plane: vertices where two bisectors meet
are exact rationals of the input doubles (fractions.Fraction); chord ends, arc spans and lengths in
mpmath at 60 digits."""
from __future__ import annotations

import math
from fractions import Fraction as F
from typing import List, Tuple

import numpy as np
import pytest

import dvoronoi as dv

mpmath = pytest.importorskip("mpmath")
mp = mpmath.mp
mp.dps = 60

ACC = 2.0 ** -40
METHODS = ["scan", "chords"]


def mpf(x: F):
    return mpmath.mpf(x.numerator) / x.denominator


def exact_vertex(c, p, q) -> Tuple[F, F]:
    """The meeting point of the bisectors of (c, p) and (c, q), relative to c, exactly."""
    ax, ay = F(p[0]) - F(c[0]), F(p[1]) - F(c[1])
    bx, by = F(q[0]) - F(c[0]), F(q[1]) - F(c[1])
    ha, hb = (ax * ax + ay * ay) / 2, (bx * bx + by * by) / 2
    d = ax * by - ay * bx
    return (ha * by - hb * ay) / d, (ax * hb - bx * ha) / d


def exact_chord_end(c, p, radius: float, sigma: int):
    """The end of the chord of (c, p)'s bisector in the disk (sigma -1 first, +1 last), relative to c."""
    ax, ay = F(p[0]) - F(c[0]), F(p[1]) - F(c[1])
    n2 = ax * ax + ay * ay
    w = mpmath.sqrt(mpf(F(radius) ** 2 - n2 / 4))
    na = mpmath.sqrt(mpf(n2))
    return mpf(ax) / 2 - sigma * w * mpf(ay) / na, mpf(ay) / 2 + sigma * w * mpf(ax) / na


def check_inside(points, i, verts, radius):
    """The reference cell is the exact cell: every vertex lies in every half-plane (up to 1e-40 of the
    cell) and in the disk."""
    c = points[i]
    scale = max(max(abs(x), abs(y)) for x, y in verts) if verts else 1
    for j, p in enumerate(points):
        if j == i:
            continue
        ax, ay = mpf(F(p[0]) - F(c[0])), mpf(F(p[1]) - F(c[1]))
        h = (ax * ax + ay * ay) / 2
        for x, y in verts:
            assert x * ax + y * ay - h <= mpmath.mpf(10) ** -40 * scale * (abs(ax) + abs(ay)), (i, j)
    if radius is not None:
        for x, y in verts:
            assert x * x + y * y <= mpmath.mpf(radius) ** 2 * (1 + mpmath.mpf(10) ** -40)


def diameter(verts, arcs: bool, radius) -> float:
    """The cell's diameter from below: its vertices and the agent (and R when it has an arc)."""
    pts = list(verts) + [(mpmath.mpf(0), mpmath.mpf(0))]
    d = max(mpmath.sqrt((x1 - x2) ** 2 + (y1 - y2) ** 2) for x1, y1 in pts for x2, y2 in pts)
    return float(max(d, radius if arcs else 0))


def off(got, c, v) -> float:
    """|got - c - v|: a reported point against an exact one relative to the agent c, in mpmath."""
    m = lambda x: mpf(x) if isinstance(x, F) else mpmath.mpf(x)
    return float(mpmath.hypot(m(got[0]) - m(c[0]) - m(v[0]), m(got[1]) - m(c[1]) - m(v[1])))


def ulp(v) -> float:
    return float(np.spacing(np.max(np.abs(np.asarray(v, dtype=float)))))


def reference_limited(points, i, radius, neighbor, spans):
    """Exact vertices (relative to p_i), spans, area, centroid (relative) and perimeter of agent i's
    limited cell, with dvoronoi's pieces (neighbour per piece, -1 arcs) as the combinatorics."""
    c = points[i]
    n = len(neighbor)
    if n == 1 and neighbor[0] < 0:
        a = mpmath.pi * mpmath.mpf(radius) ** 2
        return [(mpmath.mpf(radius), mpmath.mpf(0))], [2 * mpmath.pi], a, (0, 0), 2 * mpmath.pi * radius
    verts = []
    for k in range(n):
        prev, cur = neighbor[k - 1], neighbor[k]
        if cur >= 0 and prev >= 0:
            x, y = exact_vertex(c, points[prev], points[cur])
            verts.append((mpf(x), mpf(y)))
        elif cur >= 0:
            verts.append(exact_chord_end(c, points[cur], radius, -1))
        else:
            verts.append(exact_chord_end(c, points[prev], radius, +1))
    R = mpmath.mpf(radius)
    area = mx = my = per = mpmath.mpf(0)
    out_spans = []
    for k in range(n):
        (ux, uy), (wx, wy) = verts[k], verts[(k + 1) % n]
        if neighbor[k] < 0:
            phi = mpmath.atan2(ux * wy - uy * wx, ux * wx + uy * wy)
            # The branch nearest dvoronoi's span (which the exact combinatorics fix).
            phi += 2 * mpmath.pi * round((spans[k] - float(phi)) / (2 * math.pi))
            out_spans.append(phi)
            area += R * R * phi / 2
            mx += R * R / 3 * (wy - uy)
            my += R * R / 3 * (ux - wx)
            per += R * phi
        else:
            out_spans.append(mpmath.mpf(0))
            cr = ux * wy - uy * wx
            area += cr / 2
            mx += cr * (ux + wx) / 6
            my += cr * (uy + wy) / 6
            per += mpmath.sqrt((wx - ux) ** 2 + (wy - uy) ** 2)
    check_inside(points, i, verts, radius)
    return verts, out_spans, area, (mx / area, my / area), per


def assert_limited_accurate(points, radius, label, agents=None):
    points = np.asarray(points, dtype=float)
    for method in METHODS:
        part = dv.limited_cells(points, radius, method=method)
        for i in (range(len(points)) if agents is None else agents):
            lo, hi = part.piece_ptr[i], part.piece_ptr[i + 1]
            nb = [int(v) for v in part.piece_neighbor[lo:hi]]
            spans = [float(v) for v in part.piece_span[lo:hi]]
            verts, rspans, area, cen, per = reference_limited(points, i, radius, nb, spans)
            D = diameter(verts, any(v < 0 for v in nb), radius)
            c = points[i]
            where = f"{label} [{method}] agent {i}"
            for k in range(hi - lo):
                got = (part.piece_x[lo + k], part.piece_y[lo + k])
                err = off(got, c, verts[k])
                assert err <= ACC * D + ulp(got), f"{where}: vertex {k} off by {err:.3g} (D = {D:.3g})"
                if nb[k] < 0:
                    assert radius * abs(spans[k] - float(rspans[k])) <= ACC * D, f"{where}: span {k}"
            assert abs(part.areas[i] - float(area)) <= ACC * D * D, \
                f"{where}: area {part.areas[i]!r}, exact {float(area)!r}, D = {D:.3g}"
            assert abs(part.perimeters[i] - float(per)) <= ACC * D, f"{where}: perimeter"
            g = part.centroids[i]
            err = off(g, c, cen)
            assert err <= ACC * D + ulp(g), f"{where}: centroid off by {err:.3g} (D = {D:.3g})"


# ------------------------------------------------------------------------------------------ cases

REPRO = [[1.1443556419135317, 46.94138466863679], [77.34700595259886, 99.95513007877705],
         [77.34700595959886, 99.95513008577704]]


def test_issue_reproducer_area():
    # Near-parallel bisectors of a close pair meeting far away (issue 20, item 5): the exact area from
    # exact rational vertices and mpmath arcs, with the pieces of dvoronoi's cell.
    part = dv.limited_cells(REPRO, 1000.0)
    nb = [int(v) for v in part.piece_neighbor[part.piece_ptr[0]:part.piece_ptr[1]]]
    spans = [float(v) for v in part.piece_span[part.piece_ptr[0]:part.piece_ptr[1]]]
    _, _, area, _, _ = reference_limited(np.array(REPRO), 0, 1000.0, nb, spans)
    assert abs(float(area) - 1663592.40467) < 1e-5
    D = 2000.0  # at most the disk's diameter
    for method in METHODS:
        got = dv.limited_cells(REPRO, 1000.0, method=method).areas[0]
        assert abs(got - float(area)) <= ACC * D * D, (method, got, float(area))
        one = dv.limited_cell(center=REPRO[0], others=REPRO[1:], radius=1000.0, method=method)
        assert abs(one.area - float(area)) <= ACC * D * D, (method, one.area, float(area))
    assert_limited_accurate(REPRO, 1000.0, "reproducer")


def test_near_parallel_bisectors():
    rng = np.random.default_rng(5)
    for t in range(6):
        base = rng.uniform(-100, 100, 2)
        far = base + rng.uniform(10, 90, 2)
        eps = 10.0 ** -rng.uniform(6, 10)
        pts = np.array([base, far, far + eps * rng.normal(size=2), base + rng.uniform(-60, 60, 2)])
        assert_limited_accurate(pts, 150.0, f"near-parallel {t}", agents=[0, 3])


def test_moderately_parallel_bisectors():
    # A close pair seen from afar, 1e-3 .. 1e-6 of their distance apart: bisectors with a condition
    # number of 1e3 .. 1e6 meeting inside the disk, where the plain formula loses up to 20 bits.
    rng = np.random.default_rng(8)
    for t in range(12):
        base = rng.uniform(-100, 100, 2)
        a = rng.uniform(20, 60, 2)
        d = np.linalg.norm(a) * 10.0 ** -rng.uniform(3, 6)
        pts = np.array([base, base + a, base + a + d * rng.normal(size=2), base - a])
        assert_limited_accurate(pts, 150.0, f"moderately parallel {t}", agents=[0])


def test_thin_cells():
    # Agents along a diagonal, close together: strips whose centroid magnifies the roundings.
    for s in (1e-5, 1e-7, 1e-9):
        t = np.arange(12) * s
        pts = np.column_stack([t, t]) + np.array([3.0, -2.0])
        assert_limited_accurate(pts, 1.0, f"thin cells s={s:g}", agents=[3, 6])


def test_near_duplicate_agents():
    rng = np.random.default_rng(11)
    base = rng.uniform(0, 1, (12, 2))
    twins = base + 1e-11 * rng.normal(size=base.shape)
    pts = np.vstack([base, twins])
    assert_limited_accurate(pts, 0.25, "near-duplicates")


def test_clustered():
    rng = np.random.default_rng(3)
    centres = rng.uniform(0, 100, (3, 2))
    pts = np.vstack([c + rng.normal(scale=s, size=(8, 2)) for c, s in zip(centres, [1e-3, 1e-6, 1e-9])])
    assert_limited_accurate(pts, 40.0, "clustered")


@pytest.mark.parametrize("scale", [2.0 ** -30, 3e-7, 1.0, 2.0 ** 20, 7.3e5, 1e12])
def test_random_scales(scale):
    rng = np.random.default_rng(int(abs(math.log2(scale))) + 1)
    pts = rng.uniform(0, 1, (30, 2)) * scale + np.array([0.25, -0.5]) * scale * 37
    assert_limited_accurate(pts, 0.2 * scale, f"scale {scale:g}")


def test_far_from_origin():
    rng = np.random.default_rng(9)
    pts = rng.uniform(0, 10, (25, 2)) + np.array([1e7, -1e7])
    assert_limited_accurate(pts, 2.0, "offset 1e7")


# ------------------------------------------------------------------------------------- voronoi cells


def exact_polygon(points, i, nbs):
    """Exact vertices (relative to p_i), area and centroid of the bounded cell with these neighbours."""
    c = points[i]
    verts = [exact_vertex(c, points[nbs[k - 1]], points[nbs[k]]) for k in range(len(nbs))]
    return (verts,) + polygon_measures(verts)


def polygon_measures(verts):
    """Area and centroid of a polygon, exactly (rational vertices)."""
    a = mx = my = F(0)
    for k in range(len(verts)):
        (ux, uy), (wx, wy) = verts[k], verts[(k + 1) % len(verts)]
        cr = ux * wy - uy * wx
        a += cr / 2
        mx += cr * (ux + wx) / 6
        my += cr * (uy + wy) / 6
    return a, ((mx / a, my / a) if a else None)


@pytest.mark.parametrize("family", ["uniform", "near-duplicates", "clustered", "near-collinear"])
def test_voronoi_cells_accurate(family):
    rng = np.random.default_rng(17)
    if family == "uniform":
        pts = rng.uniform(0, 1, (60, 2)) * 3e-5 + 1e3
    elif family == "near-duplicates":
        base = rng.uniform(0, 1, (25, 2))
        pts = np.vstack([base, base + 1e-11 * rng.normal(size=base.shape)])
    elif family == "clustered":
        pts = np.vstack([c + rng.normal(scale=s, size=(15, 2)) for c, s in
                         zip(rng.uniform(0, 10, (3, 2)), [1e-2, 1e-5, 1e-8])])
    else:
        x = np.sort(rng.uniform(0, 1, 40))
        pts = np.column_stack([x, 1e-9 * rng.normal(size=40) + 0.3 * x])
        pts = np.vstack([pts, [[0.5, 3.0], [0.5, -3.0]]])
    part = dv.voronoi_cells(pts)
    checked = 0
    for i in range(len(pts)):
        cell = part.cell(i)
        if cell.on_hull:
            continue
        nbs = [e.neighbor for e in cell.edges]
        verts, area, cen = exact_polygon(pts, i, nbs)
        fv = [(float(x), float(y)) for x, y in verts]
        D = max(math.hypot(a[0] - b[0], a[1] - b[1]) for a in fv for b in fv)
        for k, e in enumerate(cell.edges):
            got = e.start
            err = off(got, pts[i], verts[k])
            assert err <= ACC * D + ulp(got), f"{family}: agent {i} vertex {k} off by {err:.3g}, D = {D:.3g}"
        for a_got, g_got in ((part.areas[i], part.centroids[i]), (cell.area, cell.centroid)):
            assert abs(F(float(a_got)) - area) <= F(ACC * D * D), f"{family}: agent {i} area {a_got!r} vs {float(area)!r}"
            err = off(g_got, pts[i], cen)
            assert err <= ACC * D + ulp(g_got), f"{family}: agent {i} centroid off by {err:.3g}"
        checked += 1
    assert checked > 0


def exact_clipped(points, i, nbs, box):
    """The cell of agent i clipped to the box, exactly (Sutherland-Hodgman in rationals)."""
    x0, y0, x1, y1 = (F(v) for v in box)
    poly = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    c = (F(points[i][0]), F(points[i][1]))
    for j in nbs:
        p = (F(points[j][0]), F(points[j][1]))
        ax, ay = p[0] - c[0], p[1] - c[1]
        h = (p[0] ** 2 + p[1] ** 2 - c[0] ** 2 - c[1] ** 2) / 2
        f = lambda q: q[0] * ax + q[1] * ay - h
        out = []
        for k in range(len(poly)):
            u, w = poly[k], poly[(k + 1) % len(poly)]
            fu, fw = f(u), f(w)
            if fu <= 0:
                out.append(u)
            if (fu < 0 < fw) or (fw < 0 < fu):
                s = fu / (fu - fw)
                out.append((u[0] + s * (w[0] - u[0]), u[1] + s * (w[1] - u[1])))
        poly = out
    poly = [q for k, q in enumerate(poly) if q != poly[k - 1]]
    return (poly,) + polygon_measures(poly)


@pytest.mark.parametrize("family", ["uniform", "near-duplicates", "far from the origin"])
def test_clipped_cells_accurate(family):
    rng = np.random.default_rng(23)
    if family == "uniform":
        pts = rng.uniform(0, 1, (40, 2))
    elif family == "near-duplicates":
        base = rng.uniform(0, 1, (15, 2))
        pts = np.vstack([base, base + 1e-11 * rng.normal(size=base.shape)])
    else:
        pts = rng.uniform(0, 1, (40, 2)) + np.array([1e6, 3e6])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    box = (lo[0] - 0.1, lo[1] - 0.05, hi[0] + 0.2, hi[1] + 0.1)
    part = dv.voronoi_cells(pts, bounds=box)
    origin = (F(0), F(0))
    for i in range(len(pts)):
        clipped = part.cell(i).clipped
        nbs = [int(j) for j in part.neighbors(i)]
        poly, area, cen = exact_clipped(pts, i, nbs, box)
        fv = [(float(x), float(y)) for x, y in poly]
        D = max(math.hypot(a[0] - b[0], a[1] - b[1]) for a in fv for b in fv)
        assert len(clipped.vertices) == len(poly), f"{family}: agent {i}"
        for got in clipped.vertices:
            err = min(off(got, origin, v) for v in poly)
            assert err <= ACC * D + ulp(got), f"{family}: agent {i} clipped vertex off by {err:.3g}"
        for a_got, g_got in ((part.areas[i], part.centroids[i]), (clipped.area, clipped.centroid)):
            assert abs(F(float(a_got)) - area) <= F(ACC * D * D), f"{family}: agent {i} clipped area"
            assert off(g_got, origin, cen) <= ACC * D + ulp(g_got), f"{family}: agent {i} clipped centroid"
