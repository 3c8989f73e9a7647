# Thesis §3.3.1: "leaving out this post-processing step [setting negative forces to zero] lead
# to results in which repeated time steps caused objects to gradually accelerate into each
# other". A resting tower of 10 unit cubes: the deepest overlap of any pair over time under the
# thesis' LCP settings with and without the clamp, and under the defaults (drift correction).
# Data: s3_3_no_clamp.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s3_3_no_clamp.gp
data = datadir.'/s3_3_no_clamp.dat'
stats data using 2 name "Fc" nooutput
stats data using 4 name "Fn" nooutput
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 760,470 noenhanced font "DejaVu Sans,11" }
  else { set terminal svg size 760,470 noenhanced font "DejaVu Sans,11" }
  set output outdir.'/s3_3_no_clamp.'.kind
  set title "Resting tower of 10 under the analytic method: does the force clamp matter?"
  set grid
  set xlabel "time (s)"
  set ylabel "deepest overlap of any pair (m)"
  set logscale y
  set format y "1e%T"
  set yrange [1e-18:1e-1]
  set key at graph 0.98, graph 0.42 right box opaque
  set xrange [0:15]
  set label 1 sprintf("most negative LCP force before the clamp: %.2g N with the clamp, %.2g N without", Fc_min, Fn_min) at graph 0.02, graph 0.95
  plot data using 1:($3 > 0 ? $3 : 1e-18) with lines lw 3 lc rgb "#1f77b4" title "thesis settings, clamp on", \
       data using 1:($5 > 0 ? $5 : 1e-18) with lines lw 1.5 dt 2 lc rgb "#d62728" title "thesis settings, clamp off", \
       data using 1:($7 > 0 ? $7 : 1e-18) with lines lw 1.5 lc rgb "#2ca02c" title "defaults: drift correction on"
  set output
}
