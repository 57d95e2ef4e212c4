# Lesson 5: the UR5e's mass matrix along the joint path of section 6: its condition number
# cond2(M) (top) and its diagonal entries M(k,k) = H(k) R(k) H*(k) (bottom), both log scale.
# Usage: gnuplot -e "outdir='DIR'" l5_ur5e_mass_matrix.gp  (reads DIR/l5_ur5e_mass_matrix.csv)
set terminal pngcairo size 800,820 enhanced font 'DejaVu Sans,12'
set output outdir.'/l5_ur5e_mass_matrix.png'
set datafile separator ','
stats outdir.'/l5_ur5e_mass_matrix.csv' skip 1 nooutput
set lmargin 12
set rmargin 4
set multiplot layout 2,1 title 'UR5e: the mass matrix along the joint path (composite inertias)'
set grid
set logscale y
set format y '10^{%L}'
set ylabel 'cond_2(M)'
unset key
plot outdir.'/l5_ur5e_mass_matrix.csv' using 1:2 with lines lw 2 lc rgb 'black'
set ylabel 'M(k,k) [kg m^2]'
set xlabel 'path parameter s'
set key outside top center horizontal maxcols 3 samplen 2 noenhanced
plot for [i=3:STATS_columns] outdir.'/l5_ur5e_mass_matrix.csv' using 1:i with lines lw 2 \
     title columnheader(i)
unset multiplot
