#!/usr/bin/env python3
"""How far one step's solve stops from its solution, by depth in the bed.

From saved states of inputs/in.chute (restart files: the bed at rest, or a flow), one time step
is solved at a tight reference tolerance and at each compared tolerance, from the same state
and the same warm start. Over the grains of each depth band (z = y - y_top in d, y_top the wall
tops), with v the translational velocity after the step and v_ref the reference solve's:

    rms_error  = rms |v - v_ref| / sqrt(g d)        the velocity error the solve leaves
    mean_dvx   = mean (vx - vx_ref) / sqrt(g d)     its part that reads as creep (a drift along x)
    rms_ref    = rms |v_ref| / sqrt(g d)            the band's own velocity, for scale

and the work of each solve: sweeps, local solves per contact (the fix's outputs 1 and 11) and
the step's loop time. A solver change shows its effect on the bed by running this on the same
states (doc/bed.md). Results: <out>/error_by_depth.csv and a table on the standard output.

    bench/solve_error_by_depth.py --out runs/solve_error --cell "reading=layer L=45 mu=0.5 theta=12" \\
        --snapshots runs/bed/floor/tol1e-3_fixed/chute.restart --tolerances 1e-3 1e-4 1e-5

The cell's in.chute -vars (--cell) must be those of the run that wrote the snapshots (walls and
friction are rebuilt from them). Standard library only.
"""

import argparse
import csv
import math
import os
import subprocess
import sys

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "studies"))

from cdtools.lammps_files import read_dump, read_time_file
from cdtools.logs import read_progress
from cdtools.run import BUILT_LMP_CD, check_snapshot_study, deck_copy, lmp_command, name_value_pairs, run_checked

STATE_COLUMNS = ("id", "radius", "x", "y", "vx", "vy")
# in.chute -vars each solve sets (--cell must leave them alone).
STUDY_VARIABLES = {"stage", "start", "dt", "duration", "sample_rate", "solver_interval", "tolerance",
                   "max_iterations", "adapt_dt", "profile_interval", "restart_interval", "snapshot_interval"}
# Columns of in.chute's solver.time: sweeps, final norm, local solves per contact, fraction of
# steps converged.
SWEEPS, NORM, LOCAL_SOLVES, CONVERGED = "f_cd[1]", "f_cd[2]", "f_cd[11]", "f_cd[7]"


def options(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="work folder (solves already made are reused)")
    parser.add_argument("--snapshots", nargs="+", required=True, help="restart files of in.chute's flow stage")
    parser.add_argument("--tolerances", type=float, nargs="+", default=[1e-3, 1e-4, 1e-5])
    parser.add_argument("--reference-tolerance", type=float, default=1e-9)
    parser.add_argument("--max-iterations", type=int, default=2000000, help="sweep cap of every solve")
    parser.add_argument("--cell", default="reading=layer L=45 mu=0.5 theta=24",
                        help="in.chute -vars of the snapshots' run, 'name=value ...'")
    parser.add_argument("--dt", type=float, default=1.0e-4, help="the step solved (s)")
    parser.add_argument("--band", type=float, default=3.0, help="depth band width (d)")
    parser.add_argument("--solver", default="",
                        help="extra in.chute -vars of the compared solves, 'name=value ...' (e.g. frozen_depth=20)")
    parser.add_argument("--reference-solver", default="",
                        help="extra in.chute -vars of the reference solve (default none: the deck's full problem)")
    parser.add_argument("--lmp", default=BUILT_LMP_CD)
    args = parser.parse_args(argv)
    if args.max_iterations < 1 or args.dt <= 0 or args.band <= 0:
        parser.error("--max-iterations must be at least 1, --dt and --band > 0")
    check_snapshot_study(parser, args)
    try:
        args.cell_vars = name_value_pairs(args.cell)
        args.solver_vars = name_value_pairs(args.solver)
        args.reference_vars = name_value_pairs(args.reference_solver)
    except ValueError as error:
        parser.error(f"--cell/--solver/--reference-solver: {error}")
    taken = (set(args.cell_vars) | set(args.solver_vars) | set(args.reference_vars)) & STUDY_VARIABLES
    if taken:
        parser.error(f"--cell/--solver set {', '.join(sorted(taken))}, which the study sets itself")
    return args


def cell_value(args, name, default):
    return float(args.cell_vars.get(name, default))


def state_dump(args, restart, dump):
    """{id: {column: value}} and the time step of the state stored in a restart file."""
    if not os.path.exists(dump):
        run_checked([args.lmp, "-restart2dump", os.path.abspath(restart), "all", "custom", os.path.basename(dump),
                     *STATE_COLUMNS, "modify", "sort", "id", "format", "float", "%.17g",
                     "-log", "none", "-screen", "none"], os.path.dirname(dump))
    frames = read_dump(dump)
    if not frames:
        raise RuntimeError(f"{dump}: no complete frame")
    step, _, atoms = frames[0]
    return atoms, step


def restart_time(args, restart, folder):
    """The chute time (s) stored in a restart file: a run with adapt_dt counts its steps at the
    step it took, so the time, not the step, places the one step solved. The fix (ID cd, as in
    in.chute) restores the time when it takes up its restart state."""
    deck = os.path.join(folder, "in.restart_time")
    with open(deck, "w") as out:
        out.write(f"read_restart {os.path.abspath(restart)}\nfix cd all contact/dynamics 0.5 0.5\n"
                  "print \"RESTART_TIME $(time:%.17g)\"\n")
    done = subprocess.run([args.lmp, "-in", deck, "-log", "none"], cwd=folder, capture_output=True, text=True)
    times = [line.split()[1] for line in done.stdout.splitlines() if line.startswith("RESTART_TIME ")]
    if done.returncode != 0 or not times:
        raise RuntimeError(f"{restart}: its chute time could not be read")
    return float(times[0])


def solve_one_step(args, snapshot, start_step, folder, tolerance, solver_vars):
    """One step of dt from snapshot at `tolerance` (fixed step) with the in.chute -vars
    solver_vars: the state after it and its work."""
    if not os.path.exists(os.path.join(folder, "after.dump")):
        one_step = {"stage": "flow", "start": os.path.abspath(snapshot), "adapt_dt": "no", "dt": f"{args.dt:.17g}",
                    "duration": f"{(start_step + 1) * args.dt:.17g}", "sample_rate": f"{1 / args.dt:.17g}",
                    "solver_interval": f"{args.dt:.17g}", "profile_interval": f"{args.dt:.17g}",
                    "snapshot_interval": f"{args.dt:.17g}", "restart_interval": f"{args.dt:.17g}",
                    "tolerance": f"{tolerance:g}", "max_iterations": str(args.max_iterations)}
        variables = {**args.cell_vars, **solver_vars, **one_step}
        run_checked(lmp_command(args.lmp, deck_copy(args.out), variables, screen="none"), folder)
        state_dump(args, os.path.join(folder, "chute.restart"), os.path.join(folder, "after.dump"))
    after, step = state_dump(args, None, os.path.join(folder, "after.dump"))
    if step != start_step + 1:
        raise RuntimeError(f"{folder}: expected one step from step {start_step}, found step {step} "
                           "(snapshot at a chute time that is not a whole number of --dt?)")
    row = read_time_file(os.path.join(folder, "solver.time"))[-1]
    work = dict(sweeps=row[SWEEPS], local_solves=row[LOCAL_SOLVES], norm=row[NORM], converged=row[CONVERGED] == 1.0,
                loop_seconds=read_progress(os.path.join(folder, "log.lammps")).wall)
    return after, work


def band_rows(args, start, after, reference):
    """Per depth band: grains, rms_error, mean_dvx, rms_ref (sqrt(g d) units)."""
    d = float(args.cell_vars.get("d", 5.0e-4))
    y_top = cell_value(args, "wall_height", 30) * d
    scale = math.sqrt(cell_value(args, "g", 9.81) * d)
    bands = {}
    for i, ref in reference.items():
        z = (start[i]["y"] - y_top) / d
        band = math.floor(z / args.band)
        dvx, dvy = after[i]["vx"] - ref["vx"], after[i]["vy"] - ref["vy"]
        sums = bands.setdefault(band, [0, 0.0, 0.0, 0.0])
        sums[0] += 1
        sums[1] += dvx * dvx + dvy * dvy
        sums[2] += dvx
        sums[3] += ref["vx"] ** 2 + ref["vy"] ** 2
    return [dict(z_low=b * args.band, z_high=(b + 1) * args.band, grains=n,
                 rms_error=math.sqrt(e / n) / scale, mean_dvx=s / n / scale, rms_ref=math.sqrt(r / n) / scale)
            for b, (n, e, s, r) in sorted(bands.items())]


def study_snapshot(args, index, snapshot):
    base = os.path.join(args.out, f"snapshot{index}")
    os.makedirs(base, exist_ok=True)
    start, _ = state_dump(args, snapshot, os.path.join(base, "start.dump"))
    step = round(restart_time(args, snapshot, base) / args.dt)    # the deck counts steps of dt from there
    reference_name = "_".join(["reference"] + [f"{k}{v}" for k, v in args.reference_vars.items()])
    reference, reference_work = solve_one_step(args, snapshot, step, os.path.join(base, reference_name),
                                               args.reference_tolerance, args.reference_vars)
    if not reference_work["converged"]:
        print(f"snapshot{index}: the reference solve stopped at the sweep cap ({args.max_iterations}) with the "
              f"norm at {reference_work['norm']:.3g}: errors below about that level are not resolved", flush=True)
    rows = []
    for tolerance in args.tolerances:
        name = "_".join([f"tol{tolerance:g}"] + [f"{k}{v}" for k, v in args.solver_vars.items()])
        after, work = solve_one_step(args, snapshot, step, os.path.join(base, name), tolerance, args.solver_vars)
        for band in band_rows(args, start, after, reference):
            rows.append(dict(snapshot=index, solver=args.solver, tolerance=tolerance, **band, **work))
    return rows, reference_work


def main(argv=None):
    args = options(argv)
    rows = []
    try:
        for index, snapshot in enumerate(args.snapshots):
            snapshot_rows, reference_work = study_snapshot(args, index, snapshot)
            rows += snapshot_rows
            print(f"snapshot{index}: {snapshot}; reference {args.reference_tolerance:g}: "
                  f"{reference_work['sweeps']:g} sweeps to norm {reference_work['norm']:.3g}, "
                  f"{reference_work['loop_seconds']:.1f} s")
    except RuntimeError as error:
        sys.exit(f"solve_error_by_depth: {error}")
    label = "_".join(f"{k}{v}" for k, v in args.solver_vars.items())
    with open(os.path.join(args.out, f"error_by_depth{'_' + label if label else ''}.csv"), "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("| snapshot | tolerance | sweeps | local solves | z (d) | grains | rms error | mean dvx | rms v_ref |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['snapshot']} | {r['tolerance']:g} | {r['sweeps']:g} | {r['local_solves']:.0f} | "
              f"{r['z_low']:g} … {r['z_high']:g} | {r['grains']} | {r['rms_error']:.2e} | {r['mean_dvx']:+.2e} | "
              f"{r['rms_ref']:.2e} |")


if __name__ == "__main__":
    main()
