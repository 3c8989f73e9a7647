# Beyond the thesis (Coulomb friction): a unit cube with mu = 0.5 released on inclines of 20 to
# 45 degrees, distance down the slope against time, beside Coulomb's a = g (sin - mu cos),
# stepped as semi-implicit Euler steps it (dashed). Three panels: the plain impulse step,
# damped integration with damping and sleeping off, damped integration as the thesis has it.
# Data: s7_friction_incline.dat (columns per angle: coulomb, impulse, damped_undamped, damped).
# Usage: gnuplot -e "datadir='...'; outdir='...'" s7_friction_incline.gp
data = datadir.'/s7_friction_incline.dat'
angles = "20 25 30 35 45"
colour(i) = word("#7f7f7f #9467bd #1f77b4 #2ca02c #d62728", i)
col(i, what) = 1 + 4 * (i - 1) + what
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,430 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1200,430 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s7_friction_incline.'.kind
  set multiplot layout 1,3 title "A cube with μ = 0.5 on an incline: distance down the slope (dashed: Coulomb, a = g (sin θ − μ cos θ); sticks below atan μ = 26.6°)"
  set grid
  set xlabel "time (s)"
  set ylabel "distance down the slope (m)"
  set yrange [-0.2:7.5]
  set key top left
  do for [panel = 1:3] {
    set title (panel == 1 ? "plain impulse step" : panel == 2 ? "damped, damping and sleeping off" : "damped, as the thesis (damping on)")
    plot for [i = 1:words(angles)] data using 1:col(i, panel + 1) with lines lw 2 lc rgb colour(i) title word(angles, i)."°", \
         for [i = 1:words(angles)] data using 1:col(i, 1) with lines lw 1 dt 2 lc rgb colour(i) notitle
  }
  unset multiplot
  set output
}
