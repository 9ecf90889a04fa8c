# docs/accuracy.md, Static obstacles: the sampled and the exact scheme
# against frame rate.
load plots.'/style.gp'
f = data.'/static.dat'
# blocks: 0 sampled, 1 exact; columns: rate first_dt first_dp max_dt max_dp
# energy missed false ns_min ns_med
set terminal pngcairo size 1200,760 font "DejaVu Sans,10" linewidth 1.4
set output out.'/static.png'
set multiplot layout 2,3 title "Sampled (the paper's per-frame tests) against exact (closed-form contacts) at 2 to 120 Hz"
set logscale x
set xrange [1.5:160]
set xtics (2, 6, 10, 15, 30, 60, 120)
set xlabel "frame rate (Hz)"
set logscale y
set yrange [1e-17:100]
set key center right
# an error below 1e-16 (or exactly 0) is drawn at 1e-16

set title "bounce time error, mean over 200 throws"
set ylabel "|time error| (s)"
plot f index 0 using 1:2 with linespoints ls 2 title "sampled, 1st bounce", \
     f index 0 using 1:4 with linespoints ls 2 dt 2 title "sampled, worst of 10", \
     f index 1 using 1:2 with linespoints ls 1 title "exact, 1st bounce", \
     f index 1 using 1:4 with linespoints ls 1 dt 2 title "exact, worst of 10"

set title "bounce point error, mean over 200 throws"
set ylabel "|point error| (m)"
plot f index 0 using 1:3 with linespoints ls 2 title "sampled, 1st bounce", \
     f index 0 using 1:5 with linespoints ls 2 dt 2 title "sampled, worst of 10", \
     f index 1 using 1:3 with linespoints ls 1 title "exact, 1st bounce", \
     f index 1 using 1:5 with linespoints ls 1 dt 2 title "exact, worst of 10"

set title "energy just after the 10th bounce"
set ylabel "|E - E_{ref}| / E_{ref}"
set yrange [1e-17:1000]
plot f index 0 using 1:6 with linespoints ls 2 title "sampled", \
     f index 1 using 1:6 with linespoints ls 1 title "exact"

set title "shots at the net (10,000)"
set ylabel "% of the net hits (missed), of the misses (made up)"
unset logscale y
set format y "%g"
set yrange [0:45]
set key top right
plot f index 0 using 1:7 with linespoints ls 2 title "sampled: missed (tunnelling)", \
     f index 0 using 1:8 with linespoints ls 2 dt 2 title "sampled: made up", \
     f index 1 using 1:7 with linespoints ls 1 title "exact: missed", \
     f index 1 using 1:8 with linespoints ls 1 dt 2 title "exact: made up"

set title "cost per frame (court scene: floor, net, 2 walls)"
set ylabel "ns per frame (min of rounds)"
set yrange [0:*]
set key top right
plot f index 0 using 1:9 with linespoints ls 2 title "sampled", \
     f index 1 using 1:9 with linespoints ls 1 title "exact"

set title "cost per simulated second"
set ylabel "ns per simulated second"
set logscale y
set format y "10^{%L}"
set yrange [*:*]
set key top left
plot f index 0 using 1:($9*$1) with linespoints ls 2 title "sampled", \
     f index 1 using 1:($9*$1) with linespoints ls 1 title "exact"
unset multiplot
