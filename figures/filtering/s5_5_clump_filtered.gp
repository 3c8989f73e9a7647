# Thesis §5.5: one cube of the clump of Fig. 6.7 (chapters/impulse_damped/scenes/clump100.json)
# under the plain impulse step, raw (grey), box-filtered (H = 2, blue) and envelope-filtered
# (orange, dashed). No cube of this clump ever rests under the plain step: it lands at 1.7 s and
# is thrown up again by the pile. Left: its height over the run; middle and right: the
# first and the second landing, zoomed, where the box filter rounds the impact and the envelope filter,
# passed by a fast body every frame, shows the raw motion.
# Data: s5_5_clump_filtered.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_5_clump_filtered.gp
data = datadir.'/s5_5_clump_filtered.dat'
body = system("grep '^# s5_5_clump_filtered' ".data." | sed \"s/.*body '\\([^']*\\)'.*/\\1/\"")
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1300,420 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1300,420 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_5_clump_filtered.'.kind
  set multiplot layout 1,3 title sprintf("Clump cube %s under the plain impulse step: raw, box filter (H = 2), envelope filter (r = 2.5 cm)", body) noenhanced
  set grid
  set key top right
  set xlabel "t (s)"
  set ylabel "height (m)"
  set title "the whole run"
  set xrange [0:5]
  plot data using 1:2 with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:3 with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:4 with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  set title "landing, zoomed"
  set xrange [1.55:1.95]
  set yrange [0.5:2.5]
  replot
  set title "second landing, zoomed (frames marked)"
  set xrange [4.65:5.0]
  set yrange [0.5:2.5]
  plot data using 1:2 with linespoints pt 7 ps 0.6 lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:3 with linespoints pt 7 ps 0.4 lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:4 with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  unset multiplot
  set output
}
