# Thesis §5.3, §6.1: chatter of settled scenes per technique. Left: sign changes of a body's
# vertical velocity (|v| > 1e-4 m/s) per body and second; right: the largest vertical jitter
# amplitude of any body. Windows: die 6-8 s, tower 2-8 s, pyramid 2-5 s (before the shot).
# Data: s5_2_chatter.dat. Usage: gnuplot -e "datadir='...'; outdir='...'" s5_2_chatter.gp
data = datadir.'/s5_2_chatter.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1100,450 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1100,450 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s5_2_chatter.'.kind
  set multiplot layout 1,2 title "Chatter once settled: plain impulse-based step (red) against damped integration (blue); 0 means perfectly still"
  set style fill solid 0.8 border -1
  set boxwidth 0.7
  set grid ytics
  set xtics rotate by -30 nomirror noenhanced
  set yrange [0:*]
  set ylabel "sign changes per body and second"
  plot data using 1:3:(int($1) % 2 == 0 ? 0xd62728 : 0x1f77b4):xtic(2) with boxes lc rgb variable notitle
  set ylabel "largest jitter amplitude (m)"
  plot data using 1:4:(int($1) % 2 == 0 ? 0xd62728 : 0x1f77b4):xtic(2) with boxes lc rgb variable notitle
  unset multiplot
  set output
}
