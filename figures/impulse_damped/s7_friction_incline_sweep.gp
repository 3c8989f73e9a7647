# Beyond the thesis (Coulomb friction), the classic incline test: a unit cube with mu = 0.5
# released on an incline of 0 to 60 degrees, its distance down the slope after 2 s against the
# angle, under the plain impulse step and under damped integration as it runs by default,
# beside Coulomb's a = g (sin - mu cos) stepped as semi-implicit Euler steps it; and the cube
# frictionless (mu = 0) under damped integration, whose damping stands in for friction (thesis
# 5.3), beside the frictionless law a = g sin stepped the same way.
# Data: s7_friction_incline_sweep.dat (angle_deg coulomb_m impulse_m damped_m frictionless_m
# damped_frictionless_m).
# Usage: gnuplot -e "datadir='...'; outdir='...'" s7_friction_incline_sweep.gp
data = datadir.'/s7_friction_incline_sweep.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 800,500 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 800,500 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s7_friction_incline_sweep.'.kind
  set title "A cube released on an incline: distance down the slope after 2 s"
  set grid
  set xlabel "incline (degrees)"
  set ylabel "distance down the slope after 2 s (m)"
  set xrange [0:60]
  set key top left Left reverse
  set arrow from 26.565,graph 0 to 26.565,graph 1 nohead dt 3 lc rgb "#7f7f7f"
  set label "atan μ = 26.6°" at 27.2,graph 0.45 tc rgb "#7f7f7f"
  plot data using 1:2 with lines lw 3 lc rgb "#bbbbbb" title "μ = 0.5: Coulomb", \
       data using 1:3 with points pt 7 ps 1.1 lc rgb "#9467bd" title "μ = 0.5: plain impulse step", \
       data using 1:4 with points pt 6 ps 1.6 lc rgb "#2ca02c" title "μ = 0.5: damped integration (damping and sleeping on)", \
       data using 1:5 with lines lw 2 dt 2 lc rgb "#7f7f7f" title "μ = 0: frictionless law", \
       data using 1:6 with points pt 5 ps 1.0 lc rgb "#ff7f0e" title "μ = 0: damped integration, the thesis' damping as friction"
  unset arrow
  unset label
  set output
}
