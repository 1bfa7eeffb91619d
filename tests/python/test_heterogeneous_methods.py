"""Heterogeneous teams, every method (docs/heterogeneous.md): "auto" (certified clipping, exact
clipping behind it), "scan" and "chords" (Boundary Scan and RCVC generalised to radical axes) give
the same cells as sets: neighbours, empty flags, pieces; areas within the stated accuracy. Also on
transformed copies (permuted, translated, rotated by 90 degrees, scaled by powers of two)."""
import numpy as np
import pytest

import dvoronoi as dv

METHODS = ("auto", "scan", "chords")


def team(seed, n=250):
    """Random teams of three kinds: radii uniform in [0.5R, 1.5R], widely spread radii (many empty
    cells and crescents), and an integer lattice with two radii (exact ties)."""
    rng = np.random.default_rng(seed)
    kind = seed % 3
    if kind == 0:
        return rng.random((n, 2)), 0.06 * (0.5 + rng.random(n))
    if kind == 1:
        return rng.random((n, 2)), 0.02 * 2.0 ** rng.integers(0, 4, n) * (0.5 + rng.random(n))
    xy = np.array([(x, y) for x in range(12) for y in range(12)], float)
    return xy, np.where(rng.random(len(xy)) < 0.5, 1.0, rng.choice([1.25, 1.5, 2.0]))


def sets(part):
    return [frozenset(part.neighbors(i).tolist()) for i in range(len(part))]


def pieces(part, i):
    """Agent i's pieces as a cyclic list of neighbours (-1 for arcs), from its smallest neighbour."""
    lab = [int(x) for x in part.piece_neighbor[part.piece_ptr[i]:part.piece_ptr[i + 1]]]
    edges = [k for k, x in enumerate(lab) if x >= 0]
    if not edges:
        return tuple(lab)
    k = min(edges, key=lambda t: lab[t])
    return tuple(lab[k:] + lab[:k])


@pytest.mark.parametrize("seed", range(9))
def test_methods_agree(seed):
    pts, radii = team(seed)
    parts = {m: dv.limited_cells(pts, radii, method=m, workers=1, progress=False) for m in METHODS}
    base = parts["auto"]
    ran = {m: p.computed_by for m, p in parts.items()}
    assert ran["scan"]["scan"] == len(pts) and ran["chords"]["chords"] == len(pts)
    assert ran["auto"]["clip"] + ran["auto"]["power"] == len(pts)
    for m in ("scan", "chords"):
        p = parts[m]
        assert p.method == m
        assert sets(p) == sets(base)
        assert np.array_equal(p.empty, base.empty)
        assert all(pieces(p, i) == pieces(base, i) for i in range(len(pts)))
        assert np.allclose(p.areas, base.areas, rtol=0, atol=1e-12 * radii.max() ** 2)
    if seed % 3 == 1:
        assert base.empty.any() and not base.empty.all()


@pytest.mark.parametrize("seed", range(6))
def test_transformed_copies(seed):
    pts, radii = team(seed, n=200)
    # Coordinates on a 2^-40 grid stay exact under translation by +4, -8 and scaling by 2^k.
    pts = np.round(pts * 2.0**40) * 2.0**-40
    perm = np.random.default_rng(seed + 100).permutation(len(pts))
    inv = np.argsort(perm)
    copies = [
        (pts[perm], radii[perm]),
        (pts[perm] + np.array([4.0, -8.0]), radii[perm]),
        (pts[perm] @ np.array([[0.0, 1.0], [-1.0, 0.0]]), radii[perm]),
        (pts[perm] * 2.0**6, radii[perm] * 2.0**6),
        (pts[perm] * 2.0**-9, radii[perm] * 2.0**-9),
    ]
    for m in METHODS:
        base = sets(dv.limited_cells(pts, radii, method=m, workers=1, progress=False))
        for p, r in copies:
            got = sets(dv.limited_cells(p, r, method=m, workers=2, progress=False))
            assert [frozenset(int(perm[j]) for j in got[inv[i]]) for i in range(len(pts))] == base, m


def test_one_agent_every_method():
    pts, radii = team(4)
    part = dv.limited_cells(pts, radii, progress=False)
    for i in range(0, len(pts), 17):
        others, ro = np.delete(pts, i, axis=0), np.delete(radii, i)
        ids = np.delete(np.arange(len(pts)), i)
        for m in METHODS:
            cell = dv.limited_cell(pts[i], others, radii[i], method=m, other_radii=ro)
            assert set(ids[cell.neighbors].tolist()) == set(part.neighbors(i).tolist()), (i, m)
            assert cell.area == pytest.approx(part.areas[i], rel=1e-12, abs=1e-12 * radii[i] ** 2)
