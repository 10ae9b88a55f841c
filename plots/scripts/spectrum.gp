# spectrum.gp: DFT magnitude of the measured record with the detected spikes.
# Input: dir/spectrum.csv (frequency_hz,data_magnitude,...) and dir/spikes.csv
#        (spike,bin,frequency_hz,magnitude,support_low_hz,support_high_hz).
# Variables: dir, out, lib, name.
# Shows what the spike cost sees: each detected peak (numbered circle) and the 20 % support
# interval around it (shaded) over which the cost compares data and model. Log y;
# x up to 1.5 x the highest support edge so that the peaks stay readable.
load lib.'/common.gp'
load lib.'/spikes.gp'
set datafile separator comma
spec = dir.'/spectrum.csv'

eval shade
set logscale y
set format y "10^{%T}"
set xrange [0:fmax]
set xlabel "frequency (Hz)"
set ylabel "DFT magnitude"
set key top right opaque box noenhanced
do for [fmt in "png svg"] {
  eval term(fmt, 1200, 800, name)
  set title "Data spectrum with the detected spikes and their 20 % supports (shaded)\n".prov noenhanced
  if (nspk > 0) {
    plot spec skip 1 using 1:(pos($2)) with lines lw 1.5 lc rgb costcolor("data") title "data", \
         spk skip 1 using 3:(pos($4)) with points pt 6 ps 2.2 lw 2 lc rgb "#d55e00" title "detected spike (number)", \
         spk skip 1 using 3:(pos($4)):(sprintf("%d", $1)) with labels offset 0, 1.4 tc rgb "#d55e00" notitle, \
         keyentry with boxes fillstyle transparent solid 0.25 noborder fillcolor rgb "#e69f00" title "20 % support"
  } else {
    plot spec skip 1 using 1:(pos($2)) with lines lw 1.5 lc rgb costcolor("data") title "data (no spikes.csv)"
  }
}
