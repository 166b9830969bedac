# SPDX-License-Identifier: MIT
# Per-step time against problem size from bench/scaling.py's tables (the script runs it):
#   gnuplot -e "data='build/scaling/scaling_dofs.tsv'; fits='build/scaling/scaling_dofs_fits.tsv'; \
#               nseries=2; nfits=4; png='docs/pictures/scaling_dofs.png'" bench/scaling.gp
# (optional: plot_title, xlabel, floor_label). Left: log-log time per step (solid) and its
# linear-solver floor (dashed) per series, with the fitted power laws (dotted, two per
# series, the exponent in the key); right: step / floor. A data block per series, first line
# the column titles; columns: 1 x, 2 step (s), 3 floor (s), 4 step / floor. A fits block has
# two points (the ends of the fitted range) and its title.
if (!exists("data")) data = 'build/scaling/scaling_dofs.tsv'
if (!exists("fits")) fits = 'build/scaling/scaling_dofs_fits.tsv'
if (!exists("nseries")) nseries = 2
if (!exists("nfits")) nfits = 2 * nseries
if (!exists("png")) png = 'docs/pictures/scaling_dofs.png'
if (!exists("plot_title")) plot_title = 'wall time per step (bench/scaling.py)'
if (!exists("xlabel")) xlabel = 'unknowns'
if (!exists("floor_label")) floor_label = 'bare factor + solve'
set datafile separator "\t"
set terminal pngcairo size 1300,560 font ",10" noenhanced
set output png
set multiplot layout 1,2 title plot_title font ",12"
set logscale xy
set format x "%g"
set format y "%g"
set grid
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
set xlabel xlabel
set ylabel "s per step (solid: step; dashed: ".floor_label."; dotted: fits)"
set key bottom right font ",9"
plot for [i=0:nseries-1] data index i using 1:2 with linespoints lw 2 pt 7 lc i+1 \
         title columnheader(2), \
     for [i=0:nseries-1] data index i using 1:3 with linespoints lw 1 dt 2 pt 6 lc i+1 \
         title columnheader(3), \
     for [j=0:nfits-1] fits index j using 1:2 with lines lw 1 dt 3 lc j/2+1 \
         title columnheader(2)
unset logscale y
set yrange [0:*]
set format y "%.1f"
set ylabel "step / (".floor_label.")"
set key top right
plot for [i=0:nseries-1] data index i using 1:4 with linespoints lw 2 pt 7 lc i+1 \
         title columnheader(4)
unset multiplot
