# docs/accuracy.md, Rackets: the sphere, disc and swept tests against the
# racket sample rate (= frame rate), and the landing of the four responses.
load plots.'/style.gp'
f = data.'/detect.dat'
# blocks: 0 sphere, 1 disc, 2 swept; columns: rate hit false toi_mean
# toi_max ns_min ns_med test_ns
set output out.'/rackets.png'
set multiplot layout 1,3 title "The detection study's seeded swings at 2 to 120 Hz"
set logscale x
set xrange [1.5:160]
set xtics (2, 6, 10, 15, 30, 60, 120)
set xlabel "racket sample rate = frame rate (Hz)"

set title "hit rate (ground-truth hits found)"
set ylabel "% of the hits"
set format y "%g"
set yrange [0:105]
set key bottom right
plot for [d=0:2] f index d using 1:2 with linespoints ls (d == 2 ? 1 : d + 2) title columnheader(1)

set title "time of impact error, mean over the hits found"
set ylabel "|t - t_{true}| (s)"
set logscale y
set format y "10^{%L}"
set yrange [1e-17:10]
set key top right
plot for [d=0:2] f index d using 1:4 with linespoints ls (d == 2 ? 1 : d + 2) title columnheader(1)

set title "cost per frame (push + step, min of rounds)"
set ylabel "ns per frame"
unset logscale y
set format y "%g"
set yrange [0:*]
plot for [d=0:2] f index d using 1:6 with linespoints ls (d == 2 ? 1 : d + 2) title columnheader(1)
unset multiplot

g = data.'/landing.dat'
# blocks: rates (10, 60 Hz) x levels (easy, mid, advanced) x responses
# (racket, autonomous, mixed, physical); columns: distance, share of hits
set terminal pngcairo size 1200,760 font "DejaVu Sans,10" linewidth 1.4
set output out.'/landing.png'
set multiplot layout 2,3 title "Where the ball lands: distance from the aim (autonomous: from the partner), share of the strokes that hit"
set logscale x
set xrange [0.01:30]
set xtics auto
set format x "%g"
set xlabel "distance (m)"
set ylabel "share of the hits at most this far"
set yrange [0:1]
set key bottom right
levels = "easy mid advanced"
do for [r=0:1] {
  do for [l=0:2] {
    set title sprintf("%s level, %d Hz", word(levels, l+1), r == 0 ? 10 : 60)
    plot for [p=0:3] g index ((r*3 + l)*4 + p) using 1:2 with steps ls (p == 0 ? 2 : p == 1 ? 1 : p == 2 ? 3 : 4) \
         title columnheader(1)
  }
}
unset multiplot
