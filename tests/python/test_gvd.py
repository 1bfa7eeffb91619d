"""Grid Voronoi diagram of obstacles (dv.grid_voronoi, `dvoronoi gvd`, dvoronoi_gvd_mpi).

Against the brute-force oracle (every corner labelled by scanning every obstacle part, same tie
rule): the traced cells are exactly the oracle's diagram cells — isolated pieces included (loops
around islands no area corner reaches, slivers thinner than a cell) — on random scenes, the paper's
maps and occupancy-grid maps, for 1, 2 and 3 workers and both approaches; thread and MPI runs
(K = 1..4, both approaches) give the single worker's cells; every diagram cell is within one cell
diagonal of a point equidistant from two obstacles, checked with exact (rational / 80-digit)
distances; paths are collision-free for the robot radius; bad input names the obstacle and field.
"""
from __future__ import annotations

import json
import os
import pickle
import shutil
import subprocess
from collections import deque
from decimal import Decimal, getcontext
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import _core, occupancy_maps

from dvoronoi.gvd_maps import mixed_shapes, random_mixed, sea_of_triangles

ROOT = Path(__file__).resolve().parents[2]
getcontext().prec = 80


# -- oracle helpers -------------------------------------------------------------------------------

def oracle(doc, resolution):
    scene = dv.gvd.load_obstacles(doc)
    labels, sq, mixed = _core._gvd_brute_force(scene, resolution)
    return scene, labels, sq, mixed


def oracle_pieces(labels, mixed):
    """Pieces of the oracle's diagram: its cells joined across label-changing edges (what the
    paper's tracing follows from a cell). Returns the piece of every cell (-1 off the diagram) and
    the piece count."""
    ny, nx = mixed.shape
    piece = np.full(mixed.shape, -1)
    n = 0
    L = labels
    for j0, i0 in zip(*np.nonzero(mixed)):
        if piece[j0, i0] >= 0:
            continue
        piece[j0, i0] = n
        q = deque([(i0, j0)])
        while q:
            i, j = q.popleft()
            for change, a, b in ((L[j, i] != L[j, i + 1], i, j - 1), (L[j, i + 1] != L[j + 1, i + 1], i + 1, j),
                                 (L[j + 1, i] != L[j + 1, i + 1], i, j + 1), (L[j, i] != L[j + 1, i], i - 1, j)):
                if change and 0 <= a < nx and 0 <= b < ny and mixed[b, a] and piece[b, a] < 0:
                    piece[b, a] = n
                    q.append((a, b))
        n += 1
    return piece, n


def corner_pieces(scene, piece, grid):
    """The pieces holding a cell at one of the area's corners (where the paper starts tracing)."""
    x0, y0, h, nx, ny = grid
    out = set()
    for vx, vy in scene.area:
        for j in range(max(0, int((vy - y0) / h) - 1), min(ny, int((vy - y0) / h) + 2)):
            for i in range(max(0, int((vx - x0) / h) - 1), min(nx, int((vx - x0) / h) + 2)):
                if x0 + i * h <= vx <= x0 + (i + 1) * h and y0 + j * h <= vy <= y0 + (j + 1) * h and piece[j, i] >= 0:
                    out.add(int(piece[j, i]))
    return out


def check_against_oracle(doc, resolution, workers=(1,), modes=("cooperative",)):
    """The traced cells are exactly the oracle's diagram cells, with its corner labels, for every
    worker count and approach given. Returns the last result, the cell count and the oracle."""
    scene, labels, sq, mixed = oracle(doc, resolution)
    for k in workers:
        for mode in modes:
            gv = dv.grid_voronoi(scene, cells=resolution, workers=k, mode=mode)
            traced = gv.diagram_mask
            assert traced.shape == mixed.shape
            extra, missed = np.argwhere(traced & ~mixed), np.argwhere(mixed & ~traced)
            assert len(extra) == 0 and len(missed) == 0, (
                f"workers {k} {mode}: {len(extra)} cells the oracle does not mark (first (row, col) "
                f"{extra[:3].tolist()}), {len(missed)} oracle cells missed (first {missed[:3].tolist()})")
            # the traced cells' corner labels are the oracle's
            c = gv.cells
            assert np.array_equal(gv.labels[:, 0], labels[c[:, 1], c[:, 0]])
            assert np.array_equal(gv.labels[:, 2], labels[c[:, 1] + 1, c[:, 0] + 1])
            assert gv.stats["traced_cells"] == len(c) and gv.stats["discarded_cells"] == 0
    return gv, int(mixed.sum()), (scene, labels, mixed)


# -- exact distances (rationals; circles through 80-digit square roots) ----------------------------

def _sq_seg(p, a, b):
    ab = (b[0] - a[0], b[1] - a[1])
    ap = (p[0] - a[0], p[1] - a[1])
    t = ap[0] * ab[0] + ap[1] * ab[1]
    if t <= 0:
        return ap[0] ** 2 + ap[1] ** 2
    l2 = ab[0] ** 2 + ab[1] ** 2
    if t >= l2:
        return (p[0] - b[0]) ** 2 + (p[1] - b[1]) ** 2
    cr = ab[0] * ap[1] - ab[1] * ap[0]
    return cr * cr / l2


def exact_distance(parts_of_label, p):
    """Exact distance (Decimal, 80 digits) from rational point p to the union of convex parts."""
    best = None
    for kind, verts, center, radius in parts_of_label:
        V = [(Fraction(x), Fraction(y)) for x, y in verts]
        if kind == "point":
            d = Decimal((p[0] - V[0][0]) ** 2 + (p[1] - V[0][1]) ** 2).sqrt() if False else _dec_sqrt((p[0] - V[0][0]) ** 2 + (p[1] - V[0][1]) ** 2)
        elif kind == "segment":
            d = _dec_sqrt(_sq_seg(p, V[0], V[1]))
        elif kind == "circle":
            c = (Fraction(center[0]), Fraction(center[1]))
            d = max(Decimal(0), _dec_sqrt((p[0] - c[0]) ** 2 + (p[1] - c[1]) ** 2) - _dec(Fraction(radius)))
        else:
            n = len(V)
            outside = any((V[(k + 1) % n][0] - V[k][0]) * (p[1] - V[k][1]) - (V[(k + 1) % n][1] - V[k][1]) * (p[0] - V[k][0]) < 0
                          for k in range(n))
            d = _dec_sqrt(min(_sq_seg(p, V[k], V[(k + 1) % n]) for k in range(n))) if outside else Decimal(0)
        best = d if best is None else min(best, d)
    return best


def _dec(f: Fraction) -> Decimal:
    return Decimal(f.numerator) / Decimal(f.denominator)


def _dec_sqrt(f: Fraction) -> Decimal:
    return _dec(f).sqrt()


def parts_by_label(scene):
    out = {}
    for kind, label, verts, center, radius in scene.parts():
        out.setdefault(label, []).append((kind, np.asarray(verts).tolist(), center, radius))
    return out


def check_equidistant(gv, scene):
    """Every diagram cell has two adjacent corners p, q labelled a != b with d_a(p) <= d_b(p) and
    d_b(q) <= d_a(q) exactly, so d_a - d_b vanishes on the edge pq: a point equidistant from two
    obstacles lies within one cell diagonal of every point of the cell."""
    parts = parts_by_label(scene)
    x0, y0 = gv.origin
    h = gv.cell_size
    corner_offsets = [(0, 0), (1, 0), (1, 1), (0, 1)]
    for k, (i, j) in enumerate(gv.cells):
        lab = gv.labels[k]
        e = next(e for e in range(4) if lab[e] != lab[(e + 1) % 4])
        a, b = int(lab[e]), int(lab[(e + 1) % 4])
        pts = []
        for t in (e, (e + 1) % 4):
            di, dj = corner_offsets[t]
            pts.append((Fraction(x0 + float(i + di) * h), Fraction(y0 + float(j + dj) * h)))
        p, q = pts
        assert exact_distance(parts[a], p) <= exact_distance(parts[b], p), (k, a, b)
        assert exact_distance(parts[b], q) <= exact_distance(parts[a], q), (k, a, b)


# -- tests ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_random_maps_match_oracle(seed):
    res = [40, 56, 64, 72][seed - 1]
    gv, marked, _ = check_against_oracle(random_mixed(seed, 18, size=5.0), res, workers=(1, 2, 3),
                                         modes=("cooperative", "independent"))
    assert marked > 0


def test_paper_maps_match_oracle():
    for doc, res in ((sea_of_triangles(2), 96), (mixed_shapes(), 96)):
        check_against_oracle(doc, res, workers=(1, 2, 3), modes=("cooperative", "independent"))


def test_convex_polygon_area():
    doc = random_mixed(8, 12, size=5.0)
    doc["area"] = {"polygon": [[50, -5], [105, 25], [105, 75], [50, 105], [-5, 75], [-5, 25]]}
    gv, marked, _ = check_against_oracle(doc, 60, workers=(1, 2, 3), modes=("cooperative", "independent"))
    assert gv.n_labels == gv.n_obstacles + 6


def _random_scene(rng):
    """Random obstacles of every kind, overlapping, crossing the area's boundary, nested in C-shaped
    rings; a random box or convex polygon area."""
    def shape():
        c = rng.uniform(-5, 105, 2)
        k = rng.integers(0, 6)
        if k == 0:
            return {"type": "point", "position": c.tolist()}
        if k == 1:
            return {"type": "circle", "center": c.tolist(), "radius": float(rng.uniform(0.5, 12))}
        if k == 2:
            return {"type": "segment", "vertices": [c.tolist(), (c + rng.uniform(-15, 15, 2)).tolist()]}
        if k == 3:
            m, r, ph = int(rng.integers(3, 8)), rng.uniform(1, 12), rng.uniform(0, 6.3)
            return {"type": "polygon", "vertices": [[float(c[0] + r * np.cos(ph + 2 * np.pi * t / m)),
                                                     float(c[1] + r * np.sin(ph + 2 * np.pi * t / m))] for t in range(m)]}
        if k == 4:  # a C-shaped ring (non-convex), nearly closed
            r, w, gap, a0 = rng.uniform(5, 20), rng.uniform(0.5, 3), rng.uniform(0.02, 0.8), rng.uniform(0, 6.3)
            ang = a0 + gap + (2 * np.pi - 2 * gap) * np.arange(25) / 24
            outer = np.stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang)], 1)
            inner = np.stack([c[0] + (r - w) * np.cos(ang[::-1]), c[1] + (r - w) * np.sin(ang[::-1])], 1)
            return {"type": "polygon", "vertices": np.concatenate([outer, inner]).tolist()}
        return {"type": "union", "parts": [{"type": "circle", "center": c.tolist(), "radius": float(rng.uniform(0.5, 5))},
                                           {"type": "point", "position": (c + rng.uniform(-3, 3, 2)).tolist()}]}
    kind = rng.integers(0, 3)
    if kind == 0:
        area = {"box": [0, 0, 100, float(rng.uniform(30, 100))]}
    elif kind == 1:
        m, ph = int(rng.integers(3, 9)), rng.uniform(0, 6.3)
        area = {"polygon": [[50 + 55 * np.cos(ph + 2 * np.pi * t / m), 50 + 55 * np.sin(ph + 2 * np.pi * t / m)] for t in range(m)]}
    else:
        area = {"box": [0, 0, 100, 100]}
    return {"area": area, "obstacles": [shape() for _ in range(int(rng.integers(1, 30)))]}


def test_every_piece_is_found_on_random_scenes():
    """Exactly the oracle's cells on scenes with disconnected diagrams: overlapping obstacles,
    obstacles outside or across the area's boundary, rings, coarse and fine grids."""
    rng = np.random.default_rng(19)
    several = 0
    for trial in range(40):
        doc = _random_scene(rng)
        res = int(rng.choice([8, 13, 24, 50, 77, 128]))
        _, marked, (scene, labels, mixed) = check_against_oracle(doc, res, workers=(1, 2, 3),
                                                                 modes=("cooperative", "independent"))
        several += oracle_pieces(labels, mixed)[1] > 1
    assert several >= 5  # the scenes do exercise disconnected diagrams


def test_slivers_thinner_than_a_cell_are_found():
    """A point just off a disc has a needle of a region behind it, thinner than a cell: the grid
    corners inside it are surrounded by the disc's label, their four cells joined to nothing."""
    rng = np.random.default_rng(7)
    isolated = 0
    for trial in range(6):
        obstacles = []
        for _ in range(6):
            c, r, a = rng.uniform(20, 80, 2), rng.uniform(3, 10), rng.uniform(0, 2 * np.pi)
            eps = 10 ** rng.uniform(-6, -2)
            obstacles.append({"type": "circle", "center": c.tolist(), "radius": float(r)})
            obstacles.append({"type": "point", "position": (c + (r + eps) * np.array([np.cos(a), np.sin(a)])).tolist()})
        doc = {"area": {"box": [0, 0, 100, 100]}, "obstacles": obstacles}
        res = int(rng.integers(100, 200))
        _, _, (scene, labels, mixed) = check_against_oracle(doc, res, workers=(1, 2, 3), modes=("cooperative", "independent"))
        piece, n = oracle_pieces(labels, mixed)
        isolated += int(sum(np.sum(piece == p) <= 8 for p in range(n)))
    assert isolated >= 5  # tiny pieces (a corner's four cells) exist and were all found


def _ring(x0, y0, x1, y1, t):
    """A closed square ring of wall thickness t: one obstacle (a union of four rectangles)."""
    def rect(a, b, c, d):
        return {"type": "polygon", "vertices": [[a, b], [c, b], [c, d], [a, d]]}
    return {"type": "union", "parts": [rect(x0, y0, x1, y0 + t), rect(x0, y1 - t, x1, y1),
                                       rect(x0, y0, x0 + t, y1), rect(x1 - t, y0, x1, y1)]}


def test_island_inside_a_ring_gives_its_loop():
    """An island fully enclosed by another obstacle's ring: the free region inside the ring touches
    no area corner, and the diagram's loop around the island is found by every build."""
    doc = {"area": {"box": [0, 0, 100, 100]},
           "obstacles": [_ring(20, 25, 80, 75, 3.0), {"type": "circle", "center": [47, 52], "radius": 6},
                         {"type": "point", "position": [10, 90]},
                         _ring(35, 35, 65, 68, 1.5)]}  # a second ring around the island, inside the first
    gv, marked, (scene, labels, mixed) = check_against_oracle(doc, 97, workers=(1, 2, 3), modes=("cooperative", "independent"))
    piece, n = oracle_pieces(labels, mixed)
    grid = (gv.origin[0], gv.origin[1], gv.cell_size, gv.shape[1], gv.shape[0])
    from_corners = corner_pieces(scene, piece, grid)
    assert n >= 3 and len(from_corners) < n  # pieces no area corner reaches
    # the loop between the inner ring (label 3) and the island (label 1) is traced, all the way round
    loop = np.array([set(map(int, row)) == {1, 3} for row in gv.labels])
    xy = gv.centers[loop]
    assert loop.sum() > 40
    assert xy[:, 0].min() < 47 < xy[:, 0].max() and xy[:, 1].min() < 52 < xy[:, 1].max()


def _occupancy_doc(name, size, seed):
    occ = getattr(occupancy_maps, name)(size, seed)
    return occ, dv.obstacles_from_occupancy_grid(occ.astype(np.float64), resolution=0.05, origin=(-3.0, 1.5))


@pytest.mark.parametrize("name", ["building", "warehouse", "cave", "rooms_with_islands"])
def test_occupancy_maps_match_oracle(name):
    """Maps whose border is a wall: the area's corners lie inside it and reach nothing (the paper's
    seeds find 0 cells); the loops around islands are found, exactly the oracle's cells, at
    cells = the map's pixels per side (the pixel grid) and at a coarser grid."""
    total = 0
    for size, seed in ((64, 1), (96, 4)):
        occ, doc = _occupancy_doc(name, size, seed)
        for res in (max(occ.shape), int(max(occ.shape) * 0.7)):
            gv, marked, (scene, labels, mixed) = check_against_oracle(doc, res, workers=(1, 2, 3),
                                                                     modes=("cooperative", "independent"))
            total += marked
            if res == max(occ.shape):
                piece, n = oracle_pieces(labels, mixed)
                grid = (gv.origin[0], gv.origin[1], gv.cell_size, gv.shape[1], gv.shape[0])
                assert not corner_pieces(scene, piece, grid)  # nothing at the area's corners
    if name != "cave":
        assert total > 0


def test_occupancy_map_labels_diagram_is_the_oracle():
    """diagram="labels" on an occupancy array (the route a ROS map takes) is the oracle's diagram in
    pixel units, where the map's exact ties lie, whatever the resolution and origin; clearances and
    blocked cells follow in map units, and a pickle gives the same diagram back."""
    occ = occupancy_maps.rooms_with_islands(80, 3)
    doc = dv.obstacles_from_occupancy_grid(occ.astype(np.float64), 1.0, occupied_thresh=0.5)
    scene, labels, sq, mixed = oracle(doc, max(occ.shape))
    assert mixed.sum() > 0
    ref = dv.grid_voronoi(occ, diagram="labels")
    for res, origin in ((1.0, (0.0, 0.0)), (0.05, (0.0, 0.0)), (0.1, (-12.3, 4.1)), (0.3, (1e4, -7.7))):
        gv = dv.grid_voronoi(occ, resolution=res, origin=origin, diagram="labels", workers=2, robot_radius=2.5 * res)
        assert np.array_equal(gv.diagram_mask, mixed), res
        assert np.array_equal(gv.labels, ref.labels) and np.array_equal(gv.vertices, ref.vertices)
        assert gv.origin == pytest.approx(origin) and gv.cell_size == pytest.approx(res)
        np.testing.assert_allclose(gv.clearance, res * ref.clearance, rtol=1e-12)
        assert np.array_equal(gv.blocked, gv.clearance <= 2.5 * res) and 0 < gv.blocked.sum() < len(gv.blocked)
        np.testing.assert_allclose(gv.centers, np.asarray(origin) + res * ref.centers, rtol=1e-12, atol=1e-9)
        back = pickle.loads(pickle.dumps(gv))
        assert np.array_equal(back.labels, gv.labels) and np.array_equal(back.clearance, gv.clearance)
        assert back.origin == gv.origin and back.to_json() != "" and np.array_equal(back.blocked, gv.blocked)


@pytest.mark.parametrize("doc_name", ["random", "sea", "mixed"])
def test_diagram_cells_are_near_equidistant_points_exactly(doc_name):
    doc = {"random": random_mixed(5, 15, size=5.0), "sea": sea_of_triangles(4, per_side=5), "mixed": mixed_shapes()}[doc_name]
    gv = dv.grid_voronoi(doc, cells=48)
    check_equidistant(gv, dv.gvd.load_obstacles(doc))


def test_corner_labels_are_exact_nearest_obstacles_on_a_sample():
    doc = mixed_shapes()
    scene = dv.gvd.load_obstacles(doc)
    parts = parts_by_label(scene)
    labels = _core._gvd_brute_force(scene, 40)[0]
    rng = np.random.default_rng(3)
    x0, y0, h = 0.0, 0.0, 100.0 / 40
    for j, i in zip(rng.integers(0, 41, 60), rng.integers(0, 41, 60)):
        p = (Fraction(x0 + float(i) * h), Fraction(y0 + float(j) * h))
        d = {lab: exact_distance(pl, p) for lab, pl in parts.items()}
        best = min(d.values())
        assert d[int(labels[j, i])] == best
        assert int(labels[j, i]) == min(lab for lab, v in d.items() if v == best)  # ties: lower label


@pytest.mark.parametrize("mode", ["cooperative", "independent"])
def test_threads_give_the_single_worker_diagram(mode):
    for doc, res in ((sea_of_triangles(5), 120), (random_mixed(6, 25), 100)):
        one = dv.grid_voronoi(doc, cells=res)
        for k in (2, 3, 4, 6):
            many = dv.grid_voronoi(doc, cells=res, workers=k, mode=mode)
            assert np.array_equal(many.cells, one.cells)
            assert np.array_equal(many.labels, one.labels)
            assert np.array_equal(many.clearance, one.clearance)
            assert many.stats["workers"] == k
            # every traced cell is either kept or discarded by the join
            assert many.stats["traced_cells"] - many.stats["discarded_cells"] == len(many.cells)
        assert one.stats["traced_cells"] == len(one.cells) and one.stats["discarded_cells"] == 0
        if mode == "independent":
            assert many.stats["border_lines_scanned"] == 2 * (6 - 1)
        else:
            assert many.stats["border_lines_scanned"] == 6 - 1


def _mpi_exe():
    env = os.environ.get("DVORONOI_GVD_MPI")
    if env:  # tools/test.sh sets it; MPI is optional, so a missing build skips
        return env if Path(env).is_file() else None
    for c in [ROOT / "build" / "cpp" / "mpi" / "dvoronoi_gvd_mpi", *sorted(ROOT.glob("build*/cpp/mpi/dvoronoi_gvd_mpi"))]:
        if c.is_file():
            return str(c)
    return shutil.which("dvoronoi_gvd_mpi")


@pytest.mark.skipif(_mpi_exe() is None or shutil.which("mpirun") is None,
                    reason="dvoronoi_gvd_mpi or mpirun not found (cmake --build build --target dvoronoi_gvd_mpi)")
def test_mpi_ranks_give_the_single_worker_diagram(tmp_path):
    doc = random_mixed(7, 30)
    path = tmp_path / "map.json"
    path.write_text(json.dumps(doc))
    one = json.loads(dv.grid_voronoi(doc, cells=96, robot_radius=1.0).to_json())
    flags = ["--oversubscribe"] + (["--allow-run-as-root"] if hasattr(os, "geteuid") and os.geteuid() == 0 else [])
    for k in (1, 2, 3, 4):
        for mode in ("cooperative", "independent"):
            out = tmp_path / f"out{k}{mode}.json"
            env = dict(os.environ)
            if not (shutil.which("ssh") or shutil.which("rsh")):
                env.setdefault("OMPI_MCA_plm_rsh_agent", "sh")  # Open MPI 4 needs an rsh agent even for local ranks
            proc = subprocess.run(["mpirun", *flags, "-n", str(k), _mpi_exe(), str(path), "--grid", "96", "--mode", mode,
                                   "--robot-radius", "1", "-o", str(out)], capture_output=True, text=True, timeout=120, env=env)
            assert proc.returncode == 0, proc.stderr
            got = json.loads(out.read_text())
            assert got["cells"] == one["cells"], (k, mode)
            assert got["roadmap"] == one["roadmap"]
            assert got["stats"]["workers"] == k
            assert got["stats"]["traced_cells"] - got["stats"]["discarded_cells"] == len(got["cells"]["col"])


def test_visibility_test_gives_the_same_diagram_with_fewer_edge_distances():
    doc = sea_of_triangles(6)
    a = dv.grid_voronoi(doc, cells=128, visibility=True)
    b = dv.grid_voronoi(doc, cells=128, visibility=False)
    assert np.array_equal(a.cells, b.cells) and np.array_equal(a.labels, b.labels)
    assert a.stats["edge_evaluations"] < b.stats["edge_evaluations"]


def test_sparse_labelling():
    gv = dv.grid_voronoi(mixed_shapes(), cells=512)
    assert gv.stats["corners_labelled"] < 0.05 * 513 * 513  # only corners near the diagram
    assert gv.stats["corners_labelled"] >= len(gv.cells)


def test_blocked_clearance_vertices_roadmap():
    gv = dv.grid_voronoi(mixed_shapes(), cells=100, robot_radius=3.0)
    assert np.array_equal(gv.blocked, gv.clearance <= 3.0)
    assert 0 < gv.blocked.sum() < len(gv.cells)
    assert gv.blocked_mask.sum() == gv.blocked.sum() and gv.diagram_mask.sum() == len(gv.cells)
    cm = gv.clearance_map
    assert np.array_equal(np.isnan(cm), ~gv.diagram_mask)
    # vertices: cells with >= 3 distinct corner labels
    distinct = np.array([len(set(r)) for r in gv.labels.tolist()])
    assert np.array_equal(np.flatnonzero(distinct >= 3), gv.vertices)
    assert len(gv.vertices) >= 8
    # roadmap: every cell is a node or interior to exactly one edge; lengths are steps of one cell
    G = gv.roadmap
    cover = [d["cell"] for _, d in G.nodes(data=True)]
    for _, _, d in G.edges(data=True):
        cover += list(d["cells"])
        assert d["length"] == pytest.approx((len(d["cells"]) + 1) * gv.cell_size)
        cl = [gv.clearance[c] for c in d["cells"]]
        assert d["min_clearance"] <= min(cl, default=np.inf)
    assert sorted(cover) == list(range(len(gv.cells)))
    assert {d["kind"] for _, d in G.nodes(data=True)} <= {"vertex", "end", "junction"}
    # the area corners (where two area edges meet) are ends of the roadmap
    ends = {tuple(gv.cells[d["cell"]]) for _, d in G.nodes(data=True) if d["kind"] == "end"}
    assert {(0, 0), (99, 0), (99, 99), (0, 99)} <= ends
    csr = gv.roadmap_csr()
    assert csr.shape == (G.number_of_nodes(),) * 2 and (csr != csr.T).nnz == 0
    # obstacle relation: neighbours share a diagram cell
    assert 1 in gv.neighbors(0) or len(gv.neighbors(0)) > 0
    assert all(0 in gv.neighbors(j) for j in gv.neighbors(0))


def _segment_clearance(doc, a, b):
    """Smallest distance from segment ab to the obstacles (shapely; circles exactly)."""
    import shapely

    seg = shapely.LineString([a, b])
    best = np.inf
    for o in doc["obstacles"]:
        for s in o.get("parts", [o]):
            if s["type"] == "circle":
                c = np.asarray(s["center"])
                pa, pb = np.asarray(a), np.asarray(b)
                t = np.clip(np.dot(c - pa, pb - pa) / max(np.dot(pb - pa, pb - pa), 1e-300), 0, 1)
                best = min(best, max(0.0, np.linalg.norm(pa + t * (pb - pa) - c) - s["radius"]))
            elif s["type"] == "point":
                best = min(best, seg.distance(shapely.Point(s["position"])))
            elif s["type"] == "segment":
                best = min(best, seg.distance(shapely.LineString(s["vertices"])))
            else:
                best = min(best, seg.distance(shapely.Polygon(s["vertices"])))
    x0, y0, x1, y1 = doc["area"]["box"]
    for p in (a, b):
        best = min(best, p[0] - x0, x1 - p[0], p[1] - y0, y1 - p[1])
    return best


@pytest.mark.parametrize("radius", [0.0, 1.0, 2.5])
def test_paths_are_collision_free(radius):
    doc = mixed_shapes()
    gv = dv.grid_voronoi(doc, cells=128, robot_radius=radius)
    rng = np.random.default_rng(int(radius * 10))
    found = 0
    for _ in range(12):
        s, g = rng.uniform(3, 97, 2), rng.uniform(3, 97, 2)
        try:
            p = gv.path(s, g)
        except ValueError as e:
            assert "blocked" in str(e)
            continue
        if len(p) == 0:
            continue
        found += 1
        assert np.array_equal(p[0], s) and np.array_equal(p[-1], g)
        for a, b in zip(p[:-1], p[1:]):
            assert _segment_clearance(doc, a, b) > radius
        assert gv.path_length(s, g) == pytest.approx(np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)))
    assert found >= 4


def test_path_errors_and_no_route():
    doc = mixed_shapes()
    gv = dv.grid_voronoi(doc, cells=128, robot_radius=1.5)
    with pytest.raises(ValueError, match="start .* is blocked"):
        gv.path((45.0, 40.5), (95, 95))  # 0.5 from a point obstacle
    with pytest.raises(ValueError, match="goal .* is blocked"):
        gv.path((5, 5), (70, 72))  # inside a circle
    with pytest.raises(ValueError, match="start .* outside the working area"):
        gv.path((-1, 5), (95, 95))
    # a wall with a gap of width 2: a robot of radius 0.3 passes (diagram cells in the gap have corner
    # clearance 0.5 at h = 0.5), one of radius 1.5 does not
    wall = {"area": {"box": [0, 0, 100, 100]}, "obstacles": [
        {"type": "polygon", "vertices": [[48, 0], [52, 0], [52, 49], [48, 49]]},
        {"type": "polygon", "vertices": [[48, 51], [52, 51], [52, 100], [48, 100]]}]}
    thin = dv.grid_voronoi(wall, cells=200, robot_radius=0.3)
    p = thin.path((20, 50), (80, 50))
    assert len(p) > 2
    for a, b in zip(p[:-1], p[1:]):
        assert _segment_clearance(wall, a, b) > 0.3
    thick = dv.grid_voronoi(wall, cells=200, robot_radius=1.5)
    assert thick.path((20, 50), (80, 50)).shape == (0, 2)
    assert thick.path_length((20, 50), (80, 50)) == np.inf


@pytest.mark.parametrize("doc, message", [
    ({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "circle", "center": [1, 1], "radius": -1}]},
     r"obstacles\[0\]\.radius: must be a positive finite number, got -1"),
    ({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [1, 1]}, {"type": "circle", "center": [1], "radius": 1}]},
     r"obstacles\[1\]\.center: expected a point \[x, y\]"),
    ({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "polygon", "vertices": [[0, 0], [2, 2], [2, 0], [0, 2]]}]},
     r"obstacles\[0\]\.vertices: polygon is not simple"),
    ({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "circle", "center": [1, 1], "raduis": 1}]},
     r"obstacles\[0\]: unknown field 'raduis'"),
    ({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "blob"}]}, r"obstacles\[0\]\.type: unknown obstacle type 'blob'"),
    ({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "union", "parts": [{"type": "point", "position": [1, "x"]}]}]},
     r"obstacles\[0\]\.parts\[0\]\.position\[1\]: expected a number"),
    ({"area": {"polygon": [[0, 0], [10, 0], [5, 2], [10, 10], [0, 10]]}, "obstacles": []}, r"area: the working area must be a convex polygon"),
    ({"obstacles": []}, r"area: required"),
    ({"area": {"box": [0, 0, 100, 100]}, "obstacles": [{"type": "polygon", "vertices": [[50, 90], [73, 20], [13, 63], [87, 63], [27, 20]]}]},
     r"obstacles\[0\]\.vertices: polygon is not simple"),  # a pentagram: left turns only, two windings
    ({"area": {"box": [0, 0, 16, 16]}, "obstacles": [{"type": "polygon", "vertices": [[2, 2], [6, 2], [6, 6], [12, 6], [6, 6], [2, 6]]}]},
     r"obstacles\[0\]\.vertices: the polygon turns back on itself at vertex 3 \(its edges overlap\)"),
])
def test_bad_obstacles_name_index_and_field(doc, message):
    with pytest.raises(ValueError, match=message):
        dv.grid_voronoi(doc, cells=16)


@pytest.mark.parametrize("shift", [0.0, 5000000264.0, 10395970331.0])
def test_polygons_far_from_the_origin_keep_their_shape(shift):
    # the ring's orientation was a shoelace sum in doubles: at these shifts a triangle vanished (no
    # label 0 anywhere, an empty raster) and a notched square became its notch
    def doc(ring, at):
        return {"area": {"box": [at - 16, at - 16, at + 16, at + 16]},
                "obstacles": [{"type": "polygon", "vertices": [[at + x, at + y] for x, y in ring]}]}
    triangle, notched = [(3, 2), (7, 2), (3, 6)], [(-5, 2), (-3, 2), (-3, 4), (-4, 3), (-5, 4)]
    for ring, area in ((triangle, 8.0), (notched, 3.0)):
        parts = [p[2] - shift for p in dv.gvd.load_obstacles(doc(ring, shift)).parts() if p[1] == 0]
        shoelace = sum(0.5 * (np.roll(v[:, 0], -1) * v[:, 1] - v[:, 0] * np.roll(v[:, 1], -1)).sum() for v in parts)
        assert abs(shoelace) == area  # small integers after the exact shift: exact
        assert 0 in dv.grid_voronoi(doc(ring, shift), cells=32, workers=1).labels
    medial = dv.grid_voronoi(doc(triangle, shift), cells=32, diagram="medial", workers=1)
    at_origin = dv.grid_voronoi(doc(triangle, 0.0), cells=32, diagram="medial", workers=1)
    assert at_origin.grid.occupied.sum() == 26 and np.array_equal(medial.grid.occupied, at_origin.grid.occupied)


def test_closed_rings_keep_every_corner():
    # Issue 20: a ring closed by repeating its first vertex (as GeoJSON writes it) lost that corner,
    # in obstacles and in the working area; a repeated vertex elsewhere dropped both copies.
    square = [[40, 40], [60, 40], [60, 60], [40, 60]]
    box = [[0, 0], [100, 0], [100, 100], [0, 100]]
    others = [{"type": "circle", "center": [80, 20], "radius": 5}, {"type": "point", "position": [15, 80]}]

    def doc(ring, area):
        return {"area": {"polygon": area}, "obstacles": [{"type": "polygon", "vertices": ring}] + others}

    plain = dv.gvd.load_obstacles(doc(square, box))
    variants = {
        "closed": (square + square[:1], box),
        "closed area": (square, box + box[:1]),
        "closed, reversed": ((square + square[:1])[::-1], box + box[:1]),
        "repeats": ([square[0], square[0], square[1], square[2], square[2], square[3]], box),
        "repeated area corners": (square, [box[0], box[1], box[1], box[2], box[3], box[3], box[0]]),
    }

    def first_lowest(v):  # the same ring from its lexicographically lowest vertex
        return np.roll(v, -min(range(len(v)), key=lambda k: tuple(v[k])), axis=0) if len(v) else v

    def same_parts(a, b):
        pa, pb = a.parts(), b.parts()
        assert len(pa) == len(pb)
        for x, y in zip(pa, pb):
            assert x[0] == y[0] and x[1] == y[1] and np.array_equal(first_lowest(x[2]), first_lowest(y[2]))

    want = dv.grid_voronoi(plain, cells=80)
    for name, (ring, area) in variants.items():
        scene = dv.gvd.load_obstacles(doc(ring, area))
        assert scene.n_labels == plain.n_labels == 3 + 4, name
        polygon = [p for p in scene.parts() if p[1] == 0]
        assert len(polygon) == 1 and polygon[0][0] == "polygon" and len(polygon[0][2]) == 4, name
        same_parts(scene, plain)
        # Just outside each corner of the square, the square is sqrt(2) away.
        for c in square:
            q = (c[0] + (c[0] - 50) / 10, c[1] + (c[1] - 50) / 10)
            assert scene.nearest(q) == (0, pytest.approx(2.0)), (name, c)
        got = dv.grid_voronoi(doc(ring, area), cells=80)
        assert np.array_equal(got.cells, want.cells) and np.array_equal(got.labels, want.labels), name
    # Still too few distinct vertices.
    with pytest.raises(ValueError, match=r"obstacles\[0\]\.vertices: a polygon needs at least three vertices that are not collinear"):
        dv.gvd.load_obstacles(doc([[1, 1], [1, 1], [2, 2], [2, 2], [1, 1]], box))


def test_python_documents_equal_their_json_text():
    # Documents of Python objects (numpy arrays and scalars, tuples) are read without a JSON text round
    # trip: the scene must be the one parsed from the text json.dumps writes.
    doc = mixed_shapes()
    text = dv.grid_voronoi(json.loads(json.dumps(doc)), cells=64)
    numpyish = {"area": {"box": np.array(doc["area"]["box"], dtype=np.float64)},
                "obstacles": [{k: (np.asarray(v) if k in ("vertices", "center", "position") else
                                   np.float64(v) if k == "radius" else v) for k, v in o.items()}
                              for o in doc["obstacles"]]}
    a = dv.grid_voronoi(numpyish, cells=64)
    assert np.array_equal(a.cells, text.cells) and np.array_equal(a.labels, text.labels)
    with pytest.raises(TypeError, match=r"obstacles\[0\]\.position\[1\]: object of type object is not JSON serialisable"):
        dv.grid_voronoi({"area": {"box": [0, 0, 1, 1]}, "obstacles": [{"type": "point", "position": [0.5, object()]}]},
                        cells=16)
    with pytest.raises(ValueError, match=r"obstacles\[0\]\.position\[0\]: must be finite"):
        dv.grid_voronoi({"area": {"box": [0, 0, 1, 1]}, "obstacles": [{"type": "point", "position": [float("nan"), 0.5]}]},
                        cells=16)


def test_bad_arguments_and_files(tmp_path):
    doc = mixed_shapes()
    with pytest.raises(ValueError, match="cells"):
        dv.grid_voronoi(doc, cells=0)
    with pytest.raises(ValueError, match="workers"):
        dv.grid_voronoi(doc, cells=16, workers=0)
    with pytest.raises(ValueError, match="robot_radius"):
        dv.grid_voronoi(doc, cells=16, robot_radius=-1)
    with pytest.raises(ValueError, match="mode"):
        dv.grid_voronoi(doc, cells=16, mode="greedy")
    bad = tmp_path / "bad.json"
    bad.write_text('{"area": {"box": [0, 0, 1, 1]},\n "obstacles": [,]}')
    with pytest.raises(ValueError, match=r"bad.json:2:16: invalid JSON"):
        dv.grid_voronoi(bad, cells=16)


@pytest.mark.parametrize("text, message", [
    # A key twice in one object: the parser kept the last one silently.
    ('{"area": {"box": [0, 0, 1, 1]},\n "obstacles": [{"type": "circle", "center": [0.5, 0.5],\n'
     '  "radius": 0.1, "radius": 0.2}]}',
     r"^m\.json:3:18: duplicate key 'radius' in one object \(first at m\.json:3:3\); a key may appear once$"),
    ('{"area": {"box": [0, 0, 1, 1]}, "obstacles": [], "area": {"box": [0, 0, 2, 2]}}',
     r"^m\.json:1:50: duplicate key 'area'"),
    # The same key, once escaped.
    ('{"area": {"box": [0, 0, 1, 1]}, "obstacles": [{"type": "point", "pos\\u0069tion": [0.5, 0.5], '
     '"position": [0.2, 0.2]}]}', r"^m\.json:1:94: duplicate key 'position' in one object \(first at m\.json:1:65\)"),
    # 1e999 was read as inf ("must be finite", no place).
    ('{"area": {"box": [0, 0, 1, 1]},\n "obstacles": [{"type": "circle", "center": [0.5, 0.5], "radius": 1e999}]}',
     r"^m\.json:2:67: number '1e999' is beyond the range of a double"),
    # A NUL byte cut the message short: quoted text is escaped.
    ('{"area": {"box": [0, 0, 1, 1]}, "obstacles": [{"type": "circ\\u0000le", "center": [0.5, 0.5]}]}',
     r"^m\.json: obstacles\[0\]\.type: unknown obstacle type 'circ\\0le' \(expected"),
])
def test_json_file_errors_name_the_place(tmp_path, monkeypatch, text, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "m.json").write_text(text)
    with pytest.raises(ValueError, match=message):
        dv.grid_voronoi("m.json", cells=16)
    with pytest.raises(ValueError, match=message):
        dv.grid_voronoi("m.json", cells=16, area=(0, 0, 1, 1))  # checked with an area argument too


def test_json_file_and_area_argument(tmp_path):
    doc = mixed_shapes()
    f = tmp_path / "m.json"
    f.write_text(json.dumps(doc))
    a = dv.grid_voronoi(f, cells=64)
    b = dv.grid_voronoi(doc["obstacles"], area=(0, 0, 100, 100), cells=64)
    assert np.array_equal(a.cells, b.cells)
    out = json.loads(a.to_json())
    assert out["kind"] == "grid_voronoi" and out["cells"]["col"] == a.cells[:, 0].tolist()


def test_occupancy_grid_pgm_yaml(tmp_path):
    img = np.full((60, 80), 254, np.uint8)  # free
    img[10:20, 10:30] = 0                    # region 1 (rows from the top)
    img[15:40, 25:30] = 0                    # joined to region 1: one L-shaped obstacle
    img[45:55, 60:70] = 0                    # region 2
    img[5, 70] = 0                           # region 3, one pixel
    pgm = tmp_path / "map.pgm"
    pgm.write_bytes(b"P5\n# test\n80 60\n255\n" + img.tobytes())
    (tmp_path / "map.yaml").write_text("image: map.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
    doc = dv.obstacles_from_occupancy_grid(tmp_path / "map.yaml")
    assert len(doc["obstacles"]) == 3
    assert doc["area"]["box"] == pytest.approx([-1.0, -2.0, -1.0 + 80 * 0.05, -2.0 + 60 * 0.05])
    gv = dv.grid_voronoi(doc, cells=160)
    scene = dv.gvd.load_obstacles(doc)
    labels = _core._gvd_brute_force(scene, 160)[0]
    # a corner at the center of an occupied pixel carries its region's label
    # regions are numbered in scan order of the image (top row first): the pixel at row 5 comes first
    for (r, c), region in (((12, 12), 1), ((30, 27), 1), ((50, 65), 2), ((5, 70), 0)):
        x, y = -1.0 + (c + 0.5) * 0.05, -2.0 + (60 - r - 0.5) * 0.05
        assert scene.nearest((x, y)) == (region, 0.0)
    assert len(gv.cells) > 0 and set(np.unique(gv.labels)) >= {0, 1, 2}
    # PNG read through matplotlib gives the same obstacles
    import matplotlib.image as mpimg
    mpimg.imsave(tmp_path / "map.png", img, cmap="gray", vmin=0, vmax=255)
    doc2 = dv.obstacles_from_occupancy_grid(tmp_path / "map.png", resolution=0.05, origin=(-1.0, -2.0))
    assert doc2 == doc


def test_plot_and_svg(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    gv = dv.grid_voronoi(mixed_shapes(), cells=64, robot_radius=2)
    route = gv.path((5, 5), (95, 95))
    ax = gv.plot(path=route)
    gids = {a.get_gid() for a in ax.get_children()}
    assert {"dvoronoi-gvd-cells", "dvoronoi-gvd-vertices", "dvoronoi-gvd-path"} <= gids
    svg = gv.to_svg(route=route)
    assert svg.startswith("<svg") and "polyline" in svg and svg.count("<rect") > 5
