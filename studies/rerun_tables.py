#!/usr/bin/env python3
"""The tables of results/rerun/*/README.md, made from the run folders: each run's solver health
(cost.json's `solver`: unconverged steps, largest final norm, sweeps median / p99, steps rescued by
block solves, legs without an end-of-run line) and, where results/runs holds a published run of the
same name, what moved: U, phi, h, f and A of the re-run against the published run's, each
difference in units of the two errors combined (U, phi, h, f; A has no error). Before a report
publishes the re-runs in the published runs' place, --supersede keeps the published runs as they
were in the set (NAME/superseded/: their small files and their row of the series' runs.csv), and
the table and studies/two_packings.py read them from there.

The table sits in the README between the lines `<!-- rerun_tables: begin -->` and
`<!-- rerun_tables: end -->`; the tool rewrites that block, and --check fails (exit 1, naming the
README) where the committed block differs from what the folders make.

    studies/rerun_tables.py                  # rewrite the block of every results/rerun/*/README.md
    studies/rerun_tables.py --check          # compare only (ctest chute.rerun_tables)
    studies/rerun_tables.py --add SET RUNS/runs/NAME ...   # a finished campaign run's small files into
                                             # results/rerun/SET/NAME first (cost.json, params.json, post/ tables)
    studies/rerun_tables.py --supersede SET  # keep the published runs the set re-runs (once, before the report)

Standard library only.
"""

import argparse
import csv
import filecmp
import glob
import json
import math
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.run import TOP
from cdtools.text import markdown_table
from packing_against_plane_shear import read_rows

RERUN = os.path.join(TOP, "results", "rerun")
PUBLISHED = os.path.join(TOP, "results", "runs")
SERIES = os.path.join(TOP, "results", "series")
SUPERSEDED = "superseded"  # SET/NAME/superseded: the published run NAME as it was before the re-run
SUPERSEDED_FILES = ("cost.json", "params.json", "profile.csv", "results.csv", "results.json")
SERIES_ROW = "series_row.csv"  # its row of the series' runs.csv (cdpost series' I_local, phi_local, ...)
BEGIN, END = "<!-- rerun_tables: begin -->", "<!-- rerun_tables: end -->"
MOVED = (("U", 2), ("phi", 4), ("h", 2), ("f", 1), ("A", 3))
# What a finished campaign run leaves here: its cost and parameters, and cdpost run's tables.
RUN_FILES = ("cost.json", "params.json")
POST_FILES = ("layers.csv", "profile.csv", "results.csv", "results.json", "spectrum.csv")


def add_run(run_folder, destination):
    """Copy a finished campaign run's small files (RUN_FILES, post/POST_FILES) into destination/NAME;
    refuses a run without them (unfinished or not analysed)."""
    sources = ([os.path.join(run_folder, f) for f in RUN_FILES]
               + [os.path.join(run_folder, "post", f) for f in POST_FILES])
    missing = [s for s in sources if not os.path.exists(s)]
    if missing:
        raise FileNotFoundError(f"{run_folder}: not a finished, analysed run (no {', '.join(missing)})")
    target = os.path.join(destination, os.path.basename(os.path.normpath(run_folder)))
    os.makedirs(target, exist_ok=True)
    for source in sources:
        shutil.copy2(source, target)
    return target


def supersede(set_folder):
    """Copy each published run that a finished re-run of set_folder replaces into NAME/superseded,
    with its row of the series' runs.csv if a series has it; a run already kept is left. [names
    kept now]."""
    kept = []
    for name in sorted(os.listdir(set_folder)):
        target = os.path.join(set_folder, name, SUPERSEDED)
        source = os.path.join(PUBLISHED, name)
        if (not os.path.exists(os.path.join(set_folder, name, "results.csv")) or os.path.exists(target)
                or not os.path.isdir(source)):
            continue
        os.makedirs(target)
        for f in SUPERSEDED_FILES:
            shutil.copy2(os.path.join(source, f), target)
        row = series_row(name)
        if row:  # a replica belongs to no series
            with open(os.path.join(target, SERIES_ROW), "w", newline="") as out:
                writer = csv.DictWriter(out, fieldnames=list(row), lineterminator="\n")
                writer.writeheader()
                writer.writerow(row)
        kept.append(name)
    return kept


def series_row(name):
    """The row of run name in a series' runs.csv, or None."""
    for path in sorted(glob.glob(os.path.join(SERIES, "*", "runs.csv"))):
        for row in read_rows(path):
            if os.path.basename(row["run"]) == name:
                return row
    return None


def published_folder(set_folder, name):
    """Where the published run a re-run replaces is read: kept in the set, else results/runs unless
    that is the run itself (a report published it: the same results.csv); None."""
    kept = os.path.join(set_folder, name, SUPERSEDED)
    if os.path.isdir(kept):
        return kept
    published = os.path.join(PUBLISHED, name)
    if os.path.isdir(published) and not filecmp.cmp(os.path.join(published, "results.csv"),
                                                    os.path.join(set_folder, name, "results.csv"), shallow=False):
        return published
    return None


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
    published = {n: f for n, f in ((n, published_folder(folder, n)) for n in names) if f}
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
            old = estimates(published[name]) if name in published else None
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
    parser.add_argument("--add", nargs="+", metavar=("SET", "RUN"),
                        help="copy finished campaign runs into results/rerun/SET first")
    parser.add_argument("--supersede", metavar="SET",
                        help="keep the published runs that results/rerun/SET re-runs in SET/NAME/superseded first")
    args = parser.parse_args(argv)
    if args.supersede:
        if not os.path.isdir(os.path.join(RERUN, args.supersede)):
            parser.error(f"--supersede {args.supersede}: not a folder of {os.path.relpath(RERUN, TOP)}")
        try:
            kept = supersede(os.path.join(RERUN, args.supersede))
        except OSError as error:
            parser.error(f"--supersede {args.supersede}: {error}")
        for name in kept:
            print(f"kept {name}'s published run in results/rerun/{args.supersede}/{name}/{SUPERSEDED}")
    if args.add:
        if len(args.add) < 2 or not os.path.isdir(os.path.join(RERUN, args.add[0])):
            parser.error(f"--add SET RUN...: SET must name a folder of {os.path.relpath(RERUN, TOP)} "
                         "with its README.md")
        try:
            for run in args.add[1:]:
                add_run(run, os.path.join(RERUN, args.add[0]))
        except FileNotFoundError as error:
            parser.error(str(error))
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
