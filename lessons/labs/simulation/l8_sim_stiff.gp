# Lesson 8 simulation: the stiff-spring chains (k = 1 ... k_max). Left: the largest stable
# step of each explicit method against k_max, the bound from the eigenvalues of the
# linearized chain (lines) and the step found on runs of soa::simulate (points; Dormand-Prince:
# the mean step of its controller), and the steps the implicit midpoint rule took (stars).
# Right: the implicit midpoint rule's error at the end against its step, from the slow start.
# Usage: gnuplot -e "outdir='DIR'" l8_sim_stiff.gp  (reads DIR/l8_sim_stiff.csv)
set terminal pngcairo size 1300,560 enhanced font 'DejaVu Sans,12'
set output outdir.'/l8_sim_stiff.png'
set datafile separator ','
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
# columns: 1 k_max, 3 method, 4 h_theory, 5 h_found (implicit: step used), 6 ratio, 9 error,
# 11 note
# (rows are grouped by method, so each method's line runs through its own rows)
f(m, c) = (strcol(3) eq m && column(c) > 0) ? column(c) : 1/0
ok(c) = (strcol(3) eq 'implicit-midpoint' && strcol(11) eq 'slow start' && column(9) > 0) ? column(c) : 1/0
file = outdir.'/l8_sim_stiff.csv'
set multiplot layout 1,2
set title 'Largest stable step: bound (lines) and found (points)'
set xlabel 'k_{max} (N m/rad), stiffest joint spring'
set ylabel 'step h (s)'
set xrange [0.3:3e8]
set key bottom left font ',10'
plot file using 1:(f('euler', 4)) with lines lw 2 dt 2 lc 1 notitle, \
     file using 1:(f('euler', 5)) with points pt 7 ps 1.3 lc 1 title 'explicit Euler', \
     file using 1:(f('symplectic-euler', 4)) with lines lw 2 dt 2 lc 2 notitle, \
     file using 1:(f('symplectic-euler', 5)) with points pt 5 ps 1.3 lc 2 title 'symplectic Euler', \
     file using 1:(f('rk4', 4)) with lines lw 2 dt 2 lc 3 notitle, \
     file using 1:(f('rk4', 5)) with points pt 9 ps 1.5 lc 3 title 'RK4', \
     file using 1:(f('dopri5', 4)) with lines lw 2 dt 2 lc 4 notitle, \
     file using 1:(f('dopri5', 5)) with points pt 11 ps 1.5 lc 4 title 'Dormand-Prince (controller mean)', \
     file using 1:(ok(5)) with points pt 3 ps 2 lw 2 lc rgb '#000000' title 'implicit midpoint, stable'
set title 'Implicit midpoint beyond the bound: error at t_{end}'
set xlabel 'h / RK4 bound'
set ylabel 'state error against the reference'
set autoscale x
set xrange [5:2000]
set key top left font ',10'
g(k) = (strcol(3) eq 'implicit-midpoint' && strcol(11) eq 'slow start' && column(1) == k && column(9) > 0) ? column(9) : 1/0
plot file using 6:(g(1e6)) with linespoints lw 2 pt 7 lc 3 title 'k_{max} = 10^6', \
     file using 6:(g(1e8)) with linespoints lw 2 pt 5 lc 4 title 'k_{max} = 10^8', \
     file using 6:(1e-4*($6/10)**2 * (strcol(3) eq 'implicit-midpoint' ? 1 : 1/0)) with lines dt 3 lc rgb '#888888' title 'slope 2'
unset multiplot
