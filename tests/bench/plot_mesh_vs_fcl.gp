# Query time against triangle count, unidist against FCL 0.7 (best of OBBRSS and RSS), generated tori.
# Run by tests/bench/run_mesh_benchmarks.sh with dir (the .dat files: triangles, ours µs, FCL µs) and out set.
set terminal pngcairo size 900,560 font ",10"
set output out
set logscale xy
set xlabel "triangles per torus"
set ylabel "median query time (µs)"
set key top left
set grid
set title "Meshes: unidist vs FCL 0.7 (same meshes and poses, same run)"
plot dir."/linked.dat"     using 1:2 with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "mesh–mesh linked tori, unidist", \
     dir."/linked.dat"     using 1:3 with linespoints lw 2 pt 7 dt 2 lc rgb "#1f77b4" title "mesh–mesh linked tori, FCL", \
     dir."/sep_0.01.dat"   using 1:2 with linespoints lw 2 pt 5 lc rgb "#d62728" title "mesh–mesh gap 1e-2, unidist", \
     dir."/sep_0.01.dat"   using 1:3 with linespoints lw 2 pt 5 dt 2 lc rgb "#d62728" title "mesh–mesh gap 1e-2, FCL", \
     dir."/point_near.dat" using 1:2 with linespoints lw 2 pt 9 lc rgb "#2ca02c" title "point → mesh (near), unidist", \
     dir."/point_near.dat" using 1:3 with linespoints lw 2 pt 9 dt 2 lc rgb "#2ca02c" title "point → mesh (near), FCL"
