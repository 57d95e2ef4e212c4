# Lesson 8: the Panda released at rest with T = 0, its seven joint angles over 1 s (RK4 on the
# accelerations of soa::forward_dynamics, h = 1 ms; joint limits not applied).
# Usage: gnuplot -e "outdir='DIR'" l8_panda_fall.gp  (reads DIR/l8_panda_fall.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_panda_fall.png'
set datafile separator ','
set title 'Franka Emika Panda falling under gravity (T = 0)'
set xlabel 'time t [s]'
set ylabel 'joint angle q [rad]'
set grid
set key outside right center vertical samplen 2
stats outdir.'/l8_panda_fall.csv' skip 1 nooutput
plot for [i=2:STATS_columns] outdir.'/l8_panda_fall.csv' using 1:i with lines lw 2 \
     title columnheader(i)
