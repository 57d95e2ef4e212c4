# Simulation report, section 2: |E(t) - E(0)| over a long horizon (the largest value in
# windows that grow geometrically), log-log: the pendulum and the double pendulum at
# h = 0.02 s, the seven-joint arm at h = 0.002 s; a cross marks the last window of a run
# stopped by a blow-up diagnostic.
# Usage: gnuplot -e "outdir='DIR'" l8_sim_energy.gp
#        (reads DIR/l8_sim_energy.csv and DIR/l8_sim_energy_stops.csv)
set terminal pngcairo size 1400,480 enhanced font 'DejaVu Sans,11'
set output outdir.'/l8_sim_energy.png'
set datafile separator ','
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set xlabel 't [s]'
set ylabel 'max |E(t) - E(0)| in the window [J]'
set key bottom right font ',10'
file = outdir.'/l8_sim_energy.csv'
stops = outdir.'/l8_sim_energy_stops.csv'
d(s, m) = (strcol(1) eq s && strcol(2) eq m && $4 > 0) ? $4 : 1/0
methods = 'symplectic-euler implicit-midpoint rk4 variational'
scenes = 'pendulum double_pendulum arm7'
titles = "'pendulum (constant mass matrix), h = 0.02 s' 'double pendulum, h = 0.02 s' 'seven-joint arm, h = 0.002 s'"
set multiplot layout 1,3
do for [k=1:3] {
  set title word(titles, k)
  plot for [i=1:4] file using 3:(d(word(scenes, k), word(methods, i))) with lines lw 2 lc i \
         title word(methods, i), \
       for [i=1:4] stops using 3:(d(word(scenes, k), word(methods, i))) with points pt 2 ps 2 \
         lw 2 lc i notitle
}
unset multiplot
