# landscape_grid.gp: two-parameter cost landscapes as heat maps, one panel per cost.
# Input: dir/landscape/grid_<cost>_<a>_<b>.dat, gnuplot blocks "x_ratio y_ratio cost log10_normalised_cost".
# Variables: dir, out, lib, name, a, b (parameter pair), costs (those present for this pair).
# Colour = log10 of the min-max normalised cost (0 = worst point of the grid, the minimum is -12);
# the colour scale stops at -6 (lower values are drawn darkest) because almost all points lie in
# [-4, 0]. White contour lines every decade. Each grid point is drawn as a cell centred on it, so
# narrow valleys (time), terraces (spike) and one smooth basin (spike-smooth) can be told apart.
# The white cross marks the truth (1,1).
load lib.'/common.gp'
# sub: a subfolder of landscape/ ("zoom/N16-noise0/": the fine grids of one N and noise level), "" for the wide grids
if (!exists("sub")) sub = ""
if (!exists("what")) what = ""
grid(cn) = sprintf("%s/landscape/%sgrid_%s_%s_%s.dat", dir, sub, cn, a, b)
# half cell width in log space: the grid is log-spaced, so use (log max - log min) / (2 (count - 1))
halfcell(f, col) = real(system(sprintf("awk '!/^#/ && NF >= 4 {v[$%d]} END {n = 0; for (k in v) {n++; lo = (n == 1 || k+0 < lo) ? k+0 : lo; hi = (n == 1 || k+0 > hi) ? k+0 : hi} printf \"%%.9e\\n\", (n > 1 && lo > 0) ? (log(hi) - log(lo)) / (2 * (n - 1)) : 0.05}' '%s'", col, f)))
n = words(costs)
W = 80 + 560 * n
cbmin = -6

# viridis-like palette, dark = low cost
set palette defined (0 "#440154", 1 "#3b528b", 2 "#21908d", 3 "#5dc963", 4 "#fde725")
set cbrange [cbmin:0]
set cbtics ("≤ -6" -6, "-5" -5, "-4" -4, "-3" -3, "-2" -2, "-1" -1, "0" 0)
set cblabel "log10 normalised cost"
set logscale xy
set autoscale xfix
set autoscale yfix
if (sub eq "") {
  set xtics (0.1, 0.2, 0.5, 0.67, 0.8, 1, 1.25, 1.5, 2, 5, 10)
  set ytics (0.1, 0.2, 0.5, 0.67, 0.8, 1, 1.25, 1.5, 2, 5, 10)
} else {  # a fine grid, a few per cent around the truth
  set xtics (0.95, 0.97, 0.98, 0.99, 0.995, 1, 1.005, 1.01, 1.02, 1.03, 1.05)
  set ytics (0.95, 0.97, 0.98, 0.99, 0.995, 1, 1.005, 1.01, 1.02, 1.03, 1.05)
}
set xlabel a." / true value" noenhanced
set ylabel b." / true value" noenhanced offset 1, 0
set label 1 "" at 1, 1 point pt 2 ps 2.5 lw 3 lc rgb "#ffffff" front
set style fill solid 1.0 noborder
unset key

# contour lines: splot into a datablock (inside the panel loop), then drawn over the cells
set cntrparam levels discrete -6, -5, -4, -3, -2, -1

do for [fmt in "png svg"] {
  eval term(fmt, W, 640, name)
  set multiplot layout 1, n title sprintf("Cost landscape over (%s, %s)%s: log10 normalised cost, contours every decade, white cross = truth\n%s", a, b, what, prov) noenhanced \
      margins 95.0 / W, 1 - 110.0 / W, 0.12, 0.82 spacing 90.0 / W
  do for [i = 1:n] {
    cn = word(costs, i)
    hx = halfcell(grid(cn), 1); hy = halfcell(grid(cn), 2)
    set contour base; unset surface
    set table $cont
    splot grid(cn) using 1:2:(fin($4)) with lines
    unset table
    unset contour
    set title cn noenhanced
    # colour box only on the last panel: all panels share the same colour range
    if (i == n) { set colorbox } else { unset colorbox }
    plot grid(cn) using 1:2:($1 * exp(-hx)):($1 * exp(hx)):($2 * exp(-hy)):($2 * exp(hy)):(fin($4) < cbmin ? cbmin : fin($4)) \
           with boxxyerror fc palette, \
         $cont using 1:2 with lines lc rgb "#ffffff" lw 1
  }
  unset multiplot
}
