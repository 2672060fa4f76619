# Work-precision figure of docs/integrators.md from docs/work-precision.csv.
#   gnuplot docs/work-precision.gp      (from any directory; writes .png and .svg beside this file)
# The CSV comes from: bench_lagrange_exact --work-precision=docs/work-precision.csv

dir = system("dirname '" . ARG0 . "'")
csv = dir . "/work-precision.csv"
set datafile separator ","

# Column numbers of the CSV.
H = 1; METHOD = 2; PARAM = 3; WALL = 4; WORK = 5; ANGLE = 6; ENERGY = 7

# One method at one horizon, column c against wall time; other rows become undefined (skipped).
pick(h, m, c) = (column(H) == h && strcol(METHOD) eq m) ? column(c) : NaN
exact_time(h) = system(sprintf("awk -F, '$1==%g && $2==\"lagrange-exact\" {print $4}' '%s'", h, csv)) + 0

set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set grid xtics ytics mxtics mytics lc rgb "#dddddd" lw 1
set key top right box opaque samplen 2 spacing 1.1 font ",10"
set xlabel "wall time per run (s, one core)"
set xrange [1e-4:2]
set style line 1 lc rgb "#1f77b4" lw 2 pt 7 ps 1.0   # adaptive
set style line 2 lc rgb "#d62728" lw 2 pt 5 ps 1.0   # splitting order 2
set style line 3 lc rgb "#2ca02c" lw 2 pt 9 ps 1.2   # splitting order 4
set style line 4 lc rgb "#555555" lw 2 dt 2          # lagrange-exact

do for [term = 1:2] {
  if (term == 1) {
    set terminal pngcairo size 1400,1000 enhanced font "Sans,11"
    set output dir . "/work-precision.png"
  } else {
    set terminal svg size 1400,1000 enhanced font "Sans,11" background rgb "white"
    set output dir . "/work-precision.svg"
  }
  set multiplot layout 2,2 title "Work-precision on the symmetric unit top (A = B = 1, C = 0.5 kg m^2, m g R = 1 N m, spin 5 rad/s, tilt 0.3 rad; nutation period T = 3.85 s), 1001 samples" font ",13"

  do for [h in "100 10000"] {
    hv = real(h)
    set title sprintf("Angle error over %s nutation periods (%s s)", (hv == 100 ? "100" : "10^4"), sprintf("%.0f", hv * 3.8514)) font ",12"
    set ylabel "max angle between axis and lagrange-exact's (rad)"
    set key bottom right
    set yrange [1e-12:3]
    te = exact_time(hv)
    set arrow 1 from te, graph 0 to te, graph 1 nohead ls 4
    set label 1 sprintf("lagrange-exact: %.2g ms", te * 1e3) at te, graph 0.22 offset 0.5,0 font ",10" tc rgb "#555555"
    plot csv using (pick(hv, "adaptive", WALL)):(pick(hv, "adaptive", ANGLE)) with linespoints ls 1 title "adaptive DOPRI5, rtol = atol = 10^{-4}..10^{-13}", \
         csv using (pick(hv, "splitting-2", WALL)):(pick(hv, "splitting-2", ANGLE)) with linespoints ls 2 title "splitting order 2, h = 0.2..0.003 s", \
         csv using (pick(hv, "splitting-4", WALL)):(pick(hv, "splitting-4", ANGLE)) with linespoints ls 3 title "splitting order 4, h = 0.8..0.0125 s"
  }
  do for [h in "100 10000"] {
    hv = real(h)
    set title sprintf("Energy error over %s nutation periods", (hv == 100 ? "100" : "10^4")) font ",12"
    set ylabel "max |E(t) - E(0)| / (T(0) + |m g R|) over all steps"
    set key top right
    set yrange [1e-14:1e-1]
    te = exact_time(hv)
    set arrow 1 from te, graph 0 to te, graph 1 nohead ls 4
    set label 1 "lagrange-exact: exact" at te, graph 0.22 offset 0.5,0 font ",10" tc rgb "#555555"
    plot csv using (pick(hv, "adaptive", WALL)):(pick(hv, "adaptive", ENERGY)) with linespoints ls 1 title "adaptive DOPRI5", \
         csv using (pick(hv, "splitting-2", WALL)):(pick(hv, "splitting-2", ENERGY)) with linespoints ls 2 title "splitting order 2", \
         csv using (pick(hv, "splitting-4", WALL)):(pick(hv, "splitting-4", ENERGY)) with linespoints ls 3 title "splitting order 4"
  }
  unset multiplot
  unset output
}
