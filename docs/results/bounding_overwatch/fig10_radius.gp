# Fig. 10: P(every r ≤ Rmax) against Rmax, verification against validation, with the three regions.
# Made by `vipars report`; redraw with `gnuplot fig10_radius.gp` in this folder.
set encoding utf8
set title "bounding_overwatch: verification vs. validation of the spatial criterion"
set xlabel "Rmax (m)"
set ylabel "P(every robot's r ≤ Rmax)"
set xrange [1:3]
set yrange [-0.02:1.05]
set grid front linecolor rgb "#bbbbbb"
set key outside below center horizontal
set bmargin 6
set tics out
set object 1 rectangle from 1, graph 0 to 1.8250000000000002, graph 1 behind fillcolor rgb "#dddddd" fillstyle solid 1.0 noborder
set label 1 "High confidence\n(unsuccessful)" at 1.4125000000000001, graph 0.93 center front
set object 2 rectangle from 1.8250000000000002, graph 0 to 2.2250000000000001, graph 1 behind fillcolor rgb "#fff4c2" fillstyle solid 1.0 noborder
set label 2 "Uncertain" at 2.0250000000000004, graph 0.93 center front
set object 3 rectangle from 2.2250000000000001, graph 0 to 3, graph 1 behind fillcolor rgb "#d9f0d3" fillstyle solid 1.0 noborder
set label 3 "High confidence\n(successful)" at 2.6124999999999998, graph 0.93 center front
set arrow 90 from 2, graph 0 to 2, graph 1 nohead back dashtype 2 linecolor rgb "#555555"
set label 90 "criterion 2 m" at 2, graph 0.02 left offset 0.5,0.6 textcolor rgb "#555555"
set arrow 91 from 1.95, 0.29894616555176512 to 1.95, 0.28220000000000001 nohead front linecolor rgb "black" linewidth 3
set label 91 "max |verify − validate| = 0.017\nat 1.95 m" at 1.95, 0.29057308277588256 left offset 1,0 front
set terminal pngcairo size 1000,620 noenhanced font "DejaVu Sans,11"
set output "fig10_radius.png"
plot "fig10_radius.dat" using 1:4:5 with filledcurves fillcolor rgb "#fdb863" fillstyle transparent solid 0.55 noborder title "validation 95 % Wilson interval", \
     "fig10_radius.dat" using 1:3 with points pointtype 7 pointsize 0.7 linecolor rgb "#d95f02" title "validation (10000 runs)", \
     "fig10_radius.dat" using 1:2 with lines linewidth 2.5 linecolor rgb "#1f4e9c" title "verification (VIPARS)"
set terminal svg size 1000,620 noenhanced font "DejaVu Sans,11" background "white"
set output "fig10_radius.svg"
plot "fig10_radius.dat" using 1:4:5 with filledcurves fillcolor rgb "#fdb863" fillstyle transparent solid 0.55 noborder title "validation 95 % Wilson interval", \
     "fig10_radius.dat" using 1:3 with points pointtype 7 pointsize 0.7 linecolor rgb "#d95f02" title "validation (10000 runs)", \
     "fig10_radius.dat" using 1:2 with lines linewidth 2.5 linecolor rgb "#1f4e9c" title "verification (VIPARS)"
unset output
