# radius_vs_modes.gp: each (cost, method) run's 50 % start-distance radius (with the interval from the 95 % Wilson
# bounds) against the number of modes in the data, one experiment per pulse width, beside the least-squares basin
# predicted for each experiment, min_k 1/(2 f_k T_eff,k) over its fitted modes (black, dashed). A censored radius
# (position "above": every offset tried kept half the starts, so the radius is at least the largest; "below": none
# did, so it is under the smallest) is a triangle pointing the way the radius lies, without an interval.
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
set key outside right top noenhanced title "cost/method\n(bars: 95 % interval)" Left reverse
do for [fmt in "png svg"] {
  eval term(fmt, 1200, 760, name)
  set title "Start-distance radius against the number of modes in the data\n".prov noenhanced
  plot for [k = 1:nr] f skip 1 using \
         (((strcol(1)."/".strcol(2)) eq word(runs, k)) && (strcol(3) ne "failed") && (strcol(7) eq "inside") ? $17 * shift(k) : NaN):(100 * $4):(100 * $5):(100 * $6) \
         with yerrorbars lw 2 ps 1.3 pt 7 lc rgb costcolor(run_cost(word(runs, k))) title word(runs, k), \
       for [k = 1:nr] f skip 1 using \
         (((strcol(1)."/".strcol(2)) eq word(runs, k)) && (strcol(3) ne "failed") && (strcol(7) eq "above") ? $17 * shift(k) : NaN):(100 * $4) \
         with points ps 1.8 pt 9 lc rgb costcolor(run_cost(word(runs, k))) notitle, \
       for [k = 1:nr] f skip 1 using \
         (((strcol(1)."/".strcol(2)) eq word(runs, k)) && (strcol(3) ne "failed") && (strcol(7) eq "below") ? $17 * shift(k) : NaN):(100 * $4) \
         with points ps 1.8 pt 11 lc rgb costcolor(run_cost(word(runs, k))) notitle, \
       NaN with points ps 1.8 pt 9 lc rgb "#555555" title "at least this (above the largest offset tried)", \
       NaN with points ps 1.8 pt 11 lc rgb "#555555" title "under this (below the smallest offset tried)", \
       f skip 1 using ((strcol(1)."/".strcol(2)) eq word(runs, 1) ? $17 : NaN):(100 * $10) \
         with linespoints dt 2 lw 2 pt 6 lc rgb "#000000" title "predicted min_k 1/(2 f_k T_eff,k)"
}
