#!/usr/bin/env bash
# Build the wheel and check what a user gets from it: the compiled module, the `dvoronoi` program,
# py.typed and the stubs, then install it in a fresh virtual environment (its dependencies from the
# package index) and run the library, the program and `python -m dvoronoi` from there.
#   bash tools/check_wheel.sh [OUT_DIR]     (default: a temporary folder, removed afterwards)
# Needs the build dependencies of `pip install .` (scikit-build-core, pybind11, CMake, Eigen, CLI11,
# nlohmann-json) in the running python3.
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
wheel=$(ls -t "$out"/dvoronoi-*.whl | head -n 1)
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
echo "check_wheel: installing into a fresh virtual environment"
"$PY" -m venv "$tmp/venv"
"$tmp/venv/bin/python" -m pip install -q "$wheel"
cd "$tmp"  # away from the source tree, so `import dvoronoi` is the installed one
"$tmp/venv/bin/python" - <<'PYEOF'
import numpy as np, dvoronoi as dv, sys
assert dv.__file__.startswith(sys.prefix), dv.__file__
part = dv.limited_cells(np.random.default_rng(0).random((200, 2)), 0.1)
assert len(part) == 200 and part.areas.sum() > 0
print(f"check_wheel: import ok, dvoronoi {dv.__version__} from {dv.__file__}")
PYEOF
v=$("$tmp/venv/bin/dvoronoi" --version)
m=$("$tmp/venv/bin/python" -m dvoronoi --version)
[ "$v" = "$m" ] || { echo "check_wheel: dvoronoi --version '$v' but python -m dvoronoi --version '$m'"; exit 1; }
echo "check_wheel: the dvoronoi program runs ($v); all good"
