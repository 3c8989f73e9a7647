# Thesis §4.3: collision events per 1/60 s frame of the dropped die, and its kinetic energy,
# under the analytic method with and without sticky collisions and under the basic colliding
# technique (which stops at its limit of 100 events per frame).
# Data: s4_3_sticky_collisions.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s4_3_sticky_collisions.gp
data = datadir.'/s4_3_sticky_collisions.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1100,450 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1100,450 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s4_3_sticky_collisions.'.kind
  set multiplot layout 1,2 title "The dropped die: analytic method (LCP contact forces) against basic colliding"
  set grid
  set xlabel "time (s)"
  set ylabel "collision events per frame"
  set yrange [0:110]
  plot data using 1:6 with steps lw 2 lc rgb "#888888" title "basic colliding", \
       data using 1:4 with steps lw 2 lc rgb "#1f77b4" title "analytic", \
       data using 1:2 with steps lw 2 lc rgb "#d62728" title "analytic, sticky"
  set ylabel "kinetic energy (J)"
  set logscale y
  set yrange [1e-12:100]
  plot data using 1:($7 > 1e-12 ? $7 : 1e-12) with lines lw 2 lc rgb "#888888" title "basic colliding", \
       data using 1:($5 > 1e-12 ? $5 : 1e-12) with lines lw 2 lc rgb "#1f77b4" title "analytic", \
       data using 1:($3 > 1e-12 ? $3 : 1e-12) with lines lw 2 lc rgb "#d62728" title "analytic, sticky"
  unset logscale y
  unset multiplot
  set output
}
