#!/usr/bin/env python3
"""Does the domain-decomposed Gauss-Seidel solve the same contact problem as one rank?

From chute snapshots (restart files written by inputs/in.chute's flow), one time step of the
same flow is solved on each rank count at a tight reference tolerance and at the compared
tolerances. Over the grains' translational velocities after the step:

    error = |v - v_ref| / |v_ref - v_start|   (relative to the step's change of velocity)
    bias  = mass-weighted mean of (vx - vx_ref) in units of g sin(theta) dt   (a drag or a push)

with v_ref the same rank count's reference-tolerance solve: how far stopping at a tolerance
leaves the solve from its solution, on N ranks against one. The N-rank reference-tolerance
solve against the 1-rank one shows whether the decomposed iteration reaches the same solution.
A frictional packing can have several solutions; where the N-rank one differs, 1-rank solves
with other contact orders and cold starts are tried: if one of them reaches the N-rank
solution, that solution is one of the problem's own.

    studies/rank_solutions.py --out runs/rank_solutions --ranks 1 2 4 \\
        --snapshots runs/rank_replicas/seed*/np1/chute.restart

The cell's in.chute -vars (--cell) must be those of the flow that wrote the snapshots.
Standard library only.
"""

import argparse
import csv
import math
import os
import statistics
import sys

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools.lammps_files import read_dump, read_time_file
from cdtools.run import (BUILT_LMP_CD, DECK, check_snapshot_study, lmp_command, mpi_launcher, name_value_pairs,
                         run_checked)

SAME_SOLUTION = 1e-3    # error below which two solves count as one solution (see doc/benchmarks.md)
# Columns of in.chute's solver.time: the sweeps and the fraction of steps converged.
SWEEPS_COLUMN, CONVERGED_COLUMN = "f_cd[1]", "f_cd[7]"
# in.chute -vars each solve sets (--cell must leave them alone).
STUDY_VARIABLES = {"stage", "start", "dt", "duration", "sample_rate", "solver_interval", "tolerance",
                   "max_iterations", "order", "seed", "warm_start"}
VELOCITY_COLUMNS = ("id", "radius", "vx", "vy", "omegaz")
ALTERNATIVE_ORDERS = [dict(order="shuffle", seed=str(s), warm_start=w) for w in ("yes", "no") for s in (1, 2, 3)]


def options(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="work folder (resumable)")
    parser.add_argument("--snapshots", nargs="+", required=True, help="restart files of in.chute's flow")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4], help="rank counts (default 1 2 4)")
    parser.add_argument("--tolerances", type=float, nargs="+", default=[1e-3, 1e-4],
                        help="Gauss-Seidel tolerances compared (default 1e-3 1e-4)")
    parser.add_argument("--reference-tolerance", type=float, default=1e-9)
    parser.add_argument("--max-iterations", type=int, default=200000, help="sweep cap of every solve")
    parser.add_argument("--cell", default="L=10 grains=200 wall_height=8 mu=0.5 theta=24",
                        help="in.chute -vars of the snapshots' flow, 'name=value ...'")
    parser.add_argument("--dt", type=float, default=2.0e-5, help="time step of the snapshots' flow (s)")
    parser.add_argument("--lmp", default=BUILT_LMP_CD)
    parser.add_argument("--mpirun", default="mpirun")
    args = parser.parse_args(argv)
    if min(args.ranks) < 1 or args.max_iterations < 1 or args.dt <= 0:
        parser.error("--ranks, --max-iterations must be at least 1 and --dt > 0")
    check_snapshot_study(parser, args)
    try:
        args.cell_vars = name_value_pairs(args.cell)
    except ValueError as error:
        parser.error(f"--cell '{args.cell}': {error}")
    # LAMMPS keeps the first -var of a name: these would override the study's own settings.
    taken = set(args.cell_vars) & STUDY_VARIABLES
    if taken:
        parser.error(f"--cell sets {', '.join(sorted(taken))}, which the study sets itself")
    return args


# ---------------------------------------------------------------- running

def read_velocities(path):
    """{id: (radius, vx, vy, spin)} and the time step of a dump written by velocity_dump."""
    try:
        frames = read_dump(path)
        if not frames:
            raise ValueError("no complete frame")
        step, _, atoms = frames[0]
        columns = sorted(next(iter(atoms.values()), {}))
        if columns != sorted(VELOCITY_COLUMNS):
            raise ValueError(f"columns {columns}")
    except (OSError, RuntimeError, ValueError) as error:
        raise RuntimeError(f"{path}: not a complete velocity dump ({error})")
    return {i: tuple(a[c] for c in VELOCITY_COLUMNS[1:]) for i, a in atoms.items()}, step


def velocity_dump(args, restart, dump):
    """The velocities stored in a restart file, through lmp's -restart2dump."""
    if not os.path.exists(dump):
        folder = os.path.dirname(dump)
        run_checked([args.lmp, "-restart2dump", os.path.abspath(restart), "all", "custom", os.path.basename(dump),
                     *VELOCITY_COLUMNS, "modify", "sort", "id", "format", "float", "%.17g",
                     "-log", "none", "-screen", "none"], folder)
    return read_velocities(dump)


def solve_one_step(args, snapshot, start_step, folder, ranks, solver):
    """One step of the flow from snapshot on `ranks` ranks with in.chute -vars `solver`;
    returns (velocities after it, sweeps, whether it converged)."""
    solved = os.path.join(folder, "solver.time")
    if not os.path.exists(os.path.join(folder, "after.dump")):
        launcher = mpi_launcher(args.mpirun, ranks) if ranks > 1 else []
        one_step = {"stage": "flow", "start": os.path.abspath(snapshot), "dt": f"{args.dt:.17g}",
                    "duration": f"{(start_step + 1) * args.dt:.17g}", "sample_rate": f"{1 / args.dt:.17g}",
                    "solver_interval": f"{args.dt:.17g}", **solver}
        run_checked(lmp_command(args.lmp, DECK, {**args.cell_vars, **one_step}, screen="none", launcher=launcher),
                    folder)
        velocity_dump(args, os.path.join(folder, "chute.restart"), os.path.join(folder, "after.dump"))
    after, step = read_velocities(os.path.join(folder, "after.dump"))
    rows = read_time_file(solved)
    if step != start_step + 1 or not rows or int(rows[-1]["TimeStep"]) != step:
        raise RuntimeError(f"{folder}: expected one step from step {start_step}, found step {step} "
                           "(snapshot written at another --dt?)")
    return after, rows[-1][SWEEPS_COLUMN], rows[-1][CONVERGED_COLUMN] == 1.0


# ---------------------------------------------------------------- measures

def solve_error(start, after, reference):
    """|v - v_ref| / |v_ref - v_start| over the grains' translational velocities."""
    wrong = sum((after[i][1] - r[1]) ** 2 + (after[i][2] - r[2]) ** 2 for i, r in reference.items())
    change = sum((r[1] - start[i][1]) ** 2 + (r[2] - start[i][2]) ** 2 for i, r in reference.items())
    return math.sqrt(wrong / change) if change > 0 else math.inf


def mean_vx_bias(after, reference, gravity_step):
    """Mass-weighted mean of vx - vx_ref (discs of one density: mass ~ r^2) / gravity_step."""
    mass = sum(r[0] ** 2 for r in reference.values())
    shift = sum(r[0] ** 2 * (after[i][1] - r[1]) for i, r in reference.items())
    return shift / mass / gravity_step


def cell_value(args, name, default):
    return float(args.cell_vars.get(name, default))


# ---------------------------------------------------------------- study

def study_snapshot(args, index, snapshot):
    """Rows {snapshot, ranks, tolerance, error, bias, sweeps, converged, other_solution}. At the
    reference tolerance the error and bias are those of the rank count's solve from the 1-rank
    one; at the other tolerances those from the same rank count's reference-tolerance solve
    (so that a second solution of the problem does not pass for an inaccurate solve)."""
    base = os.path.join(args.out, f"snapshot{index}")
    os.makedirs(base, exist_ok=True)
    start, step = velocity_dump(args, snapshot, os.path.join(base, "start.dump"))
    gravity_step = cell_value(args, "g", 9.81) * math.sin(math.radians(cell_value(args, "theta", 24))) * args.dt
    tight = dict(tolerance=f"{args.reference_tolerance:g}", max_iterations=str(args.max_iterations))

    def solve(ranks, solver, name):
        return solve_one_step(args, snapshot, step, os.path.join(base, name), ranks, solver)

    def row(ranks, tolerance, solution, reference, sweeps, converged):
        return dict(snapshot=index, ranks=ranks, tolerance=tolerance, error=solve_error(start, solution, reference),
                    bias=mean_vx_bias(solution, reference, gravity_step), sweeps=sweeps, converged=converged,
                    other_solution="")

    one_rank, *one_rank_report = solve(1, tight, "np1_reference")
    rows = [row(1, args.reference_tolerance, one_rank, one_rank, *one_rank_report)]
    for ranks in args.ranks:
        own = one_rank
        if ranks > 1:
            own, *report = solve(ranks, tight, f"np{ranks}_reference")
            rows.append(row(ranks, args.reference_tolerance, own, one_rank, *report))
            if rows[-1]["error"] >= SAME_SOLUTION:
                rows[-1]["other_solution"] = reached_by_one_rank(
                    start, own, lambda k, extra: solve(1, {**tight, **extra}, f"np1_alternative{k}")[0])
        for tolerance in args.tolerances:
            solution, *report = solve(ranks, dict(tight, tolerance=f"{tolerance:g}"), f"np{ranks}_tol{tolerance:g}")
            rows.append(row(ranks, tolerance, solution, own, *report))
    return rows


def reached_by_one_rank(start, target, solve_alternative):
    """'yes k' if the k-th of ALTERNATIVE_ORDERS on one rank reaches target's solution, else 'no'."""
    for k, extra in enumerate(ALTERNATIVE_ORDERS):
        if solve_error(start, solve_alternative(k, extra), target) < SAME_SOLUTION:
            return f"yes {k}"
    return "no"


def summarise(args, rows):
    keyed = {(r["snapshot"], r["ranks"], r["tolerance"]): r for r in rows}
    snapshots = sorted({r["snapshot"] for r in rows})
    tight = args.reference_tolerance
    print(f"{len(snapshots)} snapshots; errors and biases from each rank count's own solve at tolerance {tight:g}")
    print("\n| ranks | tolerance | median error | error / 1-rank error: median (range) | "
          "bias - 1-rank bias: mean ± SE | median sweeps |")
    print("|---|---|---|---|---|---|")
    for tolerance in args.tolerances:
        for ranks in args.ranks:
            here = [keyed[(s, ranks, tolerance)] for s in snapshots]
            one = [keyed[(s, 1, tolerance)] for s in snapshots]
            ratios = [h["error"] / o["error"] for h, o in zip(here, one) if o["error"] > 0]
            shifts = [h["bias"] - o["bias"] for h, o in zip(here, one)]
            spread = statistics.stdev(shifts) / math.sqrt(len(shifts)) if len(shifts) > 1 else math.nan
            print(f"| {ranks} | {tolerance:g} | {statistics.median(h['error'] for h in here):.3g} | "
                  f"{statistics.median(ratios):.3f} ({min(ratios):.2f}-{max(ratios):.2f}) | "
                  f"{statistics.mean(shifts):+.4f} ± {spread:.4f} | "
                  f"{statistics.median(h['sweeps'] for h in here):g} |")
    capped = [s for s in snapshots for r in args.ranks if not keyed[(s, r, tight)]["converged"]]
    print(f"\nat tolerance {tight:g} (sweep cap reached in snapshots {sorted(set(capped)) or 'none'}): "
          "N-rank solution against the 1-rank one")
    for ranks in [r for r in args.ranks if r > 1]:
        here = [keyed[(s, ranks, tight)] for s in snapshots]
        other = [h for h in here if h["error"] >= SAME_SOLUTION]
        print(f"  {ranks} ranks: error median {statistics.median(h['error'] for h in here):.2g}, "
              f"{len(here) - len(other)} of {len(here)} below {SAME_SOLUTION:g}" +
              "".join(f"; snapshot {h['snapshot']}: {h['error']:.2g}, reached by a 1-rank order: {h['other_solution']}"
                      for h in other))


def main(argv=None):
    args = options(argv)
    try:
        rows = [row for index, snapshot in enumerate(args.snapshots) for row in study_snapshot(args, index, snapshot)]
    except RuntimeError as error:
        sys.exit(f"rank_solutions: {error}")
    with open(os.path.join(args.out, "solutions.csv"), "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    for index, snapshot in enumerate(args.snapshots):
        print(f"snapshot{index}: {snapshot}")
    summarise(args, rows)


if __name__ == "__main__":
    main()
