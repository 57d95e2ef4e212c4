# Lesson 5: magnitude of the 7-joint arm's mass matrix |M(i,j)| as a heat map (log scale).
# Usage: gnuplot -e "outdir='DIR'" l5_arm7_mass_matrix.gp  (reads DIR/l5_arm7_mass_matrix.csv)
# Entries below 1e-6 are written as 1e-6 (the floor of the colour scale).
set terminal pngcairo size 640,560 enhanced font 'DejaVu Sans,12'
set output outdir.'/l5_arm7_mass_matrix.png'
set datafile separator ','
set title "7-joint arm: |M(i,j)| from the composite inertias (log scale)"
set xlabel 'column j (degree of freedom, tip first)'
set ylabel 'row i (degree of freedom, tip first)'
set logscale cb
set format cb '10^{%L}'
set cblabel '|M(i,j)| [kg m^2]'
set xrange [0.5:7.5]
set yrange [7.5:0.5]
set size ratio -1
set palette rgbformulae 33,13,10
plot outdir.'/l5_arm7_mass_matrix.csv' using ($1+1):($2+1):3 matrix with image notitle
