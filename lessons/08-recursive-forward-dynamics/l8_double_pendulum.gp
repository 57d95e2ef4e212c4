# Lesson 8: the double pendulum released at rest, its two hinge angles over 2 s (RK4 on the
# accelerations of soa::forward_dynamics, h = 1 ms).
# Usage: gnuplot -e "outdir='DIR'" l8_double_pendulum.gp  (reads DIR/l8_double_pendulum.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_double_pendulum.png'
set datafile separator ','
set title 'Double pendulum falling under gravity (T = 0)'
set xlabel 'time t [s]'
set ylabel 'hinge angle θ [rad]'
set grid
set key top right
plot outdir.'/l8_double_pendulum.csv' using 1:2 with lines lw 2 title columnheader(2), \
     ''                               using 1:3 with lines lw 2 title columnheader(3)
