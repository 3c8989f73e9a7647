# Beyond the thesis (Coulomb friction), the classic incline test: a unit cube with mu = 0.5
# released on an incline of 0 to 60 degrees, its distance down the slope after 2 s against the
# angle, under the plain impulse step and under damped integration as it runs by default,
# beside Coulomb's a = g (sin - mu cos) stepped as semi-implicit Euler steps it.
# Data: s7_friction_incline_sweep.dat (angle_deg coulomb_m impulse_m damped_m).
# Usage: gnuplot -e "datadir='...'; outdir='...'" s7_friction_incline_sweep.gp
data = datadir.'/s7_friction_incline_sweep.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 800,500 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 800,500 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s7_friction_incline_sweep.'.kind
  set title "A cube with μ = 0.5 released on an incline: distance down the slope after 2 s"
  set grid
  set xlabel "incline (degrees)"
  set ylabel "distance down the slope after 2 s (m)"
  set xrange [0:60]
  set key top left Left reverse
  set arrow from 26.565,graph 0 to 26.565,graph 1 nohead dt 3 lc rgb "#7f7f7f"
  set label "atan μ = 26.6°" at 27.2,graph 0.45 tc rgb "#7f7f7f"
  plot data using 1:2 with lines lw 3 lc rgb "#bbbbbb" title "Coulomb", \
       data using 1:3 with points pt 7 ps 1.1 lc rgb "#9467bd" title "plain impulse step", \
       data using 1:4 with points pt 6 ps 1.6 lc rgb "#2ca02c" title "damped integration (damping and sleeping on)"
  unset arrow
  unset label
  set output
}
