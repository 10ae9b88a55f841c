# overlay.gp: fitted models against the data, in time (top) and in frequency (bottom).
# Input: dir/overlay.csv (t_s,data,model_<cost>...) and dir/spectrum.csv
#        (frequency_hz,data_magnitude,model_<cost>...); dir/spikes.csv (optional) sets the x range.
# Variables: dir, out, lib, name.
# Top: the start of the record, where the response is largest: the first 25 % of the record, or
# only 6 periods of the strongest spike if that is shorter (else fast modes become a blur).
# Bottom: DFT magnitudes (log y) over the same frequency range as the spectrum plot, spike
# supports shaded. A cost can match the spikes (bottom) and still miss the waveform (top).
load lib.'/common.gp'
load lib.'/spikes.gp'
set datafile separator comma
ovl  = dir.'/overlay.csv'
spec = dir.'/spectrum.csv'
tend = real(system(sprintf("awk -F, 'NR > 1 && $1 + 0 > m {m = $1 + 0} END {printf \"%%.9e\\n\", m}' '%s'", ovl)))
fpk  = (nspk > 0) ? real(system(sprintf("awk -F, 'NR > 1 && $3 > 0 && $4 + 0 > m {m = $4 + 0; f = $3} END {printf \"%%.9e\\n\", f + 0}' '%s'", spk))) : 0
twin = (fpk > 0 && 6 / fpk < 0.25 * tend) ? 6 / fpk : 0.25 * tend
wdesc = (twin < 0.25 * tend) ? sprintf("first %.3g s = 6 periods of the strongest spike, %.3g Hz", twin, fpk) : "first 25 % of the record"
# model columns: 3.. ; the cost is the header minus "model_"
nto = ncols(ovl);  nfo = ncols(spec)
mname(f, i) = header(f, i)[7:]

do for [fmt in "png svg"] {
  eval term(fmt, 1200, 900, name)
  set multiplot layout 2, 1 title "Identified models against the data: start of the time record and DFT magnitude\n".prov noenhanced \
      margins 0.1, 0.97, 0.07, 0.88 spacing 0, 0.13
  # top: time domain
  unset object
  unset logscale y
  set format y "%g"
  set xrange [0:twin]
  set xlabel "time (s)" offset 0, 0.5
  set ylabel "response" offset 1, 0
  set title "time domain (".wdesc.")"
  set key top right opaque box noenhanced
  plot ovl skip 1 using 1:(fin($2)) with lines lw 2.5 lc rgb costcolor("data") title "data", \
       for [i = 3:nto] ovl skip 1 using 1:(fin(column(i))) with lines lw 1.5 lc rgb costcolor(mname(ovl, i)) dt costdash(mname(ovl, i)) \
       title "model, ".mname(ovl, i)." cost"
  # bottom: frequency domain, same range as spectrum.png
  eval shade
  set logscale y
  set format y "10^{%T}"
  set xrange [0:fmax]
  set xlabel "frequency (Hz)"
  set ylabel "DFT magnitude"
  set title (nspk > 0 ? "frequency domain (shaded: spike supports; legend above)" : "frequency domain (no spikes.csv; legend above)")
  unset key
  plot spec skip 1 using 1:(pos($2)) with lines lw 2.5 lc rgb costcolor("data") title "data", \
       for [i = 3:nfo] spec skip 1 using 1:(pos(column(i))) with lines lw 1.5 lc rgb costcolor(mname(spec, i)) dt costdash(mname(spec, i)) \
       title "model, ".mname(spec, i)." cost"
  unset multiplot
}
