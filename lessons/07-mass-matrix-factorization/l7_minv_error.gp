# Lesson 7: the relative error of the inverse of the mass matrix against the length of the
# chain (0.1 m, 0.2 kg links, hinges about x and y in turn), in double precision, against the
# long double reference: the O(N^2) column sweep, the O(N^2) algorithm built on Upsilon
# (section 7) and Eigen's dense inverse, with eps cond(M).
# Usage: gnuplot -e "outdir='DIR'" l7_minv_error.gp  (reads DIR/l7_minv_error.csv)
set terminal pngcairo size 800,560 enhanced font 'DejaVu Sans,12'
set output outdir.'/l7_minv_error.png'
set datafile separator ','
set title 'Relative error of M^{-1} (double) against the long double reference'
set xlabel 'number of links n'
set ylabel 'relative error'
set logscale xy
set xrange [1.5:300]
set format y '10^{%L}'
set grid
set key top left
plot outdir.'/l7_minv_error.csv' using 1:3 every ::1 with linespoints lw 2 pt 7 ps 0.8 title 'O(N^2) column sweep', \
     ''                          using 1:7 every ::1 with linespoints lw 2 pt 9 ps 0.8 dt 3 title 'O(N^2) built on Upsilon', \
     ''                          using 1:4 every ::1 with linespoints lw 2 pt 5 ps 0.8 title 'dense inverse (Eigen LU)', \
     ''                          using 1:5 every ::1 with lines lw 2 dt 2 lc rgb '#606060' title '{/Symbol e} cond(M)'
