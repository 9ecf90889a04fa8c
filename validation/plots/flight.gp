# docs/accuracy.md, Flight: position error against cost, log-log.
load plots.'/style.gp'
f = data.'/flight.dat'
# blocks: 2 s shot then 10 s flight, six methods each
set logscale xy
set format x "10^{%L}"
set key bottom right
set ytics 100

set output out.'/flight.png'
set multiplot layout 1,2 title "Largest position error over the flight against cost, a state at every step (steps 1/6 s to 1e-4 s)"
do for [c=0:1] {
  set title (c == 0 ? "2 s shot" : "10 s flight")
  set xlabel "wall clock per simulated second (ns)"
  set ylabel "largest position error (m)"
  set yrange [1e-19:10]
  plot for [m=0:5] f index (c*6 + m) using 5:2 with linespoints ls (m+1) title columnheader(1)
}
unset multiplot

set output out.'/flight_query.png'
set multiplot layout 1,2 title "One query \"where is the ball at T\": libball evaluates eq 3 once, an integrator steps from 0 to T"
do for [c=0:1] {
  set title (c == 0 ? "2 s shot, T = 2 s" : "10 s flight, T = 10 s")
  set xlabel "wall clock for one query (ns)"
  set ylabel "position error at T (m)"
  set yrange [1e-19:10]
  plot f index (c*6) every ::0::0 using 7:3 with points ls 1 ps 2 title columnheader(1), \
       for [m=1:5] f index (c*6 + m) using 7:3 with linespoints ls (m+1) title columnheader(1)
}
unset multiplot
