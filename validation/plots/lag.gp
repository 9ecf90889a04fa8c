# docs/server-design.md, Lag compensation: hit rates behind a one-way delay
# (./run lag-study, from ball_lag_study's lag.dat).
# gnuplot -e "data='D'; out='O'; plots='P'" P/lag.gp
load plots.'/style.gp'
f = data.'/lag.dat'
# columns: 1 delay ms, 2/3 swinging ahead of the delay off/on, 4/5 swinging late off/on
set terminal pngcairo size 900,560 font "DejaVu Sans,10" linewidth 1.4
set output out.'/lag.png'
set title "two bots at 15 Hz, mid level: balls returned behind a one-way delay"
set xlabel "one-way delay of the racket samples (ms)"
set ylabel "hit rate (%)"
unset logscale
set format y "%g"
set yrange [0:105]
set key bottom left
plot f using 1:($2*100) with linespoints ls 1 title "swing ahead of the delay, no compensation", \
     f using 1:($3*100) with linespoints ls 2 title "swing ahead of the delay, compensation", \
     f using 1:($4*100) with linespoints ls 3 title "swing late (as people do), no compensation", \
     f using 1:($5*100) with linespoints ls 4 title "swing late, compensation (rewind window 250 ms)"
