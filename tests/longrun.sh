#!/bin/bash
# The full long runs (docs/reliability.md, "Long runs"): tests/longrun/stack.json stepped 100,000 times (or the
# first argument) in Bullet and then in ODE, each run twice in one process (the rerun must be bitwise equal), every
# step checked against the bounds unidist_longrun prints. Exit status 1 on any violation.
# Builds unidist_longrun first, in build/ (Release) or in $UNIDIST_BUILD_DIR. Takes about 10 minutes per engine
# at 100,000 steps on a shared 2-core machine; extra arguments go to unidist_longrun (e.g. --no-rerun).
set -euo pipefail
steps="${1:-100000}"
shift || true
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${UNIDIST_BUILD_DIR:-$root/build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" --target unidist_longrun -j2
status=0
for engine in bullet ode; do
  nice "$build/tests/longrun/unidist_longrun" --engine "$engine" --steps "$steps" "$@" || status=1
done
exit "$status"
