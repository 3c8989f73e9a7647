# Thesis Fig. 5.6: side view of a pyramid whose bottom centre box has been removed;
# geometrically stable boxes dark grey, unstable ones light grey (§5.4). The title gives the
# contact LCP's size and solve time without and with the exclusion of stable bodies.
# Data: fig5_6_pyramid_stability.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" fig5_6_pyramid_stability.gp
data = datadir.'/fig5_6_pyramid_stability.dat'
full = system("grep '^# full_lcp' ".data." | sed 's/^# full_lcp: //'")
excl = system("grep '^# with_exclusion' ".data." | sed 's/^# with_exclusion: //'")
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 900,520 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 900,520 enhanced font "DejaVu Sans,11" }
  set output outdir.'/fig5_6_pyramid_stability.'.kind
  set title sprintf("Fig. 5.6: stable boxes dark, unstable light\nLCP %s; with stable bodies excluded %s", full, excl) noenhanced
  set size ratio -1
  set xrange [-5.5:5.5]
  set yrange [-0.3:9.5]
  unset ytics
  set xlabel "x (m)"
  set style fill solid 1.0 border lc rgb "#333333"
  set arrow from -5.5,0 to 5.5,0 nohead lw 2 lc rgb "#555555"
  plot data using 1:2:($1-$3):($1+$3):($2-$4):($2+$4):($5 > 0 ? 0x505050 : 0xd8d8d8) \
       with boxxyerror fc rgb variable notitle
  unset arrow
  set output
}
