#!/usr/bin/env python3
"""doc/architecture.md against the tree: every path it writes in backquotes exists (a file, a
folder, or a brace pattern such as src/fix_contact_dynamics*.{h,cpp} that matches a file), and
the page stays a map (at most 150 lines). Reads the page and the tree, runs nothing.

    tests/docs/test_architecture.py
"""

import glob
import os
import re
import sys

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir)
PAGE = os.path.join(TOP, "doc", "architecture.md")
MAX_LINES = 150
# A backquoted path: starts at one of the repository's top folders or files.
TOP_LEVEL = ("src/", "inputs/", "reference/", "postproc/", "scripts/", "studies/", "bench/", "tests/", "results/",
             "doc/")


def expanded(pattern):
    """The glob patterns of a path with one {a,b} group."""
    match = re.search(r"\{([^}]*)\}", pattern)
    if not match:
        return [pattern]
    return [pattern[:match.start()] + part + pattern[match.end():] for part in match.group(1).split(",")]


def missing_paths(text):
    missing = []
    for path in sorted(set(re.findall(r"`([^`\s]+)`", text))):
        if not path.startswith(TOP_LEVEL):
            continue
        if not any(glob.glob(os.path.join(TOP, p)) for p in expanded(path)):
            missing.append(path)
    return missing


def main():
    with open(PAGE) as src:
        text = src.read()
    problems = [f"doc/architecture.md names {path}, which is not in the tree" for path in missing_paths(text)]
    lines = text.count("\n")
    if lines > MAX_LINES:
        problems.append(f"doc/architecture.md has {lines} lines, more than {MAX_LINES}")
    if missing_paths("`src/no_such_file.cpp` `src/cd/`") != ["src/no_such_file.cpp"]:
        problems.append("the path check does not find a missing file")
    for problem in problems:
        print(problem)
    if problems:
        sys.exit(1)
    quoted = len(re.findall(r"`[^`]+`", text))
    print(f"doc/architecture.md: {quoted} quoted names, every path in the tree, {lines} lines")


if __name__ == "__main__":
    main()
