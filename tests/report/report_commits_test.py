#!/usr/bin/env python3
"""tools/report_commits.py: the census of generated blocks by commit, and --check's one-commit rule."""
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "report_commits.py")


def block(name, body):
    return "<!-- BEGIN GENERATED %s -->\n%s\n<!-- END GENERATED %s -->\n" % (name, body, name)


def run(text, *flags):
    with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
        f.write(text)
    try:
        return subprocess.run([sys.executable, TOOL, f.name, *flags], capture_output=True, text=True)
    finally:
        os.unlink(f.name)


class ReportCommits(unittest.TestCase):
    def test_one_commit_passes(self):
        text = "# r\n" + block("a/report", "*Study `a`, seed 1, commit 0123abcd4567; truth*") + \
            block("b/report", "*Study `b`, commit 0123abcd4567;*")
        r = run(text, "--check")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("every block from commit 0123abcd4567", r.stdout)

    def test_several_commits_fail_naming_the_blocks(self):
        text = block("a/report", "commit 0123abcd4567;") + block("b/report", "commit 89ef0123abcd;")
        r = run(text, "--check")
        self.assertEqual(r.returncode, 1)
        self.assertEqual(len(r.stdout.splitlines()), 1)  # one line
        self.assertIn("0123abcd4567: a/report", r.stdout)
        self.assertIn("89ef0123abcd: b/report", r.stdout)

    def test_dirty_and_unnamed_blocks_fail(self):
        r = run(block("a/report", "commit 0123abcd4567-dirty;"), "--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("dirty tree: a/report", r.stdout)
        r = run(block("a/report", "commit 0123abcd4567;") + block("v/frequencies", "no provenance here"), "--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("naming no commit: v/frequencies", r.stdout)

    def test_results_older_than_the_code_fail(self):
        text = block("a/report", "commit 0123abcd4567;") + block("b/report", "commit 0123abcd4567;")
        r = run(text, "--check", "--code", "0123abcd4567")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        r = run(text, "--check", "--code", "0123abcd")  # an abbreviation of the same commit
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        r = run(text, "--check", "--code", "89ef0123abcd")
        self.assertEqual(r.returncode, 1)
        self.assertEqual(len(r.stdout.splitlines()), 1)
        self.assertIn("older than the code's 89ef0123abcd", r.stdout)
        r = run(text, "--check", "--code", "unknown")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("--code 'unknown': must be a commit", r.stderr)

    def test_census_lists_every_commit(self):
        text = block("a/report", "commit 0123abcd4567;") + block("b/report", "commit 0123abcd4567;") + \
            block("c/report", "commit 89ef0123abcd;")
        r = run(text)
        self.assertEqual(r.returncode, 0)
        self.assertEqual(r.stdout.splitlines(), ["0123abcd4567: 2 block(s): a/report b/report",
                                                 "89ef0123abcd: 1 block(s): c/report"])

    def test_a_missing_report_is_one_line(self):
        r = subprocess.run([sys.executable, TOOL, "/nonexistent/REPORT.md"], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("/nonexistent/REPORT.md: cannot read", r.stderr)


if __name__ == "__main__":
    unittest.main()
