#!/usr/bin/env python3
"""Checks of studies/bed_study.py's --var, run by ctest (no simulation): NAME=VALUE pairs are read
into the variables the study adds to every flow leg, and a malformed pair, or one naming a
variable the study sets itself, stops with one line naming it. Standard library only."""

import contextlib
import io
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies"))

import bed_study  # noqa: E402

FAILURES = []


def check(condition, what):
    if not condition:
        FAILURES.append(what)


def refusal(argv):
    """The error line options(argv) stops with, or None if it accepts them."""
    stderr = io.StringIO()
    try:
        with contextlib.redirect_stderr(stderr):
            bed_study.options(argv)
    except SystemExit:
        return stderr.getvalue().strip().splitlines()[-1]
    return None


def main():
    base = ["--out", "runs/bed", "--only", "flow/*"]
    args = bed_study.options(base + ["--var", "skin=2", "--var", "travel=0.3"])
    check(args.extra == {"skin": "2", "travel": "0.3"}, f"--var pairs read as {args.extra}")
    check(bed_study.options(base).extra == {}, "no --var: no extra variables")
    for pair, words in (("skin", "must be NAME=VALUE"), ("=2", "must be NAME=VALUE"), ("skin=", "must be NAME=VALUE"),
                        ("start=x.restart", "start is the study's own"), ("duration=3", "duration is the study's own")):
        line = refusal(base + ["--var", pair])
        check(line is not None and f"--var {pair}: {words}" in line, f"--var {pair}: refused with {line!r}")
    if FAILURES:
        print("\n".join("FAIL: " + failure for failure in FAILURES))
        sys.exit(1)
    print("bed_study --var: pairs read, bad pairs refused in one line")


if __name__ == "__main__":
    main()
