# docs/benchmarks.md, Across the internet: real delay: latency figures of a
# match through the tests' NAT and delay relay (./run bench-wan, wan.dat).
# gnuplot -e "data='D'; out='O'; plots='P'" P/wan.gp
load plots.'/style.gp'
f = data.'/wan.dat'
# columns: 1 one-way delay ms, 2/3 sample-to-segment p50/p99 at the server,
# 4/5 at the watcher, 6 a bounce's segment received ahead of it (p50), 7 hits
set terminal pngcairo size 900,560 font "DejaVu Sans,10" linewidth 1.4
set output out.'/wan_delay.png'
set title "a match over TCP behind a home router's NAT, both directions delayed by the relay"
set xlabel "one-way delay, each direction (ms; jitter a fifth of it)"
set ylabel "ms"
unset logscale
set format y "%g"
set yrange [0:*]
set key center right
plot f using 1:2 with linespoints ls 1 title "racket sample written -> its hit's segment written by the server (p50)", \
     f using 1:3 with linespoints ls 2 title "the same, p99", \
     f using 1:4 with linespoints ls 3 title "racket sample written -> the segment received by the watcher (p50)", \
     f using 1:6 with linespoints ls 4 title "a bounce's segment received ahead of the bounce (p50)"
