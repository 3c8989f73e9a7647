# Thesis §5.1, Fig. 5.1: the collisions of one 1/60 s frame of the row A..E (A fast, D slow,
# gravity 0, restitution 1) on a time line, one row per method: the chronological reference
# (basic colliding in steps of 1e-5 s) and the three variants of the modified timewarp
# (Alg. A.1). Each marker is a resolved collision at its time, labelled "n: pair" with n the
# order in which the method resolved it; labels of near-simultaneous collisions stack upwards.
# Data: fig5_1_event_order.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" fig5_1_event_order.gp
data = datadir.'/fig5_1_event_order.dat'
frameEnd = 1000.0 / 60.0
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1000,440 noenhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1000,440 noenhanced font "DejaVu Sans,11" }
  set output outdir.'/fig5_1_event_order.'.kind
  set title "Fig. 5.1: the frame's collisions at their times, labelled with the order each method resolved them"
  set xlabel "collision time (ms after the start of the frame)"
  set xrange [0:18]
  set yrange [-0.45:3.95]
  set ytics ("reference\n(chronological)" 3, "timewarp simple" 2, "timewarp safer" 1, "timewarp swept" 0)
  set xtics 2
  set grid xtics lc rgb "#e0e0e0"
  set border 1
  set tics nomirror
  unset key
  do for [r = 0:3] { set arrow from 0, r to frameEnd, r nohead lw 1 lc rgb "#bbbbbb" back }
  set arrow from frameEnd, graph 0 to frameEnd, graph 1 nohead dt 2 lc rgb "#666666" front
  set label 1 "end of frame" at frameEnd, graph 0.03 offset -0.5, 0 right textcolor rgb "#666666"
  plot data using 4:1:($1 + 1) with points pt 7 ps 1.5 lc variable, \
       data using 4:($1 + 0.2 + 0.2 * $6):(sprintf("%d: %s", $3, strcol(5))) with labels font ",10"
  unset arrow
  unset label
  set output
}
