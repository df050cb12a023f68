#!/usr/bin/env python3
"""The bed against the solver's tolerance: tables and figure from studies/bed_study.py's runs.

    floor      u_floor(z; tolerance): the packing at rest (mu 0.5, 12 deg). Over the 0.1 s
               windows from --floor-from on (a continuation: from its second window), every
               replica's band mean of u is an error (the packing should not move): the floor is
               their rms, with the mean and its standard error beside it.
    flows      u(z) of each friction's continuations per tolerance: each replica's time mean over
               the windows from --flow-from on (s after the change of settings), then the mean
               and standard error over the replicas; the verdict per depth band (verdict()).
    relaxation the bed's band means per 0.1 s window after the change of settings (replica
               means), to choose --flow-from by measurement.
    layer      U, phi, h of the flowing layer (flow.time) over the same windows, and the cost.

Velocities in sqrt(g d), z = y - y_top in d. Writes <out>/floor.csv, flows.csv, bed.md and
bed_profiles.png (gnuplot).

    studies/bed_profiles.py --study runs/bed --out doc/bed

Standard library and gnuplot.
"""

import argparse
import csv
import glob
import json
import math
import os
import re
import statistics
import subprocess
import sys

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.lammps_files import read_chunk_file, read_time_file
from cdtools.logs import read_progress
from cdtools.stats import mean_sd_se

D, G, Y_TOP = 5.0e-4, 9.81, 30 * 5.0e-4
SCALE = math.sqrt(G * D)
RESOLVED_OVER_FLOOR = 10.0


def options(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--study", required=True, help="studies/bed_study.py's --out folder")
    parser.add_argument("--out", required=True, help="folder of the tables and the figure")
    parser.add_argument("--floor-from", type=float, default=0.3, help="floor: windows from this chute time (s)")
    parser.add_argument("--flow-from", type=float, default=0.4,
                        help="flows: windows from this long after the change of settings (s)")
    parser.add_argument("--band", type=float, default=3.0, help="depth band width (d)")
    parser.add_argument("--flows", default="flow",
                        help="the study's folder of flows, one subfolder of tol<T>_<order> jobs each: flow (the "
                             "frictions) or length (the cell lengths)")
    args = parser.parse_args(argv)
    if args.band <= 0 or args.floor_from < 0 or args.flow_from < 0:
        parser.error("--band must be > 0, --floor-from and --flow-from >= 0")
    return args


# ------------------------------------------------------------------ reading

def windows(folder):
    """[(end time s, {bin centre z: (grains, mean u)})], one per 0.1 s window of a run's
    profile.chunk."""
    times = {int(r["TimeStep"]): r["v_time"] for r in read_time_file(os.path.join(folder, "flow.time"))}
    result = []
    for step, rows in read_chunk_file(os.path.join(folder, "profile.chunk")):
        bins = {}
        for r in rows:
            if r["Ncount"] > 0:
                bins[round((r["Coord1"] - Y_TOP) / D, 3)] = (r["Ncount"], r["vx"] / SCALE)
        result.append((times.get(step, step * 1e-4), bins))
    return result


def band_means(bins, width):
    """{band index: count-weighted mean u} from {z: (count, u)}."""
    sums = {}
    for z, (count, u) in bins.items():
        entry = sums.setdefault(math.floor(z / width), [0.0, 0.0])
        entry[0] += count
        entry[1] += count * u
    return {b: s / n for b, (n, s) in sums.items() if n > 0}


def time_mean(window_list, width):
    """Over windows: {band: mean of the band means}."""
    bands = {}
    for _, window_bins in window_list:
        for b, u in band_means(window_bins, width).items():
            bands.setdefault(b, []).append(u)
    return {b: statistics.mean(v) for b, v in bands.items()}


def mean_se(values):
    """Mean and standard error over the values that are numbers (cdpost leaves NaN where a
    run has no value)."""
    mean, _, se = mean_sd_se(v for v in values if not math.isnan(v))
    return mean, se


def cost(folder):
    """CPU seconds per chute second of a finished job: LAMMPS's loop times and CPU use of its
    legs, from each leg's log.lammps or, in results/bed, the timer lines kept in timers.txt."""
    legs = sorted(glob.glob(os.path.join(folder, "legs", "*")))
    logs = [os.path.join(leg, "log.lammps") for leg in legs]
    seconds = sum(read_progress(log if os.path.exists(log) else os.path.join(os.path.dirname(log), "timers.txt")).cpu
                  for log in logs)
    rows = read_time_file(os.path.join(folder, "flow.time"))
    span = rows[-1]["v_time"] - rows[0]["v_time"] + (rows[1]["v_time"] - rows[0]["v_time"])
    return seconds / span


def tolerance_of(name):
    return re.match(r"tol([0-9.e+-]+)_", os.path.basename(name)).group(1)


def replicas(pattern):
    """{tolerance: [job folders]} of the finished jobs matching the glob."""
    found = {}
    for folder in sorted(glob.glob(pattern)):
        if os.path.exists(os.path.join(folder, "DONE")):
            found.setdefault(tolerance_of(folder), []).append(folder)
    return dict(sorted(found.items(), key=lambda item: -float(item[0])))


# ------------------------------------------------------------------ floor

def floor_table(args):
    """{tolerance: {band: (rms, mean, se, values)}} and the per-window rms (relaxation)."""
    table, relaxation = {}, {}
    for tolerance, folders in replicas(os.path.join(args.study, "floor", "tol*")).items():
        values, per_window = {}, {}
        for folder in folders:
            run_windows = windows(folder)
            first = max(args.floor_from, run_windows[0][0] + 0.1)    # a continuation: its first window is a change
            for end, bins in run_windows:
                for b, u in band_means(bins, args.band).items():
                    per_window.setdefault((round(end, 3), b), []).append(u)
                    if end > first + 1e-9:
                        values.setdefault(b, []).append(u)
        table[tolerance] = {b: (math.sqrt(statistics.mean(x * x for x in v)), *mean_se(v), len(v))
                            for b, v in sorted(values.items())}
        relaxation[tolerance] = per_window
    return table, relaxation


# ------------------------------------------------------------------ flows

def flow_tables(args):
    """{flow name: {tolerance: dict(replicas, bands={band: (mean, se)}, layer, cost, relaxation)}}."""
    flows = {}
    for flow_dir in sorted(glob.glob(os.path.join(args.study, args.flows, "*"))):
        per_tolerance = {}
        for tolerance, folders in replicas(os.path.join(flow_dir, "tol*")).items():
            replica_bands, layer, costs, relax = [], [], [], {}
            for folder in folders:
                all_windows = windows(folder)
                start = all_windows[0][0] - 0.1
                used = [w for w in all_windows if w[0] > start + args.flow_from + 0.1 - 1e-9]
                replica_bands.append(time_mean(used, args.band))
                for end, window_bins in all_windows:
                    for b, u in band_means(window_bins, args.band).items():
                        relax.setdefault((round(end - start, 3), b), []).append(u)
                layer.append(layer_quantities(folder, used))
                costs.append(cost(folder))
            per_tolerance[tolerance] = dict(
                replicas=len(folders),
                bands={b: mean_se(r[b] for r in replica_bands if b in r) for b in replica_bands[0]},
                layer={k: mean_se(x[k] for x in layer) for k in layer[0]},
                cost=statistics.median(costs),
                relaxation={k: statistics.mean(v) for k, v in relax.items()})
        if per_tolerance:
            flows[os.path.basename(flow_dir)] = per_tolerance
    return flows


POSTED = ("f", "A", "bagnold_slip", "bagnold_amplitude", "creep_lambda")


def layer_quantities(folder, used):
    """U, phi, h over the used windows (flow.time), the bed's mean u (count-weighted over
    -30 <= z < 0), and cdpost's f, A, Bagnold fit and creep length over the same windows
    (post/results.json of studies/bed_study.py --collect; NaN where missing)."""
    rows = [r for r in read_time_file(os.path.join(folder, "flow.time")) if r["v_time"] > used[0][0] - 0.1 + 1e-9]
    count = sum(n for _, bins in used for z, (n, _) in bins.items() if -30 <= z < 0)
    bed = sum(n * u for _, bins in used for z, (n, u) in bins.items() if -30 <= z < 0) / count
    quantities = dict(U=statistics.mean(r["v_u_flow"] for r in rows) / SCALE,
                      phi=statistics.mean(r["v_phi_flow"] for r in rows),
                      h=statistics.mean(r["v_h"] for r in rows) / D, u_bed=bed)
    try:
        with open(os.path.join(folder, "post", "results.json")) as src:
            posted = {r["name"]: r["value"] for r in json.load(src)["results"]}
    except (OSError, ValueError, KeyError):
        posted = {}
    quantities.update({name: posted.get(name) if posted.get(name) is not None else math.nan for name in POSTED})
    return quantities


def verdict(z_low, u, se, floor, tighter):
    """Below the wall tops: 'floor' (within 10x the tolerance's floor), 'noise' (within two
    standard errors of zero: the replicas do not resolve it), 'moves' (differs from the next
    tighter tolerance by more than two combined standard errors) or 'resolved'; 'layer' above."""
    if z_low >= 0:
        return "layer"
    if floor is None or abs(u) < RESOLVED_OVER_FLOOR * floor:
        return "floor"
    if not abs(u) > 2 * se:
        return "noise"
    if tighter is not None:
        u2, se2 = tighter
        if abs(u - u2) > 2 * math.hypot(se, se2):
            return "moves"
    return "resolved"


# ------------------------------------------------------------------ output

def band_label(b, width):
    return f"{b * width:g} … {(b + 1) * width:g}"


def write_outputs(args, floor, floor_relax, flows):
    os.makedirs(args.out, exist_ok=True)
    tolerances = list(floor)
    lines = ["# The bed against the solver's tolerance", "",
             f"Generated by `studies/bed_profiles.py --study STUDY --out {args.out} --floor-from {args.floor_from:g} "
             f"--flow-from {args.flow_from:g} --band {args.band:g} --flows {args.flows}` from the runs of "
             "`studies/bed_study.py`. "
             "u in sqrt(g d), z in d from the wall tops.", "",
             "## The floor: the packing at rest (mu 0.5, 12°)", "",
             f"Band means of u over the 0.1 s windows after {args.floor_from:g} s, all replicas: rms (the floor), "
             "mean ± standard error, and the number of values.", "",
             "| z (d) | " + " | ".join(f"{t}: rms | {t}: mean ± se" for t in tolerances) + " |",
             "|---|" + "---|---|" * len(tolerances)]
    bands = sorted({b for t in tolerances for b in floor[t]})
    with open(os.path.join(args.out, "floor.csv"), "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["tolerance", "z_low_d", "z_high_d", "floor_rms", "mean", "se", "values"])
        for t in tolerances:
            for b, (rms, mean, se, n) in floor[t].items():
                writer.writerow([t, b * args.band, (b + 1) * args.band, f"{rms:.4g}", f"{mean:.4g}", f"{se:.3g}", n])
    for b in bands:
        cells = []
        for t in tolerances:
            rms, mean, se, n = floor[t].get(b, (math.nan,) * 4)
            cells.append(f"{rms:.2e} | {mean:+.1e} ± {se:.1e}")
        lines.append(f"| {band_label(b, args.band)} | " + " | ".join(cells) + " |")
    lines += ["", "Relaxation after the tilt: rms over replicas of the band means, per 0.1 s window "
              "(window end, s).", "", "| tolerance | z (d) | " + " | ".join(
                  f"{e:g}" for e in sorted({k[0] for r in floor_relax.values() for k in r})) + " |"]
    ends = sorted({k[0] for r in floor_relax.values() for k in r})
    lines.append("|---|---|" + "---|" * len(ends))
    for t in tolerances:
        for b in [b for b in bands if b * args.band in (-30, -15, -3, 9, 30)]:
            cells = [floor_relax[t].get((e, b)) for e in ends]
            lines.append(f"| {t} | {band_label(b, args.band)} | " + " | ".join(
                f"{math.sqrt(statistics.mean(x * x for x in c)):.1e}" if c else "" for c in cells) + " |")
    with open(os.path.join(args.out, "flows.csv"), "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["flow", "tolerance", "replicas", "z_low_d", "z_high_d", "u", "se", "floor_rms", "verdict"])
        for name, per_tolerance in flows.items():
            lines += flow_section(args, name, per_tolerance, floor, writer)
    with open(os.path.join(args.out, "bed.md"), "w") as out:
        out.write("\n".join(lines) + "\n")
    plot(args, floor, flows)


def flow_section(args, name, per_tolerance, floor, writer):
    tolerances = list(per_tolerance)
    lines = ["", f"## {name}", "", f"Replica means over the windows from {args.flow_from:g} s after the change of "
             "settings; ± the standard error over replicas; verdict: resolved (≥ 10× the floor, beyond 2 "
             "errors from zero and within 2 combined errors of the next tighter tolerance), floor, noise or moves.", "",
             "| z (d) | " + " | ".join(f"{t} ({per_tolerance[t]['replicas']} replicas) | verdict" for t in tolerances)
             + " |", "|---|" + "---|---|" * len(tolerances)]
    bands = sorted({b for t in tolerances for b in per_tolerance[t]["bands"]})
    for b in bands:
        cells = []
        for i, t in enumerate(tolerances):
            u, se = per_tolerance[t]["bands"].get(b, (math.nan, math.nan))
            floor_rms = floor.get(t, {}).get(b, (None,))[0]
            tighter = per_tolerance[tolerances[i + 1]]["bands"].get(b) if i + 1 < len(tolerances) else None
            v = verdict(b * args.band, u, se, floor_rms, tighter)
            writer.writerow([name, t, per_tolerance[t]["replicas"], b * args.band, (b + 1) * args.band,
                             f"{u:.4g}", f"{se:.3g}", "" if floor_rms is None else f"{floor_rms:.3g}", v])
            cells.append(f"{u:+.2e} ± {se:.1e} | {v}")
        lines.append(f"| {band_label(b, args.band)} | " + " | ".join(cells) + " |")
    names = list(per_tolerance[tolerances[0]]["layer"])
    lines += ["", "Means ± standard errors over the replicas (u_bed: mean u over −30 ≤ z < 0; f, A, the Bagnold "
              "fit and the creep length from cdpost over the same windows).", "",
              "| tolerance | " + " | ".join(names) + " | CPU s per chute s (median) |",
              "|---|" + "---|" * (len(names) + 1)]
    for t in tolerances:
        layer = per_tolerance[t]["layer"]
        lines.append(f"| {t} | " + " | ".join(f"{layer[n][0]:.4g} ± {layer[n][1]:.2g}" for n in names) +
                     f" | {per_tolerance[t]['cost']:.0f} |")
    lines += ["", "Relaxation after the change of settings: replica mean of the band's u per 0.1 s window "
              "(time since the change, s).", ""]
    for t in tolerances:
        relax = per_tolerance[t]["relaxation"]
        ends = sorted({k[0] for k in relax})
        lines += [f"| {t}: z (d) | " + " | ".join(f"{e:g}" for e in ends) + " |", "|---|" + "---|" * len(ends)]
        for b in [b for b in bands if b * args.band in (-18, -12, -9, -6, -3)]:
            lines.append(f"| {band_label(b, args.band)} | " + " | ".join(
                f"{relax[(e, b)]:+.1e}" if (e, b) in relax else "" for e in ends) + " |")
        lines.append("")
    return lines


def plot(args, floor, flows):
    """bed_profiles.png: |u(z)| per friction and tolerance (filled: u > 0, open: u < 0), the
    floor of each tolerance dashed."""
    data = os.path.join(args.out, "bed_profiles.dat")
    blocks, styles, index = [], [], 0
    colours = {"1e-3": "#1f77b4", "1e-4": "#d62728", "1e-5": "#2ca02c", "1e-2": "#7f7f7f"}
    with open(data, "w") as out:
        for panel, (name, per_tolerance) in enumerate(flows.items()):
            for t, entry in per_tolerance.items():
                out.write(f"# {name} {t}\n")
                for b, (u, se) in sorted(entry["bands"].items()):
                    out.write(f"{(b + 0.5) * args.band:g} {abs(u):.6g} {se:.6g} {int(u > 0)}\n")
                out.write("\n\n")
                blocks.append((panel, name, t, index))
                index += 1
        for t, table in floor.items():
            out.write(f"# floor {t}\n")
            for b, (rms, *_rest) in sorted(table.items()):
                out.write(f"{(b + 0.5) * args.band:g} {rms:.6g}\n")
            out.write("\n\n")
            styles.append((t, index))
            index += 1
    names = list(flows)
    script = [f"set terminal pngcairo size {420 * max(1, len(names))},520 font ',10' noenhanced",
              f"set output '{os.path.join(args.out, 'bed_profiles.png')}'",
              f"set multiplot layout 1,{max(1, len(names))}", "set logscale x", "set format x '1e%T'", "set xtics 100",
              "set xrange [1e-8:30]", "set yrange [-30:12]", "set xlabel '|u| / sqrt(g d)'", "set ylabel 'z / d'",
              "set key bottom right"]
    for panel, name in enumerate(names):
        plots = []
        for p, n, t, i in blocks:
            if p == panel:
                colour = colours.get(t, "black")
                plots.append(f"'{data}' index {i} using ($4==1?$2:1/0):1 with linespoints pt 7 lc rgb '{colour}' "
                             f"title 'tol {t}'")
                plots.append(f"'{data}' index {i} using ($4==0?$2:1/0):1 with points pt 6 lc rgb '{colour}' notitle")
        for t, i in styles:
            plots.append(f"'{data}' index {i} using 2:1 with lines dt 2 lw 2 lc rgb '{colours.get(t, 'black')}' "
                         f"title 'floor {t}'")
        script += [f"set title '{name}'", "plot " + ", ".join(plots)]
    script.append("unset multiplot")
    subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True)


def main(argv=None):
    args = options(argv)
    floor, floor_relax = floor_table(args)
    flows = flow_tables(args)
    write_outputs(args, floor, floor_relax, flows)
    print(open(os.path.join(args.out, "bed.md")).read())


if __name__ == "__main__":
    main()
