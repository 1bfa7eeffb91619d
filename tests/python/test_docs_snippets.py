"""Every ```python block of docs/grid_diagram_maps.md runs as it stands (and the README's real-map
snippet): each in a fresh namespace, with matplotlib's Agg backend, from a temporary directory that
mirrors the repository root (its top-level entries linked in), so relative paths such as
``tests/data/maps/Paris_1_256.map`` resolve and the files a snippet writes land in the temporary
directory, never in the repository."""
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "grid_diagram_maps.md"
README = ROOT / "README.md"
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.DOTALL | re.MULTILINE)


def python_blocks(path, must_contain=None):
    text = path.read_text(encoding="utf-8")
    out = []
    for m in FENCE.finditer(text):
        if must_contain is None or must_contain in m.group(1):
            line = text.count("\n", 0, m.start()) + 2   # the block's first code line
            out.append(pytest.param(m.group(1), id=f"{path.name}:{line}"))
    return out


PAGE_BLOCKS = python_blocks(PAGE)
README_BLOCKS = python_blocks(README, must_contain="Paris_1_256")


@pytest.fixture
def repo_mirror(tmp_path, monkeypatch):
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


def run_block(code, where):
    before = {p.name for p in where.iterdir()}
    exec(compile(code, "<snippet>", "exec"), {"__name__": "__snippet__"})
    # whatever the snippet wrote is in the temporary directory, not behind a link into the repository
    for p in where.iterdir():
        if p.name not in before:
            assert not p.is_symlink()


def test_the_page_has_snippets():
    assert len(PAGE_BLOCKS) >= 8


@pytest.mark.parametrize("code", PAGE_BLOCKS)
def test_page_snippet_runs(code, repo_mirror):
    run_block(code, repo_mirror)


@pytest.mark.parametrize("code", README_BLOCKS or [pytest.param("", marks=pytest.mark.skip("no real-map snippet"))])
def test_readme_real_map_snippet_runs(code, repo_mirror):
    run_block(code, repo_mirror)


def test_no_snippet_reads_outside_the_repository():
    # the project owns its specification (docs/spec.md); nothing may reach for ../shared
    for path in (PAGE, README):
        assert "../shared" not in path.read_text(encoding="utf-8")
    assert os.path.exists(ROOT / "docs" / "spec.md")


CPP_FENCE = re.compile(r"^```cpp[ \t]*\n(.*?)^```[ \t]*$", re.DOTALL | re.MULTILINE)


def test_page_cpp_example_compiles_and_runs(tmp_path):
    """The page's C++ example against the headers of this tree (needs g++ and Eigen, as the build does)."""
    import shutil
    import subprocess

    eigen = Path("/usr/include/eigen3")
    if shutil.which("g++") is None or not eigen.is_dir():
        pytest.skip("g++ or Eigen not installed")
    blocks = CPP_FENCE.findall(PAGE.read_text(encoding="utf-8"))
    assert blocks, "the page shows the C++ API"
    src = tmp_path / "example.cpp"
    src.write_text(blocks[0])
    exe = tmp_path / "example"
    subprocess.run(["g++", "-std=c++17", "-O1", f"-I{ROOT / 'cpp' / 'include'}", f"-I{eigen}", str(src), "-o", str(exe),
                    "-pthread"], check=True, capture_output=True)
    out = subprocess.run([str(exe)], cwd=ROOT, check=True, capture_output=True, text=True).stdout
    assert "5556 diagram pixels" in out and "path: " in out and "nearest points changed" in out
