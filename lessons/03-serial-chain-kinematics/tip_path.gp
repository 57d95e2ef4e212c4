# Lesson 3: the path of the 7-joint arm's tool frame over a smooth joint motion.
# Usage: gnuplot -e "outdir='DIR'" tip_path.gp  (reads DIR/l3_tip_path.csv)
set terminal pngcairo size 800,600 enhanced font 'DejaVu Sans,12'
set output outdir.'/l3_tip_path.png'
set datafile separator ','
set title '7-joint arm: path of the tool frame (scatter recursion of the poses)'
set xlabel 'x [m]'
set ylabel 'y [m]'
set zlabel 'z [m]' rotate parallel
set view 60, 30
set grid
set ticslevel 0
set key at screen 0.97, 0.90 right top
stats outdir.'/l3_tip_path.csv' using 4 nooutput
floor = STATS_min - 0.05
splot outdir.'/l3_tip_path.csv' using 2:3:4 every ::1 with lines lw 2 lc rgb '#1f77b4' title 'tool path', \
      ''                        using 2:3:(floor) every ::1 with lines lw 1 dt 2 lc rgb 'gray50' title 'its projection', \
      ''                        using 2:3:4 every ::1::1 with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'start', \
      ''                        using 2:3:4 every ::201::201 with points pt 5 ps 1.5 lc rgb '#d62728' title 'end'
