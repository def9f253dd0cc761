#!/usr/bin/env bash
# Regenerates docs/results/raster_bench.{txt,csv} and raster_resolution.png: Kim et al.'s image-space closest
# point and penetration depth through OSMesa (tests/bench/raster_bench.cpp), beside the paper's figures, and the
# PD error against the time per query over resolutions 32² … 1024² per cube face.
# usage: tests/bench/run_raster_benchmarks.sh [build-dir] [runs]   (a Release build; gnuplot for the plot)
#        PLOT_ONLY=1 tests/bench/run_raster_benchmarks.sh          redraws the plot from the committed CSV
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
source "$ROOT/tests/bench/bench_lib.sh"
BUILD="${1:-$ROOT/build}"
RUNS="${2:-5}"
OUT="$ROOT/docs/results"
mkdir -p "$OUT"
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  cmake --build "$BUILD" --target unidist_bench_raster -j2
  "$BUILD/tests/bench/unidist_bench_raster" all "$RUNS" | tee "$OUT/raster_bench.txt"
  extract_csv "$OUT/raster_bench.txt" > "$OUT/raster_bench.csv"
fi

if command -v gnuplot >/dev/null; then
  TMP="$(mktemp -d)"
  trap 'rm -rf "$TMP"' EXIT
  # One file per case: resolution, median s, pixel error, face bound, crease bound.
  awk -F, -v dir="$TMP" '$1 == "sweep" { print $3, $4, $5, $8, $9 > (dir "/" $2 ".dat") }' "$OUT/raster_bench.csv"
  gnuplot <<GP
set terminal pngcairo size 900,560 font ",10"
set output "$OUT/raster_resolution.png"
set logscale xy
set grid
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "median time per penetration-depth query (s), OSMesa llvmpipe, 2 cores"
set ylabel "error of the image answer (depth)"
set key bottom left font ",9"
set title "Image-space PD: error vs time over 32² … 1024² pixels per cube face (the CPU polish: error 0)"
files = system("ls $TMP/*.dat")
plot for [f in files] f using 2:3 with linespoints lw 2 pt 7 title system("basename ".f." .dat"), \
     for [f in files] f using 2:3:(sprintf("%d²", \$1)) with labels offset 0,0.8 font ",7" notitle
GP
fi
echo "wrote $OUT/raster_bench.{txt,csv} and raster_resolution.png"
