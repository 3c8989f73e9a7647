# Beyond the thesis (§6.3.1): what stability under load adds to §5.4's rule on Fig. 5.6's pyramid
# with gaps, Figs. 6.4 and 6.5, and the clump and the settling pile at rest (damped integration).
# Top: movable boxes (light), stable by §5.4 (grey), stable under load as well (blue). Bottom:
# the analytic method's LCP (contact points) with geometric stability off, thesis and
# under_load; the numbers over the bars are the ms of one contact-force evaluation where timed.
# Data: s6_3_under_load.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s6_3_under_load.gp
data = datadir.'/s6_3_under_load.dat'
ms(v) = (strcol(v) eq "nan") ? "" : sprintf("%.2f ms", column(v))
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1000,800 enhanced font "DejaVu Sans,10" }
  else { set terminal svg size 1000,800 enhanced font "DejaVu Sans,10" }
  set output outdir.'/s6_3_under_load.'.kind
  set multiplot layout 2,1 title "Stability under load (blue) beside the thesis' geometric stability (grey)"
  set style data histograms
  set style histogram clustered gap 1
  set style fill solid 0.9 border -1
  set boxwidth 0.9
  set grid ytics
  set xtics nomirror noenhanced
  set key top left
  set ylabel "boxes"
  set yrange [0:*]
  plot data using 2:xtic(1) lc rgb "#d9d9d9" title "movable", \
       data using 3 lc rgb "#666666" title "stable (§5.4)", \
       data using 4 lc rgb "#2f4b7c" title "stable (§5.4 or under load)"
  set ylabel "LCP contact points"
  plot data using 8:xtic(1) lc rgb "#d9d9d9" title "geometric stability off", \
       data using 9 lc rgb "#666666" title "thesis", \
       data using 10 lc rgb "#2f4b7c" title "under load", \
       data using ($0 - 0.3):8:(ms(11)) with labels offset 0,0.8 font ",8" notitle, \
       data using ($0):9:(ms(12)) with labels offset 0,0.8 font ",8" notitle, \
       data using ($0 + 0.3):10:(ms(13)) with labels offset 0,0.8 font ",8" notitle
  unset multiplot
  set output
}
