# Fig. 13: P(t ≤ Tmax, every r ≤ Rmax) against Rmax at several Tmax (slices of Fig. 11).
# Made by `vipars report`; redraw with `gnuplot fig13_slices_rmax.gp` in this folder.
set encoding utf8
set title "concurrent_moves: spatial criterion at several Tmax"
set xlabel "Rmax (m)"
set ylabel "P(t ≤ Tmax, every r ≤ Rmax)"
set xrange [0.69999999999999996:1.3]
set yrange [-0.02:1.05]
set grid
set tics out
set key outside right top box
set terminal pngcairo size 1000,620 noenhanced font "DejaVu Sans,11"
set output "fig13_slices_rmax.png"
plot keyentry with lines linewidth 2.5 linecolor rgb "black" title "verification", \
     keyentry with points pointtype 7 linecolor rgb "black" title "validation, 95 % band", \
     "fig13_slices_rmax.dat" index 0 using 1:4:5 with filledcurves fillcolor rgb "#1b9e77" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 0 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#1b9e77" notitle, \
     "fig13_slices_rmax.dat" index 0 using 1:2 with lines linewidth 2.5 linecolor rgb "#1b9e77" title "Tmax 114.5 s", \
     "fig13_slices_rmax.dat" index 1 using 1:4:5 with filledcurves fillcolor rgb "#d95f02" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 1 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#d95f02" notitle, \
     "fig13_slices_rmax.dat" index 1 using 1:2 with lines linewidth 2.5 linecolor rgb "#d95f02" title "Tmax 127.5 s", \
     "fig13_slices_rmax.dat" index 2 using 1:4:5 with filledcurves fillcolor rgb "#7570b3" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 2 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#7570b3" notitle, \
     "fig13_slices_rmax.dat" index 2 using 1:2 with lines linewidth 2.5 linecolor rgb "#7570b3" title "Tmax 141 s", \
     "fig13_slices_rmax.dat" index 3 using 1:4:5 with filledcurves fillcolor rgb "#e7298a" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 3 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#e7298a" notitle, \
     "fig13_slices_rmax.dat" index 3 using 1:2 with lines linewidth 2.5 linecolor rgb "#e7298a" title "Tmax 154 s"
set terminal svg size 1000,620 noenhanced font "DejaVu Sans,11" background "white"
set output "fig13_slices_rmax.svg"
plot keyentry with lines linewidth 2.5 linecolor rgb "black" title "verification", \
     keyentry with points pointtype 7 linecolor rgb "black" title "validation, 95 % band", \
     "fig13_slices_rmax.dat" index 0 using 1:4:5 with filledcurves fillcolor rgb "#1b9e77" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 0 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#1b9e77" notitle, \
     "fig13_slices_rmax.dat" index 0 using 1:2 with lines linewidth 2.5 linecolor rgb "#1b9e77" title "Tmax 114.5 s", \
     "fig13_slices_rmax.dat" index 1 using 1:4:5 with filledcurves fillcolor rgb "#d95f02" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 1 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#d95f02" notitle, \
     "fig13_slices_rmax.dat" index 1 using 1:2 with lines linewidth 2.5 linecolor rgb "#d95f02" title "Tmax 127.5 s", \
     "fig13_slices_rmax.dat" index 2 using 1:4:5 with filledcurves fillcolor rgb "#7570b3" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 2 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#7570b3" notitle, \
     "fig13_slices_rmax.dat" index 2 using 1:2 with lines linewidth 2.5 linecolor rgb "#7570b3" title "Tmax 141 s", \
     "fig13_slices_rmax.dat" index 3 using 1:4:5 with filledcurves fillcolor rgb "#e7298a" fillstyle transparent solid 0.15 noborder notitle, \
     "fig13_slices_rmax.dat" index 3 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#e7298a" notitle, \
     "fig13_slices_rmax.dat" index 3 using 1:2 with lines linewidth 2.5 linecolor rgb "#e7298a" title "Tmax 154 s"
unset output
