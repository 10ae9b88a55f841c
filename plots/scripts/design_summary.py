#!/usr/bin/env python3
"""design_summary.py RESULTS_DIR OUTPUT_DIR: the data of the design's summary figure (issue 35, REPORT.md's one-page answer).

Reads, for each study of the design that has results (comparison, comparison-control, comparison-thick and
comparison-thick-control when present), its start_distance/reach.csv (50 % radius and bootstrap interval),
start_distance/reference.csv (RMSE / Cramer-Rao bound of each parameter over the fits from the truth) and
start_distance/timings.csv (median seconds per fit), and writes OUTPUT_DIR/summary.dat: one row per (beam, model
error, experiment, run) with

  beam truth modes run x radius_pct low_pct high_pct position worst_stiffness_efficiency median_seconds

where worst_stiffness_efficiency is the largest RMSE / bound over the stiffness and mass parameters (EI, rho and kAG:
the ones every beam's modes determine), and x the run's position on the figure's axis. Only the standard library:
the plots need nothing beyond Debian's python3 and gnuplot.
"""
import os
import sys

# The design's run names, their order and the CSV reader are tools/design_tables.py's, which the report's tables use.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from design_tables import ordered, rows, run_name  # noqa: E402

# (study folder, beam, truth label): the label says whether the truth has the model errors.
STUDIES = [
    ("comparison", "thin", "model error"),
    ("comparison-control", "thin", "no model error"),
    ("comparison-thick", "thick", "model error"),
    ("comparison-thick-control", "thick", "no model error"),
]
STIFFNESS = {"EI", "rho", "kAG"}


def main(results, out):
    header = "# beam truth modes run x radius_pct low_pct high_pct position worst_stiffness_efficiency median_seconds"
    records, runs = [], []
    for study, beam, truth in STUDIES:
        folder = os.path.join(results, study, "start_distance")
        if not os.path.exists(os.path.join(folder, "reach.csv")):
            continue
        reach = rows(os.path.join(folder, "reach.csv"))
        reference = rows(os.path.join(folder, "reference.csv"))
        timings = {}
        timing_file = os.path.join(folder, "timings.csv")
        if os.path.exists(timing_file):
            timings = {(r["cost"], r["method"], r["experiment"]): r["median_seconds"] for r in rows(timing_file)}
        for r in reach:
            run = run_name(r["cost"], r["method"])
            if run not in runs:
                runs.append(run)
            efficiencies = [
                float(e["rmse_over_bound"])
                for e in reference
                if e["cost"] == r["cost"] and e["method"] == r["method"] and e["experiment"] == r["experiment"]
                and e["parameter"] in STIFFNESS
            ]
            worst = max(efficiencies) if efficiencies else float("nan")
            seconds = timings.get((r["cost"], r["method"], r["experiment"]), "nan")
            records.append((beam, truth, r, run, worst, seconds))
    if not records:
        sys.exit("design_summary.py: no design study has results in " + results)
    runs = ordered(runs)
    pct = lambda v: repr(100 * float(v))
    lines = [header]
    for beam, truth, r, run, worst, seconds in records:
        lines.append(" ".join([
            beam, '"' + truth + '"', r["modes_in_data"], '"' + run + '"', str(runs.index(run)),
            pct(r["half_radius"]), pct(r["half_radius_low"]), pct(r["half_radius_high"]), r["position"],
            repr(worst), seconds
        ]))
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "summary.dat"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(out, "runs.txt"), "w") as f:
        f.write(" ".join(runs) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: design_summary.py RESULTS_DIR OUTPUT_DIR")
    main(sys.argv[1], sys.argv[2])
