#!/usr/bin/env bash
# Regenerates docs/results/{accuracy.csv, primitives_vs_fcl.csv, primitives_vs_fcl.png} from a Release build.
# usage: tests/bench/run_primitive_benchmarks.sh [build-dir]   (needs gnuplot for the plot: apt-get install gnuplot-nox)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${1:-$ROOT/build}"
OUT="$ROOT/docs/results"
mkdir -p "$OUT"
cmake --build "$BUILD" --target unidist_accuracy unidist_bench_primitives -j2

"$BUILD/tests/bench/unidist_accuracy" 50 > "$OUT/accuracy.csv"
"$BUILD/tests/bench/unidist_bench_primitives" --benchmark_format=csv --benchmark_repetitions=5 \
  --benchmark_report_aggregates_only=true 2>/dev/null > "$OUT/primitives_vs_fcl.csv"

# Median time per pair and regime for each engine, side by side: pair,regime,unidist,fcl_libccd,fcl_indep,max_diff.
python3 - "$OUT/primitives_vs_fcl.csv" > "$OUT/primitives_vs_fcl_medians.csv" <<'PY'
import csv, sys
rows = {}
header = None
with open(sys.argv[1]) as f:
    lines = [l for l in f if not l.startswith(('Run on', 'CPU', '  L', 'Load', '***', 'WARNING'))]
for r in csv.DictReader(lines):
    name = r['name'].strip('"')
    if not name.endswith('_median'):
        continue
    pair, regime, engine = name[:-len('_median')].split('/')
    cell = rows.setdefault((pair, regime), {})
    cell[engine] = float(r['real_time']) / 1000.0  # ns -> us
    if engine == 'unidist':
        cell['max_diff'] = r.get('max_diff', '')
print('pair,regime,unidist_us,fcl_libccd_us,fcl_indep_us,ratio_vs_best_fcl,max_abs_diff_vs_fcl')
for (pair, regime), c in rows.items():
    best = min(c.get('fcl_libccd', 1e300), c.get('fcl_indep', 1e300))
    print(f"{pair},{regime},{c['unidist']:.3f},{c.get('fcl_libccd', 0):.3f},{c.get('fcl_indep', 0):.3f},"
          f"{c['unidist'] / best:.2f},{c['max_diff']}")
PY

if command -v gnuplot >/dev/null; then
  gnuplot <<GP
set terminal pngcairo size 1100,520 font ",10"
set output "$OUT/primitives_vs_fcl.png"
set datafile separator ","
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set logscale y
set ylabel "median query time (µs, log)"
set xtics rotate by -40 scale 0
set key top left
set title "Primitive pairs: unidist vs FCL 0.7 (same poses, same run; 64 configurations each)"
plot "$OUT/primitives_vs_fcl_medians.csv" every ::1 using 3:xticlabels(stringcolumn(1).' '.stringcolumn(2)) title "unidist", \
     "" every ::1 using 4 title "FCL (libccd GJK/EPA)", "" every ::1 using 5 title "FCL (own GJK/EPA)"
GP
fi
echo "wrote $OUT"
