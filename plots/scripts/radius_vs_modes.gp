# radius_vs_modes.gp: each (cost, method) run's 50 % start-distance radius (with the interval from the 95 % Wilson
# bounds) against the number of modes in the data, one experiment per pulse width, beside the least-squares basin
# predicted for each experiment, min_k 1/(2 f_k T_eff,k) over its fitted modes (black, dashed). A censored radius
# (position "above": every offset tried kept half the starts, so the radius is at least the largest; "below": none
# did, so it is under the smallest) is a triangle pointing the way the radius lies, without an interval. Colour is the
# cost, and more than six runs are split into one panel per cost (issue 35: at most about six series a panel), where
# the point type tells the methods apart.
# Input: dir/start_distance/radius.csv (cost,method,reference_status,half_radius,half_radius_low,half_radius_high,
#        position,predicted_basin,ratio,predicted_basin_decay_limited (10),...,experiment (14),pulse_width_s,samples,
#        modes_in_data (17),fitted_modes).
# Variables: dir, out, lib, name.
load lib.'/common.gp'
set datafile separator comma
f = dir.'/start_distance/radius.csv'
runs = system(sprintf("awk -F, 'NR > 1 && !seen[$1 \"/\" $2]++ {printf \"%%s/%%s \", $1, $2}' '%s'", f))
nr = words(runs)
run_cost(r) = system(sprintf("echo '%s' | cut -d/ -f1", r))
shift(k) = 1 + 0.025 * (k - (nr + 1) / 2.0)   # series side by side at each mode count
set logscale y
set format y "%g %%"
set xlabel "modes in the data"
set ylabel "50 % radius (frequency offset of the start)"
set xtics 1
set autoscale yfix                          # the data range itself, not widened to whole decades,
set offsets 0, 0, graph 0.05, graph 0.05   # and a margin that keeps the triangles at its ends inside the frame
# The mode counts' range, the same in every panel.
xlo = real(system(sprintf("awk -F, 'NR > 1 && (m == \"\" || $17 < m) {m = $17} END {print m}' '%s'", f))) - 0.5
xhi = real(system(sprintf("awk -F, 'NR > 1 && $17 > m {m = $17} END {print m}' '%s'", f))) + 0.5
set xrange [xlo:xhi]
costs = system(sprintf("awk -F, 'NR > 1 && !seen[$1]++ {printf \"%%s \", $1}' '%s'", f))
npanel = nr > 6 ? words(costs) : 1
ncol = npanel > 1 ? 2 : 1
nrow = (npanel + ncol - 1) / ncol
in_panel(k, q) = npanel == 1 || run_cost(word(runs, k)) eq word(costs, q)
# A point type per run within its panel (filled circle, square, diamond, pentagon; then open ones).
array PT[nr]
do for [k = 1:nr] {
  rank = 0
  do for [j = 1:k] { if (run_cost(word(runs, j)) eq run_cost(word(runs, k))) { rank = rank + 1 } }
  PT[k] = npanel == 1 ? 7 : int(word("7 5 13 15 6 4 12 14", (rank - 1) % 8 + 1))
}
do for [fmt in "png svg"] {
  eval term(fmt, 1200, npanel > 1 ? 500 * nrow + 80 : 760, name)
  if (npanel > 1) {
    set multiplot layout nrow, ncol title "Start-distance radius against the number of modes in the data (bars: 95 % interval; triangles: censored)\n".prov noenhanced
    set key inside left bottom noenhanced Left reverse box opaque font ",11" spacing 0.9
  } else {
    set key outside right top noenhanced title "cost/method\n(bars: 95 % interval)" Left reverse
    set title "Start-distance radius against the number of modes in the data\n".prov noenhanced
  }
  do for [q = 1:npanel] {
    if (npanel > 1) { set title word(costs, q) noenhanced }
    plot for [k = 1:nr] f skip 1 using \
           (((strcol(1)."/".strcol(2)) eq word(runs, k)) && in_panel(k, q) && (strcol(3) ne "failed") && (strcol(7) eq "inside") ? $17 * shift(k) : NaN):(100 * $4):(100 * $5):(100 * $6) \
           with yerrorbars lw 2 ps 1.3 pt PT[k] lc rgb costcolor(run_cost(word(runs, k))) title (in_panel(k, q) ? word(runs, k) : ""), \
         for [k = 1:nr] f skip 1 using \
           (((strcol(1)."/".strcol(2)) eq word(runs, k)) && in_panel(k, q) && (strcol(3) ne "failed") && (strcol(7) eq "above") ? $17 * shift(k) : NaN):(100 * $4) \
           with points ps 1.8 pt 9 lc rgb costcolor(run_cost(word(runs, k))) notitle, \
         for [k = 1:nr] f skip 1 using \
           (((strcol(1)."/".strcol(2)) eq word(runs, k)) && in_panel(k, q) && (strcol(3) ne "failed") && (strcol(7) eq "below") ? $17 * shift(k) : NaN):(100 * $4) \
           with points ps 1.8 pt 11 lc rgb costcolor(run_cost(word(runs, k))) notitle, \
         NaN with points ps 1.8 pt 9 lc rgb "#555555" title (npanel == 1 ? "at least this (above the largest offset tried)" : ""), \
         NaN with points ps 1.8 pt 11 lc rgb "#555555" title (npanel == 1 ? "under this (below the smallest offset tried)" : ""), \
         f skip 1 using ((strcol(1)."/".strcol(2)) eq word(runs, 1) && (npanel == 1 || word(costs, q) eq "time") ? $17 : NaN):(100 * $10) \
           with linespoints dt 2 lw 2 pt 6 lc rgb "#000000" title (npanel == 1 || word(costs, q) eq "time" ? "predicted min_k 1/(2 f_k T_eff,k)" : "")
  }
  if (npanel > 1) { unset multiplot }
}
