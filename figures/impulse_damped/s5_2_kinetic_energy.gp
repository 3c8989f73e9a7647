# Thesis §5.2, §6.1: kinetic energy against time (log scale) of the die, the tower of 10 and the
# base-10 pyramid (shot at t = 5 s), under the plain impulse-based step and damped integration.
# Exact zeros (bodies at rest) are drawn at the floor of the axis. Data: s5_2_kinetic_energy.dat
# Usage: gnuplot -e "datadir='...'; outdir='...'" s5_2_kinetic_energy.gp
data = datadir.'/s5_2_kinetic_energy.dat'
floor = 1e-12
clip(x) = x > floor ? x : floor
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,450 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1200,450 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_2_kinetic_energy.'.kind
  set multiplot layout 1,3 title "Kinetic energy: plain impulse-based step against damped integration (Δt = 1/60 s; 10^{-12} J stands for exactly 0)"
  set logscale y
  set yrange [floor/2:1e4]
  set format y "10^{%L}"
  set grid
  set xlabel "time (s)"
  set ylabel "kinetic energy (J)"
  set key top right
  set title "die"
  plot data using 1:(clip($2)) with lines lw 1.5 lc rgb "#d62728" title "impulse", \
       data using 1:(clip($3)) with lines lw 2 lc rgb "#1f77b4" title "damped"
  set title "tower of 10"
  plot data using 1:(clip($4)) with lines lw 1.5 lc rgb "#d62728" title "impulse", \
       data using 1:(clip($5)) with lines lw 2 lc rgb "#1f77b4" title "damped"
  set title "pyramid of base 10, shot at 5 s"
  plot data using 1:(clip($6)) with lines lw 1.5 lc rgb "#d62728" title "impulse", \
       data using 1:(clip($7)) with lines lw 2 lc rgb "#1f77b4" title "damped"
  unset multiplot
  set output
}
