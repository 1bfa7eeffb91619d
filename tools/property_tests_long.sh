#!/usr/bin/env bash
# The property-based tests and the fuzz corpus pass under hypothesis's "long" profile: 5000 examples
# per property and per reader instead of CI's 200 (tests/python/conftest.py; docs/guarantees.md,
# "What the tests check"). Takes about an hour on a 2-core machine; extra arguments go to pytest
# (e.g. -k limited, -x). The CGAL oracle and the CLI are used when built (DVORONOI_CGAL_ORACLE,
# DVORONOI_CLI, or build/ as cmake -B build -DDVORONOI_BUILD_TESTS=ON -DDVORONOI_BUILD_CLI=ON makes it).
#
#   bash tools/property_tests_long.sh            # PYTHON=/path/to/python to choose the interpreter
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
if [[ -z "${DVORONOI_CGAL_ORACLE:-}" && -x build/tests/oracle/dvoronoi_cgal_oracle ]]; then
    export DVORONOI_CGAL_ORACLE="$PWD/build/tests/oracle/dvoronoi_cgal_oracle"
fi
if [[ -z "${DVORONOI_CLI:-}" && -x build/cpp/cli/dvoronoi ]]; then
    export DVORONOI_CLI="$PWD/build/cpp/cli/dvoronoi"
fi
export HYPOTHESIS_PROFILE=long
exec "$PYTHON" -m pytest -q -p no:cacheprovider \
    tests/python/test_properties_cells.py tests/python/test_properties_agents.py \
    tests/python/test_properties_grids.py tests/python/test_fuzz_corpus.py "$@"
