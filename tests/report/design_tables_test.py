#!/usr/bin/python3
"""tools/design_tables.py: the main text's tables of the design, from a small results folder written here (two
studies of the thin beam with made-up numbers): the block names the one commit its tables come from and none when
they differ, a method with the sensor's filter in its model stands beside the method it varies, radii, ratios and
biases are printed as the tables hold them (a censored radius as > or <, a bias beyond 2 MCSE starred), and a second
run writes the same bytes."""
import json
import pathlib
import subprocess
import sys
import tempfile
import unittest

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "tools" / "design_tables.py"
REACH = "cost,method,records,references_failed,starts,reached,half_radius,half_radius_low,half_radius_high,position," \
        "experiment,pulse_width_s,samples,modes_in_data\n"
REFERENCE = "cost,method,parameter,fits,records,bias,mcse,sd,rmse,bound,rmse_over_bound,fits_run,budget_exhausted," \
            "experiment,pulse_width_s,samples,modes_in_data\n"
MODES = "cost,method,mode,truth_frequency_hz,truth_damping_ratio,fits,frequency_bias,frequency_mcse,frequency_rmse," \
        "damping_bias,damping_mcse,damping_rmse,experiment,pulse_width_s,samples,modes_in_data\n"
TIMINGS = "cost,method,fits,median_evaluations,total_evaluations,median_seconds,total_seconds,experiment," \
          "pulse_width_s,samples,modes_in_data\n"


def study(root, name, commit, runs):
    """A design study's tables: `runs` as (cost, method, radius, position, EI ratio, EI bias, EI mcse)."""
    folder = root / name / "start_distance"
    folder.mkdir(parents=True)
    (root / name / "manifest.json").write_text(json.dumps({"commit": commit}))
    reach, reference, modes, timings = REACH, REFERENCE, MODES, TIMINGS
    for cost, method, radius, position, ratio, bias, mcse in runs:
        reach += f"{cost},{method},20,0,240,120,{radius},{radius / 2},{radius * 2},{position},0,0.008,4096,3\n"
        for key, r in (("EI", ratio), ("rho", 1.0), ("cDI", 99.0)):
            reference += f"{cost},{method},{key},20,20,{bias},{mcse},0,0,0,{r},260,0,0,0.008,4096,3\n"
        modes += f"{cost},{method},1,2.5,0.001,20,0.001,0,0,-0.2,0,0,0,0.008,4096,3\n"
        timings += f"{cost},{method},260,10,100,0.05,10,0,0.008,4096,3\n"
    (folder / "reach.csv").write_text(reach)
    (folder / "reference.csv").write_text(reference)
    (folder / "reference_modes.csv").write_text(modes)
    (folder / "timings.csv").write_text(timings)
    fits = "cost,method,offset,direction,status,pulse_width_s\n"
    for cost, method, *_ in runs:  # two fits from the truth a run, the second on a bound; one from a start
        fits += f"{cost},{method},0,0,converged,0.008\n{cost},{method},0,0,converged-at-bound,0.008\n"
        fits += f"{cost},{method},0.01,1,converged-at-bound,0.008\n"
    (folder / "fits.csv").write_text(fits)
    (root / name / "convergence.csv").write_text(
        "cost,method,start,elements,status,relative_error_EI,relative_error_rho,relative_error_cDI,relative_error_gamma\n"
        "time,direct,truth,16,converged,0.001,-0.002,0.5,0.1\n"
        "time,direct-sensed,truth,16,converged,0.0001,0.0002,0.05,0.01\n")


def run(root):
    return subprocess.run([sys.executable, str(SCRIPT), str(root)], capture_output=True, text=True, check=False)


class DesignTables(unittest.TestCase):
    def test_tables(self):
        with tempfile.TemporaryDirectory() as folder:
            root = pathlib.Path(folder)
            study(root, "comparison-control", "abc1234def56", [("time", "direct", 0.02, "inside", 1.1, 1e-6, 2e-6),
                                                               ("modal", "direct", 0.2, "above", 3.6, 1e-4, 1e-5)])
            study(root, "comparison", "abc1234def56", [("time", "direct", 0.02, "inside", 60.0, -6.4e-4, 1e-5),
                                                       ("modal", "direct", 0.001, "below", 78.0, 1.8e-4, 1e-4),
                                                       ("time", "direct-sensed", 0.03, "inside", 4.4, 4.7e-5, 3e-6)])
            self.assertEqual(run(root).returncode, 0)
            answer = (root / "design" / "answer.md").read_text()
            self.assertIn("commit abc1234def56", answer)
            lines = answer.splitlines()
            order = [l.split("|")[1].strip() for l in lines if l.startswith("| `")]
            self.assertEqual(order, ["`time/direct`", "`time/direct-sensed`", "`modal/direct`"])
            self.assertIn("| `time/direct` | 2 (1-4) | 2 (1-4) | 60 | 1.1 | 10 |", answer)
            self.assertIn("| `modal/direct` | < 0.1 | > 20 | 78 | 3.6 | 10 |", answer)
            self.assertIn("| `time/direct-sensed` | 3 (1.5-6) | - | 4.4 | - | 10 |", answer)
            accuracy = (root / "design" / "accuracy.md").read_text()
            self.assertIn("| `time/direct` | 1.1 | 60 |", accuracy)  # the control's column, then all three errors'
            self.assertIn("| `time/direct` | -0.064* | -0.064* |", accuracy)  # the study's EI and rho rows alike
            self.assertIn("| `modal/direct` | +0.018 | +0.018 |", accuracy)  # 1.8e-4 within 2 MCSE: no star
            # No coloured-noise study yet: the block is there, empty but for its provenance.
            self.assertNotIn("AR(1)", (root / "design" / "coloured.md").read_text())
            study(root, "comparison-coloured", "abc1234def56", [("time", "direct-sensed", 0.03, "inside", 7.5, 2e-4, 1e-5),
                                                                ("freq-ml", "estimated-sensed", 0.03, "inside", 1.9, 1e-5, 1e-5)])
            self.assertEqual(run(root).returncode, 0)
            colour = (root / "design" / "coloured.md").read_text()
            self.assertIn("`comparison-coloured`", colour)  # named among the tables it comes from
            # Its ratio beside the white design's for the same run, and "-" for a run the white design does not have.
            self.assertIn("| `time/direct-sensed` | 7.5 | 4.4 | +0.02* | +0.02* | 1/2 |", colour)
            self.assertIn("| `freq-ml/estimated-sensed` | 1.9 | - | +0.001 | +0.001 | 1/2 |", colour)
            across = (root / "design" / "across_n.md").read_text()
            self.assertIn("| `time/direct` | 0.2 / 50 |", across)
            self.assertIn("| `time/direct-sensed` | 0.02 / 5 |", across)
            # Seconds only in compute.md (a timings file): the answer's compute is evaluations, a function of the tables.
            self.assertNotIn("0.05", answer)
            timing = (root / "design" / "compute.md").read_text()
            self.assertIn("commit abc1234def56", timing)
            self.assertIn("| `time/direct` | 10 | 0.05 | 10 |", timing)
            first = {p.name: p.read_bytes() for p in (root / "design").iterdir()}
            self.assertEqual(run(root).returncode, 0)
            self.assertEqual(first, {p.name: p.read_bytes() for p in (root / "design").iterdir()})
            # Tables from two commits: the blocks name neither, so the one-commit check fails on them.
            (root / "comparison" / "manifest.json").write_text(json.dumps({"commit": "fedcba987654"}))
            self.assertEqual(run(root).returncode, 0)
            mixed = (root / "design" / "answer.md").read_text()
            self.assertNotIn("commit abc", mixed)
            self.assertIn("their commits differ (abc1234 fedcba9)", mixed)

    def test_no_design(self):
        with tempfile.TemporaryDirectory() as folder:
            result = run(pathlib.Path(folder))
            self.assertNotEqual(result.returncode, 0)
            self.assertIn("no design study has results", result.stderr)


if __name__ == "__main__":
    unittest.main()
