# SPDX-License-Identifier: MIT
# Per-step time against the number of blocks from bench/block_bench.py's table:
#   gnuplot -e "tsv='build/block-bench/block_bench.tsv'; png='docs/pictures/block_bench.png'" \
#           bench/block_bench.gp
# and, to show an earlier run's steps next to it, before='other/block_bench.tsv' (with
# before_label='what it was'). docs/pictures/block_bench.png: the two runs of
# docs/benchmarks.md, "Blocks: DDA, VEM, NMM", before_label='before the optimisations'.
# Columns of the .tsv: 1 label, 2 model, 3 blocks, 11 factorisation (s per step), 15 step (s).
if (!exists("tsv")) tsv = 'build/block-bench/block_bench.tsv'
if (!exists("png")) png = 'docs/pictures/block_bench.png'
if (!exists("before_label")) before_label = 'before'
set datafile separator "\t"
set terminal pngcairo size 900,600 font ",11" noenhanced
set output png
set title "Jointed rock mass on a foundation: wall time per step (bench/block_bench.py)"
set xlabel "rock blocks"
set ylabel "ms per step"
set logscale xy
set format y "%g"
set xrange [70:14000]
set key top left
set grid
rows(file, model) = sprintf("< awk -F'\t' '$1 == \"rock mass\" && $2 == \"%s\"' '%s'", model, file)
colour(model) = model eq "dda" ? 0x1f77b4 : model eq "vem" ? 0xd62728 : 0x2ca02c
point(model) = model eq "dda" ? 7 : model eq "vem" ? 5 : 9
models = "dda vem nmm"
plot for [m in models] rows(tsv, m) using 3:($15 * 1e3) with linespoints lw 2 pt point(m) \
         lc rgb colour(m) title sprintf("%s step", m), \
     for [m in models] rows(tsv, m) using 3:($11 * 1e3) with linespoints dt 2 pt point(m) - 1 \
         lc rgb colour(m) title sprintf("%s factorisations", m), \
     for [m in (exists("before") ? models : "")] rows(before, m) using 3:($15 * 1e3) \
         with lines dt 3 lc rgb colour(m) title sprintf("%s step, %s", m, before_label), \
     '-' using 1:2 with points pt 3 ps 2.5 lw 2 lc rgb "black" title "goal: 20 DDA steps/s at 10000 blocks"
10000	50
e
