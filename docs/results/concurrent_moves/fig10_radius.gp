# Fig. 10: P(every r ≤ Rmax) against Rmax, verification against validation, with the three regions.
# Made by `vipars report`; redraw with `gnuplot fig10_radius.gp` in this folder.
set encoding utf8
set title "concurrent_moves: verification vs. validation of the spatial criterion"
set xlabel "Rmax (m)"
set ylabel "P(every robot's r ≤ Rmax)"
set xrange [0.69999999999999996:1.3]
set yrange [-0.02:1.05]
set grid front linecolor rgb "#bbbbbb"
set key outside below center horizontal
set bmargin 6
set tics out
set object 1 rectangle from 0.69999999999999996, graph 0 to 0.96499999999999997, graph 1 behind fillcolor rgb "#dddddd" fillstyle solid 1.0 noborder
set label 1 "High confidence\n(unsuccessful)" at 0.83250000000000002, graph 0.93 center front
set object 2 rectangle from 0.96499999999999997, graph 0 to 1.0550000000000002, graph 1 behind fillcolor rgb "#fff4c2" fillstyle solid 1.0 noborder
set label 2 "Uncertain" at 1.01, graph 0.93 center front
set object 3 rectangle from 1.0550000000000002, graph 0 to 1.3, graph 1 behind fillcolor rgb "#d9f0d3" fillstyle solid 1.0 noborder
set label 3 "High confidence\n(successful)" at 1.1775000000000002, graph 0.93 center front
set arrow 90 from 1, graph 0 to 1, graph 1 nohead back dashtype 2 linecolor rgb "#555555"
set label 90 "criterion 1 m" at 1, graph 0.02 left offset 0.5,0.6 textcolor rgb "#555555"
set arrow 91 from 0.98999999999999999, 0.28142670055397706 to 0.98999999999999999, 0.22439999999999999 nohead front linecolor rgb "black" linewidth 3
set label 91 "max |verify − validate| = 0.057\nat 0.99 m" at 0.98999999999999999, 0.25291335027698852 left offset 1,0 front
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
