# Fig. 12: P(t ≤ Tmax, every r ≤ Rmax) against Tmax at several Rmax (slices of Fig. 11).
# Made by `vipars report`; redraw with `gnuplot fig12_slices_tmax.gp` in this folder.
set encoding utf8
set title "concurrent_moves: time criterion at several Rmax"
set xlabel "Tmax (s)"
set ylabel "P(t ≤ Tmax, every r ≤ Rmax)"
set xrange [105:165]
set yrange [-0.02:1.05]
set grid
set tics out
set key outside right top box
set terminal pngcairo size 1000,620 noenhanced font "DejaVu Sans,11"
set output "fig12_slices_tmax.png"
plot keyentry with lines linewidth 2.5 linecolor rgb "black" title "verification", \
     keyentry with points pointtype 7 linecolor rgb "black" title "validation, 95 % band", \
     "fig12_slices_tmax.dat" index 0 using 1:4:5 with filledcurves fillcolor rgb "#1b9e77" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 0 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#1b9e77" notitle, \
     "fig12_slices_tmax.dat" index 0 using 1:2 with lines linewidth 2.5 linecolor rgb "#1b9e77" title "Rmax 0.96 m", \
     "fig12_slices_tmax.dat" index 1 using 1:4:5 with filledcurves fillcolor rgb "#d95f02" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 1 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#d95f02" notitle, \
     "fig12_slices_tmax.dat" index 1 using 1:2 with lines linewidth 2.5 linecolor rgb "#d95f02" title "Rmax 1 m", \
     "fig12_slices_tmax.dat" index 2 using 1:4:5 with filledcurves fillcolor rgb "#7570b3" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 2 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#7570b3" notitle, \
     "fig12_slices_tmax.dat" index 2 using 1:2 with lines linewidth 2.5 linecolor rgb "#7570b3" title "Rmax 1.05 m", \
     "fig12_slices_tmax.dat" index 3 using 1:4:5 with filledcurves fillcolor rgb "#e7298a" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 3 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#e7298a" notitle, \
     "fig12_slices_tmax.dat" index 3 using 1:2 with lines linewidth 2.5 linecolor rgb "#e7298a" title "Rmax 1.09 m"
set terminal svg size 1000,620 noenhanced font "DejaVu Sans,11" background "white"
set output "fig12_slices_tmax.svg"
plot keyentry with lines linewidth 2.5 linecolor rgb "black" title "verification", \
     keyentry with points pointtype 7 linecolor rgb "black" title "validation, 95 % band", \
     "fig12_slices_tmax.dat" index 0 using 1:4:5 with filledcurves fillcolor rgb "#1b9e77" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 0 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#1b9e77" notitle, \
     "fig12_slices_tmax.dat" index 0 using 1:2 with lines linewidth 2.5 linecolor rgb "#1b9e77" title "Rmax 0.96 m", \
     "fig12_slices_tmax.dat" index 1 using 1:4:5 with filledcurves fillcolor rgb "#d95f02" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 1 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#d95f02" notitle, \
     "fig12_slices_tmax.dat" index 1 using 1:2 with lines linewidth 2.5 linecolor rgb "#d95f02" title "Rmax 1 m", \
     "fig12_slices_tmax.dat" index 2 using 1:4:5 with filledcurves fillcolor rgb "#7570b3" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 2 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#7570b3" notitle, \
     "fig12_slices_tmax.dat" index 2 using 1:2 with lines linewidth 2.5 linecolor rgb "#7570b3" title "Rmax 1.05 m", \
     "fig12_slices_tmax.dat" index 3 using 1:4:5 with filledcurves fillcolor rgb "#e7298a" fillstyle transparent solid 0.15 noborder notitle, \
     "fig12_slices_tmax.dat" index 3 using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb "#e7298a" notitle, \
     "fig12_slices_tmax.dat" index 3 using 1:2 with lines linewidth 2.5 linecolor rgb "#e7298a" title "Rmax 1.09 m"
unset output
