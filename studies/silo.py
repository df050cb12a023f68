#!/usr/bin/env python3
"""The discharge of a 2D silo through an orifice of width D: inputs/examples/in.silo_rigid (rigid
disks, Contact Dynamics) at several widths, its soft twin inputs/examples/in.silo_granular (Hooke
springs at the same mu and e) at a few, and the 2D Beverloo law fitted to the flow rates.

    studies/silo.py [--widths 4,5,6,8,11,15,20] [--flow 80] [--flow-small 120] [--transient 10]
                    [--soft-widths 8,11,15] [--soft-flow 30] [--soft-transient 8] [--width 50] [--grains 1500]
                    [--out runs/silo]

For each run: the flow rate W (mass per unit time, areal density 1, g = 1, d = 1) is the slope
of the discharged mass against the time the orifice flowed, from `transient` after the opening to
the end, the clogged spells (no discharge for clog_wait, then the arch lifted: the deck's
silo.clogs) cut out of the time; its standard error from ten blocks of equal flowing time. The
clogs are counted over the whole opening, their frequency per grain discharged (mean grain mass
pi/4 (1 + 0.4^2/12)). The Beverloo law W = C phi sqrt(g) (D - k d)^(3/2), with phi the packing
fraction near the floor at rest (the deck's "SILO filled" line), is fitted as a weighted straight
line W^(2/3) = (C phi)^(2/3) (D - k): C and k with errors from its covariance (scaled by the
reduced chi^2 when above 1). The overlaps of the settled packing (mean and largest over the
touching pairs, in d) check the soft stiffness. The CPU per unit of physical time is the flow phase's LAMMPS loop
times times its "% CPU use", over the time simulated. Runs already done (their log ends with
"SILO done") are read again, not rerun. Writes OUT/silo.csv, OUT/silo_fit.csv and the figure
OUT/silo.png. Standard library and gnuplot.
"""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools import run, stats

DECKS = {"rigid": os.path.join(run.TOP, "inputs", "examples", "in.silo_rigid"),
         "soft": os.path.join(run.TOP, "inputs", "examples", "in.silo_granular")}
GRAIN_MASS = math.pi / 4 * (1 + 0.4 ** 2 / 12)   # mean pi r^2 of diameters uniform in 0.8-1.2
LOOP = re.compile(r"^Loop time of (\S+) on \d+ procs for (\d+) steps")
CPU_USE = re.compile(r"^(\S+)% CPU use")


def read_columns(path):
    """The rows of a whitespace table, '#' lines skipped, as lists of floats."""
    with open(path) as table:
        return [[float(v) for v in line.split()] for line in table if line.strip() and not line.startswith("#")]


def flowing_time(t, stops, start):
    """Time the orifice flowed from `start` to t: the clogged spells (stopped, counted) cut out."""
    cut = sum(max(0.0, min(t, b) - max(start, a)) for a, b in stops)
    return t - start - cut


def flow_rate(samples, stops, start, blocks=10):
    """(W, standard error, flowing time) from samples (t, discharged mass) after `start`: the
    least-squares slope against the flowing time, the error from `blocks` blocks of equal flowing
    time (each one's mass over its time)."""
    points = [(flowing_time(t, stops, start), m) for t, m in samples if t >= start]
    if len(points) < 2 * blocks:
        raise ValueError(f"{len(points)} samples after t = {start}: too few for {blocks} blocks")
    ts, ms = [p[0] for p in points], [p[1] for p in points]
    slope, _ = stats.least_squares_slope(ts, ms)
    total = ts[-1] - ts[0]
    edges = [ts[0] + total * i / blocks for i in range(blocks + 1)]

    def mass_at(time):   # linear between samples
        for (t0, m0), (t1, m1) in zip(points, points[1:]):
            if t0 <= time <= t1:
                return m0 if t1 == t0 else m0 + (m1 - m0) * (time - t0) / (t1 - t0)
        return ms[-1]
    rates = [(mass_at(b) - mass_at(a)) / (b - a) for a, b in zip(edges, edges[1:])]
    _, _, se = stats.mean_sd_se(rates)
    return slope, se, total


def beverloo_fit(widths, rates, errors, phi):
    """Weighted fit of W = C phi (D - k)^(3/2) (g = 1, d = 1) through W^(2/3) = a (D - k), a =
    (C phi)^(2/3): returns {C, C_err, k, k_err, chi2_red}; the errors from the line's covariance,
    scaled by the reduced chi^2 if it exceeds 1. Needs three points or more with W > 0."""
    points = [(D, W ** (2 / 3), 2 / 3 * W ** (-1 / 3) * max(err, 1e-12))
              for D, W, err in zip(widths, rates, errors) if W > 0]
    if len(points) < 3:
        raise ValueError("the Beverloo fit needs three flow rates > 0")
    w = [1 / s ** 2 for _, _, s in points]
    sw = sum(w)
    sx = sum(wi * x for wi, (x, _, _) in zip(w, points))
    sy = sum(wi * y for wi, (_, y, _) in zip(w, points))
    sxx = sum(wi * x * x for wi, (x, _, _) in zip(w, points))
    sxy = sum(wi * x * y for wi, (x, y, _) in zip(w, points))
    det = sw * sxx - sx * sx
    a = (sw * sxy - sx * sy) / det                  # slope
    b = (sxx * sy - sx * sxy) / det                 # intercept
    var_a, var_b, cov_ab = sw / det, sxx / det, -sx / det
    chi2 = sum(wi * (y - a * x - b) ** 2 for wi, (x, y, _) in zip(w, points))
    chi2_red = chi2 / (len(points) - 2) if len(points) > 2 else math.nan
    scale = max(1.0, chi2_red) if not math.isnan(chi2_red) else 1.0
    var_a, var_b, cov_ab = var_a * scale, var_b * scale, cov_ab * scale
    k = -b / a
    k_err = math.sqrt(max(0.0, var_b / a ** 2 + b ** 2 * var_a / a ** 4 - 2 * b * cov_ab / a ** 3))
    C = a ** 1.5 / phi
    C_err = 1.5 * math.sqrt(a) * math.sqrt(var_a) / phi
    return {"C": C, "C_err": C_err, "k": k, "k_err": k_err, "chi2_red": chi2_red, "points": len(points)}


def cpu_per_time(log_text, dt):
    """(CPU s, loop s) per unit of physical time over the runs after the opening (after "SILO
    filled"): each run's LAMMPS loop time (wall), and that times its % CPU use."""
    filled = re.search(r"^SILO filled", log_text, re.M)   # the printed line, not the deck's echo
    flow = log_text[filled.end():] if filled else log_text
    cpu, wall, steps = 0.0, 0.0, 0
    loop = None
    for line in flow.splitlines():
        match = LOOP.match(line)
        if match:
            loop = (float(match.group(1)), int(match.group(2)))
            continue
        match = CPU_USE.match(line)
        if match and loop:
            cpu += loop[0] * float(match.group(1)) / 100
            wall += loop[0]
            steps += loop[1]
            loop = None
    return (cpu / (steps * dt), wall / (steps * dt)) if steps else (math.nan, math.nan)


def overlaps(path):
    """(mean, largest) overlap r_i + r_j - distance over the touching pairs (overlap > 0) of a
    frame written by write_dump custom id x y radius (the settled packing, silo.filled); (0, 0)
    if none touch. Pairs within one box, no periodic images (the packing is far from y's ends)."""
    with open(path) as frame:
        lines = frame.read().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS")) + 1
    grains = sorted(([float(v) for v in line.split()[1:4]] for line in lines[start:] if line.strip()),
                    key=lambda g: g[1])
    found = []
    for i, (x, y, r) in enumerate(grains):
        for x2, y2, r2 in grains[i + 1:]:
            if y2 - y > r + r2:
                break
            overlap = r + r2 - math.hypot(x2 - x, y2 - y)
            if overlap > 0:
                found.append(overlap)
    return (sum(found) / len(found), max(found)) if found else (0.0, 0.0)


def measure(folder, transient, dt):
    """The run's phi, W, its error, flowing time, clogs and their frequency, CPU per time unit."""
    log = open(os.path.join(folder, "log.lammps")).read()
    phi = float(re.search(r"^SILO filled .*? phi (\S+)", log, re.M).group(1))
    samples = sorted({row[0]: row[1] for row in read_columns(os.path.join(folder, "silo.flow"))}.items())
    stops = [(row[0], row[1]) for row in read_columns(os.path.join(folder, "silo.clogs"))]
    W, W_se, flowed = flow_rate(samples, stops, transient)
    grains = samples[-1][1] / GRAIN_MASS
    overlap_mean, overlap_max = overlaps(os.path.join(folder, "silo.filled"))
    cpu, loop = cpu_per_time(log, dt)
    return {"phi": phi, "overlap_mean": overlap_mean, "overlap_max": overlap_max, "W": W, "W_se": W_se,
            "flowed": flowed, "clogs": len(stops), "grains": grains,
            "clogs_per_grain": len(stops) / grains if grains > 0 else math.nan,
            "cpu_per_time": cpu, "loop_per_time": loop}


def run_one(args, model, D, flow, folder):
    """Runs the model's deck at width D into folder unless its log already ends the run."""
    log = os.path.join(folder, "log.lammps")
    if os.path.exists(log) and "SILO done" in open(log).read():
        return
    variables = {"D": D, "flow": flow, "width": args.width, "grains": args.grains}
    if model == "soft":
        del variables["grains"]     # the rigid packing's
        variables.update({"fill": args.soft_fill, "start": os.path.join(args.out, f"rigid_D{D}", "silo.filled.data")})
    # A copy: LAMMPS reads a deck as it goes (and jumps back in it), so an edit must not reach a run.
    os.makedirs(folder, exist_ok=True)
    deck = os.path.join(folder, os.path.basename(DECKS[model]))
    shutil.copy2(DECKS[model], deck)
    command = ["nice"] + run.lmp_command(args.lmp, deck, variables, screen="none")
    seconds = run.run_checked(command, folder)
    print(f"{model} D {D}: {seconds:.0f} s", flush=True)


def figure(csv, fits, stem):
    """stem.png: W against D (rigid, soft) with the fitted Beverloo curve; log-log."""
    curve = ""
    if "rigid" in fits:
        f = fits["rigid"]
        curve = (f", (x > {f['k']:.4f} ? {f['C']:.5f}*{f['phi']:.4f}*(x-{f['k']:.4f})**1.5 : 1/0) "
                 f"lc 'black' title sprintf('Beverloo C = %.3f, k = %.2f', {f['C']:.5f}, {f['k']:.4f})")
    script = f"""set terminal pngcairo size 640,480 noenhanced
set output '{stem}.png'
set datafile separator ','
set logscale xy
set xrange [3:25]
set xlabel 'orifice width D (mean diameters)'
set ylabel 'flow rate W (mass per sqrt(d/g), areal density 1)'
set key top left
set xtics (4, 5, 6, 8, 11, 15, 20)
plot '{csv}' using (strcol(1) eq 'rigid' && $3 > 0 ? $2 : 1/0):3:4 with yerrorbars pt 7 lc 'black' \\
       title 'rigid (contact/dynamics)', \\
     '{csv}' using (strcol(1) eq 'soft' ? $2 : 1/0):3:4 with yerrorbars pt 6 ps 1.5 lc 'red' title 'soft (Hooke)'{curve}
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--widths", default="4,5,6,8,11,15,20", help="orifice widths of the rigid runs")
    parser.add_argument("--flow", type=float, default=80, help="time with the orifice open (D >= 7)")
    parser.add_argument("--flow-small", type=float, default=120, help="the same for D < 7 (clogging)")
    parser.add_argument("--transient", type=float, default=10, help="time after the opening left out of W")
    parser.add_argument("--soft-widths", default="8,11,15", help="orifice widths of the soft runs ('' for none)")
    parser.add_argument("--soft-flow", type=float, default=30)
    parser.add_argument("--soft-fill", type=float, default=2, help="settling of the soft grains from the rigid packing")
    parser.add_argument("--soft-transient", type=float, default=8)
    parser.add_argument("--width", type=float, default=50, help="the silo's width (d)")
    parser.add_argument("--grains", type=int, default=1500)
    parser.add_argument("--out", default=os.path.join(run.TOP, "runs", "silo"))
    parser.add_argument("--lmp", default=run.BUILT_LMP_CD)
    args = parser.parse_args()

    plan = [("rigid", w, args.flow if float(w) >= 7 else args.flow_small, args.transient, 0.005)
            for w in args.widths.split(",") if w]
    plan += [("soft", w, args.soft_flow, args.soft_transient, None) for w in args.soft_widths.split(",") if w]
    rows = []
    for model, D, flow, transient, dt in plan:
        folder = os.path.join(args.out, f"{model}_D{D}")
        run_one(args, model, D, flow, folder)
        if dt is None:    # the soft deck's step, from its log
            with open(os.path.join(folder, "log.lammps")) as log:
                dt = float(re.search(r"^SILO soft dt (\S+)", log.read(), re.M).group(1))
        rows.append(dict(model=model, D=float(D), **measure(folder, transient, dt)))
        r = rows[-1]
        print(f"{model} D {D}: W {r['W']:.4g} +- {r['W_se']:.2g}, clogs {r['clogs']}, phi {r['phi']:.4f}, "
              f"CPU {r['cpu_per_time']:.3g} s per time unit", flush=True)

    csv = os.path.join(args.out, "silo.csv")
    with open(csv, "w") as out:
        out.write("model,D,W,W_se,flowing_time,clogs,grains_discharged,clogs_per_grain,phi,rest_overlap_mean,"
                  "rest_overlap_max,cpu_s_per_time,loop_s_per_time\n")
        for r in rows:
            out.write(f"{r['model']},{r['D']:g},{r['W']:.5g},{r['W_se']:.3g},{r['flowed']:.4g},{r['clogs']},"
                      f"{r['grains']:.1f},{r['clogs_per_grain']:.3g},{r['phi']:.4f},{r['overlap_mean']:.3g},"
                      f"{r['overlap_max']:.3g},"
                      f"{r['cpu_per_time']:.4g},{r['loop_per_time']:.4g}\n")
    fits = {}
    for model in ("rigid", "soft"):
        mine = [r for r in rows if r["model"] == model]
        if len([r for r in mine if r["W"] > 0]) < 3:
            continue
        phi = sum(r["phi"] for r in mine) / len(mine)
        fits[model] = dict(beverloo_fit([r["D"] for r in mine], [r["W"] for r in mine], [r["W_se"] for r in mine], phi),
                           phi=phi)
    with open(os.path.join(args.out, "silo_fit.csv"), "w") as out:
        out.write("model,phi,C,C_err,k,k_err,chi2_red,points\n")
        for model, f in fits.items():
            out.write(f"{model},{f['phi']:.4f},{f['C']:.4g},{f['C_err']:.2g},{f['k']:.4g},{f['k_err']:.2g},"
                      f"{f['chi2_red']:.3g},{f['points']}\n")
    figure(csv, fits, os.path.join(args.out, "silo"))
    print(open(csv).read())
    print(open(os.path.join(args.out, "silo_fit.csv")).read())


if __name__ == "__main__":
    main()
