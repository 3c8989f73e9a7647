# Thesis Fig. 5.3, right: "the contact plane". The cube over one corner of the cube below,
# seen from above: the two faces that meet, the contact points between them, and the upper
# cube's centre of mass, which lies outside the contact points' polygon: not geometrically
# stable (§5.4). Data: fig5_3_contact_plane.dat.
# Usage: gnuplot -e "datadir='...'; outdir='...'" fig5_3_contact_plane.gp
data = datadir.'/fig5_3_contact_plane.dat'
do for [kind in "png svg"] {
  if (kind eq "png") { set terminal pngcairo size 560,560 noenhanced font "DejaVu Sans,11" }
  else { set terminal svg size 560,560 noenhanced font "DejaVu Sans,11" }
  set output outdir.'/fig5_3_contact_plane.'.kind
  set title "Fig. 5.3, right: the contact plane, from above"
  set size ratio -1
  set grid
  set xlabel "x (m)"
  set ylabel "z (m)"
  set xrange [-0.75:1.5]
  set yrange [-0.75:2.0]
  set key top left box opaque
  set style fill transparent solid 0.35 noborder
  plot data index 0 using 1:2 with lines lw 2 lc rgb "#444444" title "lower cube, top face", \
       data index 1 using 1:2 with lines lw 2 dt 2 lc rgb "#1f77b4" title "upper cube, bottom face", \
       data index 2 using 1:2 with filledcurves closed lc rgb "#d62728" title "contact points' polygon", \
       data index 2 using 1:2 with points pt 7 ps 1.2 lc rgb "#d62728" notitle, \
       data index 3 using 1:2 with points pt 2 ps 2.5 lw 2 lc rgb "#1f77b4" title "upper cube's centre of mass"
  set output
}
