#!/usr/bin/env python3
"""What mapping fresh pages up front buys (core/pages.hpp): the same calls built with and without it
(``bench_pages_on`` / ``bench_pages_off``, ``-DDVORONOI_NO_PAGE_MAPPING``), run in alternation.

    cmake -S . -B build -DDVORONOI_BUILD_BENCHMARKS=ON
    cmake --build build --target bench_pages_on bench_pages_off
    python3 tools/bench_pages.py [--rounds 6]

Each run is one process making one call (fresh memory, as a user's first call); the table gives the
median over the rounds of the call's wall time and of the process's CPU time (user + system, from
``getrusage`` of the child): on a machine shared with other jobs wall times move by 10-20% between
runs, CPU time much less. Benchmarks are not tests: nothing fails on a time.
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CASES = [("limited", "1e6", 1), ("limited", "1e6", 2), ("voronoi", "1e6", 2), ("features", "2048", 1), ("features", "4096", 1), ("features", "4096", 2)]


def run(exe: Path, case) -> tuple:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([str(exe), case[0], case[1], str(case[2])], capture_output=True, text=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return float(out.stdout.split()[0]), cpu, after.ru_stime - before.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=6)
    ap.add_argument("--build", type=Path, default=REPO / "build" / "tools" / "bench")
    a = ap.parse_args()
    exes = {"on": a.build / "bench_pages_on", "off": a.build / "bench_pages_off"}
    for exe in exes.values():
        if not exe.exists():
            raise SystemExit(f"{exe} not found: build it first (see the top of this file)")
    print(f"load average at the start: {os.getloadavg()[0]:.1f}")
    times = {(c, v): [] for c in CASES for v in exes}
    for _ in range(a.rounds):
        for case in CASES:
            for v, exe in exes.items():
                times[(case, v)].append(run(exe, case))
    print("| call | threads | mapping | wall (median) | CPU user+sys (median) | of which system |")
    print("|---|---:|---|---:|---:|---:|")
    for case in CASES:
        for v in exes:
            rows = times[(case, v)]
            med = [statistics.median(r[k] for r in rows) for k in range(3)]
            print(f"| {case[0]} {case[1]} | {case[2]} | {v} | {med[0]:.3f} s | {med[1]:.3f} s | {med[2]:.3f} s |")
    print(f"load average at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
