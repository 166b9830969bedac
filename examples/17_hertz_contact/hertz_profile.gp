# SPDX-License-Identifier: MIT
# The contact pressure of examples/17_hertz_contact against Hertz's, from the profile that
# hertz_pressure.py writes (from the repository root, after the run):
#   python3 examples/17_hertz_contact/hertz_pressure.py --profile build/hertz_profile.dat
#   gnuplot -e "dat='build/hertz_profile.dat'; png='docs/pictures/hertz_profile.png'" \
#           examples/17_hertz_contact/hertz_profile.gp
# Columns: 1 x (m), 2 the run's pressure (Pa), 3 Hertz's p0 sqrt(1 - x^2/a^2) (Pa).
if (!exists("dat")) dat = 'build/hertz_profile.dat'
if (!exists("png")) png = 'docs/pictures/hertz_profile.png'
set terminal pngcairo size 900,520 font ",11" noenhanced
set output png
set title "Cylinder on a block (examples/17): contact pressure, a = 20.845 mm, p0 = 610.8 MPa"
set xlabel "x (mm)"
set ylabel "contact pressure (MPa)"
set grid
set key top right
set xrange [0:24]
set yrange [0:700]
a = 20.845e-3
p0 = 610.813e6
hertz(x) = abs(x) < a ? p0 * sqrt(1 - (x / a)**2) : 0
set samples 1000
plot hertz(x / 1e3) / 1e6 with lines lw 2 lc rgb "black" title "Hertz: p0 sqrt(1 - x^2/a^2)", \
     dat using ($1 * 1e3):($2 / 1e6) with points pt 7 ps 0.8 lc rgb "#d62728" \
         title "nmm: pressure of the contact points (mean over each chord of the cylinder)"
