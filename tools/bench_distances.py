#!/usr/bin/env python3
"""Voronoi neighbours from distances only: dvoronoi against what a Python user would otherwise do.

n robots uniform in the unit square, every pair closer than R = sqrt(k / (pi n)) measured (about k
detected robots each, exact distances). Timed side by side, in one run:

1. all robots: ``dv.neighbors_from_distances`` (1 thread, all cores; consistency step included);
2. the alternative per robot: classical MDS (numpy ``eigh`` of the double-centred squared distances of
   the robot and its detected robots) then ``scipy.spatial.Delaunay`` and the robot's vertex
   neighbours — timed on a sample and extrapolated to n (said in the output). MDS needs every pairwise
   distance, which robots up to 2R apart have not measured: we hand it the complete true local matrix,
   which favours the alternative;
3. one robot: ``dv._core.voronoi_neighbors_of(graph, i)`` (one call from Python, table built from the
   graph) against the same MDS + Delaunay for that robot, in microseconds.

The C++ side (no Python overhead, MDS with Eigen + CGAL) is ``build/tools/bench/bench_distances``.
Benchmarks are not tests: nothing fails on a time. The machine may be shared: both sides run in the
same process, and the load average is printed.
"""
from __future__ import annotations

import argparse
import os
import sys
import timeit
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from benchutil import best_of, git_describe  # noqa: E402

import dvoronoi as dv  # noqa: E402


def mds_delaunay(d2: np.ndarray) -> set:
    """Local index set of robot 0's Delaunay neighbours after classical MDS of squared distances."""
    from scipy.spatial import Delaunay

    m = len(d2)
    j = np.eye(m) - 1.0 / m
    w, v = np.linalg.eigh(-0.5 * j @ d2 @ j)
    xy = v[:, -2:] * np.sqrt(np.maximum(w[-2:], 0.0))
    tri = Delaunay(xy)
    ptr, idx = tri.vertex_neighbor_vertices
    return set(idx[ptr[0]:ptr[1]].tolist())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=float, default=1e5)
    ap.add_argument("--k", type=int, default=30)
    ap.add_argument("--sample", type=int, default=300, help="robots timed for the alternative")
    ap.add_argument("--quick", action="store_true", help="n = 1e4, sample 100")
    args = ap.parse_args(argv)
    n = int(1e4 if args.quick else args.n)
    sample_n = 100 if args.quick else args.sample
    rng = np.random.default_rng(1)
    pts = rng.uniform(0.0, 1.0, size=(n, 2))
    radius = float(np.sqrt(args.k / (np.pi * n)))
    e = dv.distances.measure(pts, radius, model="exact")
    graph = dv.distances.as_distance_graph(e)
    print(f"# bench_distances.py ({git_describe()}), load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(f"n = {n}, R = {radius:.4g}, mean detected {e.nnz / n:.1f}")

    t1, res1 = best_of(2, lambda: dv.neighbors_from_distances(graph, workers=1))
    tall, resall = best_of(2, lambda: dv.neighbors_from_distances(graph))
    assert np.array_equal(res1.indices, resall.indices)

    sample = rng.choice(n, size=sample_n, replace=False)
    ptr, idx = np.asarray(graph.indptr), np.asarray(graph.indices)
    local = []
    for i in sample:
        ids = np.concatenate([[i], idx[ptr[i]:ptr[i + 1]]])
        q = pts[ids]
        local.append((ids, ((q[:, None, :] - q[None, :, :]) ** 2).sum(-1)))
    t_alt, answers = best_of(2, lambda: [mds_delaunay(d2) for _, d2 in local])
    per_alt = t_alt / sample_n
    agree = sum(set(ids[list(a)].tolist()) == set(res1.neighbors(i).tolist()) for (ids, _), a, i in zip(local, answers, sample))
    exact = dv.voronoi_cells(pts)  # the exact answer (positions known), outside the timings
    ours_ok = sum(set(res1.neighbors(i).tolist()) == set(exact.neighbors(i).tolist()) for i in sample)
    alt_ok = sum(set(ids[list(a)].tolist()) == set(exact.neighbors(i).tolist()) for (ids, _), a, i in zip(local, answers, sample))

    print("\n| all robots | time | time / dvoronoi 1 thread |")
    print("|---|---|---|")
    print(f"| dv.neighbors_from_distances, 1 thread | {t1:.2f} s | 1 |")
    print(f"| dv.neighbors_from_distances, all cores | {tall:.2f} s | {tall / t1:.2f} |")
    print(f"| MDS (numpy) + scipy Delaunay per robot, extrapolated from {sample_n} | {per_alt * n:.1f} s | {per_alt * n / t1:.1f} |")
    print(f"\nMDS + Delaunay agrees with dvoronoi on {agree} / {sample_n} sampled robots; equal to the exact "
          f"Voronoi neighbours: dvoronoi {ours_ok}, MDS + Delaunay {alt_ok} of {sample_n}")

    i = int(sample[0])
    reps = 2000
    t_one = min(timeit.repeat(lambda: dv._core.voronoi_neighbors_of(graph, i), number=reps, repeat=3)) / reps
    d2 = local[0][1]
    t_one_alt = min(timeit.repeat(lambda: mds_delaunay(d2), number=50, repeat=3)) / 50
    print(f"\none robot ({ptr[i + 1] - ptr[i]} detected): dvoronoi {t_one * 1e6:.1f} us, MDS + Delaunay {t_one_alt * 1e6:.0f} us "
          f"(ratio {t_one_alt / t_one:.0f}x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
