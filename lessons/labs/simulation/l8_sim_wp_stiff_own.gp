# Simulation report, section 3c: final-state error against wall time on the stiffest chain
# from its own start, one curve per method (the list and title from l8_sim_wp_stiff_own.gp
# in the output folder, written by the report).
# Usage: gnuplot -e "outdir='DIR'" l8_sim_wp_stiff_own.gp  (reads DIR/l8_sim_wp_stiff_own.csv)
set terminal pngcairo size 760,540 enhanced font 'DejaVu Sans,11'
set datafile separator ','
set xlabel 'wall time per run [s]'
set ylabel 'final-state error against the reference'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left font ',10'
load outdir.'/l8_sim_wp_stiff_own.gp'
file = outdir.'/l8_sim_wp_stiff_own.csv'
e(m) = (strcol(2) eq m && $8 > 0 && $7 > 0) ? $8 : 1/0
label(m) = m eq 'cvode' ? 'CVODE (SUNDIALS BDF)' : \
           (m eq 'esdirk4' ? 'esdirk4 (L-stable, adaptive)' : \
           (m eq 'radau5' ? 'radau5 (Radau IIA, L-stable, adaptive)' : \
           (m eq 'dopri5' || m eq 'implicit-midpoint' ? m : m.' (from its stability bound down)')))
# gnuplot's default colours for the methods of kMethods; esdirk4, radau5 and CVODE their own.
palette = '#9400d3 #009e73 #56b4e9 #e69f00 #f0e442 #0072b2 #e51e10 #808080'
colour(m, i) = m eq 'cvode' ? '#000000' : (m eq 'esdirk4' ? '#d62728' : \
               (m eq 'radau5' ? '#1f3a93' : word(palette, i)))
own(m) = m eq 'cvode' || m eq 'esdirk4' || m eq 'radau5'
dashes(m) = m eq 'cvode' ? 2 : 1
set output outdir.'/l8_sim_wp_stiff_own.png'
set title title_text noenhanced
plot for [i=1:words(methods)] file using 7:(e(word(methods, i))) with linespoints \
     lw (own(word(methods, i)) ? 3 : 2) pt (own(word(methods, i)) ? 5 : 7) \
     dt dashes(word(methods, i)) lc rgb colour(word(methods, i), i) \
     title label(word(methods, i)) noenhanced
