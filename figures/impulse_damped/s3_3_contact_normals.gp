# Thesis §3.3.2 and its footnote: the contact normal models compared under the plain impulse
# step and damped integration. Left: chatter of the base-10 pyramid (1-5 s, before the shot);
# middle: its deepest penetration; right: when the die's momenta become exactly zero for good
# (-1: never within 8 s). Data: s3_3_contact_normals.dat
# Usage: gnuplot -e "datadir='...'; outdir='...'" s3_3_contact_normals.gp
data = datadir.'/s3_3_contact_normals.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 1400,480 enhanced font "DejaVu Sans,10" }
  else { set terminal svg size 1400,480 enhanced font "DejaVu Sans,10" }
  set output outdir.'/s3_3_contact_normals.'.kind
  set multiplot layout 1,3 title "Contact normal models: separating axis, previous closest face (the thesis), signed distance (its footnote)"
  set style fill solid 0.8 border -1
  set boxwidth 0.7
  set grid ytics
  set xtics rotate by -35 nomirror noenhanced
  colour(i) = i < 3 ? 0xd62728 : 0x1f77b4
  set ylabel "pyramid: sign changes per body and second"
  plot data using 1:3:(colour($1)):xtic(2) with boxes lc rgb variable notitle
  set ylabel "pyramid: deepest penetration (m)"
  plot data using 1:5:(colour($1)):xtic(2) with boxes lc rgb variable notitle
  set ylabel "die: at rest from (s)"
  plot data using 1:6:(colour($1)):xtic(2) with boxes lc rgb variable notitle
  unset multiplot
  set output
}
