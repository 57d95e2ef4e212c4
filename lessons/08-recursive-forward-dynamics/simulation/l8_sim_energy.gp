# Simulation report, section 2: |E(t) - E(0)| over a long horizon (the largest value in
# windows that grow geometrically), h = 0.02 s, log-log.
# Usage: gnuplot -e "outdir='DIR'" l8_sim_energy.gp  (reads DIR/l8_sim_energy.csv)
set terminal pngcairo size 980,480 enhanced font 'DejaVu Sans,11'
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
d(s, m) = (strcol(1) eq s && strcol(2) eq m && $4 > 0) ? $4 : 1/0
methods = 'symplectic-euler implicit-midpoint rk4'
set multiplot layout 1,2
set title 'pendulum (constant mass matrix)'
plot for [i=1:3] file using 3:(d('pendulum', word(methods, i))) with lines lw 2 lc i title word(methods, i)
set title 'double pendulum'
plot for [i=1:3] file using 3:(d('double_pendulum', word(methods, i))) with lines lw 2 lc i title word(methods, i)
unset multiplot
