# Lesson 8 timing: forward error against the long double articulated body result, and the
# round trip |ID(FD(T)) - T| / |T|, against N, per method and precision.
# Usage: gnuplot -e "outdir='DIR'" l8_error.gp  (reads DIR/l8_work_precision.csv)
set terminal pngcairo size 1200,540 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_error.png'
set datafile separator ','
set logscale xy
set format y '10^{%L}'
set grid
set xlabel 'N (joints)'
set key top left font ',10'
g(m, p, c) = (strcol(1) eq m && strcol(2) eq p && column(c) > 0) ? column(c) : 1/0
file = outdir.'/l8_work_precision.csv'
set multiplot layout 1,2
set title 'forward error |~{/Symbol b}{.5.}- ~{/Symbol b}{.5.}_{ref}| / |~{/Symbol b}{.5.}_{ref}|'
set yrange [1e-18:1]
set ylabel 'relative error'
plot file using 3:(g('ABA', 'double', 5)) with linespoints lw 2 pt 7 lc 1 title 'ABA, double', \
     file using 3:(g('ABA', 'float', 5)) with linespoints lw 2 pt 6 dt 2 lc 1 title 'ABA, float', \
     file using 3:(g('CRB+LDLT', 'double', 5)) with linespoints lw 2 pt 5 lc 2 title 'CRB + LDLT, double', \
     file using 3:(g('CRB+LDLT', 'float', 5)) with linespoints lw 2 pt 4 dt 2 lc 2 title 'CRB + LDLT, float', \
     file using 3:(g('Minv', 'double', 5)) with linespoints lw 2 pt 9 lc 3 title 'M^{-1}(T - C), double', \
     file using 3:(g('Minv', 'float', 5)) with linespoints lw 2 pt 8 dt 2 lc 3 title 'M^{-1}(T - C), float', \
     file using 3:(g('MinvUpsilon', 'double', 5)) with linespoints lw 2 pt 11 lc 4 title 'M^{-1} by Upsilon, double', \
     file using 3:(g('MinvUpsilon', 'float', 5)) with linespoints lw 2 pt 10 dt 2 lc 4 title 'M^{-1} by Upsilon, float'
set title 'round trip |ID(FD(T)) - T| / |T| (ID in the same precision)'
plot file using 3:(g('ABA', 'double', 6)) with linespoints lw 2 pt 7 lc 1 title 'ABA, double', \
     file using 3:(g('ABA', 'float', 6)) with linespoints lw 2 pt 6 dt 2 lc 1 title 'ABA, float', \
     file using 3:(g('CRB+LDLT', 'double', 6)) with linespoints lw 2 pt 5 lc 2 title 'CRB + LDLT, double', \
     file using 3:(g('CRB+LDLT', 'float', 6)) with linespoints lw 2 pt 4 dt 2 lc 2 title 'CRB + LDLT, float', \
     file using 3:(g('Minv', 'double', 6)) with linespoints lw 2 pt 9 lc 3 title 'M^{-1}(T - C), double', \
     file using 3:(g('Minv', 'float', 6)) with linespoints lw 2 pt 8 dt 2 lc 3 title 'M^{-1}(T - C), float', \
     file using 3:(g('MinvUpsilon', 'double', 6)) with linespoints lw 2 pt 11 lc 4 title 'M^{-1} by Upsilon, double', \
     file using 3:(g('MinvUpsilon', 'float', 6)) with linespoints lw 2 pt 10 dt 2 lc 4 title 'M^{-1} by Upsilon, float'
unset multiplot
