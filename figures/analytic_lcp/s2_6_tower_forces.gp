# Thesis §2.6.1: the load each level of a resting tower of 10 unit cubes carries on its
# bottom contacts under the LCP forces, against the weight above it (k m g).
# Data: s2_6_tower_forces.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s2_6_tower_forces.gp
data = datadir.'/s2_6_tower_forces.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 700,450 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 700,450 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s2_6_tower_forces.'.kind
  set title "Contact forces in a resting tower of 10 (LCP)"
  set grid
  set xlabel "level (1 = on the ground)"
  set ylabel "vertical load on the level's bottom contacts (N)"
  set style fill solid 0.7 border -1
  set boxwidth 0.6
  set xrange [0.3:10.7]
  set yrange [0:*]
  plot data using 1:2 with boxes lc rgb "#1f77b4" title "LCP forces", \
       data using 1:3 with points pt 7 ps 1.2 lc rgb "#d62728" title "weight above (k m g)"
  set output
}
