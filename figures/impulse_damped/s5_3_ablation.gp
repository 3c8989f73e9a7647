# Thesis §5.2-§5.4: which of damped integration's techniques stops the chatter. Damped
# integration whole, then with one technique off at a time (damping, FIXCONTACTCONSTRAINTS,
# geometric stability, sleeping, contacts gathered every pass as A.2 writes it), and the plain
# impulse step, on the die (6-8 s), the tower of 10 (2-8 s) and the base-10 pyramid before the
# shot (2-5 s). Top: sign changes of a body's vertical velocity (|v| > 1e-4 m/s) per body and
# second; middle: the largest vertical jitter of any body; bottom: the mean kinetic energy over
# the window. Log scales; exact zero is drawn at the axis' floor.
# Data: s5_3_ablation.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_3_ablation.gp
data = datadir.'/s5_3_ablation.dat'
atLeast(v, f) = v > f ? v : f
# One colour per variant, in the data's order: damped, no damping, no FIXCONTACTCONSTRAINTS, no
# geometric stability, no sleeping, every pass, plain impulse (red).
colour(i) = (i % 7 == 0) ? 0x1f77b4 : (i % 7 == 1) ? 0xff7f0e : (i % 7 == 2) ? 0x2ca02c : \
            (i % 7 == 3) ? 0x9467bd : (i % 7 == 4) ? 0x8c564b : (i % 7 == 5) ? 0x17becf : 0xd62728
label(i) = sprintf("%s %s", strcol(2), strcol(3))
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,900 enhanced font "DejaVu Sans,10" }
  else { set terminal svg size 1200,900 enhanced font "DejaVu Sans,10" }
  set output outdir.'/s5_3_ablation.'.kind
  set multiplot layout 3,1 title "Damped integration with one technique off at a time, and the plain impulse step (red): chatter once settled"
  set style fill solid 0.8 border -1
  set boxwidth 0.7
  set grid ytics
  set logscale y
  set xtics rotate by -35 nomirror noenhanced font ",8"
  set xrange [-0.7:20.7]
  # Scene boundaries.
  set arrow 1 from 6.5, graph 0 to 6.5, graph 1 nohead dt 2 lc rgb "#888888"
  set arrow 2 from 13.5, graph 0 to 13.5, graph 1 nohead dt 2 lc rgb "#888888"
  set label 1 "die" at 3, graph 0.92 center
  set label 2 "tower of 10" at 10, graph 0.92 center
  set label 3 "pyramid of base 10" at 17, graph 0.92 center
  set ylabel "sign changes / body / s"
  set yrange [0.01:1000]
  plot data using 1:(atLeast($4, 0.01)):(colour(int($1))):xtic(label(0)) with boxes lc rgb variable notitle
  set ylabel "largest jitter (m)"
  set yrange [1e-9:1]
  plot data using 1:(atLeast($5, 1e-9)):(colour(int($1))):xtic(label(0)) with boxes lc rgb variable notitle
  set ylabel "mean kinetic energy (J)"
  set yrange [1e-12:1e3]
  plot data using 1:(atLeast($6, 1e-12)):(colour(int($1))):xtic(label(0)) with boxes lc rgb variable notitle
  unset multiplot
  set output
}
