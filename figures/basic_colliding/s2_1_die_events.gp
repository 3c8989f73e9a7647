# Thesis §2.1, §4.3: work per frame of the basic colliding technique on the die. When the die
# would settle, its bounces crowd together: collision events and bisection steps per frame jump
# to the events-per-step limit, which from then on holds the die. Data: s2_1_die_events.dat
# Usage: gnuplot -e "datadir='...'; outdir='...'" s2_1_die_events.gp
data = datadir.'/s2_1_die_events.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1000,600 enhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1000,600 enhanced font "DejaVu Sans,11" }
  set output outdir.'/s2_1_die_events.'.kind
  set title "Basic colliding technique: collisions crowd together until the die stalls at the events limit (§4.3)"
  set grid
  set key top left
  set xlabel "time (s)"
  set ylabel "per 1/60 s frame"
  set logscale y
  set yrange [0.8:*]
  plot data using 1:($3 > 0 ? $3 : 1/0) with impulses lw 1 lc rgb "#aaaaaa" title "bisection steps", \
       data using 1:($2 > 0 ? $2 : 1/0) with points pt 7 ps 0.6 lc rgb "#1f77b4" title "collision events", \
       data using 1:($5 > 0 ? $2 : 1/0) with points pt 6 ps 1.2 lc rgb "#d62728" title "frame at the events-per-step limit"
  set output
}
