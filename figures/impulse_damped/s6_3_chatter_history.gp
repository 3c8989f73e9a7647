# Thesis §6.3.1's future work, chatter detected from history: damped integration with sleeping as
# it is (blue) and with chatter detection (orange) on the die, the shot pyramid of base 10, the
# settling pile of 343 cubes and the clump of 100 on the ground. Top: when every body is asleep
# for good (a bar at the run's length with a cross: not by the end); middle: the mean kinetic
# energy of the last 2 s (log; exact zero at the axis' floor); bottom: the mean ms a step.
# Data: s6_3_chatter_history.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s6_3_chatter_history.gp
data = datadir.'/s6_3_chatter_history.dat'
atLeast(v, f) = v > f ? v : f
colour(i) = (i % 2 == 0) ? 0x1f77b4 : 0xff7f0e
x(i) = i + int(i / 2) * 0.6
label(i) = sprintf("%s %s", strcol(2), strcol(3))
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1000,900 enhanced font "DejaVu Sans,10" }
  else { set terminal svg size 1000,900 enhanced font "DejaVu Sans,10" }
  set output outdir.'/s6_3_chatter_history.'.kind
  set multiplot layout 3,1 title "Chatter detected from history (orange) against sleeping as it is (blue), damped integration"
  set style fill solid 0.8 border -1
  set boxwidth 0.8
  set grid ytics
  set xtics rotate by -25 nomirror noenhanced font ",8"
  set xrange [-0.7:10.9]
  set ylabel "every body asleep from (s)"
  set yrange [0:32]
  plot data using (x($1)):($5 < 0 ? $4 : $5):(colour(int($1))):xtic(label(0)) with boxes lc rgb variable notitle, \
       data using (x($1)):($5 < 0 ? $4 : 1/0) with points pt 2 ps 2 lc rgb "black" title "not by the end of the run"
  set logscale y
  set ylabel "kinetic energy, last 2 s (J)"
  set yrange [1e-12:1e3]
  plot data using (x($1)):(atLeast($6, 1e-12)):(colour(int($1))):xtic(label(0)) with boxes lc rgb variable notitle
  unset logscale y
  set ylabel "ms per step"
  set autoscale y
  set yrange [0:*]
  plot data using (x($1)):7:(colour(int($1))):xtic(label(0)) with boxes lc rgb variable notitle
  unset multiplot
  set output
}
