# Lesson 8 timing: time per forward dynamics call against N (log-log), the articulated body
# algorithm, CRB + LDLT, M^-1 (T - C) and M^-1 by Upsilon (T - C) in double and float, with the ABA / CRB + LDLT
# crossover N marked.
# Usage: gnuplot -e "outdir='DIR'" l8_time.gp  (reads DIR/l8_work_precision.csv, DIR/l8_marks.gp)
set terminal pngcairo size 860,600 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_time.png'
load outdir.'/l8_marks.gp'
set datafile separator ','
set title 'Forward dynamics of a revolute chain: time per call'
set xlabel 'N (joints)'
set ylabel 'time per call [ns]'
set logscale xy
set format y '10^{%L}'
set grid
set key bottom right
f(m, p) = (strcol(1) eq m && strcol(2) eq p) ? $4 : 1/0
if (cross_double > 0) {
  set arrow 1 from cross_double, graph 0 to cross_double, graph 1 nohead dt 2 lw 2 lc rgb '#444444'
  set label 1 sprintf('crossover N ≈ %.0f (double)', cross_double) at cross_double, graph 0.95 offset 1,0
}
file = outdir.'/l8_work_precision.csv'
plot file using 3:(f('ABA', 'double')) with linespoints lw 2 pt 7 lc 1 title 'ABA, double', \
     file using 3:(f('ABA', 'float')) with linespoints lw 2 pt 6 dt 2 lc 1 title 'ABA, float', \
     file using 3:(f('CRB+LDLT', 'double')) with linespoints lw 2 pt 5 lc 2 title 'CRB + LDLT, double', \
     file using 3:(f('CRB+LDLT', 'float')) with linespoints lw 2 pt 4 dt 2 lc 2 title 'CRB + LDLT, float', \
     file using 3:(f('Minv', 'double')) with linespoints lw 2 pt 9 lc 3 title 'M^{-1}(T - C), double', \
     file using 3:(f('Minv', 'float')) with linespoints lw 2 pt 8 dt 2 lc 3 title 'M^{-1}(T - C), float', \
     file using 3:(f('MinvUpsilon', 'double')) with linespoints lw 2 pt 11 lc 4 title 'M^{-1} by Upsilon, double', \
     file using 3:(f('MinvUpsilon', 'float')) with linespoints lw 2 pt 10 dt 2 lc 4 title 'M^{-1} by Upsilon, float'
