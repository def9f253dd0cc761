#!/usr/bin/env bash
# Fuzzes every input reader with libFuzzer (tests/fuzz/, docs/reliability.md): configures a clang build with
# ASan + UBSan and coverage instrumentation in build-fuzz/, builds the targets, runs each for a bounded time on
# its corpus and prints executions, coverage and findings per target.
#   tests/fuzz.sh [seconds-per-target, default 60] [target ...]   (targets: obj stl ply ... pose; default all)
# Exit code: 0 when no target found anything, 1 otherwise. Findings are in build-fuzz/findings/<target>/.
#   UNIDIST_FUZZ_BUILD_DIR  build directory (default: <repo>/build-fuzz)
#   UNIDIST_JOBS            parallel build jobs (default: 2)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${UNIDIST_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
SECONDS_PER_TARGET="${1:-60}"
shift || true
ALL_TARGETS=(obj stl ply xyz unurbs iges convex_pieces scene spec pose)
TARGETS=("$@")
[ "${#TARGETS[@]}" -gt 0 ] || TARGETS=("${ALL_TARGETS[@]}")

command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2; exit 2; }

mkdir -p "$BUILD"
FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DUNIDIST_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DUNIDIST_BUILD_TESTS=ON -DUNIDIST_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="$FLAGS" >"$BUILD/configure.log" 2>&1 ||
  { cat "$BUILD/configure.log" >&2; exit 2; }
cmake --build "$BUILD" -j"${UNIDIST_JOBS:-2}" --target "${TARGETS[@]/#/fuzz_}" >"$BUILD/build.log" 2>&1 ||
  { tail -40 "$BUILD/build.log" >&2; exit 2; }

# Seeds: the committed hand-made ones, then every test and shared model file of the target's format (<= 64 KB).
extensions_of() {
  case "$1" in
    obj|convex_pieces) echo "obj" ;;
    stl) echo "stl" ;;
    ply) echo "ply" ;;
    xyz) echo "xyz" ;;
    unurbs) echo "unurbs.json" ;;
    iges) echo "igs iges" ;;
    scene) echo "json" ;;
    *) echo "" ;;
  esac
}
seed_corpus() {
  local target="$1" dir="$2" ext file
  mkdir -p "$dir"
  [ -d "$ROOT/tests/fuzz/corpus/$target" ] && cp -n "$ROOT/tests/fuzz/corpus/$target"/* "$dir"/ 2>/dev/null || true
  for ext in $(extensions_of "$target"); do
    for file in "$ROOT"/tests/data/*/*."$ext" "$ROOT"/../shared/acceptance/models/*."$ext" "$ROOT"/demos/scenes/*."$ext"; do
      [ -f "$file" ] || continue
      [ "$ext" = json ] && [[ "$file" == *.unurbs.json ]] && continue  # scenes only
      [ "$(stat -c %s "$file")" -le 65536 ] && cp -n "$file" "$dir/seed_$(basename "$file")"
    done
  done
}

mkdir -p "$BUILD/fuzz-tmp"
status=0
printf '\n%-14s %12s %8s %8s %8s  %s\n' target executions cov ft corpus findings
for target in "${TARGETS[@]}"; do
  corpus="$BUILD/corpus/$target"
  findings="$BUILD/findings/$target"
  log="$BUILD/fuzz-$target.log"
  seed_corpus "$target" "$corpus"
  rm -rf "$findings" && mkdir -p "$findings"  # this run's findings only
  # The readers take paths: each process writes its input under TMPDIR (fuzz_common.h, ScratchFile).
  TMPDIR="$BUILD/fuzz-tmp" "$BUILD/tests/fuzz/fuzz_$target" "$corpus" -max_total_time="$SECONDS_PER_TARGET" \
    -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$findings/" \
    >"$log" 2>&1 || true
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  last="$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)"
  cov="$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")"
  ft="$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")"
  found="$(find "$findings" -type f | sort | tr '\n' ' ')"
  printf '%-14s %12s %8s %8s %8s  %s\n' "$target" "${runs:-?}" "${cov:-?}" "${ft:-?}" \
    "$(find "$corpus" -type f | wc -l)" "${found:-none}"
  if [ -n "$found" ] || grep -qE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehavior)|runtime error:|unidist fuzz finding' "$log"; then
    status=1
    grep -m3 -E 'ERROR:|runtime error:|unidist fuzz finding|SUMMARY' "$log" | sed 's/^/    /' || true
  fi
done
[ "$status" = 0 ] && echo "fuzz.sh: no findings" || echo "fuzz.sh: findings above (logs: $BUILD/fuzz-<target>.log)"
exit "$status"
