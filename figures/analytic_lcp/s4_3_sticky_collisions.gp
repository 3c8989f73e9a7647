# Thesis §4.3: collision events per 1/60 s frame of the dropped die, and its kinetic energy,
# under the analytic method with and without sticky collisions and under the basic colliding
# technique (which stops at its limit of 100 events per frame). Top: the analytic method as
# shipped, with its drift correction; bottom: in the thesis' regime, without it.
# Data: s4_3_sticky_collisions.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s4_3_sticky_collisions.gp
data = datadir.'/s4_3_sticky_collisions.dat'
floorJ(v) = v > 1e-12 ? v : 1e-12
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1100,800 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1100,800 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s4_3_sticky_collisions.'.kind
  set multiplot layout 2,2 title "The dropped die: analytic method (LCP contact forces) against basic colliding"
  set grid
  set xlabel "time (s)"
  do for [regime = 0:1] {
    set ylabel "collision events per frame"
    set yrange [0:110]
    set title (regime == 0 ? "with the drift correction (shipped)" : "without it (the thesis' regime)")
    if (regime == 0) {
      plot data using 1:6 with steps lw 2 lc rgb "#888888" title "basic colliding", \
           data using 1:4 with steps lw 2 lc rgb "#1f77b4" title "analytic", \
           data using 1:2 with steps lw 2 lc rgb "#d62728" title "analytic, sticky"
    } else {
      plot data using 1:6 with steps lw 2 lc rgb "#888888" title "basic colliding", \
           data using 1:10 with steps lw 2 lc rgb "#1f77b4" title "analytic", \
           data using 1:8 with steps lw 2 lc rgb "#d62728" title "analytic, sticky"
    }
    set ylabel "kinetic energy (J)"
    set logscale y
    set yrange [1e-12:100]
    if (regime == 0) {
      plot data using 1:(floorJ($7)) with lines lw 2 lc rgb "#888888" title "basic colliding", \
           data using 1:(floorJ($5)) with lines lw 2 lc rgb "#1f77b4" title "analytic", \
           data using 1:(floorJ($3)) with lines lw 2 lc rgb "#d62728" title "analytic, sticky"
    } else {
      plot data using 1:(floorJ($7)) with lines lw 2 lc rgb "#888888" title "basic colliding", \
           data using 1:(floorJ($11)) with lines lw 2 lc rgb "#1f77b4" title "analytic", \
           data using 1:(floorJ($9)) with lines lw 2 lc rgb "#d62728" title "analytic, sticky"
    }
    unset logscale y
  }
  unset multiplot
  set output
}
