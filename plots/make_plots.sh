#!/usr/bin/env bash
# make_plots.sh RESULTS_DIR OUTPUT_DIR
#
# Makes every plot whose input CSV files exist in RESULTS_DIR (a study's results folder), writing
# OUTPUT_DIR/<name>.png and OUTPUT_DIR/<name>.svg, and prints one line per plot made. The plots are
# drawn by the gnuplot scripts in plots/scripts/ and depend on the CSV files only; each names the
# study, case count and commit from RESULTS_DIR/provenance.csv. Plots whose inputs are missing are
# skipped. See plots/README.md.
set -euo pipefail

die() { echo "make_plots.sh: $*" >&2; exit 1; }
[[ $# -eq 2 ]] || { echo "usage: make_plots.sh RESULTS_DIR OUTPUT_DIR" >&2; exit 2; }
res=${1%/} out=${2%/}
command -v gnuplot >/dev/null 2>&1 || die "gnuplot not found (install gnuplot 5.4)"
[[ -d $res ]] || die "results folder '$res' does not exist"
[[ -f $res/provenance.csv ]] || die "'$res/provenance.csv' not found: not a study results folder?"
[[ $res$out != *\'* ]] || die "paths must not contain a single quote"
lib=$(cd "$(dirname "${BASH_SOURCE[0]}")/scripts" && pwd)
[[ $lib != *\'* ]] || die "the script folder path must not contain a single quote"
mkdir -p "$out"

failed=0
# plot SCRIPT NAME [gnuplot assignments...]: run one script, report the outcome
plot() {
  local script=$1 name=$2
  shift 2
  if gnuplot -e "dir='$res'; out='$out'; lib='$lib'; name='$name'; $*" "$lib/$script.gp"; then
    echo "made $out/$name.png $out/$name.svg"
  else
    echo "make_plots.sh: FAILED $name ($script.gp)" >&2
    failed=1
  fi
}

# order: known names first (as in the paper), then any others, sorted; arguments: known list, found list
ordered() {
  local k x
  for k in $1; do [[ " $2 " == *" $k "* ]] && printf '%s ' "$k"; done
  for x in $(printf '%s\n' $2 | LC_ALL=C sort -u); do [[ " $1 " == *" $x "* ]] || printf '%s ' "$x"; done
}
known_costs="time spike spike-smooth"
known_params="EI rho cDI gamma kAG kAcs"
shopt -s nullglob

# landscape_slices: landscape/slice_<cost>_<param>.csv (parameters have no '_', costs may have '-')
params="" costs=""
for f in "$res"/landscape/slice_*_*.csv; do
  b=${f##*/}; b=${b%.csv}; b=${b#slice_}
  params+=" ${b##*_}"; costs+=" ${b%_*}"
done
if [[ -n $params ]]; then
  plot landscape_slices landscape_slices "params='$(ordered "$known_params" "$params")'; costs='$(ordered "$known_costs" "$costs")'"
fi

# grid_plots DIR PREFIX SUB WHAT: one landscape_grid figure PREFIX<a>_<b> per pair of DIR/grid_<cost>_<a>_<b>.dat (the
# pair is the last two fields), with the costs present for it; SUB and WHAT go to landscape_grid.gp.
grid_plots() {
  local dir=$1 prefix=$2 sub=$3 what=$4 pairs="" f b pb rest pa pair a c costs
  for f in "$dir"/grid_*_*_*.dat; do
    b=${f##*/}; b=${b%.dat}
    pb=${b##*_}; rest=${b%_*}; pa=${rest##*_}
    pairs+=" ${pa}_${pb}"
  done
  for pair in $(printf '%s\n' $pairs | LC_ALL=C sort -u); do
    a=${pair%_*} b=${pair#*_} costs=""
    for f in "$dir"/grid_*_"${a}_${b}".dat; do
      c=${f##*/}; c=${c#grid_}; c=${c%_"${a}_${b}".dat}
      costs+=" $c"
    done
    plot landscape_grid "${prefix}${a}_${b}" "a='$a'; b='$b'; sub='$sub'; what='$what'; costs='$(ordered "$known_costs" "$costs")'"
  done
}

# landscape_grid_<a>_<b>: landscape/grid_<cost>_<a>_<b>.dat, one figure per pair
grid_plots "$res/landscape" landscape_grid_ "" ""

# landscape_zoom_<setting>_<a>_<b>: landscape/zoom/<setting>/grid_<cost>_<a>_<b>.dat, the fine grids around the truth
# of one N and noise level (<setting> = N<n>-noise<level>), one figure per setting and pair
for d in "$res"/landscape/zoom/*/; do
  setting=${d%/}; setting=${setting##*/}
  n=${setting%%-*}; level=${setting#*-noise}
  grid_plots "${d%/}" "landscape_zoom_${setting}_" "zoom/$setting/" " near the truth, ${n/N/N = }, noise $level"
done

# bias_<param>: bias_<param>.csv
found=""
for f in "$res"/bias_*.csv; do
  p=${f##*/bias_}; found+=" ${p%.csv}"
done
for p in $(ordered "$known_params" "$found"); do
  plot bias "bias_$p" "param='$p'"
done

# success_vs_modes: modes.csv, only when the data have more than one modes count
if [[ -f $res/modes.csv ]] && head -n 1 "$res/modes.csv" | grep -q "^modes_in_data,"; then  # a synthetic study's table (real-steel's modes.csv lists identified modes)
  n=$(awk -F, 'NR > 1 && NF > 1 {print $1}' "$res/modes.csv" | LC_ALL=C sort -u | wc -l)
  if (( n > 1 )); then
    plot success_vs_modes success_vs_modes
  else
    echo "skipped success_vs_modes: modes.csv has $n distinct modes_in_data value(s)"
  fi
fi

# start_distance: start_distance/curves.csv and radius.csv
if [[ -f $res/start_distance/curves.csv && -f $res/start_distance/radius.csv ]]; then plot start_distance start_distance; fi
# radius_vs_modes: start_distance/radius.csv, when it holds more than one experiment (column 14)
if [[ -f $res/start_distance/radius.csv ]] && (( $(awk -F, 'NR > 1 {print $14}' "$res/start_distance/radius.csv" | sort -u | wc -l) > 1 )); then
  plot radius_vs_modes radius_vs_modes
fi

# spectrum: spectrum.csv (+ spikes.csv for the marks); overlay: overlay.csv + spectrum.csv
if [[ -f $res/spectrum.csv ]]; then plot spectrum spectrum; fi
if [[ -f $res/overlay.csv && -f $res/spectrum.csv ]]; then plot overlay overlay; fi

(( failed == 0 )) || die "some plots failed (see above)"
