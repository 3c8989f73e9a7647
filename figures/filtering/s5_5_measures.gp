# Thesis §5.5, §6.1: the measures of src/boxsim/filtering/trajectory_measures.hpp for the die,
# the clump and the pyramid under the plain impulse step, raw (grey), box-filtered (blue) and
# envelope-filtered (orange). Chatter, squirm and pops are over the bodies resting in the raw
# run (none in the clump); introduced overlap over every pair and the whole run; peak
# acceleration over an impact window, relative to raw. Log scales: a value of exactly 0 is
# drawn at the floor of the axis and marked 0; "no resting body" marks the clump.
# Data: s5_5_measures.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_5_measures.gp
data = datadir.'/s5_5_measures.dat'
x(i) = i + int(i / 3)
colour(i) = (int(i) % 3 == 0) ? 0xaaaaaa : ((int(i) % 3 == 1) ? 0x1f77b4 : 0xff7f0e)
atLeast(v, f) = v > f ? v : f
mark(v, n, i) = n == 0 ? (int(i) % 3 == 1 ? "no resting body" : "") : (v == 0 ? "0" : "")
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1300,760 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1300,760 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_5_measures.'.kind
  set multiplot layout 2,3 title "Filtering measured: raw (grey), box filter H = 2 (blue), envelope filter (orange); die, clump, pyramid under the plain impulse step"
  set style fill solid 0.85 border -1
  set boxwidth 0.8
  set grid ytics
  set xtics ("die" 1, "clump" 5, "pyramid" 9) nomirror
  set xrange [-0.8:11.8]
  set logscale y
  set format y "10^{%L}"
  set title "chatter: mean squared 2nd difference of position"
  set ylabel "m^2"
  set yrange [1e-18:1e-4]
  plot data using (x($1)):(atLeast($5, 1e-18)):(colour($1)) with boxes lc rgb variable notitle, \
       data using (x($1)):(1e-18):(mark($5, $4, $1)) with labels offset 0,0.7 notitle
  set title "chatter: of the rotation (rad^2)"
  set ylabel "rad^2"
  set yrange [1e-18:1e-4]
  plot data using (x($1)):(atLeast($6, 1e-18)):(colour($1)) with boxes lc rgb variable notitle, \
       data using (x($1)):(1e-18):(mark($6, $4, $1)) with labels offset 0,0.7 notitle
  set title "squirm: path of the low-passed position"
  set ylabel "m/s"
  set yrange [1e-9:0.1]
  plot data using (x($1)):(atLeast($7, 1e-9)):(colour($1)) with boxes lc rgb variable notitle, \
       data using (x($1)):(1e-9):(mark($7, $4, $1)) with labels offset 0,0.7 notitle
  set title "pops: largest one-frame jump"
  set ylabel "m"
  set yrange [1e-9:0.1]
  plot data using (x($1)):(atLeast($9, 1e-9)):(colour($1)) with boxes lc rgb variable notitle, \
       data using (x($1)):(1e-9):(mark($9, $4, $1)) with labels offset 0,0.7 notitle
  unset logscale y
  set format y "%g"
  set title "overlap introduced (box-box, box-ground)"
  set ylabel "mm"
  set yrange [0:*]
  plot data using (x($1)):(1e3 * ($13 > $14 ? $13 : $14)):(colour($1)) with boxes lc rgb variable notitle
  set title "impact sharpness: peak acceleration / raw"
  set ylabel "ratio"
  set yrange [0:1.2]
  plot data using (x($1)):17:(colour($1)) with boxes lc rgb variable notitle
  unset multiplot
  set output
}
