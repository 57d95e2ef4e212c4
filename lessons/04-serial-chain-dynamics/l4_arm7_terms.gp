# Lesson 4: the parts of the torque of joint 2 of the 7-joint arm: M beta_dot, the Coriolis and
# centrifugal part C(theta,beta) - C(theta,0), the static part C(theta,0), and their sum.
# Usage: gnuplot -e "outdir='DIR'" l4_arm7_terms.gp  (reads DIR/l4_arm7_terms.csv)
set terminal pngcairo size 800,560 enhanced font 'DejaVu Sans,12'
set output outdir.'/l4_arm7_terms.png'
set datafile separator ','
set title '7-joint arm, joint 2: T = M(θ) dβ/dt + C(θ,β)'
set xlabel 'time t [s]'
set ylabel 'torque [N m]'
set grid
set key outside bottom center horizontal maxcols 2 samplen 2 width 1
set offsets 0, 0, graph 0.05, graph 0.05
plot outdir.'/l4_arm7_terms.csv' using 1:2 with lines lw 2 title columnheader(2), \
     ''                          using 1:3 with lines lw 2 title columnheader(3), \
     ''                          using 1:4 with lines lw 2 title columnheader(4), \
     ''                          using 1:5 with lines lw 3 dt 2 lc rgb 'black' title columnheader(5)
