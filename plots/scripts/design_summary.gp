# design_summary.gp: the design's summary figure (issue 35, REPORT.md's one-page answer). Per method (x) and beam (rows), three
# panels: the 50 % start-distance radius with its bootstrap interval across records (a censored radius, beyond the
# largest offset tried, is an up-triangle at 20 %; below the smallest a down-triangle at 0.1 %), the worst RMSE /
# Cramer-Rao bound over the stiffness and mass parameters of the fits from the truth, and the median seconds per fit
# (from the timings file: it changes from run to run). Four series a panel: with and without model error, for the
# beam's two experiments (the modes in the data).
# Input: data (plots/scripts/design_summary.py's summary.dat: beam truth modes run x radius low high position
#        efficiency seconds), runs (the run names in x order).
# Variables: dir (a design study's results folder, for the provenance line), out, lib, name, data, runs.
load lib.'/common.gp'
nr = words(runs)
beams = system(sprintf("awk 'NR > 1 && !seen[$1]++ {printf \"%%s \", $1}' '%s'", data))
nb = words(beams)
# The experiments of a beam, by their mode counts, in order.
modes_of(b) = system(sprintf("awk '$1 == \"%s\" && !seen[$(NF - 8)]++ {printf \"%%s \", $(NF - 8)}' '%s'", b, data))
series_colour(t) = t eq "model error" ? "#d55e00" : "#0072b2"
shift(s) = 0.12 * (s - 2.5)
set datafile separator whitespace
set xrange [-0.6:nr - 0.4]
set xtics () rotate by 35 right noenhanced
do for [k = 1:nr] { set xtics add (word(runs, k) k - 1) }
set logscale y
set key noenhanced font ',12'
do for [fmt in "png svg"] {
  eval term(fmt, 1500, 430 * nb + 250, name)
  # Fixed margins, so that the panels of a row align; the key (the same four series in every panel) is in the
  # radius panel's empty lower right.
  set multiplot layout nb, 3 margins 0.06, 0.98, 190.0 / (430 * nb + 250), 1 - 110.0 / (430 * nb + 250) \
      spacing 0.075, 240.0 / (430 * nb + 250) title "Every method at its best practice, with and without model error\n".prov noenhanced
  do for [bi = 1:nb] {
    b = word(beams, bi)
    m1 = word(modes_of(b), 1)
    m2 = word(modes_of(b), 2)
    # Series s = 1..4: (model error, m1), (model error, m2), (no model error, m1), (no model error, m2).
    truth(s) = s <= 2 ? "model error" : "no model error"
    modes(s) = (s % 2) == 1 ? m1 : m2
    sel(s) = (strcol(1) eq b) && (strcol(2) eq truth(s)) && (strcol(3) eq modes(s))
    set key at graph 0.97, graph 0.42 right vertical Left reverse samplen 1 width -2 box opaque
    set title b." beam: 50 % radius (95 % bootstrap interval)"
    set ylabel "frequency offset of the start (%)"
    set yrange [0.05:40]
    plot for [s = 1:4] data using (sel(s) && strcol(9) eq "inside" ? $5 + shift(s) : NaN):6:7:8 with yerrorbars \
           pt ((s % 2) == 1 ? 7 : 5) ps 1.2 lw 2 lc rgb series_colour(truth(s)) title truth(s).", ".modes(s)." modes", \
         for [s = 1:4] data using (sel(s) && strcol(9) eq "above" ? $5 + shift(s) : NaN):6 with points \
           pt 9 ps 1.6 lc rgb series_colour(truth(s)) notitle, \
         for [s = 1:4] data using (sel(s) && strcol(9) eq "below" ? $5 + shift(s) : NaN):6 with points \
           pt 11 ps 1.6 lc rgb series_colour(truth(s)) notitle
    unset key
    set title b." beam: worst RMSE / bound, stiffness and mass"
    set ylabel "RMSE / Cramer-Rao bound"
    set yrange [*:*]
    plot for [s = 1:4] data using (sel(s) ? $5 + shift(s) : NaN):(pos($10)) with points \
           pt ((s % 2) == 1 ? 7 : 5) ps 1.3 lc rgb series_colour(truth(s)) notitle, \
         1 with lines dt 2 lc rgb "#000000" notitle
    set title b." beam: median seconds per fit"
    set ylabel "seconds"
    plot for [s = 1:4] data using (sel(s) ? $5 + shift(s) : NaN):(pos($11)) with points \
           pt ((s % 2) == 1 ? 7 : 5) ps 1.3 lc rgb series_colour(truth(s)) notitle
  }
  unset multiplot
}
