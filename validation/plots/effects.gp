# docs/accuracy.md, Effects: the cost of a frame as effects are switched on
# one by one, against the model without what the effects still off act on.
load plots.'/style.gp'
f = data.'/effects.dat'
# columns: stage, label, ns (rest off in the mask), ns (rest removed from the model)
set terminal pngcairo size 1000,420 font "DejaVu Sans,10" linewidth 1.4
set output out.'/effects.png'
set title "A frame of the 7 s court scene (60 Hz) as effects are switched on one by one (min of interleaved rounds)"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set format y "%g"
set ylabel "ns per frame"
set yrange [0:*]
set key top left
plot f using 3:xtic(2) lc rgb "#1f77b4" title "the effects still off: off in the mask", \
     f using 4 lc rgb "#aaaaaa" title "the effects still off: removed from the model"
