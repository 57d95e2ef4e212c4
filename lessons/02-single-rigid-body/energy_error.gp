# Lesson 2: relative kinetic-energy error of the Lie-group RK4 for several step sizes.
# Usage: gnuplot -e "outdir='DIR'" energy_error.gp  (reads DIR/l2_energy_error.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l2_energy_error.png'
set datafile separator ','
set title 'Torque-free body about x ≠ C, Lie-group RK4: energy error'
set xlabel 'time t [s]'
set ylabel '|E(t) - E(0)| / E(0)'
set logscale y
set format y '10^{%L}'
set yrange [1e-13:1e-3]
set grid
set key inside right bottom vertical opaque box
# |error| on a log scale: the exact zero at t = 0 is left out.
plot for [i=2:5] outdir.'/l2_energy_error.csv' using 1:(abs(column(i)) > 0 ? abs(column(i)) : NaN) \
     with lines lw 2 title columnheader(i)
