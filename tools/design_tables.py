#!/usr/bin/env python3
"""design_tables.py RESULTS_DIR: the main text's tables of the design (issue 35 items 4 and 5), from its studies'
tables, as REPORT.md blocks.

Reads results/comparison*/ (the coloured-noise studies comparison-coloured and comparison-thick-coloured too; start_distance/reach.csv, reference.csv, reference_modes.csv, timings.csv,
convergence.csv and manifest.json) and writes RESULTS_DIR/design/{answer,accuracy,coloured,modes,across_n,compute}.md, which `beamid
report` pastes into the blocks of those names under design/. Each opens with the commit that made the tables it
reads; when the studies come from several commits it names none of them, so that `make report-check` fails rather
than a block mixing them silently. compute.md alone holds seconds, from the timings files, which change from run to
run (it is a timings file, as timings.csv is); every other block is a function of the tables (the answer's compute is
the median number of model evaluations per fit), so a second run writes them byte for byte. Only the standard
library.
"""
import csv
import json
import math
import os
import sys

# (study, beam, truth) of the design: the truth's model errors, one column each in the accuracy table.
THIN = ["comparison-control", "comparison-n48", "comparison-damping", "comparison-sensor", "comparison"]
THICK = ["comparison-thick-control", "comparison-thick-n48", "comparison-thick-damping", "comparison-thick-sensor",
         "comparison-thick"]
TRUTHS = ["none (control)", "N48", "N48 + loss", "N48 + sensor", "all three"]
BEAMS = [("thin", THIN, ["EI", "rho"]), ("thick", THICK, ["EI", "kAG", "rho"])]
# The design's three model errors with AR(1) noise (issue 35 item 1), beside the white design's all-three study.
COLOURED = {"thin": "comparison-coloured", "thick": "comparison-thick-coloured"}
DAMPING = {"cDI", "gamma", "kAcs"}
WINDOWS = {"hann", "exponential", "rectangular"}


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def run_name(cost, method):
    """A run as the tables name it, (3.5)'s best window (Hann thin, exponential thick) as one name for both."""
    return cost + "/" + ("window" if method in WINDOWS else method)


def ordered(runs):
    """Runs in order of first appearance, each "-sensed" one right after the run it varies."""
    plain = [r for r in runs if not r.endswith("-sensed")]
    out = []
    for r in plain:
        out.append(r)
        if r + "-sensed" in runs:
            out.append(r + "-sensed")
    return out + [r for r in runs if r not in out]


def number(v, digits):
    """v to `digits` significant digits, without an exponent or a trailing ".0"."""
    if v == 0 or not math.isfinite(v):
        return "%g" % v
    r = float("%.*g" % (digits, v))
    return "%d" % r if abs(r) >= 10 ** (digits - 1) else "%g" % r


def pct(value, digits=3):
    """A relative value as a percentage with `digits` significant digits."""
    return number(100 * value, digits)


def signed_pct(value, digits=2):
    text = pct(value, digits)
    return text if text.startswith("-") or text in ("0", "nan") else "+" + text


def ratio(value):
    if not math.isfinite(value):
        return "-"
    return "%.2g" % value if value < 10 else "%d" % round(value)


def radius(r):
    """A 50 % radius in %, with its interval; censored ones as > or <."""
    if r["position"] == "above":
        return "> %s" % pct(float(r["half_radius"]), 2)
    if r["position"] == "below":
        return "< %s" % pct(float(r["half_radius"]), 2)
    return "%s (%s-%s)" % (pct(float(r["half_radius"]), 2), pct(float(r["half_radius_low"]), 2),
                           pct(float(r["half_radius_high"]), 2))


class Study:
    def __init__(self, results, name):
        self.name = name
        folder = os.path.join(results, name)
        self.present = os.path.exists(os.path.join(folder, "start_distance", "reference.csv"))
        if not self.present:
            return
        with open(os.path.join(folder, "manifest.json")) as f:
            self.commit = json.load(f).get("commit", "")
        sd = os.path.join(folder, "start_distance")
        self.reach = rows(os.path.join(sd, "reach.csv"))
        self.reference = rows(os.path.join(sd, "reference.csv"))
        self.modes = rows(os.path.join(sd, "reference_modes.csv"))
        timing = os.path.join(sd, "timings.csv")
        self.timings = rows(timing) if os.path.exists(timing) else []
        self.convergence = rows(os.path.join(folder, "convergence.csv"))
        fits = os.path.join(sd, "fits.csv")
        self.fits = rows(fits) if os.path.exists(fits) else []
        self.experiments = sorted({r["experiment"] for r in self.reference}, key=int)
        self.modes_in = {r["experiment"]: r["modes_in_data"] for r in self.reference}
        self.runs = ordered(list(dict.fromkeys(run_name(r["cost"], r["method"]) for r in self.reference)))

    def of(self, table, run, experiment):
        return [r for r in table if run_name(r["cost"], r["method"]) == run and r["experiment"] == experiment]

    def worst(self, run, experiment, keys):
        values = [float(r["rmse_over_bound"]) for r in self.of(self.reference, run, experiment)
                  if r["parameter"] in keys]
        return max(values) if values else float("nan")

    def biases(self, run, key):
        """A run's bias of `key` in each experiment (%, separated by /), starred beyond 2 Monte-Carlo standard
        errors; "-" where the run has no such row."""
        parts = []
        for x in self.experiments:
            found = [r for r in self.of(self.reference, run, x) if r["parameter"] == key]
            if not found:
                parts.append("-")
                continue
            bias, mcse = float(found[0]["bias"]), float(found[0]["mcse"])
            parts.append(signed_pct(bias) + ("*" if abs(bias) > 2 * mcse else ""))
        return " / ".join(parts)

    def on_bound(self, run, experiment):
        """The fits from the truth (offset 0) of a run and experiment that ended on a parameter's bound, and all of
        them, from fits.csv (its experiments in the order of reference.csv's)."""
        width = {r["experiment"]: r["pulse_width_s"] for r in self.reference}[experiment]
        mine = [r for r in self.fits if run_name(r["cost"], r["method"]) == run and float(r["offset"]) == 0
                and r["pulse_width_s"] == width]
        return sum(r["status"] == "converged-at-bound" for r in mine), len(mine)

    def timing(self, run, experiment, column):
        found = self.of(self.timings, run, experiment)
        return float(found[0][column]) if found else float("nan")


def provenance(studies):
    commits = sorted({s.commit for s in studies if s.present})
    names = ", ".join("`%s`" % s.name for s in studies if s.present)
    if len(commits) == 1:
        return "*Written by `tools/design_tables.py` from the tables of %s, commit %s.*\n" % (names, commits[0])
    return ("*Written by `tools/design_tables.py` from the tables of %s; their commits differ (%s), so this block "
            "names none.*\n" % (names, " ".join(c[:7] for c in commits)))


def answer(thin, thick):
    out = []
    for beam, studies, stiff in (("thin", thin, ["EI", "rho"]), ("thick", thick, ["EI", "kAG", "rho"])):
        control, error = studies[0], studies[-1]
        if not (control.present and error.present):
            continue
        e = error.experiments
        modes = " / ".join(error.modes_in[x] for x in e)
        out.append("**%s beam** (records of %s modes; values for each, separated by /)\n" % (beam.capitalize(), modes))
        out.append("| method | 50 %% radius, %% (95 %% interval), with model error | without | worst RMSE / bound "
                   "on %s, with model error | without | median evaluations per fit |" % ", ".join(stiff))
        out.append("|---|---|---|---|---|---|")
        for run in error.runs:
            reach_e = [error.of(error.reach, run, x) for x in e]
            reach_c = [control.of(control.reach, run, x) for x in control.experiments]
            out.append("| `%s` | %s | %s | %s | %s | %s |" % (
                run,
                " / ".join(radius(r[0]) if r else "-" for r in reach_e),
                " / ".join(radius(r[0]) if r else "-" for r in reach_c) if any(reach_c) else "-",
                " / ".join(ratio(error.worst(run, x, stiff)) for x in e),
                " / ".join(ratio(control.worst(run, x, stiff)) for x in control.experiments)
                if control.of(control.reference, run, control.experiments[0]) else "-",
                " / ".join("%.0f" % error.timing(run, x, "median_evaluations") for x in e)))
        out.append("")
    # The evaluation budget where it bound: the fits of every run of every design study that ran out of it.
    spent = []
    for s in thin + thick:
        if not s.present:
            continue
        for r in s.reference:
            if r["parameter"] == "EI" and int(r["budget_exhausted"]) > 0:
                spent.append("`%s` %s/%s in `%s` (%s modes)" % (run_name(r["cost"], r["method"]), r["budget_exhausted"],
                                                               r["fits_run"], s.name, r["modes_in_data"]))
    out.append("Fits that ran out of their evaluation budget (3,000 a stage): " +
               ("; ".join(spent) if spent else "none") + ".\n")
    return "\n".join(out)


def accuracy(thin, thick):
    out = []
    for beam, studies, stiff in (("thin", thin, ["EI", "rho"]), ("thick", thick, ["EI", "kAG", "rho"])):
        present = [s for s in studies if s.present]
        if not present:
            continue
        runs = ordered(list(dict.fromkeys(r for s in present for r in s.runs)))
        e = present[-1].experiments
        modes = " / ".join(present[-1].modes_in[x] for x in e)
        out.append("**%s beam**: worst RMSE / Cramér-Rao bound over %s of the 20 fits from the truth, records of %s "
                   "modes (separated by /), by the truth's model errors\n" % (beam.capitalize(), ", ".join(stiff), modes))
        out.append("| method | " + " | ".join(t for s, t in zip(studies, TRUTHS) if s.present) + " |")
        out.append("|---|" + "---|" * len(present))
        for run in runs:
            cells = []
            for s in present:
                cells.append(" / ".join(ratio(s.worst(run, x, stiff)) for x in s.experiments)
                             if s.of(s.reference, run, s.experiments[0]) else "-")
            out.append("| `%s` | %s |" % (run, " | ".join(cells)))
        out.append("")
        # The biases with every model error, each parameter's bias +- its Monte-Carlo standard error.
        last = present[-1]
        out.append("Bias of %s with all three model errors (%%; * beyond 2 Monte-Carlo standard errors), records of "
                   "%s modes:\n" % (", ".join(stiff), modes))
        out.append("| method | " + " | ".join(stiff) + " |")
        out.append("|---|" + "---|" * len(stiff))
        for run in last.runs:
            cells = [last.biases(run, key) for key in stiff]
            out.append("| `%s` | %s |" % (run, " | ".join(cells)))
        out.append("")
    return "\n".join(out)


def modes_table(thin, thick):
    out = []
    for beam, studies in (("thin", thin), ("thick", thick)):
        present = [s for s in studies if s.present]
        if not present:
            continue
        last = present[-1]
        x = last.experiments[-1]
        out.append("**%s beam, all three model errors, records of %s modes**: each mode's frequency and damping "
                   "ratio at the fits from the truth against the truth beam's own (mean relative error over the 20 "
                   "records, %%)\n" % (beam.capitalize(), last.modes_in[x]))
        modes = sorted({int(r["mode"]) for r in last.modes if r["experiment"] == x})
        out.append("| method | " + " | ".join("f%d" % m for m in modes) + " | " +
                   " | ".join("zeta%d" % m for m in modes) + " |")
        out.append("|---|" + "---|" * (2 * len(modes)))
        for run in last.runs:
            found = {int(r["mode"]): r for r in last.of(last.modes, run, x)}
            f = [signed_pct(float(found[m]["frequency_bias"])) if m in found else "-" for m in modes]
            z = [signed_pct(float(found[m]["damping_bias"])) if m in found else "-" for m in modes]
            out.append("| `%s` | %s | %s |" % (run, " | ".join(f), " | ".join(z)))
        out.append("")
    return "\n".join(out)


def across_n(thin, thick):
    out = []
    for beam, studies, stiff in (("thin", thin, ["EI", "rho"]), ("thick", thick, ["EI", "kAG", "rho"])):
        last = studies[-1]
        if not last.present:
            continue
        columns = [c[len("relative_error_"):] for c in last.convergence[0] if c.startswith("relative_error_")]
        elements = sorted({int(r["elements"]) for r in last.convergence})
        out.append("**%s beam, all three model errors**: noise-free fits from the truth on the first experiment's "
                   "record, each cost with the paper's settings (`direct`) and with the sensor's filter in its model "
                   "(`direct-sensed`): the largest |relative error| over %s, then over the damping parameters (%%)\n"
                   % (beam.capitalize(), ", ".join(stiff)))
        out.append("| cost/method | " + " | ".join("N = %d" % n for n in elements) + " |")
        out.append("|---|" + "---|" * len(elements))
        runs = ordered(list(dict.fromkeys(r["cost"] + "/" + r["method"] for r in last.convergence)))
        for run in runs:
            cells = []
            for n in elements:
                found = [r for r in last.convergence
                         if r["cost"] + "/" + r["method"] == run and int(r["elements"]) == n]
                if not found:
                    cells.append("-")
                    continue
                r = found[0]
                s = max(abs(float(r["relative_error_" + k])) for k in columns if k in stiff)
                d = max((abs(float(r["relative_error_" + k])) for k in columns if k in DAMPING), default=float("nan"))
                cells.append("%s / %s" % (pct(s, 2), pct(d, 2)))
            out.append("| `%s` | %s |" % (run, " | ".join(cells)))
        out.append("")
    return "\n".join(out)


def coloured(thin, thick, colour):
    """Per beam: each run of the coloured-noise study (worst RMSE over the coloured-noise bound, bias), beside the same
    run's ratio in the white design with all three model errors."""
    out = []
    for beam, studies, stiff in (("thin", thin, ["EI", "rho"]), ("thick", thick, ["EI", "kAG", "rho"])):
        c, white = colour[beam], studies[-1]
        if not c.present:
            continue
        e = c.experiments
        modes = " / ".join(c.modes_in[x] for x in e)
        out.append("**%s beam, all three model errors, AR(1) noise (a = 0.9)**: worst RMSE / coloured-noise "
                   "Cramér-Rao bound over %s of the 20 fits from the truth, records of %s modes (separated by /); "
                   "beside it the same run's ratio in white noise (the table above, all three); bias (%%; * beyond "
                   "2 Monte-Carlo standard errors); and how many of the fits from the truth ended on a parameter's bound (the fits' "
                   "status)\n" % (beam.capitalize(), ", ".join(stiff), modes))
        out.append("| method | RMSE / bound, coloured | white | " + " | ".join("bias " + k for k in stiff) +
                   " | fits on a bound |")
        out.append("|---|---|---|" + "---|" * len(stiff) + "---|")
        for run in list(dict.fromkeys(run_name(r["cost"], r["method"]) for r in c.reference)):
            biases = [c.biases(run, key) for key in stiff]
            in_white = white.present and white.of(white.reference, run, white.experiments[0])
            out.append("| `%s` | %s | %s | %s | %s |" % (
                run, " / ".join(ratio(c.worst(run, x, stiff)) for x in e),
                " / ".join(ratio(white.worst(run, x, stiff)) for x in white.experiments) if in_white else "-",
                " | ".join(biases), " / ".join("%d/%d" % c.on_bound(run, x) for x in e)))
        out.append("")
    return "\n".join(out)


def compute(thin, thick):
    """Per run and experiment of each beam's study with all three model errors: median evaluations and seconds per
    fit, and the run's total seconds (the timings files: seconds change from run to run)."""
    out = ["Median model evaluations and seconds per fit, and each run's total seconds over its fits (from the "
           "start and from the truth), in the studies with all three model errors (`start_distance/timings.csv`: "
           "the seconds change from run to run and with the machine's load).\n"]
    for beam, studies in (("thin", thin), ("thick", thick)):
        error = studies[-1]
        if not error.present:
            continue
        e = error.experiments
        out.append("**%s beam** (records of %s modes, separated by /)\n" %
                   (beam.capitalize(), " / ".join(error.modes_in[x] for x in e)))
        out.append("| method | median evaluations per fit | median s per fit | total s |")
        out.append("|---|---|---|---|")
        for run in error.runs:
            out.append("| `%s` | %s | %s | %s |" % (
                run, " / ".join("%.0f" % error.timing(run, x, "median_evaluations") for x in e),
                " / ".join("%.2g" % error.timing(run, x, "median_seconds") for x in e),
                " / ".join("%.0f" % error.timing(run, x, "total_seconds") for x in e)))
        out.append("")
    return "\n".join(out)


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: design_tables.py RESULTS_DIR")
    results = argv[1]
    thin = [Study(results, n) for n in THIN]
    thick = [Study(results, n) for n in THICK]
    if not any(s.present for s in thin + thick):
        sys.exit("design_tables.py: no design study has results in " + results)
    folder = os.path.join(results, "design")
    os.makedirs(folder, exist_ok=True)
    colour = {beam: Study(results, name) for beam, name in COLOURED.items()}
    head = provenance(thin + thick + list(colour.values()))
    for name, body in (("answer", answer(thin, thick)), ("accuracy", accuracy(thin, thick)),
                       ("coloured", coloured(thin, thick, colour)),
                       ("modes", modes_table(thin, thick)), ("across_n", across_n(thin, thick)),
                       ("compute", compute(thin, thick))):
        with open(os.path.join(folder, name + ".md"), "w") as f:
            f.write(head + "\n" + body.rstrip() + "\n")
    print("design_tables.py: wrote %s/{answer,accuracy,coloured,modes,across_n,compute}.md" % folder)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
