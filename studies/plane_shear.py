#!/usr/bin/env python3
"""mu(I) and phi(I) of rigid disks in plane shear: inputs/examples/in.plane_shear (a Lees-Edwards
cell at fixed area) run at several packing fractions, each giving one inertial number.

    studies/plane_shear.py [--phis 0.70,0.74,0.77,0.79,0.80,0.81] [--side 32] [--strain 10]
                           [--mu 0.5] [--tolerance 1e-3] [--max-iterations 10000] [--out runs/plane_shear]

For each phi: I = rate d / sqrt(P_yy / rho) and mu = -P_xy / P_yy, from the pressure tensor of
compute pressure (the fix's contact stress plus the kinetic part of compute temp/deform) over the
second half of the shear, with d = 1 the mean diameter and rho = 1 the disks' areal density; the
standard errors from five blocks of that window, and the deepest overlap the fix warned of at
the start of that window (start_overlap, mean diameters). Writes OUT/plane_shear.csv and the figure
OUT/plane_shear.png (results/plane_shear/plane_shear.png is one). Standard library and gnuplot.
"""

import argparse
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools import lammps_files, logs, run, stats

DECK = os.path.join(run.TOP, "inputs", "examples", "in.plane_shear")
# The fix's warning of grains overlapping at the start of a run (the averaging half, here).
OVERLAP_WARNING = re.compile(r"overlap by up to (\S+) mean diameters")


def start_overlap(folder):
    """The deepest overlap the fix warned of at the start of a run in folder/log.lammps (in mean
    diameters; 0 if none beyond its 0.01 threshold)."""
    with open(os.path.join(folder, "log.lammps")) as log:
        return max((float(m.group(1)) for m in OVERLAP_WARNING.finditer(log.read())), default=0.0)


def measure(folder):
    """phi, I, mu and their standard errors from one finished run in folder."""
    summary = logs.log_summary(folder, "SHEAR")
    blocks = lammps_files.read_time_file(os.path.join(folder, "stress_blocks.shear"))
    pyy = [row["c_stress[2]"] for row in blocks]
    friction = [-row["c_stress[4]"] / row["c_stress[2]"] for row in blocks]
    inertial = [summary["rate"] / math.sqrt(p) for p in pyy]    # d = 1, rho = 1
    mu, _, mu_se = stats.mean_sd_se(friction)
    inertial_mean, _, inertial_se = stats.mean_sd_se(inertial)
    return {"phi": summary["phi"], "I": inertial_mean, "I_se": inertial_se, "mu": mu, "mu_se": mu_se,
            "pyy": summary["pyy"], "capped": summary["capped"], "overlap": start_overlap(folder)}


def figure(csv, stem):
    """stem.png: mu against I and phi against I (I on a log scale), from csv."""
    script = f"""set terminal pngcairo size 900,380 noenhanced
set output '{stem}.png'
set datafile separator ','
set logscale x
set xlabel 'inertial number I = rate d / sqrt(P/rho)'
set multiplot layout 1,2
set ylabel 'mu = shear / normal stress'
plot '{csv}' every ::1 using 2:4:3:5 with xyerrorbars pt 7 lc 'black' notitle
set ylabel 'packing fraction phi'
plot '{csv}' every ::1 using 2:1:3 with xerrorbars pt 7 lc 'black' notitle
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--phis", default="0.70,0.74,0.77,0.79,0.80,0.81", help="packing fractions, one run each")
    parser.add_argument("--side", type=int, default=32, help="side x side grains")
    parser.add_argument("--strain", type=float, default=10.0, help="shear strain of a run (half averaged)")
    parser.add_argument("--mu", default="0.5", help="contact friction while shearing")
    parser.add_argument("--tolerance", default="1e-3", help="the fix's tolerance while shearing")
    parser.add_argument("--max-iterations", default="10000", help="the fix's cap of sweeps per solve while shearing")
    parser.add_argument("--out", default=os.path.join(run.TOP, "runs", "plane_shear"))
    parser.add_argument("--lmp", default=run.BUILT_LMP_CD)
    args = parser.parse_args()

    rows = []
    for phi in args.phis.split(","):
        folder = os.path.join(args.out, f"phi_{phi}")
        variables = {"phi": phi, "side": args.side, "strain": args.strain, "mu": args.mu, "tolerance": args.tolerance,
                     "max_iterations": args.max_iterations}
        seconds = run.run_checked(run.lmp_command(args.lmp, DECK, variables, screen="none"), folder)
        rows.append(measure(folder))
        print(f"phi {phi}: I {rows[-1]['I']:.4g} mu {rows[-1]['mu']:.4g} ({seconds:.0f} s)", flush=True)
    csv = os.path.join(args.out, "plane_shear.csv")
    with open(csv, "w") as out:
        out.write("phi,I,I_se,mu,mu_se,pyy,capped,start_overlap\n")
        for r in rows:
            out.write(f"{r['phi']:.4f},{r['I']:.5g},{r['I_se']:.3g},{r['mu']:.5g},{r['mu_se']:.3g},"
                      f"{r['pyy']:.5g},{r['capped']:g},{r['overlap']:g}\n")
    figure(csv, os.path.join(args.out, "plane_shear"))
    print(open(csv).read())


if __name__ == "__main__":
    main()
