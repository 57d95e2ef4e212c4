# Lesson 8 timing: the extreme chains in forward dynamics (double), the forward error per case
# and method against the long double articulated body result, the tolerance (1e-6) and the
# conditioning bound 16 n eps kappa_D of the articulated body algorithm; a method that
# refused a case with its diagnostic, or did not run (CRB + LDLT and M^-1 for n <= 500
# only), has no point there.
# Usage: gnuplot -e "outdir='DIR'" l8_extreme.gp  (reads DIR/l8_extreme.csv)
set terminal pngcairo size 1400,720 enhanced font 'DejaVu Sans,11'
set output outdir.'/l8_extreme.png'
set datafile separator ','
set title 'Extreme chains, forward dynamics in double: error against the long double ABA'
set ylabel 'forward error'
set logscale y
set format y '10^{%L}'
set yrange [1e-18:1e4]
set grid ytics
set key top left font ',10'
set xtics rotate by 90 right font ',8' nomirror  # the case names, from an invisible curve
set bmargin 13
# columns: 1 id, 3 short name, 12 ABA error, 14 ABA bound, 16 CRB error, 20 M^-1 error
pos(c) = column(c) > 0 ? column(c) : 1/0
file = outdir.'/l8_extreme.csv'
plot file using 1:(1e-30):xtic(3) with points pt -1 notitle, \
     file using ($1 - 0.2):(pos(12)) with points pt 7 ps 1.2 lc 1 title 'ABA', \
     file using ($1 - 0.2):(pos(14)) with points pt 2 ps 0.8 lc rgb '#888888' title 'ABA bound 16 n eps kappa_D', \
     file using 1:(pos(16)) with points pt 5 ps 1.0 lc 2 title 'CRB + LDLT', \
     file using ($1 + 0.2):(pos(20)) with points pt 9 ps 1.0 lc 3 title 'M^{-1}(T - C)', \
     1e-6 with lines dt 2 lw 2 lc rgb '#444444' title 'tolerance 10^{-6}'
