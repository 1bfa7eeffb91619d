#!/usr/bin/env bash
# Fresh machine -> every test: system packages, the Python package with its test extras, the wheel, the C++
# tests (unit tests and the CGAL oracle target) under ctest, the C++ unit tests again under
# AddressSanitizer and UndefinedBehaviorSanitizer, the docs site, then pytest (API, CLI, oracle, docs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_system_deps.sh
python3 -m pip install --quiet ".[test]"
# mpi4py for the MPI tests: the PyPI wheel loads the system OpenMPI; if it cannot, build it against it.
python3 -m pip install --quiet "mpi4py>=3.1"
if ! python3 -c "from mpi4py import MPI" 2>/dev/null; then
  python3 -m pip install --quiet --force-reinstall --no-binary mpi4py "mpi4py>=3.1"
fi
# The wheel a user would get: its contents (module, program, py.typed, stubs) and a fresh venv that
# installs it and runs the library, `dvoronoi` and `python -m dvoronoi`.
python3 -m pip install --quiet "scikit-build-core>=0.10" "pybind11>=2.12"
bash tools/check_wheel.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDVORONOI_BUILD_TESTS=ON -DDVORONOI_BUILD_CLI=ON
cmake --build build -j "$(nproc)"
ctest --test-dir build --output-on-failure
# Sanitizers, in a build directory of their own: every tests/cpp executable (the dvoronoi_unit_tests
# target) with ASan + UBSan; -fno-sanitize-recover makes any UB report fail its test, and ASan reports
# and leaks fail theirs. The CGAL oracle targets (label "oracle") are not built here: instrumenting
# CGAL's exact kernel costs time on code that is not ours, and the dvoronoi code they run the unit
# tests run too.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DDVORONOI_BUILD_TESTS=ON -DDVORONOI_BUILD_CLI=OFF \
  -DDVORONOI_BUILD_MPI=OFF \
  -DCMAKE_CXX_FLAGS="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
cmake --build build-sanitize -j "$(nproc)" --target dvoronoi_unit_tests
UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir build-sanitize -LE oracle -j "$(nproc)" --output-on-failure
# The docs site (Sphinx + MyST, docs/conf.py), every warning an error; its code blocks run under pytest
# (tests/python/test_docs_snippets.py).
python3 -m sphinx -W --keep-going -b html docs build/docs
DVORONOI_CGAL_ORACLE="$PWD/build/tests/oracle/dvoronoi_cgal_oracle" \
DVORONOI_CLI="$PWD/build/cpp/cli/dvoronoi" \
DVORONOI_GVD_MPI="$PWD/build/cpp/mpi/dvoronoi_gvd_mpi" \
  python3 -m pytest tests/python -q
