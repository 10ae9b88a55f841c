# spikes.gp: reads dir/spikes.csv (if present) and sets up, for the spectrum plots,
#   nspk  number of spikes,  spk  the file name,  fmax  the x range (1.5 x the highest support edge,
#   or the whole spectrum without spikes), and  shade:  "eval shade" adds one shaded rectangle per
#   spike support interval to the next plot ("unset object" removes them).
spk  = dir.'/spikes.csv'
nspk = isfile(spk) ? int(system(sprintf("awk 'END {print NR - 1}' '%s'", spk))) : 0
fmax = (nspk > 0) ? 1.5 * real(system(sprintf("awk -F, 'NR > 1 && $6 + 0 > m {m = $6 + 0} END {printf \"%%.9e\\n\", m}' '%s'", spk))) \
                  : real(system(sprintf("awk -F, 'NR > 1 && $1 + 0 > m {m = $1 + 0} END {printf \"%%.9e\\n\", m}' '%s/spectrum.csv'", dir)))
# supports: "low high" pairs, one per spike
sup = (nspk > 0) ? system(sprintf("awk -F, 'NR > 1 {printf \"%%.9e %%.9e \", ($5 < 0 ? 0 : $5), $6}' '%s'", spk)) : ""
shade = 'do for [i = 1:nspk] { set object 100 + i rectangle from real(word(sup, 2 * i - 1)), graph 0 to real(word(sup, 2 * i)), graph 1 fillcolor rgb "#e69f00" fillstyle transparent solid 0.25 noborder behind }'
