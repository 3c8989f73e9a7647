# Thesis §6.2 in its own model: frictionless unilateral contact forces (Baraff's LCP with the
# §3.3.1 epsilon and clamp) solved for the instant and held over the step, no collision
# handling. Left and middle: the hinge gaps of Figs. 6.2 and 6.3 against time at dt = 1/60 s,
# beside the sticking model's forward Euler (+ separated, - interpenetrating). Right: the
# extremes over the window against dt under forward Euler, log-log.
# Data: s6_2_unilateral.dat (blocks: pivoting_box unilateral forward Euler, semi-implicit,
# sticking forward Euler; two_frames the same) and s6_2_unilateral_vs_dt.dat.
# Usage: gnuplot -e "datadir='...'; outdir='...'" s6_2_unilateral.gp
data = datadir.'/s6_2_unilateral.dat'
sweep = datadir.'/s6_2_unilateral_vs_dt.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1650,560 noenhanced font "DejaVu Sans,11" }
  else { set terminal svg size 1650,560 noenhanced font "DejaVu Sans,11" }
  set output outdir.'/s6_2_unilateral.'.kind
  set multiplot layout 1,3 title "Exterior rotation under frictionless unilateral LCP forces (the thesis' code's model), dt = 1/60 s"
  set grid
  set xlabel "t (s)"
  set ylabel "gap (mm): + separated, - interpenetrating"
  set key top left font ",9"
  set title "Fig. 6.2: one box over the table's edge"
  plot data index 0 using 1:(1e3 * $2) with lines lw 2 lc rgb "#d62728" title "pivot, unilateral, forward Euler", \
       data index 1 using 1:(1e3 * $2) with lines lw 2 lc rgb "#ff7f0e" title "pivot, unilateral, semi-implicit Euler", \
       data index 2 using 1:(1e3 * $2) with lines lw 2 dt 2 lc rgb "#555555" title "pivot, sticking, forward Euler"
  set title "Fig. 6.3: A on the table's edge, B on A's edge"
  plot data index 3 using 1:(1e3 * $2) with lines lw 2 lc rgb "#d62728" title "pivot (table-A), unilateral, forward Euler", \
       data index 3 using 1:(1e3 * $3) with lines lw 2 dt 3 lc rgb "#d62728" title "hinge (A-B), unilateral, forward Euler", \
       data index 4 using 1:(1e3 * $2) with lines lw 2 lc rgb "#ff7f0e" title "pivot, unilateral, semi-implicit Euler", \
       data index 4 using 1:(1e3 * $3) with lines lw 2 dt 3 lc rgb "#ff7f0e" title "hinge, unilateral, semi-implicit Euler", \
       data index 5 using 1:(1e3 * $2) with lines lw 2 dt 2 lc rgb "#555555" title "pivot, sticking, forward Euler", \
       data index 5 using 1:(1e3 * $3) with lines lw 1 dt 4 lc rgb "#555555" title "hinge, sticking, forward Euler"
  set title "Forward Euler, unilateral: extremes over the window against dt"
  set logscale xy
  set xrange [0.0009:0.019]
  set xtics ("1/960" 1.0/960, "1/480" 1.0/480, "1/240" 1.0/240, "1/120" 1.0/120, "1/60" 1.0/60)
  set xlabel "dt (s)"
  set ylabel "m"
  set format y "1e%T"
  set key bottom right font ",9"
  plot sweep using 1:2 with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "Fig. 6.2: largest pivot gap", \
       sweep using 1:3 with linespoints lw 2 pt 7 dt 2 lc rgb "#1f77b4" title "Fig. 6.2: deepest overlap", \
       sweep using 1:4 with linespoints lw 2 pt 7 lc rgb "#d62728" title "Fig. 6.3: deepest pivot overlap", \
       sweep using 1:5 with linespoints lw 2 pt 7 dt 3 lc rgb "#d62728" title "Fig. 6.3: largest hinge gap"
  unset logscale xy
  unset multiplot
  set output
}
