# The NURBS point query beside OpenCASCADE's projection: median time per query for each model and method, on a
# log scale. Run by tests/bench/run_nurbs_benchmarks.sh with data (model, then one median per method) and out set.
set terminal pngcairo size 900,460 font ",10"
set output out
set title "Point projection, 10,000 random points per model: median µs per query (log scale; lower is faster)"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set logscale y
set yrange [1:1000]
set grid ytics
set ylabel "median µs per query"
set key top left font ",9"
plot data using 2:xtic(1) title "unidist prepared", '' using 3 title "unidist prepared, first pass", \
     '' using 4 title "unidist", '' using 5 title "OCC Tree", '' using 6 title "OCC Tree MIN", '' using 7 title "OCC Grad"
