"""Helpers shared by the benchmarks and paper reproductions in tools/ (not part of the package)."""
from __future__ import annotations

import math
import subprocess
import time
from pathlib import Path


def git_describe() -> str:
    """The checkout's commit (and whether it has local changes), so a number can be traced to code."""
    root = Path(__file__).resolve().parent
    try:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=root,
                               capture_output=True, text=True, check=True).stdout.strip()
        return rev + (" + local changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def best_of(reps: int, fn):
    """(best wall time in seconds over `reps` runs, result of the last run)."""
    best, out = math.inf, None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out
