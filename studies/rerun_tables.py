#!/usr/bin/env python3
"""The tables of results/rerun/*/README.md, made from the run folders: each run's solver health
(cost.json's `solver`: unconverged steps, largest final norm, sweeps median / p99, steps rescued by
block solves, legs without an end-of-run line) and, where results/runs holds a published run of the
same name, what moved: U, phi, h, f and A of the re-run against the published run's, each
difference in units of the two errors combined (U, phi, h, f; A has no error).

The table sits in the README between the lines `<!-- rerun_tables: begin -->` and
`<!-- rerun_tables: end -->`; the tool rewrites that block, and --check fails (exit 1, naming the
README) where the committed block differs from what the folders make.

    studies/rerun_tables.py                  # rewrite the block of every results/rerun/*/README.md
    studies/rerun_tables.py --check          # compare only (ctest chute.rerun_tables)

Standard library only.
"""

import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.run import TOP
from cdtools.text import markdown_table
from packing_against_plane_shear import read_rows

RERUN = os.path.join(TOP, "results", "rerun")
PUBLISHED = os.path.join(TOP, "results", "runs")
BEGIN, END = "<!-- rerun_tables: begin -->", "<!-- rerun_tables: end -->"
MOVED = (("U", 2), ("phi", 4), ("h", 2), ("f", 1), ("A", 3))


def estimates(folder):
    """{name: (value, error or None)} of a run folder's results.csv."""
    result = {}
    for r in read_rows(os.path.join(folder, "results.csv")):
        if r["value"]:
            result[r["name"]] = (float(r["value"]), float(r["error"]) if r["error"] else None)
    return result


def _thousands(n):
    return f"{n:,}".replace(",", " ")


def health_cells(cost):
    """[duration, unconverged, largest final norm, sweeps median / p99, rescued] of a cost.json."""
    solver = cost["solver"]
    unconverged = f"{solver['unconverged']} of {_thousands(solver['steps'])}"
    if solver["unconverged"]:
        unconverged += f" ({solver['unconverged_fraction']:.1e})"
    if solver["legs_unrecorded"]:
        unconverged += f"; {solver['legs_unrecorded']} leg without an end-of-run line"
    return [f"{cost['physical_seconds']:g} s", unconverged, f"{solver['largest_final_norm']:g}",
            f"{solver['sweeps_median']:g} / {solver['sweeps_p99']:g}", _thousands(solver["rescued"])]


def moved_cell(new, old, name, decimals):
    """'new (old; difference/combined error)' of one quantity."""
    value, error = new[name]
    before, before_error = old[name]
    cell = f"{value:.{decimals}f} ({before:.{decimals}f}"
    if error and before_error:
        cell += f"; {(value - before) / math.hypot(error, before_error):+.1f} σ"
    return (cell + ")").replace("-", "−")


def table(folder):
    """The markdown table of a re-run folder's finished runs (folders with cost.json and results.csv)."""
    names = sorted(n for n in os.listdir(folder)
                   if os.path.exists(os.path.join(folder, n, "cost.json"))
                   and os.path.exists(os.path.join(folder, n, "results.csv")))
    published = [n for n in names if os.path.isdir(os.path.join(PUBLISHED, n))]
    headings = ["run", "flow with health recorded", "unconverged steps", "largest final norm", "sweeps median / p99",
                "rescued steps"]
    if published:
        headings += [f"{name} (published; difference)" for name, _ in MOVED]
    rows = []
    for name in names:
        with open(os.path.join(folder, name, "cost.json")) as src:
            row = [name] + health_cells(json.load(src))
        if published:
            new = estimates(os.path.join(folder, name))
            old = estimates(os.path.join(PUBLISHED, name)) if name in published else None
            row += [moved_cell(new, old, q, d) if old else "no published run" for q, d in MOVED]
        rows.append(row)
    return markdown_table(headings, rows)


def rewritten(text, block, readme):
    """text with its block between BEGIN and END replaced."""
    if BEGIN not in text or END not in text:
        raise ValueError(f"{readme}: no '{BEGIN}' ... '{END}' block")
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    return head + BEGIN + "\n" + block + END + tail


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="compare the committed tables, write nothing")
    args = parser.parse_args(argv)
    stale = []
    for name in sorted(os.listdir(RERUN)):
        readme = os.path.join(RERUN, name, "README.md")
        if not os.path.exists(readme):
            continue
        with open(readme) as src:
            text = src.read()
        new = rewritten(text, table(os.path.join(RERUN, name)), readme)
        if new != text:
            stale.append(os.path.relpath(readme, TOP))
            if not args.check:
                with open(readme, "w") as out:
                    out.write(new)
    if args.check and stale:
        print(f"rerun_tables: stale tables in {', '.join(stale)}: run studies/rerun_tables.py", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
