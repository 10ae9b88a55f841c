# success_vs_modes.gp: how often each (cost, method) pair recovers the parameters, against the
# number of vibration modes present in the data.
# Input: dir/modes.csv (modes_in_data,pulse_width_s,samples,cost,method,cases,successes,success_rate,...).
# Variables: dir, out, lib, name.
# Lines: success rate pooled over pulse widths and sample counts at each modes count
# (sum of successes / sum of cases). Small open symbols: the individual
# (pulse width, samples) rows, so that spread hidden by the pooling stays visible.
load lib.'/common.gp'
set datafile separator comma
f = dir.'/modes.csv'
# the (cost, method) pairs, as "cost method cost method ..."
pairs = system(sprintf("awk -F, 'NR > 1 {print $4, $5}' '%s' | LC_ALL=C sort -u | tr '\\n' ' '", f))
np = words(pairs) / 2
# pooled rate per modes count for one pair, sorted by modes count ("modes,rate" lines)
pooled(cn, m) = sprintf("< awk -F, -v c='%s' -v m='%s' 'NR > 1 && $4 == c && $5 == m && $6 > 0 {n[$1] += $6; s[$1] += $7} END {for (k in n) printf \"%%s,%%.9e\\n\", k, s[k] / n[k]}' '%s' | LC_ALL=C sort -g", cn, m, f)
modes = system(sprintf("awk -F, 'NR > 1 {print $1}' '%s' | LC_ALL=C sort -gu | tr '\\n' ','", f))
eval "set xtics (".modes[1:strlen(modes) - 1].")"
# colour = cost, dash and symbol = method; series shifted a little in x so equal rates stay visible
methods = system(sprintf("awk -F, 'NR > 1 {print $5}' '%s' | LC_ALL=C sort -u | tr '\\n' ' '", f))
midx(m) = sum [j = 1:words(methods)] (word(methods, j) eq m ? j : 0)
mpt(m) = word("7 5 9 11 13 15", (midx(m) - 1) % 6 + 1) + 0
mspan = real(system(sprintf("awk -F, 'NR > 1 {v = $1 + 0; lo = (NR == 2 || v < lo) ? v : lo; hi = (v > hi) ? v : hi} END {printf \"%%.9e\\n\", hi - lo}' '%s'", f)))
dx(k) = 0.008 * mspan * (k - (np + 1) / 2.0)

set yrange [-0.05:1.05]
set ytics 0, 0.2, 1
set autoscale xfix
set offsets graph 0.05, graph 0.05, 0, 0
set xlabel "modes in the data"
set ylabel "success rate"
set key outside right top noenhanced title "cost, method\n(lines: pooled over pulse\nwidths and sample counts;\nopen symbols: single settings)" Left reverse
do for [fmt in "png svg"] {
  eval term(fmt, 1200, 800, name)
  set title "Success rate against the number of modes in the data\n".prov noenhanced
  plot for [k = 1:np] pooled(word(pairs, 2 * k - 1), word(pairs, 2 * k)) using ($1 + dx(k)):2 with linespoints lw 2 ps 1.6 \
         pt mpt(word(pairs, 2 * k)) dt midx(word(pairs, 2 * k)) lc rgb costcolor(word(pairs, 2 * k - 1)) \
         title word(pairs, 2 * k - 1).", ".word(pairs, 2 * k), \
       for [k = 1:np] f skip 1 using ($1 + dx(k)):((strcol(4) eq word(pairs, 2 * k - 1) && strcol(5) eq word(pairs, 2 * k)) ? fin($8) : NaN) \
         with points pt mpt(word(pairs, 2 * k)) - 1 ps 1 lc rgb costcolor(word(pairs, 2 * k - 1)) notitle
}
