# SPDX-License-Identifier: MIT
# Hertz's peak contact pressure: |error| against wall time, and the error against the
# refinement, from
# bench/hertz.py's table:
#   gnuplot -e "tsv='build/hertz-bench/hertz.tsv'; png='docs/pictures/hertz.png'" bench/hertz.gp
# Columns of the .tsv: 1 penalty (x E), 2 n, 3 h (m), 4 unknowns, 5 wall (s), 6 peak (Pa),
# 7 error (relative).
if (!exists("tsv")) tsv = 'build/hertz-bench/hertz.tsv'
if (!exists("png")) png = 'docs/pictures/hertz.png'
set terminal pngcairo size 1200,600 font ",11" noenhanced
set output png
set datafile separator "\t"
rows(file, penalty) = sprintf("< awk -F'\t' 'NR > 1 && $1 == %s' '%s'", penalty, file)
colour(penalty) = penalty eq "100" ? 0x1f77b4 : 0xd62728
penalties = "100 1000"
set multiplot layout 1,2 title "Hertz contact, cylinder on a block (examples/17): peak pressure against p0 = sqrt(P E* / (pi R))"
set logscale xy
set format y "%g"
set grid
set key below maxrows 3
set ylabel "|peak pressure error| (%)"
set yrange [0.01:10]
set xlabel "wall time (s)"
plot for [p in penalties] rows(tsv, p) using 5:(abs($7) * 100) with linespoints lw 2 pt 7 \
         lc rgb colour(p) title sprintf("penalty %s E", p), \
     for [p in penalties] rows(tsv, p) using 5:(abs($7) * 100):(sprintf("n=%d", $2)) \
         with labels offset 0,1 tc rgb colour(p) notitle, \
     1 with lines dt 2 lc rgb "black" title "goal 1%", \
     1.7 with lines dt 3 lc rgb "gray40" title "VEM paper 1.7% (VEM)", \
     3.6 with lines dt 4 lc rgb "gray60" title "VEM paper 3.6% (FEM)"
set xlabel "boundary edges across the half-width a (n)"
set ylabel "peak pressure error (%)"
unset logscale y
set yrange [-1.2:0.6]
set key inside top right
plot for [p in penalties] rows(tsv, p) using 2:($7 * 100) with linespoints lw 2 pt 7 \
         lc rgb colour(p) title sprintf("penalty %s E", p), \
     1 with lines dt 2 lc rgb "black" title "goal +-1%", -1 with lines dt 2 lc rgb "black" notitle, \
     0 with lines lc rgb "gray50" notitle
unset multiplot
