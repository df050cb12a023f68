#!/usr/bin/env python3
"""Does a chute's flow depend on the number of MPI ranks? Replicas from independent starts.

For every deposition seed the chute's bed is rained anew (one rank), then the same flow is run
from it on every rank count; cdpost measures U, phi, h and f over one window of each run, the
deck's log the Gauss-Seidel sweeps per step (over the whole flow). One
run's batch-means error understates the scatter between realisations of the flow, so the
comparison is made between replicas: per rank count the mean over seeds and its standard
error, and the paired difference from one rank (same start, so the slow variables of the bed
cancel) with its standard error and t = mean / error over the seeds.

    studies/rank_replicas.py --out runs/rank_replicas --seeds 1-10 --ranks 1 2
    studies/rank_replicas.py --out DIR --seeds 1-4 --ranks 4          # adds 4 ranks to the same starts
    studies/rank_replicas.py --out DIR --seeds 1-10 --ranks 1 2 4 --analyse-only
    studies/rank_replicas.py --out DIR2 --beds DIR --against DIR --ranks 1 --solver order=shuffle
                                                     # same beds, another contact order, paired with DIR
    studies/rank_replicas.py --out DIR --against DIR DIR2 --ranks 2 4 --analyse-only
                                                     # paired with both 1-rank runs of each bed (their mean)
    studies/rank_replicas.py --out DIR --seeds 1-10 --ranks 1 4 --analyse-only --timeline 0.2
                                                     # and the paired flowing-layer vx in 0.2 s bins

The default cell is the test chute (10 d, 200 grains, walls 8 d): the only cell on which 4 ranks
oversubscribed on 2 cores are affordable. Runs already done are skipped. Standard library only.
"""

import argparse
import concurrent.futures
import csv
import math
import os
import re
import sys

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools.cdpost import read_results
from cdtools.lammps_files import read_time_file
from cdtools.logs import log_summary
from cdtools.run import BUILT_CDPOST, BUILT_LMP_CD, DECK, lmp_command, mpi_launcher, name_value_pairs, run_checked
from cdtools.stats import mean_sd_se, pooled_sd

CDPOST_QUANTITIES = ("U", "phi", "h", "f")
STUDY_VARIABLES = {"stage", "start", "duration"}   # in.chute -vars the study sets (seed: the beds')
QUANTITIES = CDPOST_QUANTITIES + ("sweeps",)    # sweeps: per step over the whole flow, from the log


def parse_seeds(text):
    """'1-4,7' -> [1, 2, 3, 4, 7]."""
    seeds = []
    for part in text.split(","):
        found = re.fullmatch(r"(\d+)(?:-(\d+))?", part.strip())
        if not found:
            raise argparse.ArgumentTypeError(f"'{part}' is not N or N-M")
        low, high = int(found.group(1)), int(found.group(2) or found.group(1))
        if low > high:
            raise argparse.ArgumentTypeError(f"empty range '{part}'")
        seeds.extend(range(low, high + 1))
    return seeds


def options():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="work folder (resumable)")
    parser.add_argument("--seeds", type=parse_seeds, default=parse_seeds("1-10"),
                        help="deposition seeds, e.g. 1-10 or 1,3,5 (default 1-10)")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2], help="rank counts (default 1 2)")
    parser.add_argument("--duration", type=float, default=2.0, help="chute time of each flow (s)")
    parser.add_argument("--t-start", type=float, default=0.6, help="start of the analysed window (s)")
    parser.add_argument("--segment", type=float, default=0.5, help="spectral segment (s)")
    parser.add_argument("--cell", default="L=10 grains=200 wall_height=8 mu=0.5 theta=24",
                        help="in.chute -vars of the cell, 'name=value ...'")
    parser.add_argument("--solver", default="", help="extra in.chute -vars of the flow, 'name=value ...'")
    parser.add_argument("--lmp", default=BUILT_LMP_CD)
    parser.add_argument("--cdpost", default=BUILT_CDPOST)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--cores", type=int, default=os.cpu_count(), help="cores to fill (default all)")
    parser.add_argument("--beds", help="take the beds (seedN/deposition) from this study's folder: "
                        "flows of other settings from the same starts")
    parser.add_argument("--against", nargs="+", metavar="DIR",
                        help="pair with the 1-rank runs of these studies' folders (with several, their "
                        "mean per bed) instead of this study's fewest ranks (same beds: use --beds)")
    parser.add_argument("--timeline", type=float, metavar="SECONDS",
                        help="also the paired difference of the flowing layer's mean vx (flow.time) in "
                        "bins of this width over the whole flow: a steady offset or a passing excursion?")
    parser.add_argument("--analyse-only", action="store_true")
    args = parser.parse_args()
    if min(args.ranks) < 1 or args.cores < 1:
        parser.error(f"--ranks {args.ranks} and --cores {args.cores} must be at least 1")
    if args.timeline is not None and not 0 < args.timeline <= args.duration:
        parser.error(f"--timeline {args.timeline} must lie in (0, --duration {args.duration}]")
    if args.timeline and len(set(args.ranks)) < 2 and not args.against:
        parser.error("--timeline pairs runs: give two rank counts or --against")
    if not 0 <= args.t_start < args.duration:
        parser.error(f"--t-start {args.t_start} must lie in [0, --duration {args.duration})")
    check_variables(parser, args)
    return args


def check_variables(parser, args):
    """--cell and --solver as {name: value} (args.cell_vars, args.solver_vars): name=value pairs,
    no name in both, none that the study sets itself."""
    for name in ("cell", "solver"):
        try:
            setattr(args, name + "_vars", name_value_pairs(getattr(args, name)))
        except ValueError as error:
            parser.error(f"--{name}: {error}")
    # LAMMPS keeps the first -var of a name: a second one would be ignored without a word.
    both = set(args.cell_vars) & set(args.solver_vars)
    if both:
        parser.error(f"--solver sets {', '.join(sorted(both))}, already set by --cell (give it in one of them)")
    for name, reserved in (("cell", STUDY_VARIABLES | {"seed"}), ("solver", STUDY_VARIABLES)):
        taken = set(getattr(args, name + "_vars")) & reserved
        if taken:
            parser.error(f"--{name} sets {', '.join(sorted(taken))}, which the study sets itself")


def deposition(args, seed):
    folder = os.path.join(args.beds or args.out, f"seed{seed}", "deposition")
    restart = os.path.join(folder, "deposition.restart")
    if args.beds and not os.path.exists(restart):
        raise RuntimeError(f"--beds {args.beds}: no bed of seed {seed} ({restart})")
    if not os.path.exists(restart):
        variables = {"stage": "deposition", "seed": seed, **args.cell_vars}
        run_checked(lmp_command(args.lmp, DECK, variables, screen="none"), folder)
    return restart


def run_folder(study, seed, ranks):
    return os.path.join(study, f"seed{seed}", f"np{ranks}")


def flow(args, seed, ranks):
    """Flow from seed's deposition on `ranks` ranks, then cdpost; returns seconds spent (0 if done)."""
    folder = run_folder(args.out, seed, ranks)
    if os.path.exists(os.path.join(folder, "post", "results.csv")):
        return 0.0
    start = deposition(args, seed)
    variables = {"stage": "flow", "start": start, "duration": f"{args.duration:g}", **args.cell_vars,
                 **args.solver_vars}
    spent = run_checked(lmp_command(args.lmp, DECK, variables, screen="none",
                                    launcher=mpi_launcher(args.mpirun, ranks)), folder)
    with open(os.path.join(folder, "log.lammps")) as src:
        grid = re.search(r"(\d+) by (\d+) by (\d+) MPI processor grid", src.read())
    if ranks > 1 and (not grid or int(grid.group(1)) != ranks):
        sys.exit(f"rank_replicas: {folder}: the cell was not split along x into {ranks}")
    run_checked([args.cdpost, "run", folder, "--z0", str(log_summary(folder, "CHUTE")["y_top_m"]),
                 "--segment", f"{args.segment:g}", "--t-start", f"{args.t_start:g}"], folder)
    return spent


def run_all(args):
    """Depositions and 1-rank flows fill the cores one run each; N-rank flows take N cores."""
    jobs = [(seed, ranks) for ranks in sorted(args.ranks) for seed in args.seeds]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.cores) as pool:
        list(pool.map(lambda seed: deposition(args, seed), args.seeds))
    for ranks in sorted(args.ranks):
        workers = max(1, args.cores // ranks)
        todo = [seed for seed, r in jobs if r == ranks]
        with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
            for seed, spent in zip(todo, pool.map(lambda s: flow(args, s, ranks), todo)):
                if spent:
                    print(f"seed {seed} on {ranks} ranks: {spent:.0f} s wall", flush=True)


# ---------------------------------------------------------------- analysis

def results(study, seed, ranks):
    """cdpost's U, phi, h, f and the log's sweeps per step of a finished run; None if not finished."""
    folder = run_folder(study, seed, ranks)
    path = os.path.join(folder, "post", "results.csv")
    if not os.path.exists(path):
        return None
    values = {name: entry[0] for name, entry in read_results(path).items()}
    missing = [q for q in CDPOST_QUANTITIES if q not in values]
    if missing:
        raise RuntimeError(f"{path}: no row {', '.join(missing)} (truncated or not cdpost's?)")
    solver = log_summary(folder, "CHUTE")
    values["sweeps"] = solver["sweeps"] / solver["steps_solved"]
    return {q: values[q] for q in QUANTITIES}


def mean_run(runs, keys=QUANTITIES):
    """Key by key the mean of several runs from one bed; None unless all exist."""
    if not all(runs):
        return None
    return {q: sum(run[q] for run in runs) / len(runs) for q in keys}


def paired_differences(table, seeds, baseline, others, keys=QUANTITIES):
    """{ranks: {key: [value on ranks - value on baseline, one per seed run on both]}}."""
    differences = {}
    for ranks in others:
        pairs = [s for s in seeds if table[(s, ranks)] and table[(s, baseline)]]
        differences[ranks] = {q: [table[(s, ranks)][q] - table[(s, baseline)][q] for s in pairs]
                              for q in keys}
    return differences


def difference_cell(values, pooled, with_sd=False):
    """'mean ± SE (t ...)' of paired differences, SE = the pooled sd / sqrt(pairs)."""
    mean, sd, _ = mean_sd_se(values)
    error = pooled / math.sqrt(len(values)) if values else math.nan
    t = mean / error if error > 0 else math.nan    # nan also for identical runs (0 / 0)
    return f"{mean:+.3g} ± {error:.2g} (t {t:+.1f}" + (f"; sd {sd:.2g})" if with_sd else ")")


def write_csv(path, table):
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["seed", "ranks", *QUANTITIES])
        for (seed, ranks), row in sorted(table.items()):
            if row:
                writer.writerow([seed, ranks, *(row[q] for q in QUANTITIES)])


def analyse(args):
    table = {(s, r): results(args.out, s, r) for s in args.seeds for r in args.ranks}
    if not any(table.values()):
        raise RuntimeError(f"{args.out}: no finished run of these seeds and ranks (seedN/npR/post/results.csv)")
    print(f"window {args.t_start:g}-{args.duration:g} s; cell {args.cell}; {args.solver or 'default solver'}\n")
    print_replicas(args, table)
    write_csv(os.path.join(args.out, "replicas.csv"), table)
    baseline, others = min(args.ranks), [r for r in args.ranks if r != min(args.ranks)]
    name = f"{baseline} rank(s)"
    if args.against:    # the 1-rank runs of other studies from the same beds
        baseline, others = "against", list(args.ranks)
        name = f"the 1-rank runs of {' and '.join(args.against)}"
        if len(args.against) > 1:
            name += " (their mean per bed)"
        for s in args.seeds:
            table[(s, baseline)] = mean_run([results(study, s, 1) for study in args.against])
    if not others:
        return
    print_differences(table, args.seeds, baseline, others, name)
    if args.timeline:
        print_timeline(args, table, baseline, others, name)


def print_replicas(args, table):
    """Per rank count: the mean over seeds, its standard error and the seeds' sd."""
    print("| ranks | seeds | " + " | ".join(f"{q} mean ± SE (sd)" for q in QUANTITIES) + " |")
    print("|---" * (len(QUANTITIES) + 2) + "|")
    for ranks in args.ranks:
        done = [s for s in args.seeds if table[(s, ranks)]]
        cells = []
        for q in QUANTITIES:
            mean, sd, error = mean_sd_se([table[(s, ranks)][q] for s in done])
            cells.append(f"{mean:.4g} ± {error:.2g} ({sd:.2g})")
        print(f"| {ranks} | {len(done)} | " + " | ".join(cells) + " |")


def print_differences(table, seeds, baseline, others, name):
    differences = paired_differences(table, seeds, baseline, others)
    pooled = {q: pooled_sd([d[q] for d in differences.values()]) for q in QUANTITIES}
    print(f"\npaired differences from {name}, same start: mean ± SE (t = mean/SE; sd of "
          "the differences). SE = pooled sd / sqrt(pairs), the sd pooled over the rank counts, "
          "which share the scatter of realisations (one count's own sd is unreliable from few pairs)\n")
    print("| ranks | pairs | " + " | ".join(f"Δ{q}" for q in QUANTITIES) + " |")
    print("|---" * (len(QUANTITIES) + 2) + "|")
    for ranks, per_quantity in differences.items():
        pairs = len(per_quantity[QUANTITIES[0]])
        cells = [difference_cell(per_quantity[q], pooled[q], with_sd=True) for q in QUANTITIES]
        print(f"| {ranks} | {pairs} | " + " | ".join(cells) + " |")


# ---------------------------------------------------------------- timeline

def flow_series(folder):
    """The deck's flow.time as [(chute time in s, mean vx of the flowing grains in m/s)]."""
    path = os.path.join(folder, "flow.time")
    if not os.path.exists(path):
        raise RuntimeError(f"{path}: missing (the flow's time series)")
    rows = read_time_file(path)
    if rows and not {"v_time", "v_u_flow"} <= set(rows[0]):
        raise RuntimeError(f"{path}: no header naming v_time and v_u_flow")
    return [(row["v_time"], row["v_u_flow"]) for row in rows]


def bin_count(width, duration):
    """Bins of `width` covering [0, duration), the last one possibly shorter."""
    return math.ceil(duration / width - 1e-9)


def bin_span(k, width, duration):
    return f"{k * width:g}-{min((k + 1) * width, duration):g}"


def bin_means(series, width, duration, path):
    """{bin k: mean over [k width, (k+1) width)} for the bins covering [0, duration)."""
    bins = bin_count(width, duration)
    sums, counts = [0.0] * bins, [0] * bins
    for t, u in series:
        k = math.floor(t / width + 1e-9)
        if 0 <= k < bins and t < duration:
            sums[k] += u
            counts[k] += 1
    for k, count in enumerate(counts):
        if not count:
            raise RuntimeError(f"{path}: no sample in {bin_span(k, width, duration)} s (truncated?)")
    return {k: sums[k] / counts[k] for k in range(bins)}


def run_bins(args, study, seed, ranks):
    folder = run_folder(study, seed, ranks)
    return bin_means(flow_series(folder), args.timeline, args.duration, os.path.join(folder, "flow.time"))


def print_timeline(args, finished, baseline, others, name):
    """ΔU_flow per time bin over the whole flow, paired as the table above (`finished`: its runs);
    the baseline's own U_flow per bin beside it. A drag would show as a steady offset once the
    layer flows."""
    keys = range(bin_count(args.timeline, args.duration))
    seeds = [s for s in args.seeds if finished[(s, baseline)]]
    table = {}
    for s in seeds:
        for ranks in others:
            table[(s, ranks)] = run_bins(args, args.out, s, ranks) if finished[(s, ranks)] else None
        table[(s, baseline)] = (mean_run([run_bins(args, study, s, 1) for study in args.against], keys)
                                if args.against else run_bins(args, args.out, s, baseline))
    differences = paired_differences(table, seeds, baseline, others, keys=keys)
    pooled = {k: pooled_sd([d[k] for d in differences.values()]) for k in keys}
    print(f"\nthe flowing layer's mean vx (flow.time's v_u_flow, m/s) in {args.timeline:g} s bins: "
          f"{name} and the paired differences from it, mean ± SE (t), SE as above\n")
    print("| time (s) | baseline | " + " | ".join(f"ΔU_flow on {r} rank(s)" for r in differences) + " |")
    print("|---" * (len(differences) + 2) + "|")
    for k in keys:
        reference = sum(table[(s, baseline)][k] for s in seeds) / len(seeds)
        cells = [difference_cell(d[k], pooled[k]) for d in differences.values()]
        print(f"| {bin_span(k, args.timeline, args.duration)} | {reference:.4g} | " + " | ".join(cells) + " |")


def main():
    args = options()
    try:
        if not args.analyse_only:
            run_all(args)
        analyse(args)
    except RuntimeError as error:    # a failed run, or a log without the deck's summary line
        sys.exit(f"rank_replicas: {error}")


if __name__ == "__main__":
    main()
