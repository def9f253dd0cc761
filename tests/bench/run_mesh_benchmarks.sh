#!/usr/bin/env bash
# Regenerates docs/results/mesh_vs_fcl.{txt,csv,png}: unidist's meshes against FCL 0.7 (tests/bench/mesh_vs_fcl.cpp).
# usage: tests/bench/run_mesh_benchmarks.sh [build-dir]   (a Release build; needs libfcl-dev, and gnuplot for the plot)
#        PLOT_ONLY=1 tests/bench/run_mesh_benchmarks.sh     redraws the plot from the committed CSV
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
source "$ROOT/tests/bench/bench_lib.sh"
BUILD="${1:-$ROOT/build}"
OUT="$ROOT/docs/results"
MODELS="$ROOT/../shared/acceptance/models"
FCLDATA="$ROOT/../shared/data/fcl"
mkdir -p "$OUT"
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  cmake --build "$BUILD" --target unidist_bench_mesh_vs_fcl -j2
  : > "$OUT/mesh_vs_fcl.txt"
  for group in build tori env points; do
    "$BUILD/tests/bench/unidist_bench_mesh_vs_fcl" "$MODELS" "$FCLDATA" "$group" | tee -a "$OUT/mesh_vs_fcl.txt"
  done
  extract_csv "$OUT/mesh_vs_fcl.txt" > "$OUT/mesh_vs_fcl.csv"
fi

if command -v gnuplot >/dev/null; then
  TMP="$(mktemp -d)"
  trap 'rm -rf "$TMP"' EXIT
  # Generated tori of the same size on both sides: triangles per torus, ours, best FCL (OBBRSS or RSS).
  for c in "sep 0.01" "linked"; do
    awk -F, -v c="$c" '$1 ~ /^torus [0-9]+k\/[0-9]+k$/ && $2 == c { f = $11 < $12 ? $11 : $12; print $3, $10, f }' \
      "$OUT/mesh_vs_fcl.csv" > "$TMP/${c// /_}.dat"
  done
  awk -F, '$1 == "point" && $2 ~ /^torus/ && $3 == "near" { f = $7 < $8 ? $7 : $8; print $4, $6, f }' \
    "$OUT/mesh_vs_fcl.csv" > "$TMP/point_near.dat"
  gnuplot -e "dir='$TMP'; out='$OUT/mesh_vs_fcl.png'" "$ROOT/tests/bench/plot_mesh_vs_fcl.gp"
fi
echo "wrote $OUT/mesh_vs_fcl.{txt,csv,png}"
