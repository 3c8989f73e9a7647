# Thesis §2.1: the die under the basic colliding technique. Top: height of its centre and of
# its lowest corner under semi-implicit Euler (the default), and its centre under forward Euler
# (the thesis' integrator), which pumps in energy until it balances restitution and never lets
# the die rest. Bottom: energies. Data: s2_1_die_height_energy.dat
# Usage: gnuplot -e "datadir='...'; outdir='...'" s2_1_die_height_energy.gp
data = datadir.'/s2_1_die_height_energy.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1000,750 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1000,750 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s2_1_die_height_energy.'.kind
  set multiplot layout 2,1 title "Basic colliding technique (§2.1): a die tilted 10° dropped from 2 m, e = 0.9, Δt = 1/60 s"
  set grid
  set key top right
  set xlabel "time (s)"
  set ylabel "height (m)"
  plot data using 1:7 with lines lw 1.5 lc rgb "#bbbbbb" title "centre, forward Euler", \
       data using 1:2 with lines lw 2 lc rgb "#1f77b4" title "centre, semi-implicit Euler", \
       data using 1:3 with lines lw 1.5 lc rgb "#ff7f0e" title "lowest corner, semi-implicit Euler"
  set ylabel "energy (J)"
  plot data using 1:9 with lines lw 1.5 lc rgb "#bbbbbb" title "total, forward Euler", \
       data using 1:4 with lines lw 1.5 lc rgb "#d62728" title "kinetic", \
       data using 1:5 with lines lw 1.5 lc rgb "#2ca02c" title "potential", \
       data using 1:6 with lines lw 2 lc rgb "black" title "total"
  unset multiplot
  set output
}
