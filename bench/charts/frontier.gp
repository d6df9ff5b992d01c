# Speed against accuracy, one panel per light count: render time (log) against the 99th
# percentile of the per-pixel relative error (log). Lightcuts under each error mode is a
# curve through its ε values; the distance criterion is one point, the octree (exact: its
# float rounding sits at the left edge) another; the reference (exact) is a horizontal line. Data files come from bench/report.py.
# gnuplot -e "dir='DATA'; layout='uniform'; counts='64 1024'; out='x.png'" frontier.gp
set terminal pngcairo size 1500,900 font "sans,10"
set output out
set multiplot layout 2,3 title sprintf("Speed against accuracy, %s layout (%s)", layout, setting)
set logscale xy
set xrange [1e-5:10]
set format x "10^{%L}"
set xlabel "relative error, 99th percentile of pixels"
set ylabel "render ms"
set key top right font "sans,8"
set grid
do for [n in counts] {
  base = sprintf("%s/%s-%s", dir, layout, n)
  ref = system(sprintf("cat %s-reference.dat 2>/dev/null", base))
  set title sprintf("%s lights", n)
  plot base."-node.dat" using 1:2 with linespoints pt 7 lc rgb "#1f77b4" title "lightcuts, node rule", \
       base."-node.dat" using 1:2:3 with labels offset 0,0.8 font "sans,7" notitle, \
       base."-total.dat" using 1:2 with linespoints pt 5 lc rgb "#d62728" title "lightcuts, total rule", \
       base."-distance.dat" using 1:2 with points pt 9 ps 1.5 lc rgb "#2ca02c" title "lightcuts-distance", \
       base."-octree.dat" using 1:2 with points pt 13 ps 1.5 lc rgb "#9467bd" title "octree (exact)", \
       (ref eq "" ? 1/0 : real(ref)) with lines dt 2 lc rgb "black" title "reference (exact)"
}
unset multiplot
