# Thesis §6.1: wall time per 1/60 s step of damped integration on this machine (one thread) for
# the base-20 pyramid shot at 5 s and the clumps of 100 and 1000 cubes (Figs. 6.6, 6.7).
# Data: s6_1_ms_per_frame.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s6_1_ms_per_frame.gp
data = datadir.'/s6_1_ms_per_frame.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1000,500 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1000,500 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s6_1_ms_per_frame.'.kind
  set title "Damped integration: milliseconds per 1/60 s step (one thread)"
  set logscale y
  set grid
  set xlabel "time (s)"
  set ylabel "ms per step"
  set key top left
  plot data using 1:2 with lines lw 1.5 lc rgb "#2ca02c" title "pyramid of base 20 (shot at 5 s)", \
       data using 1:3 with lines lw 1.5 lc rgb "#9467bd" title "clump of 100", \
       data using 1:4 with lines lw 1.5 lc rgb "#8c564b" title "clump of 1000", \
       16.7 with lines dt 2 lc rgb "black" title "real time at 60 Hz"
  set output
}
