# Lesson 6: along the 50-link chain, the size of the articulated inertia P(k) relative to the
# composite inertia R(k): largest eigenvalues and traces (both <= 1 since P <= R).
# Usage: gnuplot -e "outdir='DIR'" l6_chain50_P_vs_R.gp  (reads DIR/l6_chain50.csv)
set terminal pngcairo size 800,560 enhanced font 'DejaVu Sans,12'
set output outdir.'/l6_chain50_P_vs_R.png'
set datafile separator ','
set title '50-link chain: P(k) relative to R(k)'
set xlabel 'body k (1 = tip)'
set ylabel 'ratio'
set logscale y
set grid
set key top right
plot outdir.'/l6_chain50.csv' using 1:4 with linespoints lw 2 pt 7 ps 0.6 title 'λ_{max}(P) / λ_{max}(R)', \
     ''                       using 1:5 with linespoints lw 2 pt 5 ps 0.6 title 'tr P / tr R'
