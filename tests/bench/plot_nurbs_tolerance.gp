# The tolerance dial of the NURBS–NURBS distance: median time and achieved bracket against the requested
# tolerance, one curve per placement. Run by tests/bench/run_nurbs_benchmarks.sh with dir and out set.
set terminal pngcairo size 1100,480 font ",10"
set output out
set multiplot layout 1,2 title "NURBS–NURBS distance: the tolerance dial (exact rational tori and spheres)"
set logscale xy
set grid
set xlabel "requested tolerance / model size"
set format x "10^{%L}"
set format y "10^{%L}"
set key top right font ",8"
files = system("ls ".dir."/*.dat")
set ylabel "median query time (µs)"
plot for [f in files] f using 1:2 with linespoints lw 2 title system("basename ".f." .dat | tr _ ' '")
set ylabel "bound width (upper − lower); 0 plotted at the floor"
set key bottom right font ",8"
plot for [f in files] f using 1:($4 > 0 ? $4 : 1e-17) with linespoints lw 2 title system("basename ".f." .dat | tr _ ' '"), \
     x * 2.5 with lines dt 2 lc rgb "black" title "tolerance (absolute)"
unset multiplot
