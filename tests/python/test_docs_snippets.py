"""Every code block of the README and of every page in docs/ runs as it stands, and the docs build.

How a page's fenced blocks are treated (by the fence's language):

- ``python``: executed, each block in a fresh namespace (so every block is pasteable on its own),
  with matplotlib's Agg backend.
- ``sh``: run by ``bash -e``, with the ``dvoronoi`` program on the PATH (the one ``DVORONOI_CLI``
  names, as tools/test.sh sets it, else the one ``pip install`` put on the PATH; the blocks are
  skipped when there is none). A block that calls ``mpirun`` is skipped when mpirun or the MPI
  executable it names is missing.
- ``cpp``: a complete program (it has ``int main``), compiled against this tree's headers and Eigen
  and run (skipped without g++ or Eigen).
- ``json`` / ``yaml``: parsed.
- ``text`` (outputs, file formats, trees) and MyST directives (``{toctree}``, ``{eval-rst}``, ...)
  are not code.

A block that must not run carries ``<!-- no-run: REASON -->`` on the line before its fence (installs
packages, runs the whole test suite, ...); a block that needs an optional module carries
``<!-- requires: MODULE -->`` and is skipped when the module is missing. Any other language, or
a bare fence, is an error here.

The blocks of one page run in order in one temporary directory that mirrors the repository root
(its top-level entries linked in), so relative paths such as ``tests/data/maps/Paris_1_256.map``
resolve, a later block may read a file an earlier block of the same page wrote (as a reader
following the page would), and whatever a block writes lands in the temporary directory, never in
the repository.

The Sphinx build (``python3 -m sphinx -W --keep-going -b html docs DIR``) is a test too, skipped
only when Sphinx, myst-parser or the theme is not installed.
"""
from __future__ import annotations

import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
README = ROOT / "README.md"
PAGES = [README] + sorted(DOCS.glob("*.md"))

OPEN = re.compile(r"^(?P<fence>`{3,}|~{3,})(?P<lang>[^\s`]*)[^`]*$")
MARK = re.compile(r"^<!--\s*(?P<kind>no-run|requires):\s*(?P<arg>.*?)\s*-->\s*$")
RUNNABLE = {"python", "sh", "cpp", "json", "yaml"}
NOT_CODE = {"text"}


@dataclass
class Block:
    page: Path
    line: int            # 1-based line of the first code line
    lang: str
    code: str
    no_run: Optional[str] = None
    requires: Optional[str] = None

    @property
    def where(self) -> str:
        return f"{self.page.relative_to(ROOT)}:{self.line}"


def blocks(page: Path) -> List[Block]:
    lines = page.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        m = OPEN.match(lines[i])
        if not m:
            i += 1
            continue
        fence, lang = m.group("fence"), m.group("lang")
        j = i + 1
        while j < len(lines) and lines[j].strip() != fence:
            j += 1
        block = Block(page, i + 2, lang, "\n".join(lines[i + 1:j]) + "\n")
        k = i - 1
        while k >= 0 and MARK.match(lines[k]):
            mk = MARK.match(lines[k])
            setattr(block, mk.group("kind").replace("-", "_"), mk.group("arg"))
            k -= 1
        out.append(block)
        i = j + 1
    return out


ALL = [b for page in PAGES for b in blocks(page)]


def test_pages_are_found():
    names = {p.name for p in PAGES}
    assert {"README.md", "index.md", "getting_started.md", "spec.md", "api.md"} <= names
    assert sum(b.lang == "python" for b in ALL) >= 30


@pytest.mark.parametrize("block", ALL, ids=lambda b: b.where)
def test_every_block_is_runnable_or_marked(block):
    if block.lang.startswith("{"):
        return                                      # a MyST directive
    if block.no_run is not None:
        assert block.no_run.strip(), f"{block.where}: <!-- no-run: --> needs a reason"
        return
    assert block.lang in RUNNABLE | NOT_CODE, (
        f"{block.where}: fence language {block.lang!r}; use one of {sorted(RUNNABLE | NOT_CODE)} "
        "or mark the block <!-- no-run: REASON -->")
    if block.lang == "cpp":
        assert "int main" in block.code, f"{block.where}: a C++ block is a complete program (or marked no-run)"


def test_no_run_blocks_are_rare():
    marked = [b.where for b in ALL if b.no_run is not None]
    runnable = [b for b in ALL if b.lang in RUNNABLE and b.no_run is None]
    assert len(marked) <= 12 and len(marked) < len(runnable) / 4, marked


@pytest.fixture
def page_dir(tmp_path, monkeypatch):
    for entry in ROOT.iterdir():
        if entry.name.startswith(".git"):
            continue
        (tmp_path / entry.name).symlink_to(entry, target_is_directory=entry.is_dir())
    monkeypatch.chdir(tmp_path)
    import matplotlib
    matplotlib.use("Agg")
    yield tmp_path
    import matplotlib.pyplot as plt
    plt.close("all")


def cli_dir() -> Optional[str]:
    env = os.environ.get("DVORONOI_CLI")
    if env and Path(env).is_file():
        return str(Path(env).resolve().parent)
    found = shutil.which("dvoronoi") or shutil.which("dvoronoi", path=str(Path(sys.executable).parent))
    return str(Path(found).parent) if found else None


def mpi_env() -> dict:
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1")
    if not (shutil.which("ssh") or shutil.which("rsh")):
        env.setdefault("OMPI_MCA_plm_rsh_agent", "sh")   # Open MPI 4 wants an rsh agent even for local ranks
    if hasattr(os, "geteuid") and os.geteuid() == 0:       # containers: what --allow-run-as-root says
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


def run_python(block: Block) -> None:
    exec(compile(block.code, block.where, "exec"), {"__name__": "__snippet__"})


def run_sh(block: Block, where: Path) -> Optional[str]:
    """Runs the block; returns why it was skipped, or None."""
    bindir = cli_dir()
    if bindir is None:
        return "no dvoronoi program (pip install . or set DVORONOI_CLI)"
    env = mpi_env()
    env["PATH"] = os.pathsep.join([bindir, str(Path(sys.executable).parent), env.get("PATH", "")])
    if "mpirun" in block.code:
        if shutil.which("mpirun") is None:
            return "no mpirun"
        for exe in re.findall(r"mpirun\s+(?:-\S+\s+(?:\d+\s+)?)*(\S+)", block.code):
            if exe not in ("python", "python3") and not (where / exe).is_file():
                return f"{exe} not built"
        if re.search(r"mpirun[^\n]*python3? -m dvoronoi\.mpi", block.code) and importlib.util.find_spec("mpi4py") is None:
            return "no mpi4py"
    r = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", block.code], cwd=where, env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"{block.where}: exit {r.returncode}\n{r.stdout}\n{r.stderr}"
    return None


def run_cpp(block: Block, where: Path) -> Optional[str]:
    eigen = Path("/usr/include/eigen3")
    if shutil.which("g++") is None or not eigen.is_dir():
        return "g++ or Eigen not installed"
    build = where / "_cpp_snippet"
    build.mkdir(exist_ok=True)
    src = build / f"block{block.line}.cpp"
    src.write_text(block.code)
    exe = build / f"block{block.line}"
    r = subprocess.run(["g++", "-std=c++17", "-O1", f"-I{ROOT / 'cpp' / 'include'}", f"-I{eigen}", str(src),
                        "-o", str(exe), "-pthread"], capture_output=True, text=True)
    assert r.returncode == 0, f"{block.where}: does not compile\n{r.stderr[-4000:]}"
    r = subprocess.run([str(exe)], cwd=where, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"{block.where}: exit {r.returncode}\n{r.stdout}\n{r.stderr}"
    for needle in EXPECTED_CPP.get(block.page.name, ()):
        assert needle in r.stdout, f"{block.where}: {needle!r} not in the output\n{r.stdout}"
    return None


# What the pages' C++ programs print (the pages quote it).
EXPECTED_CPP = {
    "grid_diagram_maps.md": ("5556 diagram pixels, clearance at (100, 100): 0.5", "path: 15 points, length 371.891",
                             "update: 566 nearest points changed"),
    "getting_started.md": ("54 motes", "limited neighbours of mote 0"),
}


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_page_blocks_run(page, page_dir):
    skipped = []
    for block in blocks(page):
        if block.no_run is not None or block.lang not in RUNNABLE:
            continue
        if block.requires and importlib.util.find_spec(block.requires) is None:
            skipped.append(f"{block.where}: needs {block.requires}")
            continue
        before = {p.name for p in page_dir.iterdir()}
        why = None
        if block.lang == "python":
            run_python(block)
        elif block.lang == "sh":
            why = run_sh(block, page_dir)
        elif block.lang == "cpp":
            why = run_cpp(block, page_dir)
        elif block.lang == "json":
            json.loads(block.code)
        elif block.lang == "yaml":
            import yaml
            yaml.safe_load(block.code)
        if why:
            skipped.append(f"{block.where}: {why}")
        # whatever the block wrote is in the temporary directory, not behind a link into the repository
        for p in page_dir.iterdir():
            if p.name not in before:
                assert not p.is_symlink(), f"{block.where} wrote through a link: {p.name}"
    if skipped:
        pytest.skip("; ".join(skipped))


def test_no_page_reads_outside_the_repository():
    # the project owns its specification (docs/spec.md); nothing may reach for ../shared
    for path in PAGES:
        text = path.read_text(encoding="utf-8")
        assert "../shared" not in text and "/work/" not in text, path
    assert (DOCS / "spec.md").is_file()
    for path in [ROOT / "python", ROOT / "cpp", ROOT / "tests", ROOT / "tools"]:
        for f in path.rglob("*"):
            if f.suffix in {".py", ".hpp", ".cpp", ".md"} and f.is_file():
                if f != Path(__file__).resolve():
                    assert "SPEC" + ".md" not in f.read_text(encoding="utf-8", errors="replace"), f


def test_readme_is_short_and_starts_with_the_two_commands():
    text = README.read_text(encoding="utf-8")
    assert len(text.encode("utf-8")) <= 11_000
    sh = [b.code.strip() for b in blocks(README) if b.lang == "sh"]
    assert sh[:2] == ["bash tools/demo.sh", "bash tools/test.sh"]
    for clock in re.findall(r"\d{1,2}:\d{2}(?::\d{2})? ?UTC", text):
        pytest.fail(f"README carries a clock time ({clock}): measurements belong in docs/performance.md")


def test_citation_file():
    yaml = pytest.importorskip("yaml")
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software" and cff["license"] == "BSD-3-Clause"
    assert len(cff["references"]) == 5
    for ref in cff["references"]:
        assert ref["type"] and ref["title"] and ref["authors"]


def test_docs_build_without_warnings(tmp_path):
    """The docs site, as CI builds it: every warning is an error."""
    for module in ("sphinx", "myst_parser", "furo"):
        if importlib.util.find_spec(module) is None:
            pytest.skip(f"{module} not installed (pip install '.[test]')")
    r = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                        str(DOCS), str(tmp_path / "html")], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (tmp_path / "html" / "index.html").is_file()
