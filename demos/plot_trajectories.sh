#!/usr/bin/env bash
# Plots the main demo's trajectories (centre height over time per body, Bullet solid, ODE dashed) from the
# CSVs demos/main_demo.sh writes. Usage: demos/plot_trajectories.sh DEMO_DIR OUT.png   (needs gnuplot-nox)
set -euo pipefail
DIR="$1"
OUT="$2"
BODIES=$(tail -n +2 "$DIR/trajectory_bullet.csv" | cut -d, -f3 | sort -u | tr '\n' ' ')
PLOTS=""
i=1
for b in $BODIES; do
  PLOTS+="'< grep \",$b,\" $DIR/trajectory_bullet.csv' using 2:6 with lines lw 2 lc $i title '$b (Bullet)', "
  PLOTS+="'< grep \",$b,\" $DIR/trajectory_ode.csv' using 2:6 with lines lw 2 dt 2 lc $i title '$b (ODE)', "
  i=$((i + 1))
done
gnuplot <<GP
set terminal pngcairo size 1000,600
set output "$OUT"
set datafile separator ","
set xlabel "time (s)"
set ylabel "centre height (mm)"
set title "demos/scenes/mixed.json: the same scene in Bullet (solid) and ODE (dashed) with the unidist plugin"
set key outside right noenhanced
plot ${PLOTS%, }
GP
