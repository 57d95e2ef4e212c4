# Lesson 8 simulation: the extreme chains over 0.03 s, the state error of each integrator
# against the reference (dopri5 at 1e-13) per case; a run stopped by a diagnostic (beyond
# its stability bound, blow-up, Newton's method failing, a singular D) is drawn as a cross
# at the top, a run not made (cost) has no point.
# Usage: gnuplot -e "outdir='DIR'" l8_sim_extreme.gp  (reads DIR/l8_sim_extreme.csv)
set terminal pngcairo size 1300,700 enhanced font 'DejaVu Sans,11'
set output outdir.'/l8_sim_extreme.png'
set datafile separator ','
set title 'Extreme chains simulated over 0.03 s: state error against the reference'
set ylabel 'state error'
set logscale y
set format y '10^{%L}'
set yrange [1e-14:1e6]
set grid ytics
set key top left font ',10'
set xtics rotate by 90 right font ',8' nomirror  # the case names, from an invisible curve
set bmargin 12
set offsets 0.5, 0.5, 0, 0
# columns: 1 case id, 2 case, 9 method, 10 status, 14 state error (eight rows per case)
file = outdir.'/l8_sim_extreme.csv'
is(m) = strcol(9) eq m
err(m) = is(m) && strcol(10) eq 'finished' && column(14) > 0 ? column(14) : 1/0
stop(m) = is(m) && strcol(10) eq 'diagnosed' ? 1e5 : 1/0
plot file every 8 using 1:(1e-30):xtic(2) with points pt -1 notitle, \
     file using ($1 - 0.42):(err('euler')) with points pt 7 ps 1.0 lc 1 title 'euler', \
     file using ($1 - 0.30):(err('symplectic-euler')) with points pt 5 ps 1.0 lc 2 title 'symplectic-euler', \
     file using ($1 - 0.18):(err('rk4')) with points pt 9 ps 1.2 lc 3 title 'rk4', \
     file using ($1 - 0.06):(err('dopri5')) with points pt 11 ps 1.2 lc 4 title 'dopri5', \
     file using ($1 + 0.06):(err('implicit-midpoint')) with points pt 13 ps 1.2 lc 7 title 'implicit-midpoint', \
     file using ($1 - 0.42):(stop('euler')) with points pt 2 ps 1.2 lc 1 notitle, \
     file using ($1 - 0.30):(stop('symplectic-euler')) with points pt 2 ps 1.2 lc 2 notitle, \
     file using ($1 - 0.18):(stop('rk4')) with points pt 2 ps 1.2 lc 3 notitle, \
     file using ($1 - 0.06):(stop('dopri5')) with points pt 2 ps 1.2 lc 4 notitle, \
     file using ($1 + 0.06):(stop('implicit-midpoint')) with points pt 2 ps 1.2 lc 7 notitle, \
     file using ($1 + 0.18):(err('esdirk4')) with points pt 15 ps 1.2 lc 6 title 'esdirk4', \
     file using ($1 + 0.18):(stop('esdirk4')) with points pt 2 ps 1.2 lc 6 notitle, \
     file using ($1 + 0.30):(err('radau5')) with points pt 4 ps 1.2 lc rgb '#1f3a93' title 'radau5', \
     file using ($1 + 0.30):(stop('radau5')) with points pt 2 ps 1.2 lc rgb '#1f3a93' notitle, \
     file using ($1 + 0.42):(err('variational')) with points pt 6 ps 1.2 lc rgb '#9467bd' title 'variational', \
     file using ($1 + 0.42):(stop('variational')) with points pt 2 ps 1.2 lc rgb '#9467bd' title 'stopped by a diagnostic'
