#!/usr/bin/env bash
# Fresh machine -> the main job: install dvoronoi, compute the range-limited Voronoi cells of the
# Intel Berkeley lab deployment (54 motes, built-in data) and save a picture of them.
#   bash tools/demo.sh [--no-system-deps]
# --no-system-deps (or DVORONOI_NO_SYSTEM_DEPS=1): do not run apt-get; the C++ dependencies are
# already installed (conda-forge, Homebrew, or by an administrator: docs/getting_started.md). Without
# root and without sudo this step is skipped too. VERBOSE=1 shows CMake's and the compiler's output.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
start=$SECONDS
say() { printf '\n==> [%s, %ds] %s\n' "$(date +%H:%M:%S)" "$((SECONDS - start))" "$*"; }
# Run a quiet command, saying every 30 s that it is still at work; its exit status is the command's.
heartbeat() {
  "$@" &
  local pid=$! step=$SECONDS
  while kill -0 "$pid" 2>/dev/null; do
    sleep 5
    if [ $((SECONDS - step)) -ge 30 ] && kill -0 "$pid" 2>/dev/null; then
      echo "    ... still at work ($((SECONDS - start)) s so far)"
      step=$SECONDS
    fi
  done
  wait "$pid"
}

system_deps=1
if [ "${1:-}" = "--no-system-deps" ] || [ "${DVORONOI_NO_SYSTEM_DEPS:-0}" = "1" ]; then system_deps=0; fi
if [ "$system_deps" = 1 ] && [ "$(id -u)" -ne 0 ] && ! command -v sudo >/dev/null 2>&1; then
  say "not root and no sudo: skipping the system packages (CMake will name any that are missing)"
  system_deps=0
fi
if [ "$system_deps" = 1 ]; then
  say "step 1/3: system packages with apt-get (compiler, CMake, Eigen, CLI11, nlohmann-json, libpng)"
  heartbeat bash tools/install_system_deps.sh --build-only
else
  say "step 1/3: system packages skipped; using the C++ dependencies already installed"
fi

say "step 2/3: building and installing dvoronoi with its [plot] extra (matplotlib, tqdm)"
echo "    pip runs CMake and compiles the C++ module and the dvoronoi program: several minutes on"
echo "    two cores. VERBOSE=1 shows CMake's and the compiler's progress instead of these notes."
if [ "${VERBOSE:-0}" = "1" ]; then
  "$PY" -m pip install -v ".[plot]"
else
  heartbeat "$PY" -m pip install --quiet ".[plot]"
fi

say "step 3/3: the limited cells of the Intel lab motes (R = 3 m) -> intel_lab_cells.png"
"$PY" -m dvoronoi demo --out intel_lab_cells.png
say "done: $(pwd)/intel_lab_cells.png"
