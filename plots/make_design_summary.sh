#!/usr/bin/env bash
# make_design_summary.sh RESULTS_DIR OUTPUT_DIR
#
# The design's summary figure (REPORT.md 2.0): OUTPUT_DIR/summary.png and .svg, from the design studies' results in
# RESULTS_DIR (comparison, comparison-control, comparison-thick; see plots/scripts/design_summary.py), with its data
# beside it (summary.dat, runs.txt). Prints the line "made ..." as make_plots.sh does.
set -euo pipefail
die() { echo "make_design_summary.sh: $*" >&2; exit 1; }
[[ $# -eq 2 ]] || { echo "usage: make_design_summary.sh RESULTS_DIR OUTPUT_DIR" >&2; exit 2; }
res=${1%/} out=${2%/}
command -v gnuplot >/dev/null 2>&1 || die "gnuplot not found (install gnuplot 5.4)"
[[ -f $res/comparison/provenance.csv ]] || die "'$res/comparison/provenance.csv' not found: run the comparison study first"
[[ $res$out != *\'* ]] || die "paths must not contain a single quote"
lib=$(cd "$(dirname "${BASH_SOURCE[0]}")/scripts" && pwd)
python3 "$lib/design_summary.py" "$res" "$out"
runs=$(cat "$out/runs.txt")
gnuplot -e "dir='$res/comparison'; out='$out'; lib='$lib'; name='summary'; data='$out/summary.dat'; runs='$runs'" \
  "$lib/design_summary.gp"
echo "made $out/summary.png $out/summary.svg"
