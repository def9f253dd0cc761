#!/usr/bin/env bash
# The whole ctest suite under a sanitizer (docs/reliability.md, "Sanitizers"):
#   tests/sanitize.sh [address|thread] [ctest arguments...]
# address (default): AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/; thread: ThreadSanitizer in
# build-tsan/ (or $UNIDIST_SANITIZE_BUILD_DIR). Same package set-up as tests/run.sh; benchmarks are not built
# (their peers are not instrumented and they are not part of the suite). The exit code is ctest's.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
kind="${1:-address}"
shift || true
build_type=Release
case "$kind" in
  address) default_dir="$ROOT/build-asan" ;;
  thread) default_dir="$ROOT/build-tsan"; build_type=RelWithDebInfo ;;  # race reports with source lines
  *) echo "tests/sanitize.sh: unknown sanitizer '$kind' (address or thread)" >&2; exit 2 ;;
esac
build_dir="${UNIDIST_SANITIZE_BUILD_DIR:-$default_dir}"
UNIDIST_BUILD_DIR="$build_dir" "$ROOT/.ci/setup.sh" -DUNIDIST_BUILD_TESTS=ON -DUNIDIST_BUILD_BENCHMARKS=OFF \
  -DUNIDIST_SANITIZE="$kind" -DCMAKE_BUILD_TYPE="$build_type"
exec ctest --test-dir "$build_dir" --output-on-failure -j2 --no-tests=error "$@"
