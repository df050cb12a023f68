#!/usr/bin/env python3
"""The 45 d scene: do cheaper solver settings keep the physics? Runs continue one stationary
restart per scene point; each run is cut into windows of equal length (replicas of the
stationary flow), cdpost analyses every window, and each setting's group mean and standard
error are compared with the reference's: a quantity agrees when the two means differ by at
most twice their combined standard error.

    studies/accuracy_45d.py compare --runs DIR --reference ref_mu0.5 --candidate new_mu0.5 \\
        --windows 10.2:11.2,11.2:12.2,12.2:13.2 --out results/accuracy
    studies/accuracy_45d.py convergence --runs DIR --series "tol:1e-1=tol1e-1_mu0.5,..." ...

The runs are in.chute flow runs (`-var stage flow -var start RESTART`), one folder each.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.campaign.plan import deck_defaults
from cdtools.cdpost import read_results
from cdtools.lammps_files import read_chunk_file, read_time_file
from cdtools.run import BUILT_CDPOST
from cdtools.stats import difference_in_errors, mean_sd_se

D = 5e-4  # m, mean diameter of the scene
# cdpost result names compared, and the quantities this script adds from the chunk files.
QUANTITIES = ["U", "phi", "h", "f", "A", "A_mean", "creep_lambda", "bagnold_amplitude", "bagnold_slip",
              "bed_u", "phi_bed", "phi_layer"]
UNITS = dict(U="sqrt(g d)", h="d", f="Hz", A="sqrt(g d)", A_mean="sqrt(g d)", creep_lambda="d",
             bagnold_amplitude="sqrt(g d)", bagnold_slip="sqrt(g d)", bed_u="sqrt(g d)")


def step_clock(flow):
    """TimeStep -> time (s), linear between flow.time's samples (the step changes only at them)."""
    steps = [r["TimeStep"] for r in flow]
    times = [r["v_time"] for r in flow]

    def time_of(step):
        k = max(1, min(len(steps) - 1, next((i for i, s in enumerate(steps) if s > step), len(steps) - 1)))
        return times[k - 1] + (step - steps[k - 1]) * (times[k] - times[k - 1]) / (steps[k] - steps[k - 1])
    return time_of


def cdpost(folder, z0, t0, t1, name):
    post = os.path.join(folder, name)
    # The runs continue a flow for a second or two: a fast one may stay refined throughout, so
    # the deck's sample rate sets the spectra's grid.
    cmd = [BUILT_CDPOST, "run", folder, "--z0", f"{z0:g}", "--t-start", f"{t0:g}", "--t-end", f"{t1:g}",
           "--sample-rate", deck_defaults()["sample_rate"], "--out", post]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return {name: entry[0] for name, entry in read_results(os.path.join(post, "results.csv")).items()}


def chunk_means(folder, z0, t0, t1, time_of):
    """Bed velocity (count-weighted u below the wall tops, sqrt(g d)) from profile.chunk, and
    the mean area fraction of the bed (-20 d < z < 0) and of the layer (0 < z < 40 d) from
    packing.chunk, over the blocks ending in (t0, t1]."""
    sqrt_gd = math.sqrt(9.81 * D)

    def inside(step):
        return t0 < time_of(step) <= t1 + 1e-9
    momentum = weight = 0.0
    for step, rows in read_chunk_file(os.path.join(folder, "profile.chunk")):
        if not inside(step):
            continue
        for r in rows:
            if r["Coord1"] < z0:
                momentum += r["Ncount"] * r["vx"]
                weight += r["Ncount"]
    bands = dict(phi_bed=(-20, 0), phi_layer=(0, 40))
    sums = {k: [0.0, 0] for k in bands}
    for step, rows in read_chunk_file(os.path.join(folder, "packing.chunk")):
        if not inside(step):
            continue
        for r in rows:
            z = (r["Coord1"] - z0) / D
            for key, (lo, hi) in bands.items():
                if lo < z < hi:
                    sums[key][0] += r["v_phi_of_grain"]
                    sums[key][1] += 1
    out = dict(bed_u=momentum / weight / sqrt_gd if weight else float("nan"))
    out.update({k: s / n if n else float("nan") for k, (s, n) in sums.items()})
    return out


def window_values(folder, z0, windows):
    flow = read_time_file(os.path.join(folder, "flow.time"))
    time_of = step_clock(flow)
    values = []
    for k, (t0, t1) in enumerate(windows):
        row = cdpost(folder, z0, t0, t1, f"post_w{k + 1}")
        row.update(chunk_means(folder, z0, t0, t1, time_of))
        values.append(row)
    return values


def group(values, name):
    mean, _, error = mean_sd_se(v[name] for v in values if name in v and math.isfinite(v[name]))
    return mean, error    # one window: a value without an error


def user_seconds(text):
    """The user time of /usr/bin/time's output: `-v` ("User time (seconds): X") or the
    "wall user sys" line of `-f "%e %U %S"`; None if the run stopped before it was timed."""
    verbose = re.search(r"User time \(seconds\): ([0-9.]+)", text)
    if verbose:
        return float(verbose.group(1))
    fields = text.split()
    if len(fields) < 3 or not fields[-3].replace(".", "").isdigit():
        return None
    return float(fields[-3])


def cost(folder):
    """CPU s per physical s of the run (user time over the chute time it covered)."""
    user = user_seconds(open(os.path.join(folder, "time.txt")).read())
    if user is None:
        return float("nan")    # a run stopped before it finished: no time of its own
    flow = read_time_file(os.path.join(folder, "flow.time"))
    return user / (flow[-1]["v_time"] - flow[0]["v_time"])


def parse_windows(text):
    try:
        return [tuple(float(x) for x in w.split(":")) for w in text.split(",")]
    except ValueError:
        raise SystemExit(f"accuracy_45d.py: --windows {text}: expected T0:T1,T0:T1,...")


def group_values(args, names, windows):
    """The windows of every run of a group (replica runs, e.g. another contact order each)."""
    values = []
    for name in names.split(","):
        values += window_values(os.path.join(args.runs, name), args.z0, windows)
    return values


def compare(args):
    windows = parse_windows(args.windows)
    ref = group_values(args, args.reference, windows)
    new = group_values(args, args.candidate, windows)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for q in QUANTITIES:
        (rm, rs), (nm, ns) = group(ref, q), group(new, q)
        combined = math.hypot(rs, ns)
        t = difference_in_errors(nm, ns, rm, rs)
        rows.append(dict(quantity=q, unit=UNITS.get(q, ""), reference=rm, reference_se=rs, candidate=nm,
                         candidate_se=ns, difference=nm - rm, combined_se=combined, t=t,
                         agrees=abs(t) <= 2 if math.isfinite(t) else False))
    stem = os.path.join(args.out, args.name or f"{args.candidate.split(',')[0]}_vs_{args.reference.split(',')[0]}")
    with open(stem + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = [f"| quantity | {args.reference} | {args.candidate} | difference / combined SE | agrees |",
             "|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['quantity']} ({r['unit']}) | {r['reference']:.4g} ± {r['reference_se']:.2g} | "
                     f"{r['candidate']:.4g} ± {r['candidate_se']:.2g} | {r['t']:+.2f} | "
                     f"{'yes' if r['agrees'] else 'NO'} |")
    reference, candidate = args.reference.split(",")[0], args.candidate.split(",")[0]
    lines.append(f"\ncost: {reference} {cost(os.path.join(args.runs, reference)):.0f}, "
                 f"{candidate} {cost(os.path.join(args.runs, candidate)):.1f} CPU s per physical s; "
                 f"{len(ref)} and {len(new)} windows ({args.windows} s of {args.reference} and {args.candidate})")
    open(stem + ".md", "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


# What the convergence figure shows, with its axis labels.
CONVERGENCE = [("f", "f (Hz)"), ("A", "A (sqrt(g d))"), ("A_mean", "A_mean, f >= 100 Hz (sqrt(g d))"),
               ("U", "U (sqrt(g d))"), ("phi_layer", "phi of 0 < z < 40 d")]


def convergence(args):
    """f, A, A_mean, U and the layer's packing against one setting (tolerance or dt): a CSV,
    and a gnuplot figure."""
    windows = parse_windows(args.windows)
    os.makedirs(args.out, exist_ok=True)
    names = [q for q, _ in CONVERGENCE]
    series = []
    for item in args.series.split(","):
        value, folder = item.split("=")
        values = group_values(args, folder.replace("+", ","), windows)    # RUN+RUN: replicas
        series.append((float(value), folder, {q: group(values, q) for q in names},
                       cost(os.path.join(args.runs, folder.split("+")[0]))))
    series.sort()
    reference = None
    if args.reference:
        values = group_values(args, args.reference, windows)
        reference = {q: group(values, q) for q in names}
    stem = os.path.join(args.out, args.name or f"convergence_{args.setting}")
    with open(stem + ".csv", "w") as f:
        f.write(f"{args.setting},run," + ",".join(f"{q},{q}_se" for q in names) + ",cpu_s_per_s\n")
        for value, folder, g, c in series:
            f.write(f"{value:g},{folder}," + ",".join(f"{g[q][0]:.6g},{g[q][1]:.3g}" for q in names) + f",{c:.1f}\n")
    convergence_figure(stem, args.setting, reference, [value for value, *_ in series])
    print(open(stem + ".csv").read())


def reference_band(reference, q):
    """The reference's mean and mean +- SE as horizontal lines, if there is a reference."""
    if not reference:
        return ""
    m, e = reference[q]
    return f", {m} with lines dt 2 lc 'black' title 'reference', {m - e} with lines dt 3 lc 'gray' notitle, " \
           f"{m + e} with lines dt 3 lc 'gray' notitle"


def convergence_figure(stem, setting, reference, values):
    """stem.png and stem.svg from stem.csv: each quantity of CONVERGENCE against the setting
    (its values span the x axis, with the reference band across it)."""
    panels = []
    for k, (q, label) in enumerate(CONVERGENCE):
        column = 3 + 2 * k
        key = "title 'mean of the windows +- SE'" if k == 0 else "notitle"
        panels.append(f"set ylabel '{label}'\n"
                      f"plot '{stem}.csv' every ::1 using 1:{column}:{column + 1} with yerrorlines {key}"
                      f"{reference_band(reference, q)}")
    for ext, term in (("png", "pngcairo size 1000,640"), ("svg", "svg size 1000,640")):
        script = f"""set terminal {term} noenhanced
set output '{stem}.{ext}'
set datafile separator ','
set logscale x
set xrange [{min(values) / 1.5}:{max(values) * 1.5}]
set xtics rotate by -30 ({", ".join(f"'{v:g}' {v}" for v in values)})
set key top right font ",9"
set multiplot layout 2,3
set xlabel '{setting}'
""" + "\n".join(panels) + "\nunset multiplot\n"
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    for name in ("compare", "convergence"):
        s = sub.add_parser(name)
        s.add_argument("--runs", required=True, help="folder holding one folder per run")
        s.add_argument("--windows", required=True, help="T0:T1,... chute times (s) of the replica windows")
        s.add_argument("--z0", type=float, default=0.015, help="height of the wall tops (m)")
        s.add_argument("--out", required=True)
    sub.choices["compare"].add_argument("--reference", required=True, help="RUN[,RUN...]: replicas of the reference")
    sub.choices["compare"].add_argument("--candidate", required=True, help="RUN[,RUN...]: replicas of the candidate")
    sub.choices["compare"].add_argument("--name", help="file name of the table (default CANDIDATE_vs_REFERENCE)")
    sub.choices["convergence"].add_argument("--name",
                                            help="file name of the figure and table (default convergence_SETTING)")
    sub.choices["convergence"].add_argument("--setting", required=True, help="name of the varied setting (axis label)")
    sub.choices["convergence"].add_argument("--series", required=True,
                                            help="VALUE=RUN[+RUN...],...: the run (or replicas) of each value")
    sub.choices["convergence"].add_argument("--reference", help="RUN[,RUN...]: drawn as a band")
    args = p.parse_args()
    try:
        compare(args) if args.command == "compare" else convergence(args)
    except RuntimeError as error:    # a malformed output file of a run, named
        sys.exit(f"accuracy_45d.py: {error}")


if __name__ == "__main__":
    sys.exit(main())
