"""dv.mpi: `mpirun -n 1/2/3 --oversubscribe` give the single-process API's cells and trajectories bit
for bit (uniform density; a density path to rounding), and the cost to rounding. dvoronoi_gvd_mpi on
map files (MovingAI .map, YAML + PGM) and on obstacle files with --diagram medial writes the JSON and
SVG of `dvoronoi gvd` byte for byte on 1, 2 and 3 ranks, paths included; a bad map exits 2 naming the
file, nothing written. Runs when mpirun and mpi4py are present; the map tests when $DVORONOI_GVD_MPI (or a build*/ tree) and $DVORONOI_CLI are there."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv
from dvoronoi import occupancy_maps

pytest.importorskip("mpi4py")
MPIRUN = shutil.which("mpirun")
pytestmark = pytest.mark.skipif(MPIRUN is None, reason="no mpirun on the PATH")
HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
import mpi_lloyd_case as case  # noqa: E402

FIELDS = ("piece_ptr", "piece_neighbor", "piece_x", "piece_y", "piece_span", "indptr", "indices",
          "areas", "centroids", "radii")


def mpirun(k: int, *args: str, timeout: float = 240, program: str = sys.executable,
           cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1")
    if not (shutil.which("ssh") or shutil.which("rsh")):
        # Open MPI 4 refuses to start without an rsh agent even for local ranks (a container with
        # no ssh client): any existing program will do, it is never called for a local launch.
        env.setdefault("OMPI_MCA_plm_rsh_agent", "sh")
    cmd = [MPIRUN, "-n", str(k), "--oversubscribe"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return subprocess.run(cmd + [program, *args], capture_output=True, text=True, env=env,
                          timeout=timeout, cwd=cwd)


@pytest.fixture(scope="module")
def reference():
    out = {}
    for name, c in case.CASES.items():
        pts = case.points_of(c)
        run = dv.coverage.lloyd(pts, case.radius_of(c, len(pts)), steps=c["steps"], gain=c["gain"],
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
    team = dv.coverage.LloydStepper(pts, np.random.default_rng(6).uniform(0.03, 0.15, len(pts))).cells()
    for k in FIELDS:  # a heterogeneous team's cells across ranks (halo R_j + R̄)
        assert np.array_equal(got["team_cells/" + k], getattr(team, k)), k
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
    doc = json.loads(out.read_text())
    assert len(doc["points"]) == 400 and len(doc["cost"]) == 4
    assert all(b <= a * (1 + 1e-12) for a, b in zip(doc["cost"], doc["cost"][1:]))


@pytest.mark.parametrize("args, message", [
    (["MISSING", "-r", "0.05"], "MISSING: No such file or directory"),
    (["BAD", "-r", "0.05"], "BAD:2: expected 'x y'"),
    (["-r", "0.05"], "give POINTS or --random N"),
    (["--random", "20", "-r", "-1"], "radius must be a positive finite number"),
    (["--random", "20", "-r", "0.1", "-o", "NODIR/x.json"], "-o/--output: the folder of"),
])
def test_mpi_entry_point_errors_end_every_rank(tmp_path, args, message):
    # an input read on rank 0 only: its error used to leave the other ranks waiting for ever
    (tmp_path / "BAD").write_text("0.1 0.2\n0.3 x\n")
    args = [str(tmp_path / a) if a in ("MISSING", "BAD", "NODIR/x.json") else a for a in args]
    proc = mpirun(2, "-m", "dvoronoi.mpi", *args, "--steps", "1", timeout=60)
    assert proc.returncode == 2, proc.stderr[-3000:]
    assert proc.stderr.count("python -m dvoronoi.mpi: error: ") == 1 and message in proc.stderr, proc.stderr[-3000:]
    assert "Traceback" not in proc.stderr and not (tmp_path / "NODIR").exists()


# -- dvoronoi_gvd_mpi on occupancy maps: the CLI's bytes for any rank count ---------------------------

ROOT = HERE.parents[1]


def _gvd_mpi_exe():
    env = os.environ.get("DVORONOI_GVD_MPI")
    if env:  # MPI is optional: a missing build skips
        return env if Path(env).is_file() else None
    for c in [ROOT / "build" / "cpp" / "mpi" / "dvoronoi_gvd_mpi", *sorted(ROOT.glob("build*/cpp/mpi/dvoronoi_gvd_mpi"))]:
        if c.is_file():
            return str(c)
    return shutil.which("dvoronoi_gvd_mpi")


GVD_MPI = _gvd_mpi_exe()
CLI = os.environ.get("DVORONOI_CLI")
needs_gvd = pytest.mark.skipif(GVD_MPI is None or not CLI or not Path(CLI).is_file(),
                               reason="dvoronoi_gvd_mpi or $DVORONOI_CLI not found")


def _write_movingai(path: Path, occ: np.ndarray) -> Path:
    rows = ["".join("@" if v else "." for v in row) for row in occ]
    path.write_text(f"type octile\nheight {occ.shape[0]}\nwidth {occ.shape[1]}\nmap\n" + "\n".join(rows) + "\n")
    return path


def _write_ros(folder: Path, occ: np.ndarray) -> Path:
    """map_server's files: grey 0 occupied, 254 free, 205 unknown (a block of unknown pixels)."""
    grey = np.where(occ, 0, 254).astype(np.uint8)
    grey[10:16, 20:40] = 205
    H, W = occ.shape
    (folder / "floor.pgm").write_bytes(f"P5\n{W} {H}\n255\n".encode() + grey.tobytes())
    (folder / "floor.yaml").write_text("image: floor.pgm\nresolution: 0.05\norigin: [-2.5, 1.25, 0.0]\n"
                                    "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return folder / "floor.yaml"


# map, options: defaults and non-default ones for each option of the map route
MAPS = {
    "building": ([], ["-r", "0.5"]),
    "rooms": (["--resolution", "0.5", "--origin", "10", "-4", "-r", "1"], ["--min-separation", "2", "--prune-length", "12"]),
    "ros": (["--unknown", "free", "-r", "0.1"], ["--prune-length", "5"]),
}


@pytest.fixture(scope="module")
def map_files(tmp_path_factory):
    d = tmp_path_factory.mktemp("maps")
    return {"building": _write_movingai(d / "building.map", occupancy_maps.building(96, 1)),
            "rooms": _write_movingai(d / "rooms.map", occupancy_maps.rooms_with_islands((90, 130), 2)),
            "ros": _write_ros(d, occupancy_maps.building((80, 110), 4))}


@needs_gvd
@pytest.mark.parametrize("name", sorted(MAPS))
def test_gvd_mpi_map_equals_cli_bytes(name, map_files, tmp_path):
    path = map_files[name]
    for opts in MAPS[name]:
        ref_json, ref_svg = tmp_path / "cli.json", tmp_path / "cli.svg"
        subprocess.run([CLI, "gvd", str(path), *opts, "-o", str(ref_json), "--svg", str(ref_svg), "-q"], check=True)
        ref = ref_json.read_bytes()
        assert len(json.loads(ref)["pixels"]["row"]) > 50  # a real diagram
        for k in (1, 2, 3):
            out, svg = tmp_path / f"mpi{k}.json", tmp_path / f"mpi{k}.svg"
            proc = mpirun(k, str(path), *opts, "-o", str(out), "--svg", str(svg), program=GVD_MPI, timeout=120)
            assert proc.returncode == 0, proc.stderr[-3000:]
            assert f"{k} ranks" in proc.stderr
            if name == "ros":
                assert "120 unknown pixels" in proc.stderr
            assert out.read_bytes() == ref, (name, opts, k)
            assert svg.read_bytes() == ref_svg.read_bytes(), (name, opts, k)
        # stdout as the CLI's stdout
        proc = mpirun(2, str(path), *opts, program=GVD_MPI, timeout=120)
        assert proc.returncode == 0 and proc.stdout.encode() == ref


@needs_gvd
def test_gvd_mpi_more_ranks_than_rows(tmp_path):
    path = _write_movingai(tmp_path / "thin.map", np.array([[0, 0, 0, 0, 0, 0, 0], [0, 0, 0, 1, 0, 0, 0]], bool))
    ref = subprocess.run([CLI, "gvd", str(path), "-q"], check=True, capture_output=True).stdout
    proc = mpirun(3, str(path), program=GVD_MPI, timeout=120)  # rank 0's band is empty
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert proc.stdout.encode() == ref


@needs_gvd
def test_gvd_mpi_explains_an_empty_diagram(tmp_path):
    slit = _write_movingai(tmp_path / "slit.map", np.zeros((1, 50), bool))  # 1 px wide: no diagram
    full = _write_movingai(tmp_path / "full.map", np.ones((3, 5), bool))
    for path, why in ((slit, "under 2 pixels wide"), (full, "every pixel of the 3 x 5 map is occupied")):
        for k in (1, 2):
            proc = mpirun(k, str(path), "-o", str(tmp_path / "out.json"), program=GVD_MPI, timeout=120)
            assert proc.returncode == 0, proc.stderr[-3000:]
            assert proc.stderr.count("dvoronoi_gvd_mpi: warning: no diagram pixel") == 1 and why in proc.stderr


@needs_gvd
def test_gvd_mpi_refuses_options_its_input_does_not_read(tmp_path):
    doc = tmp_path / "doc.json"
    doc.write_text(json.dumps({"area": {"box": [0, 0, 10, 10]}, "obstacles": [{"type": "point", "position": [5, 5]}]}))
    path = _write_movingai(tmp_path / "m.map", np.zeros((6, 9), bool))
    for args, message in (([str(doc), "--grid", "40", "--prune-length", "4"], "add --diagram medial"),
                          ([str(doc), "--grid", "40", "--unknown", "free"], "are for map files"),
                          ([str(doc), "--grid", "40", "--diagram", "medial", "--mode", "independent"],
                           "--mode and --no-visibility are the labelled diagram's"),
                          ([str(doc), "--grid", "40", "--path", "1", "1", "2"], "--path: At least 4 required"),
                          ([str(path), "--diagram", "labels"], "dvoronoi_gvd_mpi draws the medial diagram of map files"),
                          ([str(path), "--mode", "independent"], "--grid, --mode and --no-visibility are for obstacle files"),
                          ([str(path), "--grid", "40"], "--grid, --mode and --no-visibility are for obstacle files")):
        proc = mpirun(2, *args, "-o", str(tmp_path / "out.json"), program=GVD_MPI, timeout=120)
        assert proc.returncode == 2 and message in proc.stderr, (args, proc.stderr[-2000:])
        assert not (tmp_path / "out.json").exists()
    proc = mpirun(2, str(path), "--mode", "cooperative", "--unknown", "occupied", program=GVD_MPI, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]  # explicit defaults, as dvoronoi gvd takes them


@needs_gvd
def test_gvd_mpi_document_outputs_as_the_cli(tmp_path):
    # outputs opened before any work, with the CLI's checks (an output in a missing folder left the
    # SVG written and aborted; -o equal to --svg lost the SVG), and the CLI's empty-diagram warning
    doc = tmp_path / "doc.json"
    doc.write_text(json.dumps({"area": {"box": [0, 0, 100, 100]}, "obstacles": [
        {"type": "polygon", "vertices": [[10, 10], [30, 10], [30, 20], [18, 20], [18, 40], [10, 40]]},
        {"type": "circle", "center": [70, 60], "radius": 12}]}))
    for args, message in ((["-o", "nodir/x.json", "--svg", "a.svg"], "-o/--output: "),
                          (["-o", "c.json", "--svg", "c.json"], "--svg: same file as -o/--output"),
                          (["-o", "b.txt"], "-o/--output: the grid diagram is written as JSON"),
                          (["-r", "-1"], "--robot-radius: must be a finite number >= 0, got -1")):
        args = [str(tmp_path / a) if a.endswith((".json", ".svg", ".txt")) else a for a in args]
        proc = mpirun(3, str(doc), "--grid", "64", *args, program=GVD_MPI, timeout=120)
        assert proc.returncode == 2 and proc.stderr.count("dvoronoi_gvd_mpi: error: ") == 1, proc.stderr[-2000:]
        assert message in proc.stderr, proc.stderr[-2000:]
        assert sorted(p.name for p in tmp_path.iterdir()) == ["doc.json"]
    out, svg, one = tmp_path / "ok.json", tmp_path / "ok.svg", tmp_path / "one.json"
    proc = mpirun(3, str(doc), "--grid", "64", "-o", str(out), "--svg", str(svg), program=GVD_MPI, timeout=120)
    assert proc.returncode == 0 and svg.read_text().startswith("<svg"), proc.stderr[-2000:]
    subprocess.run([CLI, "gvd", str(doc), "--grid", "64", "-q", "-o", str(one)], check=True, timeout=120)
    mpi, cli = json.loads(out.read_text()), json.loads(one.read_text())
    mpi.pop("stats"), cli.pop("stats")
    assert mpi == cli
    full = tmp_path / "full.json"
    full.write_text(json.dumps({"area": {"box": [0, 0, 10, 10]},
                                "obstacles": [{"type": "polygon", "vertices": [[-1, -1], [11, -1], [11, 11], [-1, 11]]}]}))
    proc = mpirun(2, str(full), "--grid", "16", "-o", str(tmp_path / "f.json"), program=GVD_MPI, timeout=120)
    assert proc.returncode == 0 and proc.stderr.count("dvoronoi_gvd_mpi: warning: no diagram cell") == 1, proc.stderr


# an L-shaped (non-convex) polygon and a disk: the medial diagram separates the L's two arms
DOC = {"area": {"box": [0, 0, 100, 100]}, "obstacles": [
    {"type": "polygon", "vertices": [[10, 10], [30, 10], [30, 20], [18, 20], [18, 40], [10, 40]]},
    {"type": "circle", "center": [70, 60], "radius": 12}]}


@needs_gvd
@pytest.mark.parametrize("opts", [[], ["--min-separation", "2", "--prune-length", "5", "-r", "1.5"],
                                  ["-r", "1", "--path", "5", "5", "95", "95"]])
def test_gvd_mpi_document_medial_equals_cli_bytes(opts, tmp_path):
    # --diagram medial on an obstacle file: drawn on --grid pixels by rank 0, bands over the ranks,
    # the CLI's JSON and SVG (with its path) byte for byte
    doc = tmp_path / "doc.json"
    doc.write_text(json.dumps(DOC))
    args = [str(doc), "--grid", "120", "--diagram", "medial", *opts]
    ref_json, ref_svg = tmp_path / "cli.json", tmp_path / "cli.svg"
    subprocess.run([CLI, "gvd", *args, "-o", str(ref_json), "--svg", str(ref_svg), "-q"], check=True, timeout=120)
    ref = json.loads(ref_json.read_bytes())
    assert len(ref["pixels"]["row"]) > 100
    if "--path" in opts:
        assert ref["path"]["found"] and len(ref["path"]["points"]) >= 2
    for k in (1, 2, 3):
        out, svg = tmp_path / f"mpi{k}.json", tmp_path / f"mpi{k}.svg"
        proc = mpirun(k, *args, "-o", str(out), "--svg", str(svg), program=GVD_MPI, timeout=120)
        assert proc.returncode == 0, proc.stderr[-3000:]
        assert f"obstacle file drawn on 120 x 120 pixels, {len(ref['pixels']['row'])} diagram pixels, {k} ranks" in proc.stderr
        assert out.read_bytes() == ref_json.read_bytes(), (opts, k)
        assert svg.read_bytes() == ref_svg.read_bytes(), (opts, k)
    proc = mpirun(2, *args, "-q", program=GVD_MPI, timeout=120)  # -q: no summary line; stdout as -o
    assert proc.returncode == 0 and proc.stderr == "" and proc.stdout.encode() == ref_json.read_bytes()


@needs_gvd
def test_gvd_mpi_refuses_what_the_cli_refuses(tmp_path):
    # a drawn grid out of range (the CLI's check_grid), -o and --svg naming one file by two paths, a
    # folder named before any option check: exit 2 with the CLI's message, nothing written
    far = tmp_path / "far.json"
    far.write_text(json.dumps({"area": {"box": [1e15, 1e15, 1e15 + 100, 1e15 + 100]},
                               "obstacles": [{"type": "circle", "center": [1e15 + 50, 1e15 + 50], "radius": 10}]}))
    doc = tmp_path / "doc.json"
    doc.write_text(json.dumps(DOC))
    (tmp_path / "folder").mkdir()
    cases = (([str(far), "--grid", "50", "--diagram", "medial", "-o", "a.json"], "lies more than 2^40 pixels"),
             ([str(doc), "--grid", "32", "-o", "a.json", "--svg", "./a.json"], "--svg: same file as -o/--output ('./a.json')"),
             ([str(doc), "--grid", "32", "--diagram", "medial", "-o", "a.json", "--svg", "./a.json"], "--svg: same file"),
             ([str(tmp_path / "folder"), "-r", "-1"], "is a folder"))
    for args, message in cases:
        cli = subprocess.run([CLI, "gvd", *args], capture_output=True, text=True, cwd=tmp_path, timeout=120)
        assert cli.returncode == 2 and message in cli.stderr, cli.stderr
        proc = mpirun(2, *args, program=GVD_MPI, timeout=120, cwd=tmp_path)
        assert proc.returncode == 2 and message in proc.stderr, (args, proc.stderr[-2000:])
        assert proc.stderr.count("dvoronoi_gvd_mpi: error: ") == 1
        assert not (tmp_path / "a.json").exists()


@needs_gvd
def test_gvd_mpi_paths_as_the_cli(map_files, tmp_path):
    # --path on a map (nearest points of every pixel gathered for the search) and on an obstacle file's
    # labelled diagram: the CLI's path; a start outside the map exits 2 naming --path, nothing written
    from scipy import ndimage

    path = map_files["rooms"]
    occ = occupancy_maps.rooms_with_islands((90, 130), 2)
    clear = ndimage.distance_transform_edt(~occ)
    ends = []
    for c0, c1 in ((0, 40), (90, 130)):  # the clearest pixel of the left and right thirds: map x, y
        r, c = np.unravel_index(np.argmax(clear[:, c0:c1]), (90, c1 - c0))
        ends += [str(c0 + c + 0.5), str(90 - r - 0.5)]
    ref = subprocess.run([CLI, "gvd", str(path), "--path", *ends, "-q"], check=True,
                         capture_output=True, timeout=120).stdout
    assert json.loads(ref)["path"]["found"]
    for k in (1, 3):
        proc = mpirun(k, str(path), "--path", *ends, program=GVD_MPI, timeout=120)
        assert proc.returncode == 0 and proc.stdout.encode() == ref, proc.stderr[-3000:]
    doc = tmp_path / "doc.json"
    doc.write_text(json.dumps(DOC))
    args = [str(doc), "--grid", "64", "--path", "5", "5", "95", "95"]
    cli = json.loads(subprocess.run([CLI, "gvd", *args, "-q"], check=True, capture_output=True, timeout=120).stdout)
    assert cli["path"]["found"]
    for k in (1, 3):
        proc = mpirun(k, *args, "-q", program=GVD_MPI, timeout=120)
        assert proc.returncode == 0 and proc.stderr == "", proc.stderr[-3000:]
        mpi = json.loads(proc.stdout)
        mpi.pop("stats"), cli.pop("stats", None)
        assert mpi == cli
    out = tmp_path / "out.json"
    for extra in ([], ["--diagram", "medial"]):
        proc = mpirun(2, str(doc), "--grid", "64", *extra, "--path", "500", "5", "95", "95", "-o", str(out),
                      program=GVD_MPI, timeout=120)
        assert proc.returncode == 2 and "--path: start (500, 5) is outside the" in proc.stderr, proc.stderr[-2000:]
        assert not out.exists()


@needs_gvd
def test_gvd_mpi_bad_map_exits_2_naming_the_file(tmp_path):
    bad = tmp_path / "bad.map"
    bad.write_text("type octile\nheight 3\nwidth 4\nmap\n....\n..\n....\n")
    out = tmp_path / "out.json"
    for k in (1, 3):
        proc = mpirun(k, str(bad), "-o", str(out), "--svg", str(tmp_path / "out.svg"), program=GVD_MPI, timeout=120)
        assert proc.returncode == 2, proc.stderr[-3000:]
        assert f"{bad}:6: map row 1 has 2 characters, width is 4" in proc.stderr
        assert proc.stderr.count("dvoronoi_gvd_mpi: error:") == 1  # rank 0 alone prints
    proc = mpirun(2, str(tmp_path / "nope.yaml"), "-o", str(out), program=GVD_MPI, timeout=120)
    assert proc.returncode == 2 and f"{tmp_path / 'nope.yaml'}: cannot open file" in proc.stderr
    proc = mpirun(2, str(bad.with_name("x.map")), "--min-separation", "0.5", program=GVD_MPI, timeout=120)
    assert proc.returncode == 2 and "--min-separation: must be a number in [1, 32768]" in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.map"]  # nothing written, no temporary left


@needs_gvd
def test_gvd_mpi_outputs_never_overwrite_an_input_and_inputs_are_named(tmp_path):
    # As the CLI: an output naming INPUT (by any path) or a YAML's image, `--svg -`, a JPEG, a missing
    # file and a folder named like a map exit 2 with the CLI's message, nothing written. Before, the
    # first three replaced the input and the last ones were reported as a missing --grid.
    _write_movingai(tmp_path / "in.map", occupancy_maps.building(40, 1))
    _write_ros(tmp_path, occupancy_maps.building((40, 50), 4))
    (tmp_path / "doc.json").write_text(json.dumps(DOC))
    (tmp_path / "office.jpg").write_bytes(b"\xff\xd8\xff\xe0" + bytes(64))
    (tmp_path / "dir.pgm").mkdir()
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir() if p.is_file()}
    cases = (([ "in.map", "-o", "a.json", "--svg", "./in.map"], "--svg: './in.map' is the same file as INPUT ('in.map')"),
             (["doc.json", "--grid", "32", "-o", "doc.json"], "-o/--output: 'doc.json' is the same file as INPUT"),
             (["doc.json", "--grid", "32", "--diagram", "medial", "--svg", "doc.json"], "--svg: 'doc.json' is the same file"),
             (["floor.yaml", "--svg", "floor.pgm"], "--svg: 'floor.pgm' is the same file as the image of INPUT"),
             (["in.map", "--svg", "-"], "--svg: '-' (stdout) is for -o/--output's JSON"),
             (["office.jpg"], "office.jpg: neither a map file nor an obstacle document"),
             (["no_such_map"], "no_such_map: cannot open file: it does not exist"),
             (["dir.pgm"], "'dir.pgm' is a folder"))
    for args, message in cases:
        cli = subprocess.run([CLI, "gvd", *args, "-q"], capture_output=True, text=True, cwd=tmp_path, timeout=120)
        assert cli.returncode == 2 and message in cli.stderr, (args, cli.stderr)
        proc = mpirun(2, *args, "-q", program=GVD_MPI, timeout=120, cwd=tmp_path)
        assert proc.returncode == 2 and message in proc.stderr, (args, proc.stderr[-2000:])
        assert proc.stderr.count("dvoronoi_gvd_mpi: error: ") == 1
        assert {p.name: p.read_bytes() for p in tmp_path.iterdir() if p.is_file()} == before, args
