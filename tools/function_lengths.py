#!/usr/bin/env python3
"""Lists the C++ functions in src/ (and python/src/) longer than a limit, longest first.

    tools/function_lengths.py [--limit 100] [--check]

A function's length is its lines from the first line of its signature to its closing brace, comments and blank lines
included (what a reader scrolls through). Functions are found by scanning braces outside comments, strings and
character literals: a brace block opened at namespace or class level after a parameter list is a function body
(namespaces, classes, enums and initialisers are not). Lambdas and local classes count towards the function that
holds them. With --check the exit status is 1 when any function is over the limit, naming each as path:line name
(lines). With --allowed FILE (lines "path name lines"), the functions listed there may stay over the limit while they
are split, but no longer than listed, and a listed function that is no longer over it must leave the list: so the
list only shrinks (the test tools.function_lengths runs it so)."""
import argparse
import os
import re
import sys

ROOTS = ("src", "python/src")


def strip(text):
    """The text with comments, string and character literals blanked (newlines kept, so line numbers hold)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):  # raw string R"delim( ... )delim"
            k = text.find("(", i)
            delim = text[i + 2:k]
            j = text.find(")" + delim + '"', k)
            j = n if j < 0 else j + len(delim) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and (text[i - 1].isalnum()):  # digit separator 1'000
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + (c if j < n else ""))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


NOT_FUNCTIONS = re.compile(r"^\s*(namespace|class|struct|union|enum)\b|=\s*$|\b(namespace|class|struct|enum)\s+\w*\s*$")


def functions(path):
    """(first line, last line, name) of every function body at namespace or class level."""
    text = strip(open(path, encoding="utf-8").read())
    found = []
    stack = []  # for each open brace: (kind, start offset of its head, head text)
    head_start = 0
    for i, c in enumerate(text):
        if c == "{":
            head = text[head_start:i]
            in_function = any(kind == "function" for kind, _, _ in stack)
            kind = "block"
            if not in_function:
                h = head.strip()
                if ")" in h and not NOT_FUNCTIONS.search(h) and not re.search(r"\b(namespace|class|struct|enum|union)\b[^()]*$", h):
                    kind = "function"
                elif re.search(r"\b(class|struct|union)\b", h) and "(" not in h.split("{")[-1]:
                    kind = "class"
                elif re.search(r"\bnamespace\b", h):
                    kind = "namespace"
            offset = head_start + (len(head) - len(head.lstrip()))
            stack.append((kind, offset, head))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, offset, head = stack.pop()
                if kind == "function" and not any(k == "function" for k, _, _ in stack):
                    first = text.count("\n", 0, offset) + 1
                    last = text.count("\n", 0, i) + 1
                    name = re.findall(r"([~\w:]+(?:operator\s*\S+)?)\s*\(", head)
                    found.append((first, last, name[0] if name else "?"))
            head_start = i + 1
        elif c == ";":
            if not any(kind == "function" for kind, _, _ in stack):
                head_start = i + 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--limit", type=int, default=100)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--allowed", help="functions allowed over the limit for now: lines 'path name lines'")
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    args = parser.parse_args()
    long = []
    for root in ROOTS:
        for folder, _, files in os.walk(os.path.join(args.root, root)):
            for f in sorted(files):
                if f.endswith((".cc", ".h")):
                    path = os.path.join(folder, f)
                    for first, last, name in functions(path):
                        if last - first + 1 > args.limit:
                            long.append((last - first + 1, os.path.relpath(path, args.root), first, name))
    long.sort(key=lambda x: (-x[0], x[1]))
    allowed = {}
    if args.allowed:
        for line in open(args.allowed, encoding="utf-8"):
            if line.strip() and not line.startswith("#"):
                path, name, lines = line.split()
                allowed[(path, name)] = int(lines)
    failures = []
    for lines, path, first, name in long:
        limit = allowed.pop((path, name), None)
        verdict = "" if limit is not None and lines <= limit else "  <- over the limit"
        if verdict:
            failures.append(name)
        print(f"{path}:{first} {name} ({lines} lines){verdict}")
    for (path, name), lines in sorted(allowed.items()):
        print(f"{path} {name}: listed in {args.allowed} but no longer over {args.limit} lines: remove it")
        failures.append(name)
    print(f"{len(long)} function(s) over {args.limit} lines, {len(failures)} not allowed", file=sys.stderr)
    return 1 if args.check and failures else 0


if __name__ == "__main__":
    sys.exit(main())
