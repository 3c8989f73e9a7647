# Thesis §5.5: the top cube of the base-10 pyramid of Fig. 6.6
# (chapters/impulse_damped/scenes/pyramid10_shot.json) under the plain impulse step, raw (grey),
# box-filtered (H = 2, blue) and envelope-filtered (orange, dashed). Top: standing, 1-4.5 s,
# where it chatters; bottom: the shot at 5 s.
# Data: s5_5_pyramid_filtered.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_5_pyramid_filtered.gp
data = datadir.'/s5_5_pyramid_filtered.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,720 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1200,720 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_5_pyramid_filtered.'.kind
  set multiplot layout 2,2 title "Top cube of the pyramid under the plain impulse step: raw, box filter (H = 2), envelope filter (r = 2.5 cm)"
  set grid
  set key top right
  set xlabel "t (s)"
  set xrange [1:4.5]
  set title "standing: height"
  set ylabel "height - 8.5 m (mm)"
  plot data using 1:(($2 - 8.5) * 1e3) with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:(($3 - 8.5) * 1e3) with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:(($4 - 8.5) * 1e3) with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  set title "standing: tilt"
  set ylabel "tilt (mrad)"
  plot data using 1:($5 * 1e3) with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:($6 * 1e3) with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:($7 * 1e3) with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  set xrange [4.8:6]
  set title "the shot: height"
  set ylabel "height (m)"
  plot data using 1:2 with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:3 with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:4 with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  set title "the shot: tilt"
  set ylabel "tilt (rad)"
  plot data using 1:5 with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:6 with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:7 with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  unset multiplot
  set output
}
