#!/usr/bin/env python3
"""`make golden`: the golden columns of a smoke run's cases.csv (identity, settings, status, estimates; not the
termination text, costs or standard errors, whose optimizer-version detail does not matter to a conclusion), written
to the golden table that ctest GoldenSmoke.* compares every fresh smoke run with. Review the diff before committing.

usage: make_golden.py CASES.csv GOLDEN.csv            write the golden table
       make_golden.py --check CASES.csv GOLDEN.csv    compare a run with it, as ctest GoldenSmoke does: success
                                                      of every case, whether it failed; status and the estimates of the identifying fits
                                                      (success 1) to 1e-3 relative, damping parameters to 1e-2 (the
                                                      reasons are in tests/study/golden_smoke_test.cc)
"""
import csv
import sys

DAMPING = {"gamma", "cDI", "kAcs"}  # model::ParameterInfo role "damping"
KEEP = {"case_id", "elements", "cost", "noise", "replicate", "method", "start", "status", "success"}

def main(cases_path, golden_path):
    with open(cases_path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    keep = [i for i, name in enumerate(header) if name in KEEP or name.startswith("estimate_")]
    with open(golden_path, "w", newline="") as f:
        for row in rows:
            f.write(",".join(row[i] for i in keep) + "\n")

def check(cases_path, golden_path):
    def rows(path):
        with open(path, newline="") as f:
            r = list(csv.DictReader(f))
        return {row["case_id"]: row for row in r}
    now, golden = rows(cases_path), rows(golden_path)
    problems = []
    compared = 0
    if set(now) != set(golden):
        problems.append("the cases differ: %d in the run, %d in the golden table" % (len(now), len(golden)))
    for case_id, g in golden.items():
        n = now.get(case_id)
        if n is None:
            continue
        for column, want in g.items():
            got = n.get(column)
            if column == "status" and g["success"] != "1":
                if (got == "failed") != (want == "failed"):  # a non-identifying fit: failed or not, no more
                    problems.append("%s status: %s, golden %s" % (case_id, got, want))
                continue
            if column.startswith("estimate_"):
                if g["success"] != "1":
                    continue  # a fit that does not identify: its landing point is machine-dependent
                compared += 1
                tolerance = 1e-2 if column[len("estimate_"):] in DAMPING else 1e-3
                w, v = float(want), float(got)
                if abs(v - w) > tolerance * max(abs(w), 1e-300):
                    problems.append("%s %s: %s, golden %s" % (case_id, column, got, want))
            elif got != want:
                problems.append("%s %s: %s, golden %s" % (case_id, column, got, want))
    if problems:
        print("smoke: does NOT match the golden table %s:" % golden_path)
        for p in problems[:20]:
            print("  " + p)
        sys.exit(1)
    print("smoke: all %d cases match the golden table %s (statuses equal; %d estimates of identifying fits within "
          "1e-3, damping 1e-2)" % (len(golden), golden_path, compared))

if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--check":
        check(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3:
        main(sys.argv[1], sys.argv[2])
    else:
        sys.exit(__doc__)
