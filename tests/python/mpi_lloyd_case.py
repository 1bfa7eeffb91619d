"""Run by tests/python/test_mpi.py under `mpirun -n K`: the MPI driver on fixed random swarms, results
saved by rank 0 for the test to compare with the single-process API."""
import sys

import numpy as np
from mpi4py import MPI

import dvoronoi.mpi as dm


def gaussian(x, y):
    return np.exp(-((x - 0.3) ** 2 + (y - 0.6) ** 2) / (2 * 0.1 ** 2)) + 0.2


CASES = {
    "box": dict(seed=1, n=900, radius=0.04, steps=12, gain=1.0, bounds=(0, 0, 1, 1)),
    "polygon": dict(seed=2, n=700, radius=0.05, steps=10, gain=0.6,
                    bounds=[(0.0, 0.0), (1.0, 0.1), (0.9, 1.0), (0.1, 0.8)]),
    "plane": dict(seed=3, n=600, radius=0.06, steps=8, gain=0.8, bounds=None),
    "density": dict(seed=4, n=500, radius=0.05, steps=6, gain=1.0, bounds=(0, 0, 1, 1), density=gaussian),
    # Heterogeneous teams: one radius per agent (halo R_j + R̄).
    "team": dict(seed=6, n=700, radii=(0.02, 0.09), steps=8, gain=0.9, bounds=(0, 0, 1, 1)),
    "team_plane": dict(seed=7, n=500, radii=(0.03, 0.12), steps=6, gain=1.0, bounds=None),
}


def points_of(case):
    rng = np.random.default_rng(case["seed"])
    pts = rng.uniform(0.0, 1.0, (case["n"], 2))
    if case["bounds"] is not None and not isinstance(case["bounds"], tuple):
        from dvoronoi import _core
        from dvoronoi.coverage import as_bounds

        pts = pts[_core.bounds_contains(as_bounds(case["bounds"]), pts)]
    return pts


def radius_of(case, n):
    """The case's radius, or one radius per agent drawn from its range."""
    if "radii" not in case:
        return case["radius"]
    lo, hi = case["radii"]
    return np.random.default_rng(case["seed"] + 100).uniform(lo, hi, n)


def main(out):
    comm = MPI.COMM_WORLD
    saved = {}
    for name, case in CASES.items():
        pts = points_of(case)
        res = dm.lloyd(pts if comm.rank == 0 else None, radius_of(case, len(pts)), steps=case["steps"],
                       gain=case["gain"], bounds=case["bounds"], density=case.get("density"), workers=1)
        if comm.rank == 0:
            saved[name + "/trajectory"] = res["trajectory"]
            saved[name + "/cost"] = res["cost"]
            for k in ("piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span", "indptr",
                      "indices", "areas", "centroids", "radii"):
                saved[name + "/" + k] = getattr(res["cells"], k)
            saved[name + "/halo_bytes"] = np.array(res["stats"]["halo_bytes_per_step"])
    # One partition (no steps) across ranks: dv.mpi.cells.
    pts = np.random.default_rng(5).uniform(0, 3, (1500, 2))
    cells = dm.cells(pts if comm.rank == 0 else None, 0.08, workers=1)
    if comm.rank == 0:
        for k in ("piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span", "indptr",
                  "indices", "areas", "centroids", "radii"):
            saved["cells/" + k] = getattr(cells, k)
    team_radii = np.random.default_rng(6).uniform(0.03, 0.15, len(pts))
    team_cells = dm.cells(pts if comm.rank == 0 else None, team_radii if comm.rank == 0 else None, workers=1)
    if comm.rank == 0:
        for k in ("piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span", "indptr",
                  "indices", "areas", "centroids", "radii"):
            saved["team_cells/" + k] = getattr(team_cells, k)
    # Bad input on root is raised on every rank (no rank hangs).
    try:
        dm.lloyd(np.array([[0.5, 0.5], [2.0, 0.5]]) if comm.rank == 0 else None, 0.1, steps=1,
                 bounds=(0, 0, 1, 1))
    except ValueError as e:
        if comm.rank == 0:
            saved["error"] = np.array(str(e))
    # Coinciding agents (found by whichever rank owns them) stop every rank with an error.
    dup = np.random.default_rng(9).uniform(0, 1, (300, 2))
    dup[250] = dup[17]
    try:
        dm.lloyd(dup if comm.rank == 0 else None, 0.05, steps=2, bounds=(0, 0, 1, 1))
    except ValueError as e:
        saved[f"dup_error_{comm.rank}"] = np.array(str(e))
    counts = comm.gather(sum(k.startswith("dup_error") for k in saved), root=0)
    if comm.rank == 0:
        saved["dup_error_ranks"] = np.array(sum(counts))
        np.savez(out, **saved)


if __name__ == "__main__":
    main(sys.argv[1])
