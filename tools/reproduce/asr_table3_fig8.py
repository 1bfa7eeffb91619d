#!/usr/bin/env python3
"""Adjust-Sensing-Radius with Boundary Scan or EVT as its inner step: Table 3 and Figure 8 of He, Feng &
Ren (2018), "Distributed Algorithm for Voronoi Partition of Wireless Sensor Networks with a Limited
Sensing Range", Section 4.1.

Paper: Table 3 - 30 sensors uniform in a 3 x 3 square, sensing range r = 1, 100 configurations: time of
the limited partition by EVT, BS, ASR+EVT and ASR+BS (mean +- std; MATLAB, seconds: 0.02703, 0.00574,
0.06043, 0.01177). Figure 8 - 500 sensors, r = 1, square side L = 1..15, 100 networks per L: BS vs
ASR+BS; the two cost the same at L = 4, ASR+BS wins above that density (smaller L), BS below it.

Here: the four routes are timed in C++ by tools/reproduce/asr_timing (build it with
``cmake -S . -B build -DDVORONOI_BUILD_BENCHMARKS=ON && cmake --build build --target asr_timing``),
each sensor computing its cell of radius R = r/2 from the sensors within r (docs/spec.md), every time the
best of 3 runs of the whole configuration; asr_timing checks that the four routes give the same
cells. This script writes out/asr_table3.csv, out/asr_figure8.csv, out/asr_figure8.png and prints the
table and the crossover side next to the paper's.
"""
from __future__ import annotations

import argparse
import csv
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchutil import git_describe  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
OUT = Path(__file__).resolve().parent / "out"
PAPER_TABLE3 = {"EVT": (0.02703, 0.00926), "BS": (0.00574, 0.00096),
                "ASR+EVT": (0.06043, 0.00537), "ASR+BS": (0.01177, 0.00190)}
COLUMNS = {"EVT": "evt_s", "BS": "bs_s", "ASR+EVT": "asr_evt_s", "ASR+BS": "asr_bs_s"}


def run(exe: Path, experiment: str, configs: int, total: int, extra=()) -> list:
    from tqdm import tqdm

    # The CSV goes to a temporary file, so the progress lines on stderr can be read as they come.
    with tempfile.TemporaryFile("w+") as out:
        proc = subprocess.Popen([str(exe), experiment, "--configs", str(configs), *extra],
                                stdout=out, stderr=subprocess.PIPE, text=True)
        bar = tqdm(total=total, unit="config", desc=experiment)
        for line in proc.stderr:
            if line.startswith("progress"):
                bar.update(1)
            else:
                sys.stderr.write(line)
        bar.close()
        if proc.wait() != 0:
            raise SystemExit(f"{exe} {experiment} failed (exit {proc.returncode})")
        out.seek(0)
        return list(csv.DictReader(out))


def write_csv(rows: list, path: Path) -> None:
    with path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", type=Path, default=ROOT / "build" / "tools" / "reproduce" / "asr_timing")
    ap.add_argument("--configs", type=int, default=100, help="Table 3 configurations (paper: 100)")
    ap.add_argument("--fig8-configs", type=int, default=100, help="Figure 8 networks per side (paper: 100)")
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--quick", action="store_true", help="10 configurations, sides 1,4,8,15")
    args = ap.parse_args(argv)
    if not args.exe.is_file():
        raise SystemExit(f"{args.exe} not found: cmake -S . -B build -DDVORONOI_BUILD_BENCHMARKS=ON && "
                         "cmake --build build --target asr_timing (or pass --exe)")
    sides = "1,4,8,15" if args.quick else ",".join(str(L) for L in range(1, 16))
    configs = 10 if args.quick else args.configs
    stem = "_quick" if args.quick else ""
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"git {git_describe()}")

    t3 = run(args.exe, "table3", configs, configs)
    write_csv(t3, args.out / f"asr_table3{stem}.csv")
    print("\nTable 3: 30 sensors in 3 x 3, r = 1 (time of all 30 limited cells)")
    print("| route | dvoronoi (ms) | paper (ms, MATLAB) | dvoronoi / BS | paper / BS |")
    print("|---|---|---|---|---|")
    bs = np.mean([float(r["bs_s"]) for r in t3])
    for name, col in COLUMNS.items():
        t = np.array([float(r[col]) for r in t3])
        pm, ps = PAPER_TABLE3[name]
        print(f"| {name} | {1e3 * t.mean():.4f} +- {1e3 * t.std():.4f} | {1e3 * pm:.2f} +- {1e3 * ps:.2f} | "
              f"{t.mean() / bs:.2f} | {pm / PAPER_TABLE3['BS'][0]:.2f} |")

    n_sides = len(sides.split(","))
    f8_configs = 10 if args.quick else args.fig8_configs
    f8 = run(args.exe, "figure8", f8_configs, f8_configs * n_sides, ("--sides", sides))
    write_csv(f8, args.out / f"asr_figure8{stem}.csv")
    Ls = sorted({float(r["side"]) for r in f8})
    stats = {}
    for name, col in COLUMNS.items():
        stats[name] = [(np.mean(v), np.std(v)) for v in
                       ([float(r[col]) for r in f8 if float(r["side"]) == L] for L in Ls)]
    ratio = [a[0] / b[0] for a, b in zip(stats["ASR+BS"], stats["BS"])]
    cross = None
    for k in range(1, len(Ls)):
        if (ratio[k - 1] - 1.0) * (ratio[k] - 1.0) <= 0 and ratio[k - 1] != ratio[k]:
            L0, L1 = Ls[k - 1], Ls[k]
            cross = L0 + (1.0 - ratio[k - 1]) * (L1 - L0) / (ratio[k] - ratio[k - 1])
            break
    print(f"\nFigure 8: 500 sensors, r = 1, {f8_configs} networks per side; ASR+BS / BS time by side L")
    print("| L | neighbours in r | ASR+BS / BS | ASR steps |")
    print("|---|---|---|---|")
    for L, q in zip(Ls, ratio):
        rows = [r for r in f8 if float(r["side"]) == L]
        print(f"| {L:g} | {np.mean([float(r['mean_neighbors']) for r in rows]):.1f} | {q:.2f} | "
              f"{np.mean([float(r['mean_asr_steps']) for r in rows]):.2f} |")
    print(f"crossover (ASR+BS = BS): L = {cross:.2f}" if cross is not None else "no crossover in range",
          "(paper: L = 4)")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for name, style in (("BS", "o-"), ("ASR+BS", "s-"), ("EVT", "^--"), ("ASR+EVT", "v--")):
        m = np.array([s[0] for s in stats[name]]) * 1e3
        sd = np.array([s[1] for s in stats[name]]) * 1e3
        ax.errorbar(Ls, m, yerr=sd, fmt=style, ms=4, capsize=2, label=name)
    if cross is not None:
        ax.axvline(cross, color="0.5", lw=0.8, ls=":")
        ax.text(cross, ax.get_ylim()[1] * 0.9, f" crossover L={cross:.1f}\n (paper: 4)", fontsize=8, va="top")
    ax.set_yscale("log")
    ax.set_xlabel("side L of the square (500 sensors, r = 1)")
    ax.set_ylabel("time of all 500 limited cells (ms)")
    ax.set_title("Boundary Scan paper, Fig. 8: BS vs ASR+BS (dvoronoi, C++)")
    ax.legend()
    fig.tight_layout()
    png = args.out / f"asr_figure8{stem}.png"
    fig.savefig(png, dpi=110)
    print(f"wrote {args.out / f'asr_table3{stem}.csv'}, {args.out / f'asr_figure8{stem}.csv'}, {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
