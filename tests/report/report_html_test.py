#!/usr/bin/python3
"""REPORT.html (tools/report_html.py): every table and every linked plot of the Markdown is on the page, the plots
as images of the SVG files beside it (the page small: its figures are files), and a plot without its SVG named rather
than dropped; and the page as headless Chromium renders it (Debian's chromium): every table and figure in its DOM,
every plot's image loaded and drawn with a size, a screenshot of the top of the page in the output folder. Run by ctest with the source folder and an output folder as
the arguments."""
import json
import pathlib
import re
import subprocess
import sys
import tempfile
import unittest

SOURCE = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
OUTPUT = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="report-html-")).resolve()

# Appended to a copy of the page: after the load event, what the browser built, as an attribute --dump-dom shows.
CHECK = """<script>window.addEventListener('load', () => {
  const plots = [...document.querySelectorAll('figure img')];
  const drawn = plots.filter(e => { const r = e.getBoundingClientRect();
    return e.complete && e.naturalWidth > 0 && r.width > 0 && r.height > 0; });
  document.body.setAttribute('data-check', JSON.stringify({figures: document.querySelectorAll('figure').length,
    plots: plots.length, drawn: drawn.length, tables: document.querySelectorAll('table').length,
    missing: document.querySelectorAll('.missing').length}));
});</script>"""
CHROMIUM = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
            "--virtual-time-budget=60000"]
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
            # Three figures: two images of their SVG files, one named as missing; a plot linked twice is shown once.
            self.assertEqual(page.count("<figure"), 3)
            self.assertEqual(page.count("<img"), 2)
            self.assertIn('<img src="plots/s/a.svg"', page)
            self.assertIn('<img src="plots/s/b.svg"', page)
            self.assertNotIn("<svg", page)
            self.assertIn('class="missing"', page)
            self.assertIn("plots/s/c.png is linked but has no plots/s/c.svg", run.stderr)
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
            self.assertEqual(len(re.findall(r'<figure id="[^"]*"><img ', page)), len(linked))
            # The figures are files beside the page: the page itself is the text and tables, under 3 MB.
            self.assertLess(len(page.encode("utf-8")), 3e6)

    def test_the_report_in_chromium(self):
        with tempfile.TemporaryDirectory() as folder:
            copy = pathlib.Path(folder) / "REPORT.md"
            text = (SOURCE / "REPORT.md").read_text(encoding="utf-8")
            copy.write_text(text, encoding="utf-8")
            (pathlib.Path(folder) / "plots").symlink_to(SOURCE / "plots")
            run, page = render(copy)
            self.assertEqual(run.returncode, 0, run.stderr)
            checked = pathlib.Path(folder) / "checked.html"
            checked.write_text(page.replace("</body>", CHECK + "</body>"), encoding="utf-8")
            dom = subprocess.run(CHROMIUM + ["--dump-dom", checked.as_uri()], capture_output=True, text=True,
                                 timeout=600)
            found = re.search(r'data-check="([^"]*)"', dom.stdout)
            self.assertIsNotNone(found, "chromium did not finish the page: " + dom.stderr[-2000:])
            seen = json.loads(found.group(1).replace("&quot;", '"'))
            tables = len(re.findall(r"^\|(?:\s*:?-+:?\s*\|)+\s*$", text, flags=re.M))
            linked = set(re.findall(r"\]\((plots/[^)\s]+)\.png\)", text))
            self.assertEqual(seen["tables"], tables)
            self.assertEqual(seen["figures"], len(linked))
            self.assertEqual(seen["plots"], len(linked))
            self.assertEqual(seen["drawn"], len(linked), "every plot laid out with a width and a height")
            self.assertEqual(seen["missing"], 0)
            OUTPUT.mkdir(parents=True, exist_ok=True)
            screenshot = OUTPUT / "REPORT.png"
            subprocess.run(CHROMIUM + ["--window-size=1280,3000", f"--screenshot={screenshot}", copy.with_suffix(
                ".html").as_uri()], capture_output=True, text=True, timeout=600, check=True)
            self.assertGreater(screenshot.stat().st_size, 20000)
            print(f"report.html: chromium drew {seen['tables']} tables and {seen['drawn']} of {seen['plots']} plots; "
                  f"screenshot {screenshot}")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
