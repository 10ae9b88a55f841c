#!/usr/bin/env bash
# design_along_beam.sh DESIGN.csv OUTPUT_STEM
#
# The criterion of `beamid design` along the beam (issue 34 item 4): each candidate's criterion and every parameter's
# relative sd bound (%, log scale) against its sensor position, from the CSV that beamid design wrote for one sensor a
# candidate (--sensors 1). Candidates that differ in another choice (force position, pulse width, dt, samples) are
# one line each per choice, at most six lines a panel. Writes OUTPUT_STEM.png and OUTPUT_STEM.svg and prints "made ...".
# A candidate without a bound (a sensor at the clamp) is left out of the lines; its position is named in the title.
set -euo pipefail
die() { echo "design_along_beam.sh: $*" >&2; exit 1; }
[[ $# -eq 2 ]] || { echo "usage: design_along_beam.sh DESIGN.csv OUTPUT_STEM" >&2; exit 2; }
csv=$1 stem=$2
command -v gnuplot >/dev/null 2>&1 || die "gnuplot not found (install gnuplot 5.4)"
[[ -f $csv ]] || die "'$csv' not found: write it with beamid design ... > '$csv'"
head -1 "$csv" | grep -q '^rank,sensors_x_m,force_x_m,pulse_width_s,dt_s,samples,criterion' ||
  die "'$csv': not a table of beamid design (its header must start rank,sensors_x_m,...)"
if awk -F, 'NR > 1 && $2 ~ /;/ { found = 1 } END { exit !found }' "$csv"; then
  die "'$csv': candidates with several sensors; plot a design of one sensor a candidate (--sensors 1)"
fi
[[ $csv$stem != *\'* ]] || die "paths must not contain a single quote"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One block per choice of the other columns (force, width, dt, samples), sorted by position; percentages. The
# criterion's column is left out when it is one of the bounds (--criterion KEY); a block is named by the choices that
# vary among the candidates ("pulse 0.008 s").
awk -F, 'NR == 1 { n = NF; next } $1 != "" {
    key = $3 " " $4 " " $5 " " $6; if (!(key in seen)) { seen[key] = ++k; name[k] = key }
    for (i = 8; i < n; ++i) if ($i != $7) differs[i] = 1; else same[i] = 1
    line = $2; for (i = 7; i < n; ++i) line = line " " 100 * $i; rows[seen[key]] = rows[seen[key]] line "\n" }
  END { for (i = 1; i <= k && i <= 6; ++i) { printf "# %s\n%s\n", name[i], rows[i] }
        dup = 0; for (i = 8; i < n; ++i) if (same[i] && !differs[i]) dup = 1; print dup > "'"$work"'/criterion_is_a_bound" }' \
  "$csv" >"$work/blocks.dat"
# Each block sorted by position on its own (gnuplot's index: blocks two blank lines apart).
awk 'BEGIN { RS = ""; FS = "\n" } { print $1; cmd = "sort -g"; for (i = 2; i <= NF; ++i) print $i | cmd; close(cmd); print ""; print "" }' \
  "$work/blocks.dat" >"$work/sorted.dat"
names=$(head -1 "$csv" | tr -d '\r' | awk -F, '{ for (i = 7; i < NF; ++i) { n = $i; sub(/^relative_sd_/, "", n); printf "%s ", n } }')
first=$(( $(cat "$work/criterion_is_a_bound") == 1 ? 3 : 2 ))  # gnuplot's first column to draw
blocks=$(grep -c '^#' "$work/sorted.dat")
[[ $blocks -gt 0 ]] || die "'$csv': no candidate has a bound"
# Each block's label: the choices that differ between blocks (force, pulse, dt, samples), e.g. "pulse 0.008 s".
labels=$(grep '^#' "$work/sorted.dat" | awk '{ for (i = 2; i <= 5; ++i) v[NR, i] = $i; if (NR > 1) for (i = 2; i <= 5; ++i)
    if ($i != v[1, i]) vary[i] = 1 } END { split("force|pulse|dt|samples", what, "|"); split(" m| s| s|", unit, "|")
    for (r = 1; r <= NR; ++r) { l = ""; for (i = 2; i <= 5; ++i) if (vary[i]) l = l (l == "" ? "" : ", ") what[i - 1] " " sprintf("%g", v[r, i]) unit[i - 1]
      printf "%s|", l } }')
unbounded=$(awk -F, 'NR > 1 && $1 == "" { printf "%s%s", sep, $2; sep = ", " }' "$csv")
for fmt in png svg; do
  term=$([[ $fmt == png ]] && echo "pngcairo" || echo "svg")
  gnuplot <<GP
set terminal $term size 1000,620 enhanced font 'Sans,13' background '#ffffff'
set output '$stem.$fmt'
set key outside below horizontal maxrows 4 noenhanced font 'Sans,11'
set logscale y
set format y '%g'
set grid
set xlabel 'sensor position x (m)'
set ylabel 'bound on the relative sd (%)'
set title "beamid design: the Fisher information's bound along the beam$( [[ -n $unbounded ]] && echo "\\\\n(no bound at x = $unbounded m)")" noenhanced
names = "$names"
labels = "$labels"
label_rest(s, b) = (b == 0 ? s[1:strstrt(s, "|") - 1] : label_rest(s[strstrt(s, "|") + 1:], b - 1))
# A parameter is a colour (the criterion, D or A, thick and black), a choice of the other columns a dash pattern.
plot for [b = 0:$((blocks - 1))] for [c = $first:words(names) + 1] '$work/sorted.dat' index b using 1:c \
  with linespoints lw (c == 2 ? 3 : 1.8) lc (c == 2 ? -1 : c - 2) pt c dt b + 1 \
  title sprintf("%s%s", word(names, c - 1), $blocks > 1 ? " (" . label_rest(labels, b) . ")" : "")
GP
done
echo "made $stem.png $stem.svg"
