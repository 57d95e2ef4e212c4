# Lesson 8 timing: forward error against run time, one point per method x precision x N
# (the points of one method and precision joined in the order of N; N written beside the
# articulated body points in double).
# Usage: gnuplot -e "outdir='DIR'" l8_work_precision.gp  (reads DIR/l8_work_precision.csv)
set terminal pngcairo size 860,600 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_work_precision.png'
set datafile separator ','
set title 'Error against run time (forward dynamics, revolute chains)'
set xlabel 'time per call [ns]'
set ylabel 'forward error against long double'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set yrange [1e-18:1]
set grid
set key bottom right font ',10'
h(m, p) = (strcol(1) eq m && strcol(2) eq p && $5 > 0 && $4 > 0) ? $5 : 1/0
file = outdir.'/l8_work_precision.csv'
plot file using 4:(h('ABA', 'double')) with linespoints lw 2 pt 7 lc 1 title 'ABA, double', \
     file using 4:(h('ABA', 'double')):(sprintf('%d', $3)) with labels offset 0,-0.9 font ',8' notitle, \
     file using 4:(h('ABA', 'float')) with linespoints lw 2 pt 6 dt 2 lc 1 title 'ABA, float', \
     file using 4:(h('CRB+LDLT', 'double')) with linespoints lw 2 pt 5 lc 2 title 'CRB + LDLT, double', \
     file using 4:(h('CRB+LDLT', 'float')) with linespoints lw 2 pt 4 dt 2 lc 2 title 'CRB + LDLT, float', \
     file using 4:(h('Minv', 'double')) with linespoints lw 2 pt 9 lc 3 title 'M^{-1}(T - C), double', \
     file using 4:(h('Minv', 'float')) with linespoints lw 2 pt 8 dt 2 lc 3 title 'M^{-1}(T - C), float', \
     file using 4:(h('MinvUpsilon', 'double')) with linespoints lw 2 pt 11 lc 4 title 'M^{-1} by Upsilon, double', \
     file using 4:(h('MinvUpsilon', 'float')) with linespoints lw 2 pt 10 dt 2 lc 4 title 'M^{-1} by Upsilon, float'
