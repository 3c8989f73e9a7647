# Thesis §3.3.1: the outer loop of Baraff's method runs "while some a_d < -ε" rather than < 0.
# The contact LCPs of towers, pyramids and uneven stacks along 1 s of the analytic method,
# solved with ε in {0, 1e-8, 1e-5} m/s², each linear solver, snapping to the bounds off and on:
# the share of solves that hit the pivot guard (cycling), and the mean pivots a solve.
# Data: s3_3_epsilon_sweep.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s3_3_epsilon_sweep.gp
data = datadir.'/s3_3_epsilon_sweep.dat'
stats data using 9 name "V" nooutput
epsIndex(e) = e == 0 ? 0 : (e < 1e-6 ? 1 : 2)
x(e, snap, s) = (epsIndex(e) * 2 + snap) * 5 + s
colours = "#d62728 #1f77b4 #2ca02c #9467bd"
names = "'Cholesky grown per clamped contact' 'LDLᵀ per pivot' 'complete orthogonal per pivot' 'Gaussian elimination per pivot (thesis)'"
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 860,720 noenhanced font "DejaVu Sans,11" }
  else { set terminal svg size 860,720 noenhanced font "DejaVu Sans,11" }
  set output outdir.'/s3_3_epsilon_sweep.'.kind
  set multiplot layout 2,1 title sprintf("Baraff's LCP: does ε end the loop? (worst scaled LCP violation of any returned force: %.1e)", V_max)
  set grid ytics
  set bmargin 4
  set style fill solid 0.9 noborder
  set boxwidth 0.9
  set xrange [-1:30]
  set xtics ("ε = 0\nsnap off" 1.5, "ε = 0\nsnap on" 6.5, "ε = 1e-8\nsnap off" 11.5, "ε = 1e-8\nsnap on" 16.5, \
             "ε = 1e-5\nsnap off" 21.5, "ε = 1e-5\nsnap on" 26.5)
  set ylabel "solves stopped by the pivot guard (%)"
  set yrange [0:*]
  set key top right
  plot for [s=0:3] data using ($3 == s ? x($1, $2, s) : NaN):7 with boxes lc rgb word(colours, s + 1) title word(names, s + 1)
  set ylabel "pivots per solve (mean)"
  set yrange [1:1000]
  set logscale y
  unset key
  plot for [s=0:3] data using ($3 == s ? x($1, $2, s) : NaN):8 with boxes lc rgb word(colours, s + 1) notitle
  unset multiplot
  unset logscale y
  set output
}
