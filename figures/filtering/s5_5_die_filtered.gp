# Thesis §5.5: the die of chapters/impulse_damped/scenes/die.json under the plain impulse step,
# raw (grey), box-filtered (H = 2, blue) and envelope-filtered (orange, dashed). Left: at rest
# (10.5-12 s), height and tilt of each version as deviations from its own mean over the window,
# in micrometres and microradians: the chatter the filters act on. The key gives each version's
# mean against raw's: the envelope filter holds the die where its last jump left it. Right: 7.4-10.4 s, the die toppling off the edge
# it balanced on, landing and rocking to rest.
# Data: s5_5_die_filtered.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_5_die_filtered.gp
data = datadir.'/s5_5_die_filtered.dat'
stats [10.5:12] data using 1:2 name "Y" nooutput
stats [10.5:12] data using 1:3 name "YB" nooutput
stats [10.5:12] data using 1:4 name "YE" nooutput
stats [10.5:12] data using 1:5 name "T" nooutput
stats [10.5:12] data using 1:6 name "TB" nooutput
stats [10.5:12] data using 1:7 name "TE" nooutput
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1200,720 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1200,720 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_5_die_filtered.'.kind
  set multiplot layout 2,2 title "Die under the plain impulse step: raw, box filter (H = 2) and envelope filter (r = 2.5 cm)"
  set grid
  set key top right
  set xlabel "t (s)"
  set xrange [10.5:12]
  set key bottom right
  set ylabel "height - its mean (µm)"
  set title "at rest: chatter of the height"
  plot data using 1:(($2 - Y_mean_y) * 1e6) with lines lw 3 lc rgb "#aaaaaa" title sprintf("raw (mean %.6f m)", Y_mean_y), \
       data using 1:(($3 - YB_mean_y) * 1e6) with lines lw 1.5 lc rgb "#1f77b4" title sprintf("box (mean %+.2g mm)", 1e3 * (YB_mean_y - Y_mean_y)), \
       data using 1:(($4 - YE_mean_y) * 1e6) with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title sprintf("envelope (mean %+.3g mm)", 1e3 * (YE_mean_y - Y_mean_y))
  set key top right
  set xrange [7.4:10.4]
  set ylabel "height (m)"
  set title "toppling, landing, rocking"
  plot data using 1:2 with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:3 with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:4 with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  set xrange [10.5:12]
  set key bottom right
  set ylabel "tilt - its mean (µrad)"
  set title "at rest: chatter of the tilt"
  plot data using 1:(($5 - T_mean_y) * 1e6) with lines lw 3 lc rgb "#aaaaaa" title sprintf("raw (mean %.2g rad)", T_mean_y), \
       data using 1:(($6 - TB_mean_y) * 1e6) with lines lw 1.5 lc rgb "#1f77b4" title sprintf("box (mean %+.2g rad)", TB_mean_y - T_mean_y), \
       data using 1:(($7 - TE_mean_y) * 1e6) with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title sprintf("envelope (mean %+.3g rad)", TE_mean_y - T_mean_y)
  set key top right
  set xrange [7.4:10.4]
  set ylabel "tilt (rad)"
  set title "tilt: angle between y and the nearest body axis"
  plot data using 1:5 with lines lw 3 lc rgb "#aaaaaa" title "raw", \
       data using 1:6 with lines lw 1.5 lc rgb "#1f77b4" title "box", \
       data using 1:7 with lines lw 1.5 dt 2 lc rgb "#ff7f0e" title "envelope"
  unset multiplot
  set output
}
