# Thesis §2.4.3, §5.1: what rolling back only the colliding pair buys. k independent pairs of
# cubes, each colliding once at its own instant within 30 frames: body integrations per frame
# (roll-back re-integrations included) and wall time per frame against k, log-log, for the
# basic colliding technique (every collision rolls back every body) and the three timewarps.
# Dashed grey guides grow as k and k^2 from the basic technique's value at k = 1.
# Data: s5_1_cost.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_1_cost.gp
data = datadir.'/s5_1_cost.dat'
frames = real(system("grep '^# frames:' ".data." | sed 's/^# frames: //'"))
stats data using ($2 / frames) every ::0::0 name "I1" nooutput
stats data using 6 every ::0::0 name "T1" nooutput
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1100,460 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1100,460 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_1_cost.'.kind
  set multiplot layout 1,2 title sprintf("k pairs colliding at distinct instants, %d frames of 1/60 s: basic colliding against the timewarps", frames)
  set grid
  set logscale xy
  set xrange [0.8:80]
  set xtics (1, 2, 4, 8, 16, 32, 64)
  set xlabel "colliding pairs k (2k bodies)"
  set key top left
  set ylabel "body integrations per frame"
  plot I1_min * x with lines dt 2 lc rgb "#aaaaaa" title "∝ k", \
       I1_min * x**2 with lines dt 3 lc rgb "#aaaaaa" title "∝ k^2", \
       data using 1:($2 / frames) with linespoints lw 2 pt 7 lc rgb "#888888" title "basic colliding", \
       data using 1:($7 / frames) with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "timewarp simple", \
       data using 1:($12 / frames) with linespoints lw 2 pt 9 dt 2 lc rgb "#2ca02c" title "timewarp safer", \
       data using 1:($17 / frames) with linespoints lw 2 pt 11 lc rgb "#d62728" title "timewarp swept"
  set ylabel "wall time per frame (ms, this machine)"
  plot T1_min * x with lines dt 2 lc rgb "#aaaaaa" title "∝ k", \
       T1_min * x**2 with lines dt 3 lc rgb "#aaaaaa" title "∝ k^2", \
       data using 1:6 with linespoints lw 2 pt 7 lc rgb "#888888" title "basic colliding", \
       data using 1:11 with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "timewarp simple", \
       data using 1:16 with linespoints lw 2 pt 9 dt 2 lc rgb "#2ca02c" title "timewarp safer", \
       data using 1:21 with linespoints lw 2 pt 11 lc rgb "#d62728" title "timewarp swept"
  unset multiplot
  set output
}
