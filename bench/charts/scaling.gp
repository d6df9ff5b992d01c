# Render time against light count (log-log), one line per method at the default ε = 0.02,
# and the 1-light floor (the cost of a frame with almost no lighting) as a flat line.
# gnuplot -e "dir='DATA'; layout='uniform'; floor='12.3'; out='x.png'" scaling.gp
set terminal pngcairo size 900,600 font "sans,10"
set output out
set logscale xy
set format x "10^{%L}"
set xlabel "lights"
set ylabel "render ms"
set key top left
set grid
set title sprintf("Render time against light count, %s layout (%s)", layout, setting)
base = sprintf("%s/%s", dir, layout)
plot base."-scaling-reference.dat" using 1:2 with linespoints pt 7 lc rgb "black" title "reference", \
     base."-scaling-node.dat" using 1:2 with linespoints pt 7 lc rgb "#1f77b4" title "lightcuts, node rule, ε = 0.02", \
     base."-scaling-total.dat" using 1:2 with linespoints pt 5 lc rgb "#d62728" title "lightcuts, total rule, ε = 0.02", \
     base."-scaling-distance.dat" using 1:2 with linespoints pt 9 lc rgb "#2ca02c" title "lightcuts-distance", \
     base."-scaling-octree.dat" using 1:2 with linespoints pt 13 lc rgb "#9467bd" title "octree (exact)", \
     real(floor) with lines dt 2 lc rgb "gray40" title "1-light floor"
