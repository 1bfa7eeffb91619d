"""The file readers against their fuzz corpus (tests/data/fuzz_corpus/<reader>/), and a short
hypothesis byte-mutation pass per reader (tools/fuzz/fuzz_readers.py; the "ci" profile's 200 inputs
per reader, HYPOTHESIS_PROFILE=long 5000).

Invariant for every input and route: the Python reader returns or raises ValueError naming the file;
the CLI (``dvoronoi cells | neighbors-from-distances | gvd``) exits 0, or 2 with a message naming the
file -- never another exception type, status 1, a signal, a hang or memory beyond the RLIMIT_AS the
fuzzer sets for the worker and the CLI. The CLI routes run when $DVORONOI_CLI (or a build/ tree, or
`dvoronoi` on the PATH) is there.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "fuzz"))
import fuzz_readers as fz  # noqa: E402

CLI = fz.find_cli()


@pytest.fixture(scope="module")
def runner():
    r = fz.Runner(CLI, sys.executable, timeout=20.0)
    yield r
    r.close()


def _corpus():
    out = []
    for name, target in fz.TARGETS.items():
        for seed in target.seeds():
            out.append(pytest.param(name, seed, id=f"{name}/{seed.name}"))
    return out


def test_every_reader_has_a_corpus():
    for name, target in fz.TARGETS.items():
        assert len(target.seeds()) >= 5, f"{target.corpus}: too few seed files"


@pytest.mark.parametrize("name,seed", _corpus())
def test_corpus_file(runner, name, seed):
    got = runner.check(fz.TARGETS[name], seed, seed.read_bytes())
    assert got is None, f"{got.kind} via {got.route}: {got.detail}"


@pytest.mark.parametrize("name", list(fz.TARGETS))
def test_mutated_corpus(runner, name):
    target = fz.TARGETS[name]

    @settings(suppress_health_check=list(HealthCheck), database=None)
    @given(case=fz.mutated_inputs(target))
    def check(case):
        seed, data = case
        got = runner.check(target, seed, data)
        assert got is None, f"{got.kind} via {got.route} (mutated from {seed.name}): {got.detail}"

    check()
