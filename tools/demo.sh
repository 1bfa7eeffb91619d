#!/usr/bin/env bash
# Fresh machine -> the main job: install dvoronoi, compute the range-limited Voronoi cells of the
# Intel Berkeley lab deployment (54 motes, built-in data) and save a picture of them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_system_deps.sh --build-only
python3 -m pip install --quiet .
python3 -m dvoronoi demo --out intel_lab_cells.png
