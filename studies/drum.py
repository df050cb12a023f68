#!/usr/bin/env python3
"""The 2D rotating drum: inputs/examples/in.drum_rigid (rigid disks, the drum a turning LAMMPS
region) or inputs/examples/in.drum_granular (its soft twin: --deck, with --lmp lmp) run at several
Froude numbers Fr = omega^2 R / g, each measured over its turns after the first half.

    studies/drum.py --run [--froude 1e-4,1e-3,3e-3,1e-2] [--dt 0.04,0.02,0.01,0.01] [--out runs/drum]
    studies/drum.py --analyse DIR [DIR ...] [--out OUT]

Per run (a folder holding dump.drum and log.lammps), in units of the mean diameter d and
sqrt(d/g):
- the free surface of each frame: in columns 2 d wide over |x| <= R/2, the height where the
  area fraction of the grains' centres in 1 d bins first reaches half the bulk's (0.4), from the
  top, interpolated between bin centres; a straight line fitted through the columns gives the
  dynamic angle of repose theta (the drum turns counter-clockwise: the surface rises towards
  +x); its mean, standard deviation over the frames and standard error over five blocks;
- the flowing layer along the surface's normal through the drum's axis (a strip 6 d wide): the
  grains' mean velocity down the slope against depth in 1 d bins over all frames; the layer's
  thickness h is the depth where that velocity changes sign (below, the bed turns with the drum
  and climbs), u_s its value in the top bin;
- the deepest overlap over the frames (between grains, or with the drum), the solver's health
  (the fix's end-of-run line; none for the soft twin) and the CPU time of the turning run.
Writes OUT/drum.csv, OUT/profiles.csv and, with gnuplot, OUT/drum.png. Standard library only.
"""

import argparse
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools import lammps_files, logs, plane_shear, run, stats

DECK = os.path.join(run.TOP, "inputs", "examples", "in.drum_rigid")
# The same grains' rheology, measured elsewhere in the project: plane shear's mu(I) at contact
# friction 0.5 and the chute's Pouliquen fit (layer reading, mu 0.5).
PLANE_SHEAR = os.path.join(run.TOP, "results", "plane_shear", "plane_shear_mu0.5.csv")
CHUTE_FITS = os.path.join(run.TOP, "results", "series", "layer_flow_rules", "fits.json")
BETA = 0.136
RADIUS = 25.0           # the decks' drum radius (d)
COLUMN = 2.0            # surface columns' width (d)
BIN = 1.0               # height and depth bins (d)
HALF_BULK = 0.4         # area fraction marking the surface: half a random packing's
STRIP = 3.0             # half-width of the strip along the normal through the axis (d)
DISCARDED_TURNS = 0.5   # the start
BLOCKS = 5


def surface_height(grains, x_lo, x_hi, top):
    """Height of the free surface over the column [x_lo, x_hi), or None if the column is empty:
    scanning 1 d bins down from `top`, where the area fraction of the centres first reaches
    HALF_BULK, interpolated between that bin's centre and the one above."""
    areas = {}
    for x, y, _, _, radius in grains:
        if x_lo <= x < x_hi:
            k = int(math.floor((top - y) / BIN))
            areas[k] = areas.get(k, 0.0) + math.pi * radius * radius
    width = x_hi - x_lo
    for k in sorted(areas):
        phi = areas[k] / (BIN * width)
        if phi >= HALF_BULK:
            above = areas.get(k - 1, 0.0) / (BIN * width)
            centre = top - (k + 0.5) * BIN
            return centre + BIN * (phi - HALF_BULK) / (phi - above)
    return None


def frame_surface(grains):
    """(height over the axis, angle in degrees) of one frame's free surface."""
    xs, ys = [], []
    x = -0.5 * RADIUS
    while x < 0.5 * RADIUS - 1e-9:
        height = surface_height(grains, x, x + COLUMN, RADIUS)
        if height is not None:
            xs.append(x + 0.5 * COLUMN)
            ys.append(height)
        x += COLUMN
    if len(xs) < 3:
        raise ValueError("fewer than three surface columns: is the drum filled?")
    intercept, slope = stats.least_squares_line(xs, ys)
    return intercept, math.degrees(math.atan(slope))


def add_profile(grains, intercept, angle_deg, sums):
    """Adds a frame's grains near the normal through the axis to sums {depth bin: [count, sum u,
    area]}: depth below the surface, u the velocity down the slope, the grains' area."""
    a = math.radians(angle_deg)
    down = (-math.cos(a), -math.sin(a))   # along the surface, downhill (towards -x)
    normal = (-math.sin(a), math.cos(a))  # out of the bed
    for x, y, vx, vy, radius in grains:
        rx, ry = x, y - intercept
        if abs(rx * down[0] + ry * down[1]) > STRIP:
            continue
        depth = -(rx * normal[0] + ry * normal[1])
        if depth < 0.0:
            continue
        entry = sums.setdefault(int(depth // BIN), [0, 0.0, 0.0])
        entry[0] += 1
        entry[1] += vx * down[0] + vy * down[1]
        entry[2] += math.pi * radius * radius


def sign_change_depth(profile):
    """Depth (d) where the mean downhill velocity first turns negative, interpolated; None if
    it never does."""
    for (d0, u0), (d1, u1) in zip(profile, profile[1:]):
        if u0 > 0.0 >= u1:
            return d0 + (d1 - d0) * u0 / (u0 - u1)
    return None


def deepest_overlap(grains):
    """The deepest overlap (d) of a frame between two grains or a grain and the drum's wall,
    from the positions (grains binned by 2 d cells)."""
    cells = {}
    for k, (x, y, _, _, radius) in enumerate(grains):
        cells.setdefault((int(math.floor(x / 2.0)), int(math.floor(y / 2.0))), []).append(k)
    deepest = max(math.hypot(x, y) + radius - RADIUS for x, y, _, _, radius in grains)
    for (cx, cy), members in cells.items():
        neighbours = [j for dx in (-1, 0, 1) for dy in (-1, 0, 1) for j in cells.get((cx + dx, cy + dy), [])]
        for i in members:
            xi, yi, _, _, ri = grains[i]
            for j in neighbours:
                if j > i:
                    xj, yj, _, _, rj = grains[j]
                    deepest = max(deepest, ri + rj - math.hypot(xi - xj, yi - yj))
    return max(deepest, 0.0)


def plane_shear_mu(inertial):
    """mu at inertial number I from plane shear's table, linear in log I (None outside it)."""
    return plane_shear.at_inertial(plane_shear.read_table(PLANE_SHEAR), inertial, "mu")


def pouliquen_angle(h, mean_velocity):
    """The chute's flow rule tan theta = tan theta1 + (tan theta2 - tan theta1) exp(-beta h
    sqrt(g h) / (ell d U)) for a layer h (d) flowing at U (sqrt(g d)), in degrees."""
    import json
    with open(CHUTE_FITS) as src:
        fits = {r["name"]: r["value"] for r in json.load(src)["results"]}
    t1 = math.tan(math.radians(fits["pouliquen_theta1_mu0.5"]))
    t2 = math.tan(math.radians(fits["pouliquen_theta2_mu0.5"]))
    ell = fits["pouliquen_ell_mu0.5"]
    return math.degrees(math.atan(t1 + (t2 - t1) * math.exp(-BETA * h * math.sqrt(h) / (ell * mean_velocity))))


def layer_rheology(profile, packing, h, angle_deg):
    """The flowing layer as a uniform shear flow: its packing, mean velocity U and shear rate
    u_s / h, the pressure at mid-depth from the weight above (g cos theta times the packing
    integrated over h/2), the inertial number I = rate d / sqrt(P / rho) there, and what plane
    shear's mu(I) and the chute's flow rule give for such a layer (angles in degrees)."""
    if h is None or not profile:
        return {"phi_layer": None, "U_layer": None, "I_layer": None, "theta_mu_I": None, "theta_pouliquen": None}
    inside = [u for depth, u in profile if depth < h]
    mean_velocity = sum(inside) / len(inside)
    in_layer = [k for k in packing if (k + 0.5) * BIN < h]
    phi = sum(packing[k] for k in in_layer) / max(1, len(in_layer))
    pressure = math.cos(math.radians(angle_deg)) * sum(packing.get(k, 0.0) * BIN for k in range(int(h / 2 / BIN)))
    pressure += math.cos(math.radians(angle_deg)) * packing.get(int(h / 2 / BIN), 0.0) * (h / 2 % BIN)
    inertial = profile[0][1] / h / math.sqrt(pressure)
    mu = plane_shear_mu(inertial)
    return {"phi_layer": phi, "U_layer": mean_velocity, "I_layer": inertial,
            "theta_mu_I": None if mu is None else math.degrees(math.atan(mu)),
            "theta_pouliquen": pouliquen_angle(h, mean_velocity)}


def frames_of(folder):
    """[(time since the drum started, [(x, y, vx, vy, radius)])] of dump.drum."""
    rows = logs.thermo_rows(logs.read_outputs(folder, names=("log.lammps",)))[-2:]
    dt = (rows[1]["Time"] - rows[0]["Time"]) / (rows[1]["Step"] - rows[0]["Step"])
    frames = []
    for step, _, atoms in lammps_files.read_dump(os.path.join(folder, "dump.drum")):
        grains = [(a["x"], a["y"], a["vx"], a["vy"], a["radius"]) for a in atoms.values()]
        frames.append((step * dt, grains))
    return frames


def turning_cpu(folder):
    """CPU seconds of the last run loop in folder/log.lammps (the drum turning): its loop time
    times the tasks' CPU use."""
    loop = use = None
    for line in logs.read_outputs(folder, names=("log.lammps",)).splitlines():
        if line.startswith("Loop time of"):
            fields = line.split()
            loop = float(fields[3]) * int(fields[5])
        elif "% CPU use with" in line and loop is not None:
            use = float(line.split("%")[0])
    return loop * use / 100.0 if loop is not None and use is not None else None


def analyse(folder):
    summary = logs.log_summary(folder, "DRUM")
    omega = summary["omega"]
    start = DISCARDED_TURNS * 2.0 * math.pi / omega
    angles, sums, overlap = [], {}, 0.0
    for time, grains in frames_of(folder):
        if time < start:
            continue
        overlap = max(overlap, deepest_overlap(grains))
        intercept, angle = frame_surface(grains)
        angles.append(angle)
        add_profile(grains, intercept, angle, sums)
    mean, sd, _ = stats.mean_sd_se(angles)
    size = len(angles) // BLOCKS
    block_means = [sum(angles[b * size:(b + 1) * size]) / size for b in range(BLOCKS)]
    _, _, se = stats.mean_sd_se(block_means)
    profile = [((k + 0.5) * BIN, sums[k][1] / sums[k][0]) for k in sorted(sums) if sums[k][0] >= 10]
    packing = {k: sums[k][2] / (2.0 * STRIP * BIN * len(angles)) for k in sums}
    health = logs.solver_health(os.path.join(folder, "log.lammps")) or {}
    h = sign_change_depth(profile)
    layer = layer_rheology(profile, packing, h, mean)
    return {**layer, "folder": folder, "froude": summary["froude"], "omega": omega, "turns": summary["turns"],
            "frames": len(angles), "theta": mean, "theta_sd": sd, "theta_se": se,
            "h": h, "u_surface": profile[0][1] if profile else None,
            "unconverged": health.get("unconverged"), "steps": health.get("steps"),
            "sweeps_median": health.get("sweeps_median"), "sweeps_p99": health.get("sweeps_p99"),
            "overlap": overlap, "cpu_s": turning_cpu(folder), "profile": profile}


COLUMNS = ["froude", "omega", "turns", "frames", "theta", "theta_sd", "theta_se", "h", "u_surface", "U_layer",
           "phi_layer", "I_layer", "theta_mu_I", "theta_pouliquen",
           "unconverged", "steps", "sweeps_median", "sweeps_p99", "overlap", "cpu_s", "folder"]


def write_tables(results, out):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "drum.csv"), "w", newline="") as dst:
        writer = csv.writer(dst)
        writer.writerow(COLUMNS)
        for r in results:
            writer.writerow([r[c] if not isinstance(r[c], float) else f"{r[c]:.6g}" for c in COLUMNS])
    with open(os.path.join(out, "profiles.csv"), "w", newline="") as dst:
        writer = csv.writer(dst)
        writer.writerow(["folder", "froude", "depth", "u_downhill"])
        for r in results:
            for depth, u in r["profile"]:
                writer.writerow([r["folder"], r["froude"], f"{depth:.3g}", f"{u:.6g}"])


def draw(out):
    """OUT/drum.png: the angle against Fr, and the profiles (gnuplot; skipped without it)."""
    script = f"""
set terminal pngcairo size 1100,450
set output '{out}/drum.png'
set datafile separator ','
set multiplot layout 1,2
set logscale x
set xrange [5e-5:2e-2]
set xlabel 'Fr = omega^2 R / g'
set ylabel 'dynamic angle of repose (deg)'
plot '{out}/drum.csv' every ::1 using 1:5:7 with yerrorbars pt 7 title 'mean +- s.e.', \\
     '' every ::1 using 1:5:6 with yerrorbars lt 2 pt 0 title 'fluctuation (s.d.)'
unset logscale x
set autoscale x
set xlabel 'depth below the surface (d)'
set ylabel 'velocity down the slope (sqrt(g d))'
plot for [fr in "{' '.join(sorted({r for r in _froudes(out)}))}"] '{out}/profiles.csv' every ::1 \\
     using ($2 == fr ? $3 : 1/0):4 with linespoints title 'Fr '.fr
unset multiplot
"""
    try:
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as failure:
        print(f"drum.py: no figure ({failure})", file=sys.stderr)


def _froudes(out):
    with open(os.path.join(out, "drum.csv")) as src:
        return [row["froude"] for row in csv.DictReader(src)]


def run_deck(froude, dt, folder, deck, lmp):
    os.makedirs(folder, exist_ok=True)
    command = [lmp, "-in", deck, "-log", "log.lammps", "-screen", "none", "-var", "froude", froude, "-var", "dt", dt]
    subprocess.run(command, cwd=folder, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run", action="store_true", help="run the deck at each Froude number first")
    parser.add_argument("--froude", default="1e-4,1e-3,3e-3,1e-2")
    parser.add_argument("--dt", default="0.04,0.02,0.01,0.01", help="the step of each Froude number")
    parser.add_argument("--deck", default=DECK)
    parser.add_argument("--lmp", default=os.path.join(run.TOP, "build", "lmp_cd"))
    parser.add_argument("--out", default="runs/drum")
    parser.add_argument("--analyse", nargs="*", default=None, help="run folders to analyse (default: OUT/fr_*)")
    args = parser.parse_args()
    froudes, dts = args.froude.split(","), args.dt.split(",")
    if len(froudes) != len(dts):
        parser.error(f"--froude gives {len(froudes)} values, --dt {len(dts)}")
    folders = [os.path.join(args.out, f"fr_{fr}") for fr in froudes]
    if args.run:
        for fr, dt, folder in zip(froudes, dts, folders):
            run_deck(fr, dt, folder, args.deck, args.lmp)
    if args.analyse:
        folders = args.analyse
    results = []
    for folder in folders:
        try:
            results.append(analyse(folder))
        except (OSError, RuntimeError, ValueError) as problem:
            sys.exit(f"drum.py: {folder}: {problem}")
    results.sort(key=lambda r: r["froude"])
    write_tables(results, args.out)
    draw(args.out)
    for r in results:
        print(f"Fr {r['froude']:g}: theta {r['theta']:.2f} +- {r['theta_se']:.2f} (s.d. {r['theta_sd']:.2f}) deg, "
              f"h {r['h'] if r['h'] is None else round(r['h'], 1)} d, u_s {r['u_surface']:.2f}, I {r['I_layer']}, "
              f"mu(I) angle {r['theta_mu_I']}, flow-rule angle {r['theta_pouliquen']}, "
              f"unconverged {r['unconverged']} of {r['steps']}, CPU {r['cpu_s']} s")


if __name__ == "__main__":
    main()
