# Thesis Fig. 5.2 (§5.3): damping against Newtonian friction along a chain. Box A slides at
# 2 m/s on box B, which rests on frictionless ground. Damped integration as the thesis has it
# (frictionless, its damping standing in for friction) slows A and never moves B; Coulomb
# friction (mu = 0.5 between A and B, closed form) slows A by the force that drags B along
# (the caption's force B), until both move at 1 m/s, the velocity momentum conservation gives.
# Data: fig5_2_damping_vs_friction.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" fig5_2_damping_vs_friction.gp
data = datadir.'/fig5_2_damping_vs_friction.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 800,450 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 800,450 enhanced font "DejaVu Sans,11" }
  set output outdir.'/fig5_2_damping_vs_friction.'.kind
  set title "Fig. 5.2: A slides on B, B on frictionless ground"
  set grid
  set xlabel "time (s)"
  set ylabel "velocity along the slide (m/s)"
  set yrange [-0.1:2.2]
  set key top right
  plot data using 1:2 with lines lw 2 lc rgb "#1f77b4" title "A, damped integration", \
       data using 1:3 with lines lw 2 dt 2 lc rgb "#1f77b4" title "B, damped integration", \
       data using 1:4 with lines lw 2 lc rgb "#d62728" title "A, Coulomb friction (closed form)", \
       data using 1:5 with lines lw 2 dt 2 lc rgb "#d62728" title "B, Coulomb friction (closed form)"
  set output
}
