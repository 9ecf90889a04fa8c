# docs/server-reference.md, Load: the server's load benchmark (./run bench-server), from
# ball-load's load.dat (medians of the interleaved rounds, figures per match).
# gnuplot -e "data='D'; out='O'; plots='P'" P/load.gp
load plots.'/style.gp'
f = data.'/load.dat'
# states off with the server's loop thread under SCHED_FIFO (./run bench-server as root)
g = data.'/fifo/load.dat'
has_fifo = system("[ -f '".g."' ] && echo 1 || echo 0") + 0
# columns: 1 matches, 2 state rate, 3 overrun %, 4 work p50 ms, 5 work p99 ms,
# 6/7 sample-to-segment p50/p99 ms, 8/9 hit-to-wire p50/p99 ms, 10 server CPU %,
# 11 server RSS KiB, 12 bots CPU %, 13 server bytes/s, 14 bots bytes/s, 15 loopback bytes/s
set terminal pngcairo size 1200,800 font "DejaVu Sans,10" linewidth 1.4
set output out.'/load.png'
set logscale x
set xlabel "matches"
set format y "%g"
on(c) = ($2 > 0 ? column(c) : NaN)
off(c) = ($2 == 0 ? column(c) : NaN)
lat(c) = ($2 > 0 && column(c) > 0 ? column(c) : NaN)  # a point without a hit has no latency
set multiplot layout 2,2 title "ball-server at 60 Hz frames, server and bots on one 2-core machine (medians of rounds)"
set title "frames that overrun"
set ylabel "%"
set key top left
if (has_fifo) {
  plot f using 1:(on(3)) with linespoints ls 1 title "ball states on", \
       f using 1:(off(3)) with linespoints ls 2 title "ball states off", \
       g using 1:(off(3)) with linespoints ls 3 title "states off, loop thread SCHED\\_FIFO"
} else {
  plot f using 1:(on(3)) with linespoints ls 1 title "ball states on", \
       f using 1:(off(3)) with linespoints ls 2 title "ball states off"
}
set key top right
set title "server work per frame"
set ylabel "ms"
plot f using 1:(on(4)) with linespoints ls 1 title "p50, states on", \
     f using 1:(on(5)) with linespoints ls 4 title "p99, states on", \
     f using 1:(off(4)) with linespoints ls 2 title "p50, states off", \
     f using 1:(off(5)) with linespoints ls 3 title "p99, states off"
set title "bytes per match per second"
set ylabel "B/s"
set logscale y
set format y "10^{%L}"
plot f using 1:(on(13)) with linespoints ls 1 title "server payload, states on", \
     f using 1:(off(13)) with linespoints ls 2 title "server payload, states off", \
     f using 1:(on(15)) with linespoints ls 4 title "loopback device, states on", \
     f using 1:(off(15)) with linespoints ls 3 title "loopback device, states off"
unset logscale y
set format y "%g"
set title "latency (states on)"
set ylabel "ms"
plot f using 1:(lat(6)) with linespoints ls 1 title "sample-to-segment p50", \
     f using 1:(lat(7)) with linespoints ls 4 title "sample-to-segment p99", \
     f using 1:(lat(8)) with linespoints ls 2 title "hit-to-wire p50", \
     f using 1:(lat(9)) with linespoints ls 3 title "hit-to-wire p99"
unset multiplot
