"""The conventions of docs/spec.md that span the package and the CLI: one program behind `dvoronoi` and
`python -m dvoronoi`, one version everywhere, one --bounds syntax, the same CSV columns, and the CSV
neighbour relation (indptr/indices, neighbors(i), to_csr()) on every result that relates agents."""
from __future__ import annotations

import csv
import importlib.metadata
import io
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dvoronoi as dv

ROOT = Path(__file__).resolve().parents[2]
RNG = np.random.default_rng(9)
P = RNG.random((50, 2))


def _cli():
    env = os.environ.get("DVORONOI_CLI")
    return env if env else shutil.which("dvoronoi")


CLI = _cli()
needs_cli = pytest.mark.skipif(CLI is None, reason="no dvoronoi executable (set DVORONOI_CLI or pip install .)")


def run(*args, module=False):
    cmd = [sys.executable, "-m", "dvoronoi"] if module else [CLI]
    return subprocess.run([*cmd, *map(str, args)], capture_output=True, text=True, timeout=300)


def points_file(tmp_path, pts):
    path = tmp_path / "pts.txt"
    path.write_text("".join(f"{float(x)!r} {float(y)!r}\n" for x, y in pts))
    return path


def test_one_version_everywhere():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    source = re.search(r"project\(dvoronoi\s+VERSION\s+([0-9][0-9.]*)", cmake).group(1)  # pyproject reads this
    assert dv.__version__ == source
    assert importlib.metadata.version("dvoronoi") == source


@needs_cli
def test_cli_version_is_the_package_version():
    r = run("--version")
    assert r.returncode == 0 and r.stdout.strip() == dv.__version__


@needs_cli
def test_python_m_dvoronoi_is_the_cli(tmp_path, monkeypatch):
    monkeypatch.setenv("DVORONOI_CLI", CLI)  # the same program the other CLI tests run
    pts = points_file(tmp_path, P)
    for args in (["--version"], ["cells", pts, "-r", 0.2, "-q"], ["voronoi", pts, "--bounds", 0, 0, 1, 1, "-q"]):
        a, b = run(*args), run(*args, module=True)
        assert a.returncode == b.returncode == 0, b.stderr
        assert a.stdout == b.stdout
    bad_a, bad_b = run("cells", pts, "-r", -1), run("cells", pts, "-r", -1, module=True)
    assert bad_a.returncode == bad_b.returncode == 2 and bad_a.stderr == bad_b.stderr
    helped = run("--help", module=True)
    assert helped.returncode == 0 and "lloyd" in helped.stdout and "network" in helped.stdout
    demo = run("demo", "--help", module=True)  # the Python demo stays
    assert demo.returncode == 0 and "--radius" in demo.stdout


def test_python_m_dvoronoi_without_the_program(monkeypatch, capsys):
    from dvoronoi import __main__ as main

    monkeypatch.setattr(main, "cli_path", lambda: None)
    assert main.main(["cells", "x.txt", "-r", "1"]) == 2
    assert "dvoronoi program is not installed" in capsys.readouterr().err


@needs_cli
def test_one_bounds_syntax(tmp_path):
    pts = points_file(tmp_path, P * 100)
    commands = {
        "voronoi": ["voronoi", pts],
        "lloyd": ["lloyd", pts, "-r", 10, "--steps", 1],
        "network": ["network", "bd07", pts, "--range", 30],
    }
    for name, cmd in commands.items():
        helped = run(*cmd[:2] if name == "network" else cmd[:1], "--help")
        assert "XMIN YMIN XMAX YMAX" in helped.stdout, name
        ok = run(*cmd, "--bounds", -1, -1, 101, 101, "-q")
        assert ok.returncode == 0, (name, ok.stderr)
        bad = run(*cmd, "--bounds", 0, 0, 100, "-q")
        assert bad.returncode == 2 and "--bounds" in bad.stderr, name


@needs_cli
def test_csv_columns_agree(tmp_path):
    pts = points_file(tmp_path, P * 100)
    outputs = {
        "cells": (["cells", pts, "-r", 10], dv.limited_cells(P * 100, 10.0)),
        "voronoi": (["voronoi", pts], dv.voronoi_cells(P * 100)),
        "network": (["network", "bs", pts, "--range", 20], dv.network.simulate("bs", P * 100, 20.0)),
    }
    for name, (cmd, ref) in outputs.items():
        out = tmp_path / f"{name}.csv"
        r = run(*cmd, "-o", out, "-q")
        assert r.returncode == 0, r.stderr
        rows = list(csv.DictReader(io.StringIO(out.read_text())))
        assert list(rows[0])[:3] == ["agent", "x", "y"] and "neighbors" in rows[0], name
        for row in rows:  # the neighbour list, space-separated and ascending, in every writer
            i = int(row["agent"])
            assert [int(v) for v in row["neighbors"].split()] == ref.neighbors(i).tolist(), (name, i)


def _relating_results():
    d = np.linalg.norm(P[:, None] - P[None], axis=-1)
    return {
        "LimitedPartition": dv.limited_cells(P, 0.15),
        "VoronoiPartition": dv.voronoi_cells(P),
        "DistanceNeighbors": dv.neighbors_from_distances(d),
        "GridVoronoi": dv.grid_voronoi([{"type": "circle", "center": [30, 40], "radius": 8},
                                        {"type": "point", "position": [75, 75]},
                                        {"type": "point", "position": [20, 80]}],
                                       area=(0, 0, 100, 100), cells=32),
        "CcResult": dv.network.simulate("cc", P * 100, 30.0),
        "Bd07Result": dv.network.simulate("bd07", P * 100, 30.0),
        "BoundaryScanResult": dv.network.simulate("bs", P * 100, 30.0),
        "LloydResult": dv.coverage.lloyd(P, 0.15, steps=1),
    }


@pytest.mark.parametrize("name", list(_relating_results()))
def test_every_result_relating_agents_has_the_csr_surface(name):
    pytest.importorskip("scipy")
    r = _relating_results()[name]
    n = len(r)
    assert r.indptr.dtype == np.int64 and r.indices.dtype == np.int64 and len(r.indptr) == n + 1
    m = r.to_csr()
    assert m.shape == (n, n) and m.nnz == len(r.indices)
    for i in range(n):
        assert sorted(r.neighbors(i).tolist()) == sorted(m.indices[m.indptr[i]:m.indptr[i + 1]].tolist())
