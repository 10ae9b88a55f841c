# bias.gp: accuracy of one identified parameter against the number of finite elements N.
# Input: dir/bias_<param>.csv, header elements,"<series> rmse","<series> sd",... (values may be nan).
# Variables: dir, out, lib, name, param.
# y = RMSE over the cases of the relative error (log scale), bars = +-1 sd. Colour = cost,
# dash/point type = the rest of the series name (method, noise). Series are shifted slightly
# along x so their error bars do not hide each other. Lower bar ends below the axis are clipped
# to it, non-positive RMSEs are drawn on the bottom axis, nan values are left out.
# More than six series are split into panels, one per noise level (the series name's last two
# words), or, with one noise level, one per method (its second word), so that a panel holds at
# most about six (issue 35: 18 series on one axis were unreadable); the panels share the y range.
load lib.'/common.gp'
set datafile separator comma
f  = sprintf("%s/bias_%s.csv", dir, param)
ns = (ncols(f) - 1) / 2

# series titles from the header, trailing " rmse" removed
array T[ns]
do for [k = 1:ns] {
  t = header(f, 2 * k)
  T[k] = (strlen(t) > 5 && t[strlen(t) - 4:] eq " rmse") ? t[1:strlen(t) - 5] : t
}

# y range from the finite positive values (awk, so that all-nan columns cannot break it).
# awk prints numbers with %e: gnuplot's real() rejects forms like "1e-07".
range = system(sprintf("awk -F, 'NR > 1 {for (i = 2; i < NF; i += 2) if ($i ~ /^[0-9.eE+-]+$/ && $i > 0) { \
  lo = (lo == \"\" || $i < lo) ? $i : lo; hi = ($i > hi) ? $i : hi; \
  if ($(i+1) ~ /^[0-9.eE+-]+$/ && $i + $(i+1) > hi) hi = $i + $(i+1) }} END {if (lo == \"\") print \"0.01 1\"; else printf \"%%.9e %%.9e\\n\", lo, hi}' '%s'", f))
ymin = real(word(range, 1)) / 2
ymax = real(word(range, 2)) * 2
clip(y) = y < ymin ? ymin : y
rmse(k) = (valid(k) && abs(column(k)) < 1e300) ? clip(column(k)) : NaN   # nan: left out, <= 0: bottom axis
xspan = real(system(sprintf("awk -F, 'NR > 1 && $1 > 0 {lo = (lo == \"\" || $1 < lo) ? $1 : lo; hi = ($1 > hi) ? $1 : hi} END {printf \"%%.9e\\n\", (hi > lo) ? log(hi / lo) : 1}' '%s'", f)))

# x tics at the N values present
eval "set xtics (".system(sprintf("awk -F, 'NR > 1 {printf \"%%s%%s\", (NR > 2 ? \",\" : \"\"), $1}' '%s'", f)).")"
set logscale x 2
set logscale y
set yrange [ymin:ymax]
set autoscale xfix
set offsets graph 0.05, graph 0.05, 0, 0
set format y "%g"
# label 2x and 5x ticks too when the range is short (few decades)
if (log10(ymax / ymin) < 4) {
  do for [e = floor(log10(ymin)):ceil(log10(ymax))] { set ytics add (sprintf("%g", 2 * 10.0**e) 2 * 10.0**e, sprintf("%g", 5 * 10.0**e) 5 * 10.0**e) }
}
set xlabel "N (finite elements)" offset 0, 0.6
set ylabel sprintf("RMSE of relative error in %s", param) noenhanced
set key outside bottom center horizontal samplen 3 width 1 height 1 noenhanced

# Panels: each series' key (its noise level, the name's last two words; or its method, the second word, when there
# is one noise level), and the distinct keys in order of first appearance.
noise_of(k) = words(T[k]) >= 3 && word(T[k], words(T[k]) - 1) eq "noise" ? word(T[k], words(T[k]) - 1)." ".word(T[k], words(T[k])) : ""
levels = 0
do for [k = 1:ns] { new = 1; do for [j = 1:k - 1] { if (noise_of(j) eq noise_of(k)) { new = 0 } }; levels = levels + new }
key_of(k) = ns <= 6 ? "" : (levels > 1 && noise_of(k) ne "") ? noise_of(k) : word(T[k], 2)
array P[ns]; array K[ns]
npanel = 0
do for [k = 1:ns] {
  P[k] = 0
  do for [j = 1:npanel] { if (P[k] == 0 && K[j] eq key_of(k)) { P[k] = j } }
  if (P[k] == 0) { npanel = npanel + 1; K[npanel] = key_of(k); P[k] = npanel }
}
# Within a panel: the style by what is left of the name once the cost and the panel's key are taken out (the same
# method looks the same in every panel), and the shift along x by the series' rank in its panel.
strip(t, key) = (strlen(key) > 0 && strstrt(t, key) > 0) ? t[1:strstrt(t, key) - 1].t[strstrt(t, key) + strlen(key):] : t
rest_of(k) = strip(T[k][strlen(word(T[k], 1)) + 1:], K[P[k]])
array S[ns]; array R[ns]; array M[npanel]
do for [q = 1:npanel] { M[q] = 0 }
nstyle = 0
do for [k = 1:ns] {
  M[P[k]] = M[P[k]] + 1
  R[k] = M[P[k]]
  S[k] = 0
  do for [j = 1:k - 1] { if (S[k] == 0 && rest_of(j) eq rest_of(k)) { S[k] = S[j] } }
  if (S[k] == 0) { nstyle = nstyle + 1; S[k] = nstyle }
}
# small multiplicative x offset per series within its panel: 1 % of the log x span each
shift(k) = exp(0.01 * xspan * (R[k] - (M[P[k]] + 1) / 2.0))
ncol = npanel > 1 ? 2 : 1
nrow = (npanel + ncol - 1) / ncol

do for [fmt in "png svg"] {
  eval term(fmt, 1200, npanel > 1 ? 560 * nrow + 80 : 800, name)
  if (npanel > 1) {
    set multiplot layout nrow, ncol title sprintf("Accuracy of %s against mesh size: RMSE over cases of the relative error, bars = 1 sd (series shifted apart in N)\n%s", param, prov) noenhanced
  }
  do for [q = 1:npanel] {
    if (npanel > 1) { set title K[q] noenhanced } else {
      set title sprintf("Accuracy of %s against mesh size: RMSE over cases of the relative error, bars = 1 sd (series shifted apart in N)\n%s", param, prov) noenhanced
    }
    # x : y (clipped) : y - sd (clipped) : y + sd ; a missing sd gives no bar
    plot for [k = 1:ns] f skip 1 using ($1 * shift(k)):(P[k] == q ? rmse(2 * k) : NaN):(clip(rmse(2 * k) - colz(2 * k + 1))):(rmse(2 * k) + colz(2 * k + 1)) \
         with yerrorlines lw 2 ps 1.3 pt (S[k] == 1 ? 7 : S[k] == 2 ? 5 : S[k] == 3 ? 9 : S[k] + 4) dt S[k] \
         lc rgb costcolor(word(T[k], 1)) title (P[k] == q ? T[k] : "")
  }
  if (npanel > 1) { unset multiplot }
}
