# Lesson 2: body-frame angular velocity of the torque-free body (the Dzhanibekov flip).
# Usage: gnuplot -e "outdir='DIR'" flip.gp  (reads DIR/l2_flip.csv)
set terminal pngcairo size 800,500 enhanced font 'DejaVu Sans,12'
set output outdir.'/l2_flip.png'
set datafile separator ','
set title 'Dzhanibekov effect: the spin about the intermediate axis flips (h = 0.005 s)'
set xlabel 'time t [s]'
set ylabel 'ω in body axes [rad/s]'
set yrange [-8:10]
set ytics -8,2,8
set grid
set key inside top center horizontal opaque samplen 2 width -3
plot outdir.'/l2_flip.csv' using 1:2 every ::1 with lines lw 2 title 'ω_1 (smallest J)', \
     ''                 using 1:3 every ::1 with lines lw 2 title 'ω_2 (intermediate J)', \
     ''                 using 1:4 every ::1 with lines lw 2 dt 2 title 'ω_3 (largest J)'
