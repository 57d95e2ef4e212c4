# Simulation report, section 1: final-state error against wall time, one figure per scene,
# one curve per integrator (the fitted order in its title, from l8_sim_orders.gp), esdirk4,
# radau5, the variational integrator and SUNDIALS CVODE with their own line styles (CVODE's fitted slope is not an order: BDF 1-5).
# Usage: gnuplot -e "outdir='DIR'" l8_sim_work_precision.gp  (reads DIR/l8_sim_work_precision.csv)
set terminal pngcairo size 760,540 enhanced font 'DejaVu Sans,11'
set datafile separator ','
set xlabel 'wall time per run [s]'
set ylabel 'final-state error against the reference'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left font ',10'
load outdir.'/l8_sim_orders.gp'
file = outdir.'/l8_sim_work_precision.csv'
methods = 'euler symplectic-euler rk4 dopri5 implicit-midpoint'
expected = '1 1 4 5 2'
e(s, m) = (strcol(1) eq s && strcol(2) eq m && $8 > 0 && $7 > 0) ? $8 : 1/0
order(s, i) = value('o_'.s.'_'.i)
otext(s, i) = (order(s, i) == order(s, i)) ? sprintf('%.2f', order(s, i)) : 'no fit'
do for [s in 'double_pendulum arm7 chain50 stiff_chain'] {
  set output outdir.'/l8_sim_wp_'.s.'.png'
  set title 'Error against run time: '.s noenhanced
  plot for [i=1:5] file using 7:(e(s, word(methods, i))) with linespoints lw 2 pt 7 lc i \
       title sprintf('%s (order %s, expected %s)', word(methods, i), otext(s, i), word(expected, i)), \
       file using 7:(e(s, 'esdirk4')) with linespoints lw 3 pt 5 lc rgb '#d62728' \
       title sprintf('esdirk4 (slope %s, expected 4)', otext(s, 'esdirk4')), \
       file using 7:(e(s, 'radau5')) with linespoints lw 3 pt 4 lc rgb '#1f3a93' \
       title sprintf('radau5 (slope %s, expected 5)', otext(s, 'radau5')), \
       file using 7:(e(s, 'variational')) with linespoints lw 2 pt 13 lc rgb '#9467bd' \
       title sprintf('variational (order %s, expected 2)', otext(s, 'variational')), \
       file using 7:(e(s, 'cvode')) with linespoints lw 3 pt 9 dt 2 lc rgb '#000000' \
       title (cvode_built ? sprintf('CVODE (SUNDIALS BDF) (slope %s)', otext(s, 'cvode')) : \
              'CVODE: not built (libsundials-dev missing)')
}
