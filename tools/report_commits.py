#!/usr/bin/env python3
"""report_commits.py REPORT.md [--check [--code COMMIT]]: which commit made each generated block of a report (issue 35 item 4).

A block is the text between marker lines (each on its own line, as beamid report writes them). A study's block
opens with "... commit <hash>; ..." (study/tables/report_block.cc): the commit of the program that
wrote its tables. This lists the blocks by that commit, one line per commit, the commit with the most blocks first,
and the blocks that name none. With --check it exits 1 after one line
naming the blocks when they come from more than one commit, a dirty tree, or name no commit: the one-commit rule
("a number in REPORT.md comes from the tables of the commit that states it") that `make report-check` applies.
With --code COMMIT (the program's own commit, `beamid --version`) it also fails when that one commit is not the
code's: results older than the code that writes them. The commit is the last one that changed what the programs
compute (cmake/version.cmake), so committing regenerated results and prose does not make them older.
Only the standard library.
"""
import re
import sys

BLOCK = re.compile(r"^<!-- BEGIN GENERATED (\S+) -->$(.*?)^<!-- END GENERATED \1 -->$", re.S | re.M)
COMMIT = re.compile(r"\bcommit ([0-9a-f]{7,40}(?:-dirty)?)\b")


def census(text):
    """{commit or None: [block names]} in report order."""
    by_commit = {}
    for name, body in BLOCK.findall(text):
        match = COMMIT.search(body)
        by_commit.setdefault(match.group(1) if match else None, []).append(name)
    return by_commit


def same_commit(a, b):
    """Whether two abbreviations name one commit (either may be the longer)."""
    n = min(len(a), len(b))
    return n >= 7 and a[:n] == b[:n]


def problems(by_commit, code=None):
    """The one line --check prints, or None when every block names one clean commit (the code's, when given)."""
    named = [c for c in by_commit if c is not None]
    bad = []
    if code is not None and len(named) == 1 and not same_commit(named[0].replace("-dirty", ""), code):
        bad.append("blocks from commit %s, older than the code's %s: rerun make study" % (named[0], code))
    if len(named) > 1:
        bad.append("blocks from %d commits (%s)" % (len(named), ", ".join(
            "%s: %s" % (c, " ".join(by_commit[c])) for c in named)))
    dirty = [c for c in named if c.endswith("-dirty")]
    if dirty:
        bad.append("from a dirty tree: " + " ".join(" ".join(by_commit[c]) for c in dirty))
    if None in by_commit:
        bad.append("naming no commit: " + " ".join(by_commit[None]))
    return "; ".join(bad) if bad else None


def main(argv):
    usage = "usage: report_commits.py REPORT.md [--check [--code COMMIT]]"
    code = None
    if len(argv) == 5 and argv[2] == "--check" and argv[3] == "--code":
        code = argv[4]
        if not re.fullmatch(r"[0-9a-f]{7,40}", code):
            sys.exit("report_commits.py: --code %r: must be a commit (7 to 40 hexadecimal digits)" % code)
        argv = argv[:3]
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] != "--check"):
        sys.exit(usage)
    path = argv[1]
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        sys.exit("report_commits.py: %s: cannot read: %s" % (path, e.strerror))
    by_commit = census(text)
    if len(argv) == 3:
        line = problems(by_commit, code)
        if line:
            print("report_commits.py: %s: not one commit: %s" % (path, line))
            return 1
        print("report_commits.py: %s: every block from commit %s" % (path, next(iter(by_commit))))
        return 0
    for commit, names in sorted(by_commit.items(), key=lambda kv: -len(kv[1])):
        print("%s: %d block(s): %s" % (commit or "no commit", len(names), " ".join(names)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
