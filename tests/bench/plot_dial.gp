# The tolerance dial of one pair family: left, the Pareto curve (median time against the largest true error,
# ours labelled with the requested tolerance, peers at each setting of their own dial); right, the true error
# against the requested tolerance (or the peer's setting). Run by tests/bench/run_dial_benchmarks.sh with dir,
# out and family set; dir holds one file per method: tolerance, median µs, p90 µs, max error, median error,
# median bound width, share certified (errors and widths relative to the model size).
set terminal pngcairo size 1280,520 font ",10"
set output out
set multiplot layout 1,2 title "Tolerance dial, ".family." (errors relative to model size; 0 drawn at 10^{-17})"
set logscale xy
set grid
set format x "10^{%L}"
set format y "10^{%L}"
shown(v) = v > 1e-17 ? v : 1e-17
files = system("ls ".dir."/*.dat")
ours = system("ls ".dir."/0_*.dat")
title_of(f) = system("basename '".f."' .dat | sed 's/^[0-9]*_//; s/_/ /g'")
set xlabel "largest true error"
set ylabel "median time per query (µs)"
set key top right font ",8"
plot for [f in files] f using (shown($4)):2 with linespoints lw 2 pt 7 ps 0.6 title title_of(f), \
     ours using (shown($4)):2:(sprintf("%.0e", $1)) with labels offset 1.6,0.6 font ",7" notitle
set xlabel "requested tolerance (peers: their dial)"
set ylabel "true error, bound width"
set key bottom right font ",8"
plot for [f in files] f using 1:(shown($4)) with linespoints lw 2 pt 7 ps 0.6 title title_of(f)." (largest)", \
     ours using 1:(shown($5)) with linespoints dt 2 lc rgb "gray30" title "unidist (median)", \
     ours using 1:(shown($6)) with linespoints dt 3 lc rgb "dark-green" title "unidist bound width (median)", \
     x with lines dt 2 lc rgb "black" title "error = tolerance"
unset multiplot
