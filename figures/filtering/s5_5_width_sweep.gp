# Thesis §5.5: the box filter's trade-off. Widening the kernel (half width H, window 2H + 1
# frames) lowers chatter further but softens impacts and moves bodies into each other. Left:
# chatter of the resting bodies relative to raw (die, pyramid); middle: peak acceleration in
# the impact windows relative to raw, against 1/(2H + 1), what a box filter does to one sharp
# velocity step; right: the deepest overlap the filter introduces.
# Data: s5_5_width_sweep.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_5_width_sweep.gp
data = datadir.'/s5_5_width_sweep.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1300,430 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1300,430 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_5_width_sweep.'.kind
  set multiplot layout 1,3 title "Box filter half width H: chatter against impact sharpness and introduced overlap (plain impulse step)"
  set grid
  set xlabel "half width H (frames; window 2H + 1)"
  set xrange [0:16.5]
  set key top right
  set logscale y
  set ylabel "chatter, box / raw"
  plot data using 1:2 with linespoints lw 2 pt 7 lc rgb "#d62728" title "die", \
       data using 1:10 with linespoints lw 2 pt 5 lc rgb "#2ca02c" title "pyramid"
  set ylabel "peak acceleration, box / raw"
  plot 1 / (2 * x + 1) with lines dt 2 lc rgb "#888888" title "1/(2H+1)", \
       data using 1:4 with linespoints lw 2 pt 7 lc rgb "#d62728" title "die", \
       data using 1:8 with linespoints lw 2 pt 9 lc rgb "#9467bd" title "clump", \
       data using 1:12 with linespoints lw 2 pt 5 lc rgb "#2ca02c" title "pyramid"
  unset logscale y
  set key top left
  set ylabel "overlap introduced (m)"
  plot data using 1:5 with linespoints lw 2 pt 7 lc rgb "#d62728" title "die", \
       data using 1:9 with linespoints lw 2 pt 9 lc rgb "#9467bd" title "clump", \
       data using 1:13 with linespoints lw 2 pt 5 lc rgb "#2ca02c" title "pyramid"
  unset multiplot
  set output
}
