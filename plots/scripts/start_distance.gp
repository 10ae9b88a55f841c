# start_distance.gp: the share of starts from which each (cost, method) run reaches the minimum it reaches from
# the truth, against the start's frequency offset (log axis), with 95 % Wilson intervals, and the basin that theory
# predicts for least squares, 1/(2 f T) of the highest fitted mode over the record length T (dashed vertical line)
# and over the time the mode is visible, T_eff = min(T, 1/sigma) (dotted).
# Input: dir/start_distance/curves.csv (cost,method,offset,reached,fits,rate,wilson_low,wilson_high,...) and
#        dir/start_distance/radius.csv (...,predicted_basin in column 8, decay-limited in column 10). With several
#        experiments (start_distance.experiments = "all"), the first one's curves (column 11 = 0; radius_vs_modes.gp
#        draws the radii of all of them).
# Variables: dir, out, lib, name.
load lib.'/common.gp'
set datafile separator comma
f = dir.'/start_distance/curves.csv'
runs = system(sprintf("awk -F, 'NR > 1 && !seen[$1 \"/\" $2]++ {printf \"%%s/%%s \", $1, $2}' '%s'", f))
nr = words(runs)
predicted = real(system(sprintf("awk -F, 'NR == 2 {print $8}' '%s/start_distance/radius.csv'", dir)))
decayed = real(system(sprintf("awk -F, 'NR == 2 {print $10}' '%s/start_distance/radius.csv'", dir)))
run_cost(r) = system(sprintf("echo '%s' | cut -d/ -f1", r))
run_method(r) = system(sprintf("echo '%s' | cut -d/ -f2", r))
methods = system(sprintf("awk -F, 'NR > 1 {print $2}' '%s' | LC_ALL=C sort -u | tr '\\n' ' '", f))
midx(m) = sum [j = 1:words(methods)] (word(methods, j) eq m ? j : 0)
mpt(m) = word("7 5 9 11 13 15", (midx(m) - 1) % 6 + 1) + 0
# series shifted a little along the log axis so equal rates stay visible
shift(k) = 1 + 0.03 * (k - (nr + 1) / 2.0)

set logscale x
set format x "%g %%"
set yrange [-0.05:1.05]
set ytics 0, 0.2, 1
set xlabel "frequency offset of the start (largest over the fitted modes)"
set ylabel "share of starts that reach the minimum"
# The least-squares basins that theory predicts, drawn where the time cost is.
show_basins = "set arrow 1 from 100 * predicted, graph 0 to 100 * predicted, graph 1 nohead dt 2 lw 2 lc rgb '#555555'; ".\
  "set label 1 '1/(2 f T)' at 100 * predicted, graph 0.55 right offset -0.5, 0; ".\
  "set arrow 2 from 100 * decayed, graph 0 to 100 * decayed, graph 1 nohead dt 3 lw 2 lc rgb '#555555'; ".\
  "set label 2 '1/(2 f T_{eff})' at 100 * decayed, graph 0.55 left offset 0.5, 0 enhanced"
hide_basins = "unset arrow 1; unset label 1; unset arrow 2; unset label 2"
# More than six runs: one panel per cost (issue 35: a panel holds at most about six series), in order of first
# appearance.
costs = system(sprintf("awk -F, 'NR > 1 && !seen[$1]++ {printf \"%%s \", $1}' '%s'", f))
npanel = nr > 6 ? words(costs) : 1
ncol = npanel > 1 ? 2 : 1
nrow = (npanel + ncol - 1) / ncol
in_panel(k, q) = npanel == 1 || run_cost(word(runs, k)) eq word(costs, q)
do for [fmt in "png svg"] {
  eval term(fmt, 1200, npanel > 1 ? 520 * nrow + 80 : 800, name)
  if (npanel > 1) {
    set multiplot layout nrow, ncol title "Start-distance curves: reaching the minimum from farther away (bars: 95 % Wilson)\n".prov noenhanced
    set key inside left bottom noenhanced Left reverse box opaque
  } else {
    set key outside right top noenhanced title "cost/method\n(bars: 95 % Wilson)" Left reverse
    set title "Start-distance curves: reaching the minimum from farther away\n".prov noenhanced
  }
  do for [q = 1:npanel] {
    if (npanel > 1) { set title word(costs, q) noenhanced }
    if (npanel == 1 || word(costs, q) eq "time") { eval show_basins } else { eval hide_basins }
    plot for [k = 1:nr] f skip 1 using \
           (((strcol(1)."/".strcol(2)) eq word(runs, k)) && ($11 == 0) && in_panel(k, q) ? 100 * $3 * shift(k) : NaN):6:7:8 \
           with yerrorlines lw 2 ps 1.4 pt mpt(run_method(word(runs, k))) dt midx(run_method(word(runs, k))) \
           lc rgb costcolor(run_cost(word(runs, k))) title (in_panel(k, q) ? word(runs, k) : "")
  }
  if (npanel > 1) { unset multiplot }
}
