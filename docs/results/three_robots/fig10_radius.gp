# Fig. 10: P(every r ≤ Rmax) against Rmax, verification against validation, with the three regions.
# Made by `vipars report`; redraw with `gnuplot fig10_radius.gp` in this folder.
set encoding utf8
set title "three_robots: verification vs. validation of the spatial criterion"
set xlabel "Rmax (m)"
set ylabel "P(every robot's r ≤ Rmax)"
set xrange [0.5:1.3]
set yrange [-0.02:1.05]
set grid front linecolor rgb "#bbbbbb"
set key outside below center horizontal
set bmargin 6
set tics out
set object 1 rectangle from 0.5, graph 0 to 0.71499999999999997, graph 1 behind fillcolor rgb "#dddddd" fillstyle solid 1.0 noborder
set label 1 "High confidence\n(unsuccessful)" at 0.60749999999999993, graph 0.93 center front
set object 2 rectangle from 0.71499999999999997, graph 0 to 0.93500000000000005, graph 1 behind fillcolor rgb "#fff4c2" fillstyle solid 1.0 noborder
set label 2 "Uncertain" at 0.82499999999999996, graph 0.93 center front
set object 3 rectangle from 0.93500000000000005, graph 0 to 1.3, graph 1 behind fillcolor rgb "#d9f0d3" fillstyle solid 1.0 noborder
set label 3 "High confidence\n(successful)" at 1.1175000000000002, graph 0.93 center front
set arrow 90 from 0.80000000000000004, graph 0 to 0.80000000000000004, graph 1 nohead back dashtype 2 linecolor rgb "#555555"
set label 90 "criterion 0.8 m" at 0.80000000000000004, graph 0.02 left offset 0.5,0.6 textcolor rgb "#555555"
set arrow 91 from 0.98999999999999999, 0.9823231419021633 to 0.98999999999999999, 0.97799999999999998 nohead front linecolor rgb "black" linewidth 3
set label 91 "max |verify − validate| = 0.004\nat 0.99 m" at 0.98999999999999999, 0.98016157095108158 right offset -1,0 front
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
