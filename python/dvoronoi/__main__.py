"""``python -m dvoronoi``: the ``dvoronoi`` command-line program (the same program, same options),
plus ``python -m dvoronoi demo``: the limited cells of the Intel lab motes, with a picture.

The program is the compiled CLI that ``pip install`` puts next to the interpreter (its scripts
folder); ``$DVORONOI_CLI`` names another one.
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import sysconfig
from typing import List, Optional


def _demo(args: argparse.Namespace) -> int:
    import numpy as np

    import dvoronoi as dv
    from dvoronoi._io import atomic_write

    points = dv.datasets.intel_lab()
    part = dv.limited_cells(points, args.radius, method=args.method)
    n = len(part)
    degree = np.diff(part.indptr)
    total = float(np.sum(part.areas))
    print(f"Intel Berkeley lab motes: {n} agents, cell radius R = {args.radius:g} m, method {args.method}")
    print(f"limited neighbours per agent: mean {degree.mean():.2f}, min {degree.min()}, max {degree.max()}"
          f" ({int(np.sum(degree == 0))} agents alone within 2R)")
    print(f"total cell area: {total:.2f} m^2 (covered area; {n} full disks would be "
          f"{n * np.pi * args.radius ** 2:.2f} m^2)")

    from dvoronoi._optional import require_matplotlib

    matplotlib = require_matplotlib("python -m dvoronoi demo")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 7), dpi=120)
    part.plot(ax=ax, labels=True)
    ax.set_title(f"Range-limited Voronoi cells, Intel lab motes, R = {args.radius:g} m")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.tight_layout()
    atomic_write(args.out, lambda f: fig.savefig(f, format="png"))
    plt.close(fig)
    print(f"picture: {args.out}")
    return 0


def cli_path() -> Optional[str]:
    """The ``dvoronoi`` program: ``$DVORONOI_CLI``, else the one installed with this package (the
    scripts folder of this interpreter's environment, or the user scheme's), else the PATH's."""
    env = os.environ.get("DVORONOI_CLI")
    if env:
        return env
    exe = "dvoronoi.exe" if os.name == "nt" else "dvoronoi"
    folders = [sysconfig.get_path("scripts"), os.path.dirname(sys.executable)]
    try:
        folders.append(sysconfig.get_path("scripts", f"{os.name}_user"))
    except KeyError:  # pragma: no cover - no user scheme on this platform
        pass
    for folder in folders:
        candidate = os.path.join(folder, exe)
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return shutil.which(exe)


def run_cli(argv: List[str]) -> int:
    """Run the ``dvoronoi`` program with `argv` and return its exit code."""
    exe = cli_path()
    if exe is None:
        print("python -m dvoronoi: error: the dvoronoi program is not installed with this package "
              "(pip install . builds it; or set DVORONOI_CLI to its path)", file=sys.stderr)
        return 2
    try:
        return subprocess.call([exe, *argv])
    except OSError as e:
        print(f"python -m dvoronoi: error: cannot run {exe}: {e}", file=sys.stderr)
        return 2


def main(argv: Optional[List[str]] = None) -> int:
    args_in = sys.argv[1:] if argv is None else list(argv)
    if not args_in or args_in[0] != "demo":
        return run_cli(args_in)  # every subcommand, --help and --version: the CLI itself
    parser = argparse.ArgumentParser(prog="python -m dvoronoi",
                                     description="dvoronoi: exact range-limited Voronoi cells.")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="limited cells of the built-in Intel lab data, with a PNG picture")
    demo.add_argument("--out", default="dvoronoi_demo.png", help="PNG file to write (default: %(default)s)")
    demo.add_argument("--radius", type=float, default=3.0, help="cell radius R in metres (default: %(default)s)")
    demo.add_argument("--method", choices=["auto", "scan", "chords"], default="auto")
    args = parser.parse_args(args_in)
    if args.command == "demo":
        try:
            return _demo(args)
        except (ValueError, OSError, ImportError) as e:
            print(f"python -m dvoronoi demo: error: {e}", file=sys.stderr)
            return 1
    return 2  # pragma: no cover


if __name__ == "__main__":
    sys.exit(main())
