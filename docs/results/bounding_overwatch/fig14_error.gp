# Fig. 14: the verification error |verify − validate| of P(t ≤ Tmax, every r ≤ Rmax) over the grid; the circle marks its maximum.
# Made by `vipars report`; redraw with `gnuplot fig14_error.gp` in this folder.
set encoding utf8
set title "bounding_overwatch: |verification − validation| of P(t ≤ Tmax, every r ≤ Rmax)"
set xlabel "Tmax (s)"
set ylabel "Rmax (m)"
set cblabel "|verify − validate|"
set autoscale xfix
set autoscale yfix
set tics out
set cbrange [0:0.10000000000000001]
set rmargin at screen 0.8
set colorbox user origin screen 0.83, screen 0.15 size screen 0.02, screen 0.7
set cbtics add ("limit 0.08" 0.080000000000000002)
set palette defined (0 "white", 0.3 "#fee08b", 0.65 "#f46d43", 1 "#67001f")
set label 1 "max 0.018 at 201 s, 1.95 m" at 201, 1.95 point pointtype 6 pointsize 3 linecolor rgb "black" offset 1.5,1.5 front
set terminal pngcairo size 1000,680 noenhanced font "DejaVu Sans,11"
set output "fig14_error.png"
plot "fig14_error.dat" using 1:2:3 with image notitle
set terminal svg size 1000,680 noenhanced font "DejaVu Sans,11" background "white"
set output "fig14_error.svg"
plot "fig14_error.dat" using 1:2:3 with image notitle
unset output
