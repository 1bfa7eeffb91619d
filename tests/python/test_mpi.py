"""dv.mpi: `mpirun -n 1/2/3 --oversubscribe` give the single-process API's cells and trajectories bit
for bit (uniform density; a density path to rounding), and the cost to rounding. Runs when mpirun and
mpi4py are present."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv

pytest.importorskip("mpi4py")
MPIRUN = shutil.which("mpirun")
pytestmark = pytest.mark.skipif(MPIRUN is None, reason="no mpirun on the PATH")
HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
import mpi_lloyd_case as case  # noqa: E402

FIELDS = ("piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span", "indptr", "indices",
          "areas", "centroids")


def mpirun(k: int, *args: str, timeout: float = 240) -> subprocess.CompletedProcess:
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1")
    if not (shutil.which("ssh") or shutil.which("rsh")):
        # Open MPI 4 refuses to start without an rsh agent even for local ranks (a container with
        # no ssh client): any existing program will do, it is never called for a local launch.
        env.setdefault("OMPI_MCA_plm_rsh_agent", "sh")
    cmd = [MPIRUN, "-n", str(k), "--oversubscribe"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return subprocess.run(cmd + [sys.executable, *args], capture_output=True, text=True, env=env,
                          timeout=timeout)


@pytest.fixture(scope="module")
def reference():
    out = {}
    for name, c in case.CASES.items():
        run = dv.coverage.lloyd(case.points_of(c), c["radius"], steps=c["steps"], gain=c["gain"],
                                bounds=c["bounds"], density=c.get("density"), progress=False)
        out[name] = run
    return out


@pytest.mark.parametrize("ranks", [1, 2, 3])
def test_mpi_equals_single_process(ranks, reference, tmp_path):
    path = tmp_path / "out.npz"
    proc = mpirun(ranks, str(HERE / "mpi_lloyd_case.py"), str(path))
    assert proc.returncode == 0, proc.stderr[-3000:]
    got = np.load(path)
    for name, run in reference.items():
        exact = case.CASES[name].get("density") is None
        traj = got[name + "/trajectory"]
        assert traj.shape == run.trajectory.shape
        if exact:
            assert np.array_equal(traj, run.trajectory), name
            for k in FIELDS:
                assert np.array_equal(got[name + "/" + k], getattr(run, k)), (name, k)
        else:  # numpy's vectorised exp may round differently by array layout
            np.testing.assert_allclose(traj, run.trajectory, rtol=0, atol=1e-12)
            for k in ("piece_ptr", "piece_neighbor", "indptr", "indices"):
                assert np.array_equal(got[name + "/" + k], getattr(run, k)), (name, k)
        np.testing.assert_allclose(got[name + "/cost"], run.cost, rtol=1e-12)
        if ranks > 1:
            assert float(got[name + "/halo_bytes"]) > 0  # ranks really exchanged halos
    pts = np.random.default_rng(5).uniform(0, 3, (1500, 2))
    single = dv.coverage.LloydStepper(pts, 0.08).cells()
    for k in FIELDS:
        assert np.array_equal(got["cells/" + k], getattr(single, k)), k
    part = dv.limited_cells(pts, 0.08)  # unclipped: the limited partition itself
    assert np.array_equal(got["cells/indptr"], part.indptr)
    assert np.array_equal(got["cells/indices"], part.indices)
    np.testing.assert_allclose(got["cells/areas"], part.areas, rtol=1e-12)
    assert "points[1] lies outside bounds" in str(got["error"])
    assert int(got["dup_error_ranks"]) == ranks  # every rank raised, none hung
    assert "points[17] and points[250] coincide" in str(got["dup_error_0"])


def test_mpi_entry_point(tmp_path):
    out = tmp_path / "run.json"
    proc = mpirun(2, "-m", "dvoronoi.mpi", "--random", "400", "-r", "0.05", "--steps", "3",
                  "--bounds", "0", "0", "1", "1", "-o", str(out))
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "400 agents on 2 ranks, 3 steps" in proc.stdout
    import json

    doc = json.loads(out.read_text())
    assert len(doc["points"]) == 400 and len(doc["cost"]) == 4
    assert all(b <= a * (1 + 1e-12) for a, b in zip(doc["cost"], doc["cost"][1:]))
