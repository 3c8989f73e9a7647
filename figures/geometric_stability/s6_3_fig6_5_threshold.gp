# Beyond the thesis (§6.3.1, Fig. 6.5): the heavy block across two supports that would each tip
# alone, against the top block's mass (arms of 1 kg). Points: the largest acceleration the full
# frictionless LCP gives any box (the brute-force answer; log, zero drawn at the floor), dark blue
# where stability under load holds all three boxes, light grey where it does not. Dashed: the
# threshold derived by hand, a top of twice an arm's mass.
# Data: s6_3_fig6_5_threshold.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s6_3_fig6_5_threshold.gp
data = datadir.'/s6_3_fig6_5_threshold.dat'
floor = 1e-14
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 900,520 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 900,520 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s6_3_fig6_5_threshold.'.kind
  set title "Fig. 6.5: the verdict under load against the full LCP, as the top block gets heavier"
  set xlabel "mass of the top block (kg); each arm 1 kg"
  set ylabel "largest acceleration, full LCP (m/s^2, rad/s^2)"
  set logscale y
  set yrange [floor/2:100]
  set xrange [0:5.2]
  set grid
  set key top right
  set arrow from 2,floor/2 to 2,100 nohead dt 2 lw 2 lc rgb "#aa3333"
  set label "hand-derived threshold: 2 kg" at 2.08,20 textcolor rgb "#aa3333"
  plot data using 1:($2 == 1 ? ($3 > floor ? $3 : floor) : 1/0) with points pt 7 ps 1.3 lc rgb "#2f4b7c" \
         title "stable under load", \
       data using 1:($2 == 0 ? ($3 > floor ? $3 : floor) : 1/0) with points pt 7 ps 1.3 lc rgb "#b0b0b0" \
         title "not stable under load"
  unset arrow
  unset label
  set output
}
