# Thesis §6.2, Fig. 6.1: the top box TR of the four sticking boxes should follow a circle about
# the table's edge. Left: its centre's path under each integrator at dt = 1/60 s against that
# circle (grey). Right: its distance from the pivot minus the circle's radius, against the
# group's rotation (+ outside the circle).
# Data: fig6_1_top_box_path.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" fig6_1_top_box_path.gp
data = datadir.'/fig6_1_top_box_path.dat'
array colour[6] = ["#d62728", "#ff7f0e", "#9467bd", "#1f77b4", "#2ca02c", "#17becf"]
array dash[6] = [1, 1, 2, 1, 1, 2]
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,520 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1200,520 enhanced font "DejaVu Sans,11" }
  set output outdir.'/fig6_1_top_box_path.'.kind
  set multiplot layout 1,2 title "Fig. 6.1: the top box's centre against its circle about the pivot, dt = 1/60 s"
  set grid
  set size ratio -1
  set xlabel "x (m)"
  set ylabel "y (m)"
  set xrange [0.06:0.34]
  set yrange [0.1:0.3]
  set key at graph 0.02, 0.02 left bottom Left reverse font ",9"
  plot data index 6 using 2:3 with lines lw 6 lc rgb "#cccccc" title columnheader(1), \
       for [i=0:5] data index i using 2:3 with linespoints lw 1.5 pt 7 ps 0.5 dt dash[i+1] \
       lc rgb colour[i+1] title columnheader(1)
  set size noratio
  set autoscale xy
  set xlabel "rotation of the group (degrees, clockwise)"
  set ylabel "radial error of the top box (mm; + outside the circle)"
  set key default
  set key top left font ",9"
  plot for [i=0:5] data index i using 7:($6 * 1e3) with linespoints lw 2 pt 7 ps 0.6 dt dash[i+1] \
       lc rgb colour[i+1] title columnheader(1)
  unset multiplot
  set output
}
