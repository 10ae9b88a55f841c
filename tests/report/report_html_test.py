#!/usr/bin/python3
"""REPORT.html (tools/report_html.py): every table and every linked plot of the Markdown is on the page, the plots
inline as SVG with their ids made unique, and a plot without its SVG named rather than dropped. Run by ctest with the
source folder as the argument."""
import pathlib
import re
import subprocess
import sys
import tempfile
import unittest

SOURCE = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
SCRIPT = SOURCE / "tools" / "report_html.py"


def render(markdown_path: pathlib.Path) -> tuple:
    out = markdown_path.with_suffix(".html")
    run = subprocess.run(["/usr/bin/python3", str(SCRIPT), str(markdown_path), str(out)], capture_output=True,
                         text=True, check=False)
    return run, out.read_text(encoding="utf-8") if out.exists() else ""


SVG = """<?xml version="1.0" encoding="utf-8"  standalone="no"?>
<svg width="100" height="50" viewBox="0 0 100 50" xmlns="http://www.w3.org/2000/svg">
<g id="gnuplot_canvas"><defs><clipPath id="gpClip"><rect width="1" height="1"/></clipPath></defs>
<use href="#gpDot"/><path clip-path="url(#gpClip)" d="M0,0 L1,1"/></g></svg>
"""


class ReportHtml(unittest.TestCase):
    def test_a_small_report(self):
        with tempfile.TemporaryDirectory() as folder:
            root = pathlib.Path(folder)
            (root / "plots" / "s").mkdir(parents=True)
            (root / "plots" / "s" / "a.svg").write_text(SVG)
            (root / "plots" / "s" / "b.svg").write_text(SVG)
            (root / "R.md").write_text(
                "# Title\n\n## 2.1 `s`: a study\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n"
                "Plots: [first](plots/s/a.png), [second](plots/s/b.png), [gone](plots/s/c.png).\n\n"
                "Again [first](plots/s/a.png).\n")
            run, page = render(root / "R.md")
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(page.count("<table"), 1)
            # Three figures: two inline, one named as missing; a plot linked twice is shown once.
            self.assertEqual(page.count("<figure"), 3)
            self.assertEqual(page.count("<svg"), 2)
            self.assertIn('class="missing"', page)
            self.assertIn("plots/s/c.png is linked but has no plots/s/c.svg", run.stderr)
            # Ids unique per figure, references following them; no XML prolog inside the page.
            self.assertIn('id="f1-gnuplot_canvas"', page)
            self.assertIn('id="f2-gnuplot_canvas"', page)
            self.assertIn("url(#f2-gpClip)", page)
            self.assertIn('href="#f1-gpDot"', page)
            self.assertNotIn("<?xml", page)
            ids = re.findall(r'\bid="([^"]+)"', page)
            self.assertEqual(len(ids), len(set(ids)), "every id once")
            # Links go to the figures; the study's heading has an anchor.
            self.assertIn('href="#fig-plots-s-a"', page)
            self.assertIn('id="fig-plots-s-a"', page)
            self.assertIn('id="21-s-a-study"', page)

    def test_the_report(self):
        with tempfile.TemporaryDirectory() as folder:
            copy = pathlib.Path(folder) / "REPORT.md"
            copy.write_text((SOURCE / "REPORT.md").read_text(encoding="utf-8"), encoding="utf-8")
            (pathlib.Path(folder) / "plots").symlink_to(SOURCE / "plots")
            run, page = render(copy)
            self.assertEqual(run.returncode, 0, run.stderr)
            text = copy.read_text(encoding="utf-8")
            tables = len(re.findall(r"^\|(?:\s*:?-+:?\s*\|)+\s*$", text, flags=re.M))
            self.assertEqual(page.count("<table"), tables)
            linked = set(re.findall(r"\]\((plots/[^)\s]+)\.png\)", text))
            self.assertGreater(len(linked), 50)
            self.assertEqual(page.count("<figure"), len(linked))
            self.assertNotIn('class="missing"', page, run.stderr)
            self.assertEqual(page.count("<svg"), len(linked))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
