# Shared look of docs/accuracy.md's plots (loaded by each script). The
# scripts take `data` (the directory of ball_accuracy's .dat files) and `out`
# (where the PNGs go): gnuplot -e "data='D'; out='O'; plots='P'" P/flight.gp
set terminal pngcairo size 1200,480 font "DejaVu Sans,10" linewidth 1.4
set datafile missing "NaN"
set grid lc rgb "#dddddd"
set key top right box opaque samplen 2 font ",9"
set style line 1 lc rgb "#000000" pt 7 ps 0.8   # libball / exact / swept
set style line 2 lc rgb "#d62728" pt 5 ps 0.7   # Euler / sampled / sphere
set style line 3 lc rgb "#ff7f0e" pt 9 ps 0.8   # semi-implicit Euler / disc
set style line 4 lc rgb "#1f77b4" pt 13 ps 0.8  # RK4
set style line 5 lc rgb "#9467bd" pt 4 ps 0.8 dt 2  # MuJoCo Euler
set style line 6 lc rgb "#2ca02c" pt 6 ps 0.8 dt 2  # MuJoCo RK4
set format y "10^{%L}"
