"""Shared fixtures and helpers of the Python tests.

The exact CGAL oracle is the executable `dvoronoi_cgal_oracle POINTS_FILE RADIUS` (tests/oracle). It is
found through the environment variable DVORONOI_CGAL_ORACLE, else in the usual CMake build folders
(build/tests/oracle/, build*/tests/oracle/), else on the PATH. The oracle tests are skipped only when
it is missing, and say how to build it.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import List, Optional, Tuple

import numpy as np
import pytest

try:  # the property tests (test_properties*.py, test_fuzz_corpus.py) need hypothesis; the rest do not
    from hypothesis import HealthCheck, settings as _hypothesis_settings
except ImportError:  # pragma: no cover - hypothesis missing: those files skip themselves
    _hypothesis_settings = None

if _hypothesis_settings is not None:
    # Hypothesis profiles (docs/guarantees.md, "What the tests check"): "ci" is the default, 200 examples
    # per property; "long" (HYPOTHESIS_PROFILE=long, tools/property_tests_long.sh) runs 5000. No deadline:
    # the shared 2-core machine's timings vary too much for one.
    _slow = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]
    _hypothesis_settings.register_profile("ci", max_examples=200, deadline=None, suppress_health_check=_slow,
                                          print_blob=True)
    _hypothesis_settings.register_profile("long", max_examples=5000, deadline=None, suppress_health_check=_slow,
                                          print_blob=True)
    _hypothesis_settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
CORPUS = DATA / "degenerate_corpus.txt"
ORACLE_NAME = "dvoronoi_cgal_oracle"
BUILD_HINT = ("build it with: cmake -B build -DDVORONOI_BUILD_TESTS=ON && "
              "cmake --build build --target dvoronoi_cgal_oracle (needs CGAL), "
              "or point DVORONOI_CGAL_ORACLE at the executable")


def find_oracle() -> Optional[Path]:
    env = os.environ.get("DVORONOI_CGAL_ORACLE")
    if env:
        path = Path(env)
        if not (path.is_file() and os.access(path, os.X_OK)):
            raise RuntimeError(f"DVORONOI_CGAL_ORACLE={env!r} is not an executable file")
        return path
    candidates = [ROOT / "build" / "tests" / "oracle" / ORACLE_NAME]
    candidates += sorted(ROOT.glob(f"build*/tests/oracle/{ORACLE_NAME}"))
    candidates += sorted(ROOT.glob(f"build/*/tests/oracle/{ORACLE_NAME}"))
    for path in candidates:
        if path.is_file() and os.access(path, os.X_OK):
            return path
    found = shutil.which(ORACLE_NAME)
    return Path(found) if found else None


def write_points(path: Path, points: np.ndarray) -> None:
    """One `x y` line per agent, in the shortest text that reads back to the same double."""
    with open(path, "w") as f:
        for x, y in np.asarray(points, dtype=np.float64).reshape(-1, 2):
            f.write(f"{float(x)!r} {float(y)!r}\n")


def run_oracle(exe: Path, points: np.ndarray, radius: float, box=None) -> dict:
    """The oracle's JSON; with `box` = (xmin, ymin, xmax, ymax) also "clipped_areas"."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "points.txt"
        write_points(path, points)
        extra = [repr(float(b)) for b in box] if box is not None else []
        proc = subprocess.run([str(exe), str(path), repr(float(radius))] + extra, capture_output=True,
                              text=True, timeout=600)
    if proc.returncode != 0:
        raise RuntimeError(f"{exe} failed ({proc.returncode}): {proc.stderr.strip()}")
    return json.loads(proc.stdout)


@pytest.fixture(scope="session")
def oracle():
    """Callable (points, radius, box=None) -> oracle JSON dict; skips when the executable is missing."""
    exe = find_oracle()
    if exe is None:
        pytest.skip(f"CGAL oracle executable {ORACLE_NAME} not found; {BUILD_HINT}")
    return lambda points, radius, box=None: run_oracle(exe, points, radius, box)


def read_corpus(path: Path = CORPUS) -> List[Tuple[str, float, np.ndarray]]:
    """Named cases of tests/data/degenerate_corpus.txt: `case NAME RADIUS`, `x y` lines, `end`."""
    cases: List[Tuple[str, float, np.ndarray]] = []
    if not path.is_file():
        return cases
    name: Optional[str] = None
    radius = math.nan
    rows: List[Tuple[float, float]] = []
    for lineno, raw in enumerate(path.read_text().splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        fields = line.split()
        if fields[0] == "case":
            assert name is None and len(fields) == 3, f"{path}:{lineno}: bad case line"
            name, radius, rows = fields[1], float(fields[2]), []
        elif fields[0] == "end":
            assert name is not None, f"{path}:{lineno}: 'end' without 'case'"
            cases.append((name, radius, np.array(rows, dtype=np.float64).reshape(-1, 2)))
            name = None
        else:
            assert name is not None and len(fields) == 2, f"{path}:{lineno}: bad point line"
            rows.append((float(fields[0]), float(fields[1])))
    assert name is None, f"{path}: last case has no 'end'"
    return cases


def neighbor_sets(indptr: np.ndarray, indices: np.ndarray) -> List[set]:
    return [set(indices[indptr[i]:indptr[i + 1]].tolist()) for i in range(len(indptr) - 1)]


def random_points(seed: int, n: int, scale: float = 1.0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(0.0, scale, size=(n, 2))


def grid_points(seed: int, n: int, side: int) -> np.ndarray:
    """n distinct random nodes of a side x side integer grid: many exact cocircularities, collinear
    triples and distances exactly 2R."""
    rng = np.random.default_rng(seed)
    flat = rng.choice(side * side, size=n, replace=False)
    return np.column_stack([flat % side, flat // side]).astype(np.float64)


def densified_disk(center, radius: float, k: int):
    """Regular k-gon inscribed in the circle: its area is below pi R^2 by exactly `disk_deficit`."""
    import shapely

    t = 2.0 * np.pi * np.arange(k) / k
    return shapely.Polygon(np.column_stack([center[0] + radius * np.cos(t),
                                            center[1] + radius * np.sin(t)]))


def disk_deficit(radius: float, k: int) -> float:
    """pi R^2 minus the area of the inscribed regular k-gon: bounds the area lost per disk."""
    return math.pi * radius ** 2 - 0.5 * k * radius ** 2 * math.sin(2.0 * math.pi / k)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


@pytest.fixture(scope="session")
def intel():
    import dvoronoi as dv

    return dv.datasets.intel_lab()
