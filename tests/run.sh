#!/usr/bin/env bash
# Install missing Debian packages (as root), build Release in build/, run the whole test suite.
# Extra arguments go to ctest (e.g. tests/run.sh -R cli). The exit code is ctest's.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/.ci/setup.sh" -DUNIDIST_BUILD_TESTS=ON
# --no-tests=error: a tree configured without tests must not pass as "all green".
exec ctest --test-dir "${UNIDIST_BUILD_DIR:-$ROOT/build}" --output-on-failure -j2 --no-tests=error "$@"
