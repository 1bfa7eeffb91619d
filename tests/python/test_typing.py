"""Type information users get: `mypy --strict` on typed code that uses dvoronoi, and stubtest comparing
the compiled module with its stub (python/dvoronoi/_core.pyi) and the package with its annotations.

Runs mypy on the installed package (what a user's mypy sees: py.typed, _core.pyi). Skipped only when
mypy is not installed (`pip install .[test]` installs it).
"""
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("mypy", reason="mypy is not installed (pip install .[test])")

HERE = Path(__file__).resolve().parent / "typing"


def _mypy(*args, cwd):
    # Run from a folder outside the repository, so `dvoronoi` is the installed package, not the source
    # tree, and mypy's cache stays out of the repository.
    env = dict(os.environ)
    env.pop("MYPYPATH", None)
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True, cwd=cwd, env=env,
                          timeout=600)


def test_typed_usage_passes_mypy_strict(tmp_path):
    r = _mypy("mypy", "--strict", "--config-file", str(HERE / "mypy.ini"), "--cache-dir", str(tmp_path / "cache"),
              str(HERE / "usage.py"), cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr


def test_mypy_strict_catches_a_wrong_type(tmp_path):
    # The check above is only worth something if the stubs make mypy reject misuse.
    bad = tmp_path / "bad.py"
    bad.write_text("import dvoronoi as dv\n"
                   "part = dv.limited_cells([[0.0, 0.0]], 1.0)\n"
                   "x: str = part.cell(0).area\n")
    r = _mypy("mypy", "--strict", "--config-file", str(HERE / "mypy.ini"), "--cache-dir", str(tmp_path / "cache"),
              str(bad), cwd=tmp_path)
    assert r.returncode == 1 and 'incompatible types in assignment (expression has type "float"' in r.stdout.lower()


def test_stubtest(tmp_path):
    r = _mypy("mypy.stubtest", "dvoronoi", "--mypy-config-file", str(HERE / "mypy.ini"),
              "--allowlist", str(HERE / "stubtest_allowlist.txt"), cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
