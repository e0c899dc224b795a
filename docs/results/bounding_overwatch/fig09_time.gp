# Fig. 9: P(t ≤ Tmax) against Tmax, verification against validation, with the three regions.
# Made by `vipars report`; redraw with `gnuplot fig09_time.gp` in this folder.
set encoding utf8
set title "bounding_overwatch: verification vs. validation of the time criterion"
set xlabel "Tmax (s)"
set ylabel "P(t ≤ Tmax)"
set xrange [170:230]
set yrange [-0.02:1.05]
set grid front linecolor rgb "#bbbbbb"
set key outside below center horizontal
set bmargin 6
set tics out
set object 1 rectangle from 170, graph 0 to 187.5, graph 1 behind fillcolor rgb "#dddddd" fillstyle solid 1.0 noborder
set label 1 "High confidence\n(unsuccessful)" at 178.75, graph 0.93 center front
set object 2 rectangle from 187.5, graph 0 to 201.5, graph 1 behind fillcolor rgb "#fff4c2" fillstyle solid 1.0 noborder
set label 2 "Uncertain" at 194.5, graph 0.93 center front
set object 3 rectangle from 201.5, graph 0 to 230, graph 1 behind fillcolor rgb "#d9f0d3" fillstyle solid 1.0 noborder
set label 3 "High confidence\n(successful)" at 215.75, graph 0.93 center front
set arrow 90 from 200, graph 0 to 200, graph 1 nohead back dashtype 2 linecolor rgb "#555555"
set label 90 "criterion 200 s" at 200, graph 0.02 left offset 0.5,0.6 textcolor rgb "#555555"
set arrow 91 from 201, 0.92710977589960974 to 201, 0.91949999999999998 nohead front linecolor rgb "black" linewidth 3
set label 91 "max |verify − validate| = 0.008\nat 201 s" at 201, 0.92330488794980492 right offset -1,0 front
set terminal pngcairo size 1000,620 noenhanced font "DejaVu Sans,11"
set output "fig09_time.png"
plot "fig09_time.dat" using 1:4:5 with filledcurves fillcolor rgb "#fdb863" fillstyle transparent solid 0.55 noborder title "validation 95 % Wilson interval", \
     "fig09_time.dat" using 1:3 with points pointtype 7 pointsize 0.7 linecolor rgb "#d95f02" title "validation (10000 runs)", \
     "fig09_time.dat" using 1:2 with lines linewidth 2.5 linecolor rgb "#1f4e9c" title "verification (VIPARS)"
set terminal svg size 1000,620 noenhanced font "DejaVu Sans,11" background "white"
set output "fig09_time.svg"
plot "fig09_time.dat" using 1:4:5 with filledcurves fillcolor rgb "#fdb863" fillstyle transparent solid 0.55 noborder title "validation 95 % Wilson interval", \
     "fig09_time.dat" using 1:3 with points pointtype 7 pointsize 0.7 linecolor rgb "#d95f02" title "validation (10000 runs)", \
     "fig09_time.dat" using 1:2 with lines linewidth 2.5 linecolor rgb "#1f4e9c" title "verification (VIPARS)"
unset output
