#!/usr/bin/env python3
"""Error against work on the corpus of hard steps: the figure and table of bench/solver_corpus.

Each folder is one solver_corpus --out (one set of saved steps, e.g. mu 2 at e 0.5). For each
set, two panels: the natural-map residual and the rms velocity error against a reference solve
(sqrt(g d)), both against the work (local solves per contact), one line per problem, one colour
per setting. The table gives per set and setting: problems converged to the tolerance, sweeps
(median, largest), the final natural map and rms error (medians). Writes <out>.png and <out>.md.

    bench/corpus_figure.py --out doc/stalls/corpus runs/study/mu2_e0.5 runs/study/mu5_e0.5 ...

Standard library and gnuplot.
"""

import argparse
import csv
import os
import statistics
import subprocess

COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf")


def options(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sets", nargs="+", help="solver_corpus output folders, one per set of problems")
    parser.add_argument("--out", required=True, help="output path without extension")
    args = parser.parse_args(argv)
    for folder in args.sets:
        for name in ("history.csv", "solves.csv"):
            if not os.path.isfile(os.path.join(folder, name)):
                parser.error(f"no {name} in {folder} (not a solver_corpus --out folder)")
    return args


def read_rows(path):
    with open(path) as src:
        return list(csv.DictReader(src))


def settings_in(rows):
    """The settings in the order they first appear."""
    seen = []
    for row in rows:
        if row["setting"] not in seen:
            seen.append(row["setting"])
    return seen


def table_rows(folder):
    """[set, setting, converged/problems, sweeps median, sweeps max, natural map, rms error]."""
    solves = read_rows(os.path.join(folder, "solves.csv"))
    rows = []
    for setting in settings_in(solves):
        mine = [r for r in solves if r["setting"] == setting]
        sweeps = [int(r["sweeps"]) for r in mine]
        rows.append([os.path.basename(os.path.normpath(folder)), setting,
                     f"{sum(int(r['converged']) for r in mine)}/{len(mine)}", f"{statistics.median(sweeps):g}",
                     str(max(sweeps)), f"{statistics.median(float(r['natural_map']) for r in mine):.3g}",
                     f"{statistics.median(float(r['rms_error']) for r in mine):.3g}"])
    return rows


def write_table(path, folders):
    header = ["set", "setting", "converged", "sweeps (median)", "sweeps (max)", "natural map (median)",
              "rms error (median, sqrt(g d))"]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for folder in folders:
        lines += ["| " + " | ".join(row) + " |" for row in table_rows(folder)]
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


def panel_data(folder, column, work_dir):
    """One data file per (setting, problem) of the history, for gnuplot; [(setting, file)]."""
    history = read_rows(os.path.join(folder, "history.csv"))
    files = []
    tag = os.path.basename(os.path.normpath(folder))
    for setting in settings_in(history):
        for problem in sorted({r["problem"] for r in history if r["setting"] == setting}):
            path = os.path.join(work_dir, f"{tag}.{setting}.{problem}.{column}.dat")
            with open(path, "w") as out:
                for r in history:
                    if r["setting"] == setting and r["problem"] == problem and float(r[column]) > 0:
                        out.write(f"{r['local_solves_per_contact']} {r[column]}\n")
            files.append((setting, path))
    return files


def plot_command(folders, out_png, work_dir):
    settings = []
    for folder in folders:
        for s in settings_in(read_rows(os.path.join(folder, "solves.csv"))):
            if s not in settings:
                settings.append(s)
    colour = {s: COLOURS[k % len(COLOURS)] for k, s in enumerate(settings)}
    lines = [f"set terminal pngcairo size {420 * len(folders)},760 font ',10'", f"set output '{out_png}'",
             "set termoption noenhanced", f"set multiplot layout 2,{len(folders)}", "set logscale xy",
             "set format y '%.0e'",
             "set xlabel 'work (local solves per contact)'", "set key bottom left font ',8'"]
    for column, label in (("natural_map", "natural-map residual"), ("rms_error", "rms error (sqrt(g d))")):
        for folder in folders:
            lines += [f"set title '{os.path.basename(os.path.normpath(folder))}'", f"set ylabel '{label}'"]
            plots, keyed = [], set()
            for setting, path in panel_data(folder, column, work_dir):
                title = f"title '{setting}'" if setting not in keyed else "notitle"
                keyed.add(setting)
                plots.append(f"'{path}' using 1:2 with lines lc rgb '{colour[setting]}' {title}")
            lines.append("plot " + ", ".join(plots))
    lines.append("unset multiplot")
    return "\n".join(lines) + "\n"


def main(argv=None):
    args = options(argv)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    work_dir = args.out + ".data"
    os.makedirs(work_dir, exist_ok=True)
    subprocess.run(["gnuplot"], input=plot_command(args.sets, args.out + ".png", work_dir), text=True, check=True)
    for name in os.listdir(work_dir):
        os.remove(os.path.join(work_dir, name))
    os.rmdir(work_dir)
    write_table(args.out + ".md", args.sets)
    print(f"wrote {args.out}.png and {args.out}.md")


if __name__ == "__main__":
    main()
