# Lesson 6: along the 50-link chain, D(k) (what hinge k feels with every outboard hinge free)
# against H(k) R(k) H*(k) (with every outboard hinge locked).
# Usage: gnuplot -e "outdir='DIR'" l6_chain50_D.gp  (reads DIR/l6_chain50.csv)
set terminal pngcairo size 800,560 enhanced font 'DejaVu Sans,12'
set output outdir.'/l6_chain50_D.png'
set datafile separator ','
set title '50-link chain: articulated vs composite hinge inertia'
set xlabel 'body k (1 = tip)'
set ylabel 'inertia about the hinge axis [kg m^2]'
set logscale y
set format y '10^{%L}'
set grid
set key top left
plot outdir.'/l6_chain50.csv' using 1:2 with linespoints lw 2 pt 7 ps 0.6 title 'D(k) = H P H*', \
     ''                       using 1:3 with linespoints lw 2 pt 5 ps 0.6 title 'H R H* (hinges locked)'
