# Fig. 11: P(t ≤ Tmax, every r ≤ Rmax) over the grid, verification (a) beside validation (b).
# Made by `vipars report`; redraw with `gnuplot fig11_joint.gp` in this folder.
set encoding utf8
set xlabel "Tmax (s)" offset 0,-1
set ylabel "Rmax (m)" offset 1,-1
set zlabel "P" rotate parallel
set zrange [0:1]
set cbrange [0:1]
set xyplane at 0
set view 55, 300
set grid
set tics out
set palette defined (0 "#08306b", 0.05 "#2171b5", 0.5 "#f7f7f7", 0.95 "#cb181d", 1 "#67000d")
set pm3d depthorder
set terminal pngcairo size 1400,620 noenhanced font "DejaVu Sans,11"
set output "fig11_joint.png"
set multiplot title "bounding_overwatch: P(t ≤ Tmax, every r ≤ Rmax)"
set size 0.46, 0.92
set origin 0, 0
unset colorbox
set title "(a) verification (VIPARS)"
splot "fig11_joint.dat" using 1:2:3 with pm3d notitle
set origin 0.46, 0
set colorbox user origin 0.925, 0.25 size 0.015, 0.5
set title "(b) validation (10000 runs)"
splot "fig11_joint.dat" using 1:2:4 with pm3d notitle
unset multiplot
set terminal svg size 1400,620 noenhanced font "DejaVu Sans,11" background "white"
set output "fig11_joint.svg"
set multiplot title "bounding_overwatch: P(t ≤ Tmax, every r ≤ Rmax)"
set size 0.46, 0.92
set origin 0, 0
unset colorbox
set title "(a) verification (VIPARS)"
splot "fig11_joint.dat" using 1:2:3 with pm3d notitle
set origin 0.46, 0
set colorbox user origin 0.925, 0.25 size 0.015, 0.5
set title "(b) validation (10000 runs)"
splot "fig11_joint.dat" using 1:2:4 with pm3d notitle
unset multiplot
unset output
