"""`dvoronoi lloyd`: the CLI runs the same steps as dv.coverage.lloyd (bit for bit), writes the run as
JSON and one SVG per recorded step, and rejects bad input with exit code 2 and no output."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import dvoronoi as dv
from test_cli import CLI, SVG_NS, run, write_points  # noqa: F401  (CLI: the skip condition)

pytestmark = pytest.mark.skipif(CLI is None, reason="no dvoronoi executable")


@pytest.fixture
def swarm(tmp_path):
    pts = np.random.default_rng(3).uniform(0, 1, (120, 2))
    return pts, write_points(tmp_path / "pts.txt", pts.tolist())


def test_cli_equals_python_and_draws_every_frame(swarm, tmp_path):
    pts, path = swarm
    out, svg = tmp_path / "run.json", tmp_path / "frames"
    r = run("lloyd", path, "-r", "0.09", "--steps", "12", "--gain", "0.8", "--bounds", "0", "0", "1", "1",
            "--svg-dir", svg, "--svg-every", "5", "--trajectory", "-o", out, "-t", "1")
    assert r.returncode == 0, r.stderr
    doc = json.loads(out.read_text())
    ref = dv.coverage.lloyd(pts, 0.09, steps=12, gain=0.8, bounds=(0, 0, 1, 1), record_every=5)
    assert doc["cost"] == ref.cost.tolist()
    assert np.array_equal(np.array(doc["points"]), ref.trajectory[-1])
    assert doc["frame_steps"] == [0, 5, 10, 12]
    assert np.array_equal(np.array(doc["trajectory"]), ref.trajectory)
    names = sorted(p.name for p in svg.iterdir())
    assert names == ["step_000000.svg", "step_000005.svg", "step_000010.svg", "step_000012.svg"]
    root = ET.parse(svg / "step_000012.svg").getroot()
    cells = [e for e in root.iter(SVG_NS + "path") if e.get("id", "").startswith("cell-")]
    assert len(cells) == 120


def test_cli_polygon_environment_and_stdout(swarm, tmp_path):
    pts, path = swarm
    poly = write_points(tmp_path / "poly.txt", [(-0.1, -0.1), (1.2, -0.1), (1.2, 1.2), (-0.1, 1.2)])
    r = run("lloyd", path, "-r", "0.09", "--steps", "3", "--polygon", poly, "-q")
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    doc = json.loads(r.stdout)
    ref = dv.coverage.lloyd(pts, 0.09, steps=3, bounds=(-0.1, -0.1, 1.2, 1.2))
    assert np.allclose(doc["cost"], ref.cost, rtol=1e-13)
    assert len(doc["bounds"]) == 4


@pytest.mark.parametrize("args,message", [
    (("--bounds", "0", "0", "0.5", "1"), "lies outside the environment"),
    (("--gain", "1.5"), "--gain"),
    (("--steps", "-1"), "--steps"),
    (("-r", "0"), "--radius"),
    (("--bounds", "1", "0", "0", "1"), "--bounds"),
    (("-o", "run.csv"), "-o/--output"),
])
def test_cli_bad_input(swarm, tmp_path, args, message):
    _, path = swarm
    base = ["lloyd", path, "--steps", "2", "-r", "0.1", "--svg-dir", tmp_path / "frames"]
    r = run(*base, *args, cwd=tmp_path)
    assert r.returncode == 2
    assert message in r.stderr
    assert not (tmp_path / "frames").exists() or not any((tmp_path / "frames").iterdir())
    assert not (tmp_path / "run.csv").exists()
