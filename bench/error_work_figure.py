#!/usr/bin/env python3
"""Error against work, by depth band: the figure that judges a solver (doc/bed.md).

Reads bench/solve_error_by_depth.py's CSV files (one per solver setting, each over a range of
tolerances on the same snapshots) and draws, for a few depth bands, the rms velocity error after
one step (sqrt(g d), median over snapshots) against the work of the solve (local solves per
contact, median over snapshots): one curve per file. Writes <out>.png and <out>.md (the table).

    bench/error_work_figure.py --out doc/bed/error_work runs/solve_error/error_by_depth*.csv

Standard library and gnuplot.
"""

import argparse
import csv
import os
import statistics
import subprocess

DEFAULT_BANDS = (-30, -18, -9, -3, 0, 9, 30)


def options(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("tables", nargs="+", help="CSV files of bench/solve_error_by_depth.py")
    parser.add_argument("--out", required=True, help="output path without extension")
    parser.add_argument("--bands", type=float, nargs="+", default=list(DEFAULT_BANDS),
                        help="lower edges (d) of the depth bands drawn")
    args = parser.parse_args(argv)
    for table in args.tables:
        if not os.path.isfile(table):
            parser.error(f"no file {table}")
    return args


def curves(path, bands):
    """{band lower edge: [(tolerance, work, error)]} of one CSV file, medians over snapshots."""
    grouped = {}
    with open(path) as src:
        for row in csv.DictReader(src):
            low = float(row["z_low"])
            if low in bands:
                grouped.setdefault((low, float(row["tolerance"])), []).append(row)
    result = {}
    for (low, tolerance), rows in sorted(grouped.items(), key=lambda item: (item[0][0], -item[0][1])):
        work = statistics.median(float(r["local_solves"]) for r in rows)
        error = statistics.median(float(r["rms_error"]) for r in rows)
        result.setdefault(low, []).append((tolerance, work, error))
    return result


def label(path):
    name = os.path.splitext(os.path.basename(path))[0]
    return name.replace("error_by_depth", "").strip("_") or "Gauss-Seidel"


def main(argv=None):
    args = options(argv)
    series = [(label(t), curves(t, set(args.bands))) for t in args.tables]
    data = args.out + ".dat"
    lines = ["| solver | z band (d) | tolerance | local solves per contact | rms error (sqrt(g d)) |",
             "|---|---|---|---|---|"]
    blocks = []
    with open(data, "w") as out:
        for name, by_band in series:
            for low, points in sorted(by_band.items()):
                out.write(f"# {name} {low:g}\n")
                for tolerance, work, error in points:
                    out.write(f"{work:.6g} {error:.6g} {tolerance:g}\n")
                    lines.append(f"| {name} | {low:g} | {tolerance:g} | {work:.0f} | {error:.2e} |")
                out.write("\n\n")
                blocks.append((name, low))
    with open(args.out + ".md", "w") as out:
        out.write("\n".join(lines) + "\n")
    panels = sorted({low for _, low in blocks})
    rows, columns = (len(panels) + 3) // 4, min(4, len(panels))
    script = [f"set terminal pngcairo size {columns * 380},{rows * 340} font ',9' noenhanced",
              f"set output '{args.out}.png'",
              f"set multiplot layout {rows},{columns}",
              "set logscale xy", "set format y '1e%T'", "set format x '1e%T'", "set xlabel 'local solves per contact'",
              "set ylabel 'rms velocity error / sqrt(g d)'", "set key top right font ',8'"]
    names = [name for name, _ in series]
    for low in panels:
        plots = [f"'{data}' index {i} using 1:2 with linespoints pt {7 + names.index(n)} title '{n}'"
                 for i, (n, b) in enumerate(blocks) if b == low]
        script += [f"set title 'z in [{low:g}, {low:g} + band) d'", "plot " + ", ".join(plots)]
    script.append("unset multiplot")
    subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
