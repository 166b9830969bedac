# SPDX-License-Identifier: MIT
# Work-precision diagram of one problem from bench/work_precision.py's tables: the relative
# error against the time of the steps (left) and against the mesh size or time step (right),
# one line per series; a second table (tsv2) adds a second row of the same two panels.
# bench/work_precision.py runs it for every problem; by hand, e.g.
#   gnuplot -e "tsv='build/work-precision/work_precision_incline.tsv'; blocks=2; \
#               png='docs/pictures/work_precision_incline.png'" bench/work_precision.gp
# (optional: plot_title, hlabel, elabel; tsv2, blocks2, elabel2). A table has one block per
# series (two blank lines between), headed by the series' title; columns: 1 h (or dt),
# 2 unknowns, 3 seconds_steps, 4 wall_seconds, 5 value, 6 exact, 7 relative error.
if (!exists("tsv")) tsv = 'build/work-precision/work_precision_cantilever.tsv'
if (!exists("png")) png = 'docs/pictures/work_precision_cantilever.png'
if (!exists("blocks")) blocks = 1
if (!exists("plot_title")) plot_title = 'work-precision'
if (!exists("hlabel")) hlabel = 'h (m)'
if (!exists("elabel")) elabel = 'relative error'
rows = exists("tsv2") ? 2 : 1
set datafile separator "\t"
set terminal pngcairo size 1200,(rows == 2 ? 960 : 500) font ",10" noenhanced
set output png
set multiplot layout rows,2 title plot_title font ",12"
set logscale xy
set format x "%g"
set format y "%.0e"
set grid
tlabel = "time of the steps, s (summary.json counters.seconds_steps)"
set xlabel tlabel
set ylabel elabel
set key top right
plot for [i=0:blocks-1] tsv index i using 3:7 with linespoints lw 2 pt 7 title columnheader(1)
set xlabel hlabel
set key top left
plot for [i=0:blocks-1] tsv index i using 1:7 with linespoints lw 2 pt 7 title columnheader(1)
if (rows == 2) {
  set ylabel elabel2
  set xlabel tlabel
  set key top right
  plot for [i=0:blocks2-1] tsv2 index i using 3:7 with linespoints lw 2 pt 7 title columnheader(1)
  set xlabel hlabel
  set key top left
  plot for [i=0:blocks2-1] tsv2 index i using 1:7 with linespoints lw 2 pt 7 title columnheader(1)
}
unset multiplot
