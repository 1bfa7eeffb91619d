#!/usr/bin/env python3
"""A hypothesis-driven byte fuzzer of dvoronoi's file readers, from Python and from the CLI.

    python3 tools/fuzz/fuzz_readers.py --seconds 60 --target all      # 60 s per reader
    python3 tools/fuzz/fuzz_readers.py --seconds 300 --target png --cli build/cpp/cli/dvoronoi

Each reader has a seed corpus in tests/data/fuzz_corpus/<reader>/ (small valid and near-valid files,
written by tools/fuzz/make_corpus.py, plus inputs that once broke a reader). An input is a corpus
file mutated by a few operations hypothesis draws (byte flips, inserted bytes and format tokens,
deleted, duplicated or repeated ranges, truncation, splices with other corpus files, numbers
replaced by interesting ones, PNG chunks edited with their CRCs fixed, .npy headers edited), so
hypothesis also shrinks any input that breaks the invariant to a small one.

The invariant, for every input and every route to its reader:

* Python (``dv.OccupancyGrid.load``, ``dvoronoi.occupancy_maps.read_movingai_map``,
  ``dv.grid_voronoi(path)`` of an obstacle file, the point reader of ``python -m dvoronoi.mpi``):
  the call returns, or raises ValueError (the documented error type) whose message names the file.
  Any other exception (IndexError, UnicodeDecodeError, MemoryError, numpy errors, RuntimeError ...),
  a dead worker (a signal), more than --timeout seconds (a hang) or memory beyond --worker-memory-mb
  (the worker runs under RLIMIT_AS) breaks it.
* CLI (``dvoronoi cells | neighbors-from-distances | gvd``): exit status 0, or 2 with a message on
  stderr naming the file. Status 1 (an internal error, "out of memory"), death by a signal (a crash),
  a timeout or memory beyond --memory-mb (RLIMIT_AS) breaks it.

Findings are shrunk, written to --findings (default tools/fuzz/findings/<reader>/) with a note of
what happened, and summarised at the end; the exit status is 1 when there are any.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import resource
import select
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Tuple

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "data" / "fuzz_corpus"

# ------------------------------------------------------------------------------------ targets
INTERESTING_NUMBERS = [
    b"0", b"-0", b"1", b"-1", b"2", b"255", b"256", b"65535", b"65536", b"16383", b"16384", b"32767",
    b"2147483647", b"2147483648", b"-2147483649", b"4294967295", b"4294967296", b"9223372036854775807",
    b"9223372036854775808", b"18446744073709551616", b"1152921504606846976", b"99999999999999999999",
    b"1e308", b"1.7976931348623157e308", b"1e999", b"-1e999", b"1e-320", b"4.9e-324", b"1e-400", b"nan",
    b"-nan", b"inf", b"-inf", b"0.5", b"1e15", b"0x10", b"1_0", b"+-1", b"--1", b".", b"1.", b".5e",
]
GENERIC_TOKENS = [b"\n", b"\r\n", b"\r", b"\t", b" ", b"#", b",", b"\x00", b"\xff", b"\xef\xbb\xbf", b"\xc3\xa9",
                  b"\xed\xa0\x80", b"\x80"]


@dataclass
class Target:
    name: str
    python: Optional[str]   # worker route, or None
    cli: Optional[str]      # CLI route, or None
    tokens: List[bytes] = field(default_factory=list)
    siblings: bool = False  # the corpus folder's other files go beside the input (a YAML's images)
    input_glob: str = "*"   # which corpus files are inputs (the rest are siblings)

    @property
    def corpus(self) -> Path:
        return CORPUS / self.name

    def seeds(self) -> List[Path]:
        return sorted(p for p in self.corpus.glob(self.input_glob) if p.is_file())


TARGETS: Dict[str, Target] = {t.name: t for t in [
    Target("points", "points", "cells",
           [b"x y\n", b"x,y\n", b"1.5", b"-2e3", b"\x93NUMPY", b"'descr': '<f8'", b"'descr': '>i4'", b"'shape': (",
            b"'fortran_order': True", b"(3, 2)", b"), }", b"\x01\x00", b"\x02\x00"]),
    Target("distances", None, "distances", [b"i j d\n", b"0 1 1\n", b"1 0 1\n", b"0 1 2\n", b"7 7 1\n"]),
    Target("obstacles", "obstacles", "gvd-json",
           [b"{", b"}", b"[", b"]", b'"', b":", b",", b"\\u0000", b"\\ud800", b"\\", b'"type"', b'"polygon"',
            b'"circle"', b'"point"', b'"segment"', b'"union"', b'"parts"', b'"vertices"', b'"radius"',
            b'"center"', b'"position"', b'"area"', b'"box"', b'"name"', b'"obstacles"', b"null", b"true",
            b"[[0,0],[1,0],[0,1]]", b"[0,0,1,1]", b"[" * 64, b"]" * 64, b"{}", b"[]"]),
    Target("ros_yaml", "map", "gvd-map",
           [b"image: ", b"resolution: ", b"origin: ", b"[0, 0, 0]", b"negate: ", b"mode: ", b"trinary",
            b"occupied_thresh: ", b"free_thresh: ", b"room.pgm", b"room.png", b'"', b"'", b":", b"[", b"]", b"/", b".."],
           siblings=True, input_glob="*.y*ml"),
    Target("pgm", "map", "gvd-map", [b"P5", b"P2", b"P6", b"# c\n", b"65535", b"16383", b"255"]),
    Target("png", "map", "gvd-map", [b"IHDR", b"IDAT", b"IEND", b"PLTE", b"tRNS", b"\x89PNG\r\n\x1a\n"]),
    Target("movingai", "movingai", "gvd-map",
           [b"type octile\n", b"height ", b"width ", b"map\n", b".", b"@", b"G", b"S", b"W", b"T", b"O", b"x"]),
]}


def cli_argv(route: str, path: str, out_dir: str) -> List[str]:
    out = os.path.join(out_dir, "out.json")
    if route == "cells":
        return ["cells", path, "-r", "1.5", "--threads", "1", "-q", "-o", out]
    if route == "distances":
        return ["neighbors-from-distances", path, "--threads", "1", "-o", out]
    if route == "gvd-json":
        return ["gvd", path, "--grid", "16", "--workers", "1", "-o", out]
    if route == "gvd-map":
        return ["gvd", path, "--workers", "1", "-o", out]
    raise ValueError(route)


def find_cli() -> Optional[str]:
    env = os.environ.get("DVORONOI_CLI")
    if env:
        return env
    for p in [ROOT / "build" / "cpp" / "cli" / "dvoronoi", *sorted(ROOT.glob("build*/cpp/cli/dvoronoi"))]:
        if p.is_file() and os.access(p, os.X_OK):
            return str(p)
    return shutil.which("dvoronoi")


# ------------------------------------------------------------------------------------ mutations
def _png_chunks(data: bytes) -> Optional[List[Tuple[bytes, bytes]]]:
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return None
    out, pos = [], 8
    while pos + 8 <= len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + n]
        out.append((kind, body))
        pos += 12 + n
    return out


def _png_join(chunks: List[Tuple[bytes, bytes]]) -> bytes:
    return b"\x89PNG\r\n\x1a\n" + b"".join(
        struct.pack(">I", len(b)) + k + b + struct.pack(">I", zlib.crc32(k + b) & 0xFFFFFFFF) for k, b in chunks)


def _png_mutation(draw, data: bytes, st) -> bytes:
    """Edits a PNG and fixes the CRCs, so that libpng looks past them: IHDR fields, the inflated image
    data, or whole chunks."""
    chunks = _png_chunks(data)
    if not chunks:
        return data
    how = draw(st.sampled_from(["ihdr", "idat", "chunks"]))
    if how == "ihdr" and chunks[0][0] == b"IHDR" and len(chunks[0][1]) == 13:
        w, h, depth, colour, comp, filt, inter = struct.unpack(">IIBBBBB", chunks[0][1])
        fieldname = draw(st.sampled_from(["w", "h", "depth", "colour", "inter", "comp", "filt"]))
        big = st.sampled_from([0, 1, 2, 3, 7, 8, 9, 255, 16383, 16384, 65535, 2**31 - 1, 2**31, 2**32 - 1])
        if fieldname == "w":
            w = draw(big)
        elif fieldname == "h":
            h = draw(big)
        elif fieldname == "depth":
            depth = draw(st.sampled_from([0, 1, 2, 4, 8, 16, 3, 32, 255]))
        elif fieldname == "colour":
            colour = draw(st.sampled_from([0, 2, 3, 4, 6, 1, 5, 7, 255]))
        elif fieldname == "inter":
            inter = draw(st.sampled_from([0, 1, 2]))
        elif fieldname == "comp":
            comp = draw(st.integers(0, 255))
        else:
            filt = draw(st.integers(0, 255))
        chunks[0] = (b"IHDR", struct.pack(">IIBBBBB", w, h, depth, colour, comp, filt, inter))
    elif how == "idat":
        z = b"".join(b for k, b in chunks if k == b"IDAT")
        try:
            raw = bytearray(zlib.decompress(z))
        except zlib.error:
            return data
        if raw:
            for _ in range(draw(st.integers(1, 4))):
                op = draw(st.sampled_from(["set", "cut", "grow"]))
                p = draw(st.integers(0, max(0, len(raw) - 1)))
                if op == "set" and raw:
                    raw[p] = draw(st.integers(0, 255))
                elif op == "cut":
                    del raw[p:p + draw(st.integers(1, 64))]
                else:
                    raw[p:p] = bytes(draw(st.integers(1, 64)))
        chunks = [c for c in chunks if c[0] != b"IDAT"]
        at = next((k for k, c in enumerate(chunks) if c[0] == b"IEND"), len(chunks))
        chunks.insert(at, (b"IDAT", zlib.compress(bytes(raw))))
    else:
        k = draw(st.integers(0, len(chunks) - 1))
        op = draw(st.sampled_from(["drop", "dup", "swap", "body"]))
        if op == "drop":
            del chunks[k]
        elif op == "dup":
            chunks.insert(k, chunks[k])
        elif op == "swap" and len(chunks) > 1:
            j = draw(st.integers(0, len(chunks) - 1))
            chunks[k], chunks[j] = chunks[j], chunks[k]
        else:
            body = bytearray(chunks[k][1])
            body[draw(st.integers(0, len(body))):0] = draw(st.binary(min_size=1, max_size=8))
            chunks[k] = (chunks[k][0], bytes(body))
    return _png_join(chunks)


_NUMBER = re.compile(rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def mutated_inputs(target: Target):
    """Hypothesis strategy of (seed file, mutated bytes) for a target."""
    from hypothesis import strategies as st

    seeds = target.seeds()
    if not seeds:
        raise RuntimeError(f"no corpus in {target.corpus}")
    others = sorted(p for p in target.corpus.parent.glob("*/*") if p.is_file())
    tokens = target.tokens + GENERIC_TOKENS

    @st.composite
    def strategy(draw):
        seed = draw(st.sampled_from(seeds))
        data = bytearray(seed.read_bytes())
        for _ in range(draw(st.integers(0, 5))):
            op = draw(st.sampled_from(["flip", "insert", "token", "delete", "duplicate", "truncate", "splice",
                                       "number", "number", "repeat", "structure", "structure"]))
            n = len(data)
            pos = draw(st.integers(0, n))
            if op == "flip" and n:
                data[min(pos, n - 1)] = draw(st.integers(0, 255))
            elif op == "insert":
                data[pos:pos] = draw(st.binary(min_size=1, max_size=8))
            elif op == "token":
                data[pos:pos] = draw(st.sampled_from(tokens))
            elif op == "delete":
                del data[pos:pos + draw(st.integers(1, 16))]
            elif op == "duplicate" and n:
                a = draw(st.integers(0, n - 1))
                data[pos:pos] = data[a:a + draw(st.integers(1, 32))]
            elif op == "truncate":
                del data[pos:]
            elif op == "splice":
                other = draw(st.sampled_from(others)).read_bytes()
                if other:
                    a = draw(st.integers(0, len(other) - 1))
                    piece = other[a:a + draw(st.integers(1, 64))]
                    end = pos + draw(st.integers(0, 16))
                    data[pos:end] = piece
            elif op == "number":
                found = list(_NUMBER.finditer(bytes(data)))
                if found:
                    m = found[draw(st.integers(0, len(found) - 1))]
                    data[m.start():m.end()] = draw(st.sampled_from(INTERESTING_NUMBERS))
            elif op == "repeat" and n:
                a = draw(st.integers(0, n - 1))
                piece = bytes(data[a:a + draw(st.integers(1, 4))])
                data[a:a] = piece * draw(st.integers(1, 300))
            elif op == "structure":
                if bytes(data[:8]) == b"\x89PNG\r\n\x1a\n":
                    data = bytearray(_png_mutation(draw, bytes(data), st))
        return seed, bytes(data)

    return strategy()


# ------------------------------------------------------------------------------------ running
def _limit(memory_mb: int, cpu_seconds: int):
    def apply():
        os.setsid()
        if memory_mb > 0:  # 0: no limit (a sanitizer build reserves terabytes of address space)
            resource.setrlimit(resource.RLIMIT_AS, (memory_mb << 20, memory_mb << 20))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds + 1))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


WORKER_CODE = r"""
import json, os, sys, traceback, warnings
warnings.simplefilter("ignore")
import dvoronoi as dv
from dvoronoi.mpi import _read_points
from dvoronoi.occupancy_maps import read_movingai_map

def call(route, path):
    if route == "points":
        _read_points(path)
    elif route == "obstacles":
        dv.grid_voronoi(path, cells=16, workers=1)
    elif route == "map":
        dv.OccupancyGrid.load(path)
    elif route == "movingai":  # the loader and the array reader (one C++ reader); the worst outcome counts
        errors = []
        for f in (dv.OccupancyGrid.load, read_movingai_map):
            try:
                f(path)
            except Exception as e:
                errors.append(e)
        errors.sort(key=lambda e: isinstance(e, ValueError) and path in str(e))
        if errors:
            raise errors[0]
    else:
        raise KeyError(route)

print("ready", flush=True)
for line in sys.stdin:
    req = json.loads(line)
    try:
        call(req["route"], req["path"])
        out = {"ok": True}
    except BaseException as e:
        out = {"ok": False, "type": type(e).__name__, "valueerror": isinstance(e, ValueError),
               "message": str(e)[:2000], "trace": traceback.format_exc()[-3000:]}
    print(json.dumps(out), flush=True)
"""


@dataclass
class Finding:
    target: str
    route: str
    kind: str          # wrong-type, no-file-name, crash, hang, internal-error, memory
    detail: str
    data: bytes = b""
    seed: str = ""
    #: for a dead worker: the inputs it had run before (the crash may come from damage one of them did)
    context: List[Tuple[str, bytes]] = field(default_factory=list)

    def key(self) -> Tuple[str, str, str, str]:
        head = re.sub(r"\d+", "N", self.detail.split("\n")[0])[:60]
        return (self.target, self.route, self.kind, head)


class Runner:
    """Runs inputs through the Python worker (a long-lived subprocess under RLIMIT_AS) and the CLI."""

    def __init__(self, cli: Optional[str], python: str = sys.executable, timeout: float = 10.0,
                 memory_mb: int = 256, worker_memory_mb: int = 1024, use_python: bool = True, use_cli: bool = True):
        self.cli = cli if use_cli else None
        self.python = python
        self.timeout = timeout
        self.memory_mb = memory_mb                # the CLI: a few MB for these inputs
        self.worker_memory_mb = worker_memory_mb  # the worker: Python, numpy and dvoronoi, plus the input
        self.use_python = use_python
        self.tmp = Path(tempfile.mkdtemp(prefix="dvoronoi-fuzz-"))
        self.worker: Optional[subprocess.Popen] = None
        self.executions = 0
        self.history: List[Tuple[str, bytes]] = []  # (file name, bytes) the current worker has run

    # -- the Python worker
    def _start_worker(self) -> None:
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", PYTHONUNBUFFERED="1")
        self.worker = subprocess.Popen([self.python, "-c", WORKER_CODE], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                       stderr=subprocess.DEVNULL, text=True, env=env,
                                       preexec_fn=_limit(self.worker_memory_mb, 3600))
        self.history = []
        line = self._read_line(60.0)
        if line is None or line.strip() != "ready":
            raise RuntimeError(f"the fuzz worker did not start ({self.python}): {line!r}")

    def _read_line(self, timeout: float) -> Optional[str]:
        assert self.worker is not None and self.worker.stdout is not None
        ready, _, _ = select.select([self.worker.stdout], [], [], timeout)
        if not ready:
            return None
        return self.worker.stdout.readline()

    def _stop_worker(self) -> None:
        if self.worker is not None:
            try:
                os.killpg(self.worker.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            self.worker.wait()
            self.worker = None

    def run_python(self, route: str, path: str) -> Optional[Tuple[str, str]]:
        if self.worker is None:
            self._start_worker()
        assert self.worker is not None and self.worker.stdin is not None
        try:
            self.worker.stdin.write(json.dumps({"route": route, "path": path}) + "\n")
            self.worker.stdin.flush()
        except BrokenPipeError:
            pass
        line = self._read_line(self.timeout)
        if line is None:
            self._stop_worker()
            return ("hang", f"no answer within {self.timeout} s")
        if not line:
            code = self.worker.wait()
            self.worker = None
            return ("crash", f"the worker died: {'signal ' + str(-code) if code < 0 else 'exit ' + str(code)}")
        out = json.loads(line)
        if out["ok"]:
            return None
        if out["type"] == "MemoryError":
            return ("memory", f"MemoryError (RLIMIT_AS {self.worker_memory_mb} MiB): {out['message']}\n{out['trace']}")
        if not out["valueerror"]:
            return ("wrong-type", f"{out['type']}: {out['message']}\n{out['trace']}")
        if path not in out["message"]:
            return ("no-file-name", f"ValueError without the file name: {out['message']}")
        return None

    # -- the CLI
    def run_cli(self, route: str, path: str, out_dir: str) -> Optional[Tuple[str, str]]:
        argv = [self.cli] + cli_argv(route, path, out_dir)
        proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                preexec_fn=_limit(self.memory_mb, int(self.timeout) + 1))
        try:
            _, err = proc.communicate(timeout=self.timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            return ("hang", f"{' '.join(argv[1:2])}: no exit within {self.timeout} s")
        text = err.decode("utf-8", "replace")
        rc = proc.returncode
        if rc == 0:
            return None
        if rc < 0:
            kind = "hang" if -rc in (signal.SIGXCPU, signal.SIGKILL) else "crash"
            return (kind, f"killed by signal {-rc} ({signal.Signals(-rc).name}); stderr: {text[-500:]}")
        if rc == 2:
            return None if path in text else ("no-file-name", f"exit 2 without the file name: {text[-500:]}")
        if "out of memory" in text:
            return ("memory", f"exit {rc} (RLIMIT_AS {self.memory_mb} MiB): {text[-500:]}")
        return ("internal-error", f"exit {rc}: {text[-500:]}")

    # -- one input through every route of its target
    def check(self, target: Target, seed: Path, data: bytes) -> Optional[Finding]:
        self.executions += 1
        case = Path(tempfile.mkdtemp(dir=self.tmp))
        try:
            if target.siblings:
                for p in target.corpus.iterdir():
                    if p.is_file() and p.name != seed.name and not p.match(target.input_glob):
                        shutil.copyfile(p, case / p.name)
            path = case / seed.name
            path.write_bytes(data)
            if self.use_python and target.python:
                before = list(self.history[-200:])
                got = self.run_python(target.python, str(path))
                self.history.append((seed.name, data))
                if got:
                    return Finding(target.name, "python:" + target.python, got[0], got[1], data, seed.name,
                                   before if got[0] == "crash" else [])
            if self.cli and target.cli:
                got = self.run_cli(target.cli, str(path), str(case))
                if got:
                    return Finding(target.name, "cli:" + target.cli, got[0], got[1], data, seed.name)
            return None
        finally:
            shutil.rmtree(case, ignore_errors=True)

    def close(self) -> None:
        self._stop_worker()
        shutil.rmtree(self.tmp, ignore_errors=True)


# ------------------------------------------------------------------------------------ fuzzing
class _Broken(Exception):
    pass


def fuzz(target: Target, runner: Runner, seconds: float, batch: int = 50) -> Tuple[int, List[Finding]]:
    """Mutate the target's corpus for `seconds`; returns (executions, distinct shrunk findings)."""
    from hypothesis import HealthCheck, Phase, given, settings

    start = runner.executions
    findings: Dict[Tuple[str, ...], Finding] = {}
    deadline = time.monotonic() + seconds
    strategy = mutated_inputs(target)
    while time.monotonic() < deadline:
        failures: List[Finding] = []

        @settings(max_examples=batch, deadline=None, database=None, derandomize=False,
                  suppress_health_check=list(HealthCheck), phases=[Phase.generate, Phase.shrink])
        @given(case=strategy)
        def one(case):
            seed, data = case
            got = runner.check(target, seed, data)
            if got is not None:
                failures.append(got)
                raise _Broken(got.kind)

        try:
            one()
        except BaseException as e:  # _Broken, or an ExceptionGroup of several distinct ones
            if isinstance(e, KeyboardInterrupt):
                raise
        # the shrunk example of each kind of failure is the last one seen; for a dead worker also the
        # first, with the inputs that worker had run (a crash may be the late effect of one of them)
        for f in failures:
            findings[f.key()] = f
        first_crash = next((f for f in failures if f.kind == "crash" and f.context), None)
        if first_crash is not None:
            findings[first_crash.key() + ("first",)] = first_crash
    return runner.executions - start, list(findings.values())


def save_finding(f: Finding, folder: Path) -> Path:
    folder = folder / f.target
    folder.mkdir(parents=True, exist_ok=True)
    digest = hashlib.sha1(f.data).hexdigest()[:12]
    ext = Path(f.seed).suffix
    path = folder / f"{f.kind}-{digest}{ext}"
    path.write_bytes(f.data)
    note = f"target {f.target}, route {f.route}, kind {f.kind}, mutated from {f.seed}\n{f.detail}\n"
    if f.context:  # a dead worker: what it ran before, oldest first, to replay in one fresh worker
        ctx = folder / f"{path.stem}-context"
        ctx.mkdir(exist_ok=True)
        for k, (name, data) in enumerate(f.context):
            (ctx / f"{k:03d}{Path(name).suffix}").write_bytes(data)
        note += f"the worker had run {len(f.context)} inputs before it: {ctx}\n"
    path.with_suffix(path.suffix + ".txt").write_text(note)
    return path


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description="Fuzz dvoronoi's file readers (see the module docstring).")
    ap.add_argument("--seconds", type=float, default=60.0, help="time budget per reader (default 60)")
    ap.add_argument("--target", default="all", help=f"all or a comma-separated list of: {', '.join(TARGETS)}")
    ap.add_argument("--cli", default=None, help="the dvoronoi executable (default $DVORONOI_CLI, build/, PATH)")
    ap.add_argument("--no-cli", action="store_true", help="the Python routes only")
    ap.add_argument("--no-python", action="store_true", help="the CLI routes only")
    ap.add_argument("--python", default=sys.executable, help="interpreter that imports dvoronoi (the worker)")
    ap.add_argument("--timeout", type=float, default=10.0, help="seconds per input and route before it is a hang")
    ap.add_argument("--memory-mb", type=int, default=256, help="RLIMIT_AS of the CLI (MiB, default 256)")
    ap.add_argument("--worker-memory-mb", type=int, default=1024,
                    help="RLIMIT_AS of the Python worker (MiB, default 1024; Python, numpy and dvoronoi take ~400)")
    ap.add_argument("--findings", type=Path, default=ROOT / "tools" / "fuzz" / "findings")
    args = ap.parse_args(argv)
    names = list(TARGETS) if args.target == "all" else [t.strip() for t in args.target.split(",")]
    unknown = [n for n in names if n not in TARGETS]
    if unknown:
        ap.error(f"unknown target(s) {unknown}; choose from {list(TARGETS)}")
    cli = None if args.no_cli else (args.cli or find_cli())
    if not args.no_cli and cli is None:
        ap.error("no dvoronoi executable: pass --cli, set DVORONOI_CLI, build it (cmake) or use --no-cli")
    runner = Runner(cli, args.python, args.timeout, args.memory_mb, args.worker_memory_mb, use_python=not args.no_python,
                    use_cli=not args.no_cli)
    total, found = 0, []
    try:
        for name in names:
            t0 = time.monotonic()
            n, fs = fuzz(TARGETS[name], runner, args.seconds)
            total += n
            found += fs
            print(f"{name:10s} {n:7d} inputs in {time.monotonic() - t0:6.1f} s, {len(fs)} finding(s)", flush=True)
            for f in fs:
                print(f"    {f.kind} via {f.route}: {f.detail.splitlines()[0][:160]}\n    -> {save_finding(f, args.findings)}")
    finally:
        runner.close()
    print(f"total: {total} inputs, {len(found)} finding(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
