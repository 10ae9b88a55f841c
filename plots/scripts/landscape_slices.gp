# landscape_slices.gp: one-parameter slices of each cost through the truth.
# Input: dir/landscape/slice_<cost>_<param>.csv (ratio,value,cost,normalised_cost).
# Variables: dir, out, lib, name, params (e.g. "EI rho cDI gamma"), costs (e.g. "time spike spike-smooth").
# One panel per parameter; each cost is min-max normalised to [0,1] so that their shapes compare:
# time is narrow and wiggly, spike a staircase (it only moves when a peak changes DFT bin),
# spike-smooth a smooth bowl. The dashed vertical line marks the truth (ratio 1).
load lib.'/common.gp'
set datafile separator comma
slice(cn, p) = sprintf("%s/landscape/slice_%s_%s.csv", dir, cn, p)

n  = words(params)
nc = (n <= 1) ? 1 : (n <= 4) ? 2 : 3          # panel grid: 1, 1x2, 2x2, 2x3, ...
nr = int(ceil(1.0 * n / nc))
H  = (nr == 1) ? 560 : 400 * nr               # figure height in pixels
ky = 1 - 76.0 / H                              # height of the shared legend line (screen units)

do for [fmt in "png svg"] {
  eval term(fmt, 1200, H, name)
  # the top margin is left free for the title and the shared legend
  set multiplot layout nr, nc title "Cost landscape: one-parameter slices through the truth (each cost scaled to [0,1])\n".prov noenhanced \
      margins 0.07, 0.98, 56.0 / H, 1 - 136.0 / H spacing 0.08, 104.0 / H
  set logscale x
  set autoscale xfix
  set offsets graph 0.01, graph 0.01, 0, 0
  set xtics (0.1, 0.2, 0.5, 0.67, 0.8, 1, 1.25, 1.5, 2, 5, 10)
  set yrange [-0.03:1.05]
  set ytics 0, 0.25, 1
  set xlabel "value / true value" offset 0, 0.5
  set ylabel "normalised cost" offset 1, 0
  set arrow 1 from 1, graph 0 to 1, graph 1 nohead dt 2 lc rgb "#444444" back
  unset key
  do for [i = 1:n] {
    p = word(params, i)
    present = ""
    do for [cn in costs] { if (isfile(slice(cn, p))) { present = present." ".cn } }
    # legend: one line under the title (screen coordinates), drawn by the first panel only
    do for [k = 1:words(costs)] {
      if (i == 1) {
        cn = word(costs, k); kx = 0.5 + (k - (words(costs) + 1) / 2.0) * 0.17 - 0.05
        set arrow 10 + k from screen kx, screen ky to screen kx + 0.04, screen ky nohead lw 2 lc rgb costcolor(cn) dt costdash(cn)
        set label 10 + k cn at screen kx + 0.05, screen ky left noenhanced
      } else { unset arrow 10 + k; unset label 10 + k }
    }
    set title p noenhanced
    plot for [cn in present] slice(cn, p) using 1:(fin($4)) with lines lw 2 lc rgb costcolor(cn) dt costdash(cn)
  }
  unset multiplot
}
