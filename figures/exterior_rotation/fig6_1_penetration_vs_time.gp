# Thesis §6.2, Fig. 6.1: the four boxes stuck in a 2 x 2 block, pivoting as one body about the
# table's edge, integrated at dt = 1/60 s by six methods with the sticking contact forces of
# each instant. Left: the signed drift of the pivot (mean over its two points; + the block's
# material points have left the table's edge, - they have moved into the table). Right: the
# largest distance between any two material points that should coincide, log scale (exact zeros
# are not drawn).
# Data: fig6_1_penetration_vs_time.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" fig6_1_penetration_vs_time.gp
data = datadir.'/fig6_1_penetration_vs_time.dat'
array colour[6] = ["#d62728", "#ff7f0e", "#9467bd", "#1f77b4", "#2ca02c", "#17becf"]
array dash[6] = [1, 1, 2, 1, 1, 2]
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,480 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1200,480 enhanced font "DejaVu Sans,11" }
  set output outdir.'/fig6_1_penetration_vs_time.'.kind
  set multiplot layout 1,2 title "Fig. 6.1: four sticking boxes pivoting about the table's edge, dt = 1/60 s"
  set grid
  set xlabel "t (s)"
  set key top left font ",10"
  set ylabel "pivot drift (mm): + apart, - into the table"
  plot for [i=0:5] data index i using 1:($5 * 1e3) with linespoints lw 2 pt 7 ps 0.6 dt dash[i+1] \
       lc rgb colour[i+1] title columnheader(1)
  set logscale y
  set format y "10^{%L}"
  set yrange [1e-18:1e-1]
  set ylabel "largest |p_b - p_a| over all contact points (m)"
  set key at graph 0.98, 0.42 right top
  plot for [i=0:5] data index i using 1:7 with linespoints lw 2 pt 7 ps 0.6 dt dash[i+1] \
       lc rgb colour[i+1] title columnheader(1)
  unset logscale y
  set format y "%g"
  set autoscale y
  unset multiplot
  set output
}
