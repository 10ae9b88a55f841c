# common.gp: settings shared by every beamid plot script (loaded first).
# Needs the variables  dir  (results folder) and  out  (output folder).
set encoding utf8

# Provenance: every plot names its study, case count and commit.
prov_get(k) = system(sprintf("awk -F, '$1==\"%s\"{v=$2} END{print v}' '%s/provenance.csv'", k, dir))
study  = prov_get("study")
cases  = prov_get("cases")
commit = prov_get("commit")
prov   = sprintf("study %s, %s cases, commit %s", study, cases, commit)

# Robustness: nan/inf/unparsable values become NaN, which gnuplot skips. Note that a "nan" field
# makes every expression using $N undefined; test valid(N) first where a fallback is needed.
fin(x) = abs(x) < 1e300 ? x : NaN
pos(x) = (abs(x) < 1e300 && x > 0) ? x : NaN          # for log axes
colz(k) = (valid(k) && abs(column(k)) < 1e300) ? column(k) : 0   # column k, 0 if nan/inf/missing
isfile(f) = int(system(sprintf("test -f '%s' && echo 1 || echo 0", f)))
# One column of a CSV header (1-based), quotes removed.
header(f, i) = system(sprintf("head -n 1 '%s' | tr -d '\"\\r' | awk -F, '{print $%d}'", f, i))
ncols(f) = int(system(sprintf("head -n 1 '%s' | awk -F, '{print NF}'", f)))

# One colour per cost, the same in every plot (Okabe-Ito, colour-blind safe).
costcolor(c) = c eq "time" ? "#0072b2" : c eq "spike" ? "#d55e00" : \
               c eq "spike-smooth" ? "#009e73" : c eq "data" ? "#000000" : \
               c eq "freq-band" ? "#56b4e9" : c eq "modal" ? "#e69f00" : "#cc79a7"
costdash(c)  = c eq "spike-smooth" ? 2 : c eq "time" || c eq "spike" || c eq "data" ? 1 : 4

# Every script draws its plot twice:  do for [fmt in "png svg"] { eval term(fmt, W, H, name) ... }
term(fmt, w, h, n) = sprintf("set terminal %s size %d,%d enhanced font 'Sans,13' background '#ffffff'; set output '%s/%s.%s'", \
                             fmt eq "png" ? "pngcairo" : "svg", w, h, out, n, fmt)

# Data-derived text (study, parameter, series names) may contain '_' or '^': no enhanced markup there.
set key noenhanced
set grid lc rgb "#dddddd"
