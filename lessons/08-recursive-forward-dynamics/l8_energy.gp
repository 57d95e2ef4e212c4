# Lesson 8: relative energy error |E(t) - E(0)|/|E(0)| of RK4 on the double pendulum for four
# step sizes (O(h^4): each halving of h divides it by about 16).
# Usage: gnuplot -e "outdir='DIR'" l8_energy.gp  (reads DIR/l8_energy.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_energy.png'
set datafile separator ','
set title 'Double pendulum: energy error of RK4'
set xlabel 'time t [s]'
set ylabel '|E(t) - E(0)| / |E(0)|'
set logscale y
set format y '10^{%L}'
set yrange [1e-16:*]
set grid
set key outside right top vertical
plot for [i=2:5] outdir.'/l8_energy.csv' using 1:i with lines lw 2 title columnheader(i)
