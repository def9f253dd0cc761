#!/usr/bin/env bash
# Regenerates docs/results/nurbs_vs_occt.{txt,csv}, nurbs_overlap.txt, nurbs_pairs_random.txt,
# nurbs_convex_depth.txt and nurbs_tolerance.png: unidist's NURBS queries beside OpenCASCADE 7.6
# (tests/bench/nurbs_vs_occt.cpp), our time and error against the tolerance, the point query medians beside
# OpenCASCADE's (nurbs_points.png), surface pairs in random poses (nurbs_pair_profile.cpp random), and the
# penetration depth of non-convex and of convex NURBS solids (nurbs_overlap_bench.cpp, nurbs_convex_depth_bench.cpp).
# usage: tests/bench/run_nurbs_benchmarks.sh [build-dir] [points-per-model]
#        (a Release build; needs libocct-modeling-algorithms-dev and libtbb-dev, and gnuplot for the plot)
#        PLOT_ONLY=1 tests/bench/run_nurbs_benchmarks.sh    redraws the plot from the committed CSV
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
source "$ROOT/tests/bench/bench_lib.sh"
BUILD="${1:-$ROOT/build}"
POINTS="${2:-10000}"
OUT="$ROOT/docs/results"
mkdir -p "$OUT"
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  cmake --build "$BUILD" --target unidist_bench_nurbs_vs_occt -j2
  : > "$OUT/nurbs_vs_occt.txt"
  for group in points pairs tolerance; do
    "$BUILD/tests/bench/unidist_bench_nurbs_vs_occt" "$group" "$POINTS" | tee -a "$OUT/nurbs_vs_occt.txt"
  done
  extract_csv "$OUT/nurbs_vs_occt.txt" > "$OUT/nurbs_vs_occt.csv"
  # Non-convex NURBS penetration depth by depth band (no peer answers it).
  cmake --build "$BUILD" --target unidist_bench_nurbs_overlap -j2
  "$BUILD/tests/bench/unidist_bench_nurbs_overlap" 20 | tee "$OUT/nurbs_overlap.txt"
  "$BUILD/tests/bench/unidist_bench_nurbs_overlap" 60 1e-9 sweep | tee -a "$OUT/nurbs_overlap.txt"
  # Surface pairs in random separated poses (ours alone): what a speed-up of the fixed placements must not lose.
  cmake --build "$BUILD" --target unidist_bench_nurbs_pair_profile -j2
  "$BUILD/tests/bench/unidist_bench_nurbs_pair_profile" random 200 | tee "$OUT/nurbs_pairs_random.txt"
  # Convex NURBS penetration depth beside FCL's ellipsoids (built where FCL is found).
  if cmake --build "$BUILD" --target unidist_bench_nurbs_convex_depth -j2 >/dev/null 2>&1; then
    "$BUILD/tests/bench/unidist_bench_nurbs_convex_depth" 40 | tee "$OUT/nurbs_convex_depth.txt"
  fi
fi

if command -v gnuplot >/dev/null; then
  TMP="$(mktemp -d)"
  trap 'rm -rf "$TMP"' EXIT
  # One file per placement: relative tolerance, median µs, error, bound width.
  awk -F, -v dir="$TMP" '$1 == "tolerance" { name = $2; gsub(/ /, "_", name); print $3, $4, $5, $6 > (dir "/" name ".dat") }' \
    "$OUT/nurbs_vs_occt.csv"
  gnuplot -e "dir='$TMP'; out='$OUT/nurbs_tolerance.png'" "$ROOT/tests/bench/plot_nurbs_tolerance.gp"
  # Point medians: one row per model, columns in the plot's order.
  awk -F, '$1 == "point" { m[$2 "|" $3] = $5; if (!($2 in seen)) { seen[$2] = 1; order[++n] = $2 } }
    END { for (i = 1; i <= n; ++i) { k = order[i]; name = k; gsub(/ /, "-", name)
            printf "%s %s %s %s %s %s %s\n", name, m[k "|unidist prepared"], m[k "|unidist prepared cold"],
                   m[k "|unidist"], m[k "|occt Tree"], m[k "|occt Tree MIN"], m[k "|occt Grad"] } }' \
    "$OUT/nurbs_vs_occt.csv" > "$TMP/points.dat"
  gnuplot -e "data='$TMP/points.dat'; out='$OUT/nurbs_points.png'" "$ROOT/tests/bench/plot_nurbs_points.gp"
fi
echo "wrote $OUT/nurbs_vs_occt.{txt,csv}, nurbs_tolerance.png and nurbs_points.png"
