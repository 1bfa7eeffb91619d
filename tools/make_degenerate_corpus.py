#!/usr/bin/env python3
"""Writes tests/data/degenerate_corpus.txt: named degenerate inputs for the exact-oracle tests.

Both ctest (tests/oracle/test_limited_oracle.cpp) and pytest read the generated file, so the two
suites test the same cases. The generator is deterministic (numpy PCG64 with fixed seeds); run it
again only to add cases, and commit the regenerated file.

Format (one case after another; `#` starts a comment line):

    case NAME RADIUS
    x y            # %.17g, so the file reads back to the same doubles
    ...
    end

Families: square lattices (spacings 1, 2, 0.1) at radii where neighbours sit exactly at 2R
(tangent bisectors) and Voronoi vertices exactly or nearly on the circle; hexagonal lattices;
points on one circle (floating-point and exactly cocircular Pythagorean points, with and without
the centre); regular polygons with their centre; exactly and nearly collinear points; lattices and
random points near 1e7 with unit spacing; spacings near 1e-9; random subsets of an integer grid
(many exact cocircularities and exact 2R distances); unit lattices jittered by a few units in the
last place; the Intel lab motes; and tiny inputs.

Usage: python tools/make_degenerate_corpus.py [OUTPUT]   (default: tests/data/degenerate_corpus.txt)
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def square_lattice(nx, ny, spacing=1.0, origin=(0.0, 0.0)):
    return np.array([(origin[0] + i * spacing, origin[1] + j * spacing)
                     for j in range(ny) for i in range(nx)], dtype=float)


def hex_lattice(nx, ny, spacing=1.0):
    h = spacing * math.sqrt(3.0) / 2.0
    return np.array([((i + 0.5 * (j % 2)) * spacing, j * h)
                     for j in range(ny) for i in range(nx)], dtype=float)


def circle_points(k, radius=1.0, center=(0.0, 0.0), phase=0.0):
    t = phase + 2.0 * math.pi * np.arange(k) / k
    return np.column_stack([center[0] + radius * np.cos(t), center[1] + radius * np.sin(t)])


def pythagorean_circle(r):
    """All integer points on x^2 + y^2 = r^2 (exactly cocircular in doubles)."""
    pts = [(x, y) for x in range(-r, r + 1) for y in range(-r, r + 1) if x * x + y * y == r * r]
    pts.sort(key=lambda p: math.atan2(p[1], p[0]))
    return np.array(pts, dtype=float)


def with_center(pts, center=(0.0, 0.0)):
    return np.vstack([pts, np.array([center], dtype=float)])


def intel_motes():
    rows = []
    for line in (ROOT / "tests" / "data" / "intel_lab_motes.txt").read_text().splitlines():
        line = line.split("#", 1)[0].split()
        if line:
            rows.append((float(line[1]), float(line[2])))
    return np.array(rows, dtype=float)


def cases():
    out = []

    def add(name, pts, radii):
        pts = np.asarray(pts, dtype=float).reshape(-1, 2)
        for r in radii:
            out.append((f"{name}/R={float(r)!r}", pts, float(r)))

    # Tiny inputs.
    add("empty", np.zeros((0, 2)), [1.0])
    add("single", [(0.25, -3.0)], [1.0])
    add("pair_tangent", [(0.0, 0.0), (2.0, 0.0)], [1.0])  # bisector tangent to both disks
    add("pair_close", [(0.0, 0.0), (2.0, 0.0)], [1.0000000000000002, 0.9999999999999999, 3.0])
    add("triple_collinear", [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)], [0.5, 0.75, 3.0])
    add("square4", [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)],
        [0.5, 0.7071067811865476, 0.7071067811865475, 1.0])

    # Square lattices. Spacing 1: R = 0.5 puts every neighbour at exactly 2R (tangent, no limited
    # neighbours); R ~ sqrt(2)/2 puts Voronoi vertices on the circle up to one rounding.
    for n in (3, 5, 8):
        add(f"square_lattice_{n}x{n}", square_lattice(n, n),
            [0.25, 0.5, 0.7071067811865476, 0.7071067811865475, 1.0, 1.5, 2.5])
    add("square_lattice_6x4_spacing2", square_lattice(6, 4, 2.0),
        [1.0, 1.4142135623730951, 1.4142135623730949, 2.0, 3.0])
    # Spacing 0.1 (not a double): coordinates i*0.1 differ by almost-but-not-exactly 2R = 0.1.
    add("square_lattice_7x7_spacing0.1", square_lattice(7, 7, 0.1),
        [0.05, 0.07071067811865475, 0.1, 0.15])
    add("square_lattice_10x10_offset", square_lattice(10, 10, 1.0, (-4.5, -4.5)),
        [0.5, 0.7071067811865476, 1.0, 2.0])

    # Hexagonal lattices (sqrt(3)/2 row spacing, so only approximately regular in doubles):
    # R = 0.5 near tangency, R = 1/sqrt(3) near the Voronoi vertices.
    for nx, ny in ((4, 4), (7, 6), (10, 9)):
        add(f"hex_lattice_{nx}x{ny}", hex_lattice(nx, ny),
            [0.5, 0.5773502691896258, 0.5773502691896257, 0.6, 1.0, 2.0])

    # Points on one circle.
    for k in (4, 8, 12, 13, 32):
        add(f"circle_{k}", circle_points(k, 5.0), [0.5, 2.5, 5.0, 12.0])
        add(f"circle_{k}_center", with_center(circle_points(k, 5.0)), [1.0, 2.5, 5.0, 12.0])
    for r in (5, 25, 65):
        pc = pythagorean_circle(r)
        add(f"pythagorean_circle_{r}_{len(pc)}", pc, [r / 2.0, r / 4.0, float(r), 3.0 * r])
        add(f"pythagorean_circle_{r}_{len(pc)}_center", with_center(pc),
            [r / 2.0, r / 4.0, float(r), 3.0 * r])

    # Regular polygons with their centre.
    for k in (3, 4, 5, 6, 7, 8, 16):
        add(f"regular_{k}gon_center", with_center(circle_points(k, 1.0, phase=0.3)),
            [0.5, 0.75, 1.0, 2.0])
    add("exact_square_center", [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (0.0, 0.0)],
        [0.5, 0.7071067811865476, 1.0, 1.4142135623730951, 3.0])

    # Collinear and nearly collinear.
    add("collinear_row_20", [(float(i), 0.0) for i in range(20)], [0.5, 0.75, 2.0, 20.0])
    add("collinear_diagonal_15", [(float(i), float(2 * i + 1)) for i in range(15)],
        [1.0, 1.118033988749895, 1.2, 5.0])
    add("collinear_uneven", [(0.1 * i * i, 0.0) for i in range(12)], [0.05, 0.3, 1.0])
    add("two_rows", [(float(i), float(j)) for j in (0, 1) for i in range(12)],
        [0.5, 0.7071067811865476, 1.0])
    rng = np.random.default_rng(1001)
    for n in (10, 25):
        x = np.arange(n, dtype=float)
        add(f"nearly_collinear_{n}", np.column_stack([x, 1e-12 * rng.standard_normal(n)]),
            [0.5, 0.75, 3.0])
        add(f"nearly_collinear_rows_{n}",
            np.vstack([np.column_stack([x, 1e-12 * rng.standard_normal(n)]),
                       np.column_stack([x + 0.5, 1.0 + 1e-12 * rng.standard_normal(n)])]),
            [0.5, 0.6, 1.0, 2.0])
    add("collinear_plus_one", [(float(i), 0.0) for i in range(10)] + [(4.5, 1e-9)],
        [0.5, 1.0, 4.0])

    # Far from the origin: coordinates near 1e7 with unit spacing.
    add("far_lattice_6x6", square_lattice(6, 6, 1.0, (1e7, 1e7)), [0.5, 0.7071067811865476, 1.0, 1.5])
    add("far_lattice_neg_5x5", square_lattice(5, 5, 1.0, (-1e7, 3e7)), [0.5, 1.0, 3.0])
    rng = np.random.default_rng(1002)
    for n in (30, 100):
        add(f"far_random_{n}", 1e7 + rng.random((n, 2)) * math.sqrt(n), [0.5, 1.0, 3.0])
    add("far_hex_5x5", hex_lattice(5, 5) + 1e7, [0.5, 0.5773502691896258, 1.0])

    # Tiny scale: spacings near 1e-9.
    add("tiny_lattice_6x6", square_lattice(6, 6, 1e-9), [5e-10, 7.0710678118654757e-10, 1e-9, 3e-9])
    rng = np.random.default_rng(1003)
    for n in (30, 100):
        add(f"tiny_random_{n}", rng.random((n, 2)) * 1e-9 * math.sqrt(n), [5e-10, 1e-9, 3e-9])
    add("tiny_lattice_offset", square_lattice(5, 5, 1e-9, (1.0, 1.0)), [5e-10, 1e-9])

    # Random subsets of an integer grid: exact cocircularities and exact distances 2R.
    rng = np.random.default_rng(1004)
    for size, keep in ((8, 0.5), (12, 0.3), (20, 0.6), (30, 0.15)):
        grid = square_lattice(size, size)
        pts = grid[rng.random(len(grid)) < keep]
        add(f"grid_subset_{size}_{keep}", pts,
            [0.5, 1.0, 1.118033988749895, 1.5, 2.5, 3.5355339059327378])
    # Integer points at odd multiples of 1/2 (Voronoi vertices on half-integers).
    pts = square_lattice(15, 15)
    pts = pts[rng.random(len(pts)) < 0.4] * 0.5
    add("half_grid_subset", pts, [0.25, 0.5, 0.75, 1.25])

    # Unit lattices moved by a few units in the last place: the exact ties above become near-ties.
    rng = np.random.default_rng(1005)
    for jitter in (2.0 ** -50, 2.0 ** -40, 1e-12):
        pts = square_lattice(9, 9) + jitter * 0.5 * rng.integers(-2, 3, size=(81, 2))
        add(f"jittered_lattice_9x9_{jitter:.3g}", pts, [0.5, 0.7071067811865476, 1.0, 1.5])

    # Intel Berkeley lab motes (half-integer metres: many exact ties).
    add("intel_lab_motes", intel_motes(), [2.0, 3.0, 5.0, 8.0])
    return out


def main(argv):
    path = Path(argv[1]) if len(argv) > 1 else ROOT / "tests" / "data" / "degenerate_corpus.txt"
    lines = [
        "# dvoronoi degenerate corpus: generated by tools/make_degenerate_corpus.py (do not edit).",
        "# Read by tests/oracle/test_limited_oracle.cpp and the pytest oracle tests.",
        "# Format: `case NAME RADIUS`, then one `x y` per line (%.17g), then `end`.",
    ]
    names = set()
    for name, pts, r in cases():
        assert name not in names, name
        names.add(name)
        assert len({(float(x), float(y)) for x, y in pts}) == len(pts), f"{name}: duplicate points"
        lines.append(f"case {name} {r:.17g}")
        lines.extend(f"{x:.17g} {y:.17g}" for x, y in pts)
        lines.append("end")
    path.write_text("\n".join(lines) + "\n")
    print(f"wrote {len(names)} cases to {path}")


if __name__ == "__main__":
    main(sys.argv)
