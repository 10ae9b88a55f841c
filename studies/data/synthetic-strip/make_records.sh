#!/usr/bin/env bash
# Regenerates the synthetic records of studies/synthetic-strip.toml: one aluminium strip (25 x 3 mm) clamped at four
# free lengths, a 6.0 g sensor board 58 mm inboard of the tip, plucked at the tip and read by a laser vibrometer (velocity) at the
# tip, with 1 % white noise (of each record's RMS). The truth (truth/*.toml) differs from the nominal beams the study
# starts from (strip_*.toml: E 69 GPa, a 5 g board 60 mm from the tip) by E 71 GPa, the board's mass and position.
# Solved at N = 48 by the exact modal propagator ("fast"), 8192 samples at 4 kHz (2.05 s).
# Usage: bash studies/data/synthetic-strip/make_records.sh [path/to/beamid]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
beamid=${1:-$here/../../../build/beamid}
seed=1
for length in 200 250 300 350; do
  "$beamid" simulate --beam "$here/truth/strip_L$length.toml" --elements 48 --excitation pluck --output velocity \
    --dt 2.5e-4 --samples 8192 --noise-level 0.01 --seed $seed > "$here/strip_L$length.csv"
  echo "strip_L$length.csv: exact frequencies (Hz) $("$beamid" modes --beam "$here/truth/strip_L$length.toml" --exact \
    --count 4 | tail -n +2 | cut -d, -f2 | paste -sd' ')"
  seed=$((seed + 1))
done
