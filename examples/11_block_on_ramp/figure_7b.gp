# SPDX-License-Identifier: MIT
# Luo 2021, 5.2, Figure 7b: relative error of the distance slid per step, DDA and VEM blocks,
# from figure_7b.py's table (run that first). From the repository root:
#   gnuplot examples/11_block_on_ramp/figure_7b.gp
# or gnuplot -e "dat='...'; png='...'" examples/11_block_on_ramp/figure_7b.gp.
# Columns of the .dat: 1 step, 2 time, then percent: 3 dda15, 4 vem15, 5 dda30, 6 vem30,
# 7 dda40, 8 vem40. The paper's first- and last-step values (from its text; the figure
# itself is not available) are drawn as open symbols at steps 1 and 35.
if (!exists("dat")) dat = 'examples/11_block_on_ramp/figure_7b.dat'
if (!exists("png")) png = 'docs/pictures/figure_7b.png'
set terminal pngcairo size 900,600 font ",11" noenhanced
set output png
set title "Block sliding on a 45° ramp (Luo 2021, 5.2, Figure 7b): (s - s_exact) / s_exact"
set xlabel "step (0.02 s)"
set ylabel "relative error of the distance slid, %"
set logscale y
set format y "%g"
set xrange [0:36]
set yrange [1e-4:100]
set key top right
set grid
colour(phi) = phi == 15 ? 0x1f77b4 : phi == 30 ? 0x2ca02c : 0xd62728
plot for [i=0:2] dat using 1:(column(3 + 2 * i)) with points pt 7 ps 1 \
         lc rgb colour(15 + 15 * i - 5 * (i == 2)) \
         title sprintf("DDA, phi = %d", 15 + 15 * i - 5 * (i == 2)), \
     for [i=0:2] dat using 1:(column(4 + 2 * i)) with lines dt 2 lw 2 \
         lc rgb colour(15 + 15 * i - 5 * (i == 2)) \
         title sprintf("VEM, phi = %d", 15 + 15 * i - 5 * (i == 2)), \
     '-' using 1:2:(colour($3)) with points pt 6 ps 2 lw 2 lc rgb variable \
         title "paper, DDA (first and last step)", \
     '-' using 1:2:(colour($3)) with points pt 4 ps 2 lw 2 lc rgb variable \
         title "paper, VEM (first and last step)"
1	0.65	15
35	0.06	15
1	2.4	30
35	0.2	30
1	55	40
35	2.9	40
e
1	0.65	15
35	0.06	15
1	2.4	30
35	0.2	30
1	37	40
35	2.0	40
e
