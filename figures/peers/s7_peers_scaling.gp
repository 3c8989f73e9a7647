# Side by side with Bullet and ODE: mean ms per step against the number of unit cubes in the
# clump of Fig. 6.7 (cubes flying towards its centre, falling onto the ground and piling up)
# at restitution 0, log-log, for boxsim's damped integration (as the thesis, with friction,
# with chatter detection, with impact passes, with damping of supported bodies only, on two
# threads) and every peer engine the harness was built with.
# Points: the mean step over every repetition; error bars: the range of the repetitions' means;
# dashed: the 95th percentile. The grey dashed guide grows as n from the damped mean at 100 cubes; the
# dotted line is real time at 60 Hz (16.7 ms).
# Data: s7_peers_scaling.dat, written by boxsim_peers (rows: boxes "engine" mean_ms median_ms
# p95_ms rep_min_ms rep_max_ms seconds).
# Usage: gnuplot -e "datadir='...'; outdir='...'" s7_peers_scaling.gp
data = datadir.'/s7_peers_scaling.dat'
seconds = system("grep -v '^#' ".data." | head -n 1 | awk '{print $NF}'")
stamp = system("sed -n 's/^# date: \\(.*\\)/\\1/p' ".data)
commit = system("sed -n 's/^# commit: \\(.*\\)/\\1/p' ".data)
engines = system("grep -v '^#' ".data." | sed 's/^[0-9]* \"\\([^\"]*\\)\".*/\\1/' | awk '!seen[$0]++' | tr ' ' '_' | tr '\\n' ' '")
stats data using 1:(strcol(2) eq "boxsim damped" ? $3 : NaN) nooutput name "D"
colour(i) = word("#d62728 #1f77b4 #2ca02c #ff7f0e #9467bd #8c564b #e377c2 #7f7f7f #bcbd22 #17becf #393b79 #637939", i)
label(e) = system("echo '".e."' | tr '_' ' '")
# One engine's rows alone, so its points join into one line.
rows(e) = "< grep -F '\"".label(e)."\"' ".data
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1300,600 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1300,600 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s7_peers_scaling.'.kind
  set title sprintf("Clump of n unit cubes, restitution 0, Δt = 1/60 s, one thread unless marked: ms per step over %s s\n{/*0.8 measured %s at %s}", seconds, stamp, commit)
  set grid
  set logscale xy
  set xrange [80:12500]
  set xlabel "cubes n"
  set ylabel "ms per step (this machine)"
  # Outside the plot: inside, the entries covered the lines at 100-1000 cubes.
  set key outside right top Left reverse samplen 2
  plot D_min_y * (x / D_min_x) with lines dt 2 lc rgb "#aaaaaa" title "∝ n", \
       16.7 with lines dt 3 lc rgb "#555555" title "60 Hz", \
       for [i = 1:words(engines)] rows(word(engines, i)) using 1:3:6:7 \
         with yerrorlines lw 2 pt 7 lc rgb colour(i) title label(word(engines, i)).", mean", \
       for [i = 1:words(engines)] rows(word(engines, i)) using 1:5 \
         with linespoints lw 1 dt 2 pt 6 lc rgb colour(i) title label(word(engines, i)).", 95th percentile"
  set output
}
