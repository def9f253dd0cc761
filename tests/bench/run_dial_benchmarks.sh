#!/usr/bin/env bash
# Regenerates docs/results/dial.{csv,txt}, dial_compute.csv and docs/results/dial_<family>.png: the tolerance dial of every pair
# family (tests/bench/dial_bench.cpp), with FCL, OpenCASCADE and Bullet on the same inputs where installed.
# usage: tests/bench/run_dial_benchmarks.sh [build-dir] [poses-per-kind]   (a Release build; gnuplot for the plots)
#        PLOT_ONLY=1 tests/bench/run_dial_benchmarks.sh                    redraws the plots from the committed CSV
#        DIAL_VERBOSE=1 also prints every single answer to dial.txt
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${1:-$ROOT/build}"
POSES="${2:-8}"
OUT="$ROOT/docs/results"
mkdir -p "$OUT"
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  cmake --build "$BUILD" --target unidist_bench_dial -j2
  start=$(date +%s)
  nice "$BUILD/tests/bench/unidist_bench_dial" all "$POSES" > "$OUT/dial.csv.new" 2> "$OUT/dial.txt"
  mv "$OUT/dial.csv.new" "$OUT/dial.csv"
  nice "$BUILD/tests/bench/unidist_bench_dial" compute "$POSES" > "$OUT/dial_compute.csv"
  echo "run time: $(( $(date +%s) - start )) s, $POSES poses per kind" >> "$OUT/dial.txt"
fi

if command -v gnuplot >/dev/null; then
  TMP="$(mktemp -d)"
  trap 'rm -rf "$TMP"' EXIT
  # One directory per family, one file per method (ours first): tolerance, median and p90 µs, largest and
  # median error, median bound width, share certified. Answers that failed (infinite error) are left out.
  awk -F, -v dir="$TMP" 'NR > 1 && $6 != "inf" && $6 != "nan" {
      if (!(($1, $2) in index_of)) index_of[$1, $2] = count[$1]++
      name = $2; gsub(/[ \/]/, "_", name)
      system("mkdir -p " dir "/" $1)
      file = dir "/" $1 "/" index_of[$1, $2] "_" name ".dat"
      print $3, $4, $5, $6, $7, $8, $9 > file
    }' "$OUT/dial.csv"
  for family in "$TMP"/*/; do
    family="$(basename "$family")"
    gnuplot -e "dir='$TMP/$family'; out='$OUT/dial_$family.png'; family='$family'" "$ROOT/tests/bench/plot_dial.gp"
  done
fi
echo "wrote $OUT/dial.{csv,txt} and dial_<family>.png"
