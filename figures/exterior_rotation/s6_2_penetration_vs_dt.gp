# Thesis §6.2 and its footnote (would Runge-Kutta help?): the largest distance between any two
# material points that should coincide, over each scene's window, against dt (1/60 s and four
# halvings), log-log, one line per integrator; the key gives the least-squares slope. Runs at
# rounding (the screw update on a single hinge) have no slope and show as points near 1e-16.
# Data: s6_2_penetration_vs_dt.dat (blocks scene-major: 6 methods per scene).
# Usage: gnuplot -e "datadir='...'; outdir='...'" s6_2_penetration_vs_dt.gp
data = datadir.'/s6_2_penetration_vs_dt.dat'
array colour[6] = ["#d62728", "#ff7f0e", "#9467bd", "#1f77b4", "#2ca02c", "#17becf"]
array dash[6] = [1, 1, 2, 1, 1, 2]
array sceneTitle[3] = ["Fig. 6.1: four boxes, one pivot", "Fig. 6.2: one box, one pivot", "Fig. 6.3: double hinge"]
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1650,560 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1650,560 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s6_2_penetration_vs_dt.'.kind
  set multiplot layout 1,3 title "Largest contact-point drift over the window against the step, sticking contact forces of each instant"
  set grid
  set logscale xy
  set format y "10^{%L}"
  set xrange [0.0009:0.019]
  set yrange [1e-18:1e-1]
  set xtics ("1/960" 1.0/960, "1/480" 1.0/480, "1/240" 1.0/240, "1/120" 1.0/120, "1/60" 1.0/60)
  set xlabel "dt (s)"
  set ylabel "largest |p_b - p_a| (m)"
  set key at graph 0.02, 0.76 left top Left reverse font ",9" spacing 1.0
  do for [s=0:2] {
    set title sceneTitle[s+1]
    plot for [i=0:5] data index (6 * s + i) using 1:2 with linespoints lw 2 pt 7 ps 0.7 dt dash[i+1] \
         lc rgb colour[i+1] title columnheader(1)
  }
  unset multiplot
  set output
}
