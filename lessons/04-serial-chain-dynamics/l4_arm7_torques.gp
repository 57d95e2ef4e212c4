# Lesson 4: joint torques of the 7-joint arm along the motion theta_i(t) = theta_0,i + A_i sin(w_i t).
# Usage: gnuplot -e "outdir='DIR'" l4_arm7_torques.gp  (reads DIR/l4_arm7_torques.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l4_arm7_torques.png'
set datafile separator ','
set title '7-joint arm: joint torques by Newton-Euler inverse dynamics'
set xlabel 'time t [s]'
set ylabel 'joint torque T [N m]'
set grid
set key outside right center vertical samplen 2
set offsets 0, 0, graph 0.05, graph 0.05
stats outdir.'/l4_arm7_torques.csv' skip 1 nooutput
plot for [i=2:STATS_columns] outdir.'/l4_arm7_torques.csv' using 1:i with lines lw 2 \
     title columnheader(i)
