# Thesis §3.3.1, §5.3: time of one LCP solve against the number of contacts (resting towers),
# per linear solver of fdirection; log-log.
# Data: s3_3_lcp_solve_time.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s3_3_lcp_solve_time.gp
data = datadir.'/s3_3_lcp_solve_time.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 700,450 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 700,450 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s3_3_lcp_solve_time.'.kind
  set title "Baraff's LCP: solve time against contacts (one thread)"
  set grid
  set logscale xy
  set xlabel "contacts"
  set ylabel "ms per solve"
  set key top left
  plot data using 1:2 with linespoints lw 2 lc rgb "#d62728" title "Cholesky grown per clamped contact", \
       data using 1:3 with linespoints lw 2 lc rgb "#1f77b4" title "LDL^T refactored per pivot", \
       data using 1:4 with linespoints lw 2 lc rgb "#2ca02c" title "complete orthogonal, per pivot"
  set output
}
