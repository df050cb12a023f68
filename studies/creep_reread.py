#!/usr/bin/env python3
"""The published series' creep read again: every run of results/runs/ measured with cdpost's creep
measure (doc/postproc.md, The creep measure) from its committed profile.csv, its results.csv and
results.json updated (`cdpost creep RUN --update`), the series' runs.csv and report.md made again
(`cdpost series`), and results/series/creep_reread.md written:
per run the creep length before (the results.csv of git revision --old-rev) and after, with the
fit range, the floor and the local decay lengths; per friction and reading the medians.

usage: python3 studies/creep_reread.py CDPOST [--old-rev REV] [--creep-floor U]
"""
import argparse
import csv
import io
import os
import re
import statistics
import subprocess
import shutil
import sys
import tempfile

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUNS = os.path.join("results", "runs")
OUT = os.path.join("results", "series", "creep_reread.md")
NAME = re.compile(r"mu([0-9.]+)_theta([0-9.]+)_L([0-9]+)(_seed[0-9]+)?(_layer)?$")
BANDS = ("0_3", "3_6", "6_9", "9_12")
SERIES = ("flow_rules", "layer_flow_rules", "L_series")
SERIES_CREEP_FILES = ("runs.csv", "report.md")  # what the creep changes of a series' outputs


def rows_of(text):
    """{name: (value, error or None)} of a results.csv's text; rows not recorded (no value) left out."""
    rows = {}
    for row in csv.DictReader(io.StringIO(text)):
        if row["value"]:
            rows[row["name"]] = (float(row["value"]), float(row["error"]) if row["error"] else None)
    return rows


def estimate(rows, name, digits=2):
    if name not in rows:
        return ""
    value, error = rows[name]
    return f"{value:.{digits}f}" + (f" ± {error:.{digits}f}" if error is not None else "")


def reread(cdpost, run, floor):
    """Runs cdpost creep --update on one published run; returns its creep warnings."""
    cmd = [cdpost, "creep", os.path.join(RUNS, run), "--update"] + (["--creep-floor", floor] if floor else [])
    result = subprocess.run(cmd, capture_output=True, text=True, cwd=TOP)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed: {result.stderr.strip()}")
    return [line.split(": creep ", 1)[1] for line in result.stderr.splitlines() if ": creep " in line]


def record(cdpost, run, old_rev, floor):
    mu, theta, length, seed, layer = NAME.match(run).groups()
    old = rows_of(subprocess.run(["git", "show", f"{old_rev}:{RUNS}/{run}/results.csv"], capture_output=True,
                                 text=True, check=True, cwd=TOP).stdout)
    warnings = reread(cdpost, run, floor)
    with open(os.path.join(TOP, RUNS, run, "results.csv")) as f:
        new = rows_of(f.read())
    return {"run": run, "mu": mu, "theta": theta, "L": int(length), "reading": "layer" if layer else "count",
            "old": old, "new": new, "warnings": warnings}


def verdict(new):
    """Why a run has no creep length, in short (its results.json says it in full)."""
    if "creep_floor" not in new:
        return "unresolved: no floor below the decay"
    return f"unresolved: {new['creep_points'][0]:.0f} bins above 10 × the floor"


def run_row(r):
    new = r["new"]
    lam = estimate(new, "creep_lambda") or verdict(new)
    span = f"{new['creep_z_low'][0]:g} to {new['creep_z_high'][0]:g}" if "creep_z_low" in new else ""
    points = f"{new['creep_points'][0]:.0f}" if "creep_points" in new else ""
    floor = f"{new['creep_floor'][0]:.1e}" if "creep_floor" in new else ""
    bands = [estimate(new, "creep_lambda_band_" + b) for b in BANDS]
    return [r["run"], estimate(r["old"], "creep_lambda"), lam, span, points, floor] + bands


def median(records, key, name="creep_lambda"):
    values = [r[key][name][0] for r in records if name in r[key]]
    if not values:
        return "–", "–"
    return f"{statistics.median(values):.2f}", f"{min(values):.2f}–{max(values):.2f} ({len(values)})"


def summary_rows(records):
    rows = []
    groups = sorted({(float(r["mu"]), r["reading"]) for r in records if r["L"] == 45})
    for mu, reading in groups:
        group = [r for r in records if r["L"] == 45 and float(r["mu"]) == mu and r["reading"] == reading]
        old, new = median(group, "old"), median(group, "new")
        bands = [median(group, "new", "creep_lambda_band_" + b)[0] for b in BANDS[:3]]
        rows.append([f"{mu:g}", reading, str(len(group)), old[0], old[1], new[0], new[1]] + bands)
    return rows


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in rows]) + "\n"


def write_report(records, command, floor):
    floor_text = (f"the floor given as {floor} sqrt(g d)" if floor else
                  "the floor estimated from each profile (the rms of u over the deep bed, below where u stops "
                  "decaying)")
    text = ("# The published series' creep, read again\n\n"
            "Every run of `results/runs/` (both readings: folders ending `_layer`, the layer reading; the others, "
            "the count reading) measured again from its committed `profile.csv` with cdpost's creep measure "
            "(`doc/postproc.md`, *The creep measure*): u = u0 exp(z/λ) fitted from the wall tops down to where u "
            f"first falls below 10 × the floor, {floor_text}, with the local decay length over 3 d bands. The "
            "runs' `results.csv` and `results.json` carry the new `creep_*` rows; the old λ is the whole-bed fit "
            "(every bin with u > 0 over −30 d ≤ z < 0) they held before. The new λ is one line through a local "
            "decay length that changes with depth (the band columns) over a range the floor sets: runs compare "
            "best by their bands. The series tables that carry the creep length (`results/series/*/runs.csv`, "
            "the creep table of each series' `report.md`) were made again by `cdpost series` on the updated runs "
            "(the script does both). "
            "Made by\n\n"
            f"```sh\n{command}\n```\n\n"
            "## Per friction and reading (L = 45 d)\n\n"
            "Median and range (number of runs with a λ) of the creep length, and the medians of the local "
            "decay length over 0–3, 3–6 and 6–9 d below the wall tops, in d.\n\n"
            + table(["mu", "reading", "runs", "old median", "old range", "new median", "new range", "λ 0–3",
                     "λ 3–6", "λ 6–9"],
                    summary_rows(records))
            + "\n## Per run\n\n"
            "z of the fit range: centres of its highest and deepest bins (d); floor in sqrt(g d); the local "
            "decay length over 0–3, 3–6, 6–9 and 9–12 d below the wall tops (d), where the range holds 3 bins "
            "of the band (a fit of 3 bins: its error rests on one degree of freedom). A run without a λ says "
            "why (in full in its results.json).\n\n"
            + table(["run", "old λ (d)", "new λ (d)", "fit range z (d)", "bins", "floor", "λ 0–3", "λ 3–6",
                     "λ 6–9", "λ 9–12"], [run_row(r) for r in records]))
    with open(os.path.join(TOP, OUT), "w") as out:
        out.write(text)


def remake_series(cdpost):
    """cdpost series on each published series' manifest, over the updated runs; copies the files the
    creep changes into results/series/<series>/."""
    for series in SERIES:
        folder = os.path.join("results", "series", series)  # as the report's title names it
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([cdpost, "series", os.path.join(folder, "manifest.csv"), "--out", out],
                           capture_output=True, text=True, check=True, cwd=TOP)
            for name in SERIES_CREEP_FILES:
                shutil.copy(os.path.join(out, name), os.path.join(TOP, folder, name))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cdpost", help="the cdpost executable")
    parser.add_argument("--old-rev", default="HEAD", help="git revision holding the old results (default HEAD)")
    parser.add_argument("--creep-floor", help="cdpost creep's --creep-floor for every run (sqrt(g d))")
    args = parser.parse_args()
    runs = sorted(r for r in os.listdir(os.path.join(TOP, RUNS)) if NAME.match(r))
    records = [record(os.path.abspath(args.cdpost), run, args.old_rev, args.creep_floor) for run in runs]
    command = "python3 studies/creep_reread.py build/postproc/cdpost --old-rev " + args.old_rev + \
        (f" --creep-floor {args.creep_floor}" if args.creep_floor else "")
    write_report(records, command, args.creep_floor)
    remake_series(os.path.abspath(args.cdpost))
    print(f"{len(records)} runs read again: {OUT}")


if __name__ == "__main__":
    main()
