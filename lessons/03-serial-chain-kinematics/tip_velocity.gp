# Lesson 3: the tool velocity of the 7-joint arm, from the Jacobian and by finite differences.
# Usage: gnuplot -e "outdir='DIR'" tip_velocity.gp  (reads DIR/l3_tip_path.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l3_tip_velocity.png'
set datafile separator ','
set title 'Tool velocity in inertial axes: R_F [J β]_v (lines), d/dt of the path (points)'
set xlabel 'time t [s]'
set ylabel 'v_F [m/s]'
set grid
set key below horizontal maxrows 1 width -1
plot outdir.'/l3_tip_path.csv' using 1:5 every ::1 with lines lw 2 lc rgb '#1f77b4' title 'v_x', \
     ''                        using 1:6 every ::1 with lines lw 2 lc rgb '#ff7f0e' title 'v_y', \
     ''                        using 1:7 every ::1 with lines lw 2 lc rgb '#2ca02c' title 'v_z', \
     ''                        using 1:8 every 8::1 with points pt 6 ps 1 lc rgb '#1f77b4' notitle, \
     ''                        using 1:9 every 8::1 with points pt 6 ps 1 lc rgb '#ff7f0e' notitle, \
     ''                        using 1:10 every 8::1 with points pt 6 ps 1 lc rgb '#2ca02c' title 'finite differences'
