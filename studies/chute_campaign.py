#!/usr/bin/env python3
"""Run the erodible-bed chute series with inputs/in.chute (doc/chute.md).

Every deposition and every run has its own folder under --out (depositions/<name>/,
runs/<name>/ with legs/NN/, one lmp_cd process each; series/<analysis>/ for cdpost's series
analyses). Interrupt the runner (Ctrl-C, kill, power cut) and start it again with the same
options: finished runs are skipped, unfinished ones continue from their newest restart. The
folder layout and the steps of a run: studies/cdtools/campaign/__init__.py.

Standard library only.
"""

import argparse
import os
import shlex
import sys

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.campaign.plan import SERIES, build_jobs
from cdtools.campaign.report import write_results
from cdtools.campaign.schedule import list_jobs, run_campaign
from cdtools.run import BUILT_LMP_CD, TOP, mpi_launcher


def series_summary():
    return "Series: " + "; ".join(
        f"{k}: " + ", ".join(f"mu {p['mu']} theta {p['theta']} L {p['L']}" for p in v[:1]) + f" ... ({len(v)} runs)"
        for k, v in SERIES.items())


def argument_parser():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=series_summary())
    parser.add_argument("--out", default=os.path.join(TOP, "runs", "campaign"),
                        help="results folder (default runs/campaign)")
    parser.add_argument("--series", action="append", choices=sorted(SERIES),
                        help="series to run (repeatable; default all)")
    parser.add_argument("--only", action="append", metavar="GLOB",
                        help="only runs whose name matches, e.g. 'mu0.5_theta2[45]_*' (repeatable)")
    parser.add_argument("--duration", type=float, default=10.0,
                        help="chute time of each run in s (default 10)")
    parser.add_argument("--max-duration", type=float, default=20.0,
                        help="extend a run that cdpost finds not stationary, up to this chute time "
                             "in s (default 20; at most --duration disables)")
    parser.add_argument("--extend", type=float, default=5.0, help="extension step in s (default 5)")
    parser.add_argument("--min-window-seconds", type=float, default=3.0,
                        help="extend a run whose stationary window is shorter than this, in s (default 3)")
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="deck variable for every run, e.g. --var tolerance=1e-4 (repeatable)")
    parser.add_argument("--jobs", type=int, default=1, help="simulations at once (default 1)")
    parser.add_argument("--mpi", type=int, default=1,
                        help="MPI ranks per simulation (default 1; CPU time is counted over all ranks)")
    parser.add_argument("--launcher", default=None,
                        help="command put before lmp_cd (default 'mpirun -np N' when --mpi N > 1)")
    parser.add_argument("--lmp", default=os.environ.get("LMP_CD", BUILT_LMP_CD),
                        help="lmp_cd executable (default build/lmp_cd, or $LMP_CD)")
    parser.add_argument("--cdpost", default=None,
                        help="cdpost executable, or 'none' (default build/postproc/cdpost or PATH)")
    parser.add_argument("--cdpost-option", action="append", default=[], metavar="OPT",
                        help="extra cdpost option, e.g. --cdpost-option=--segment --cdpost-option=0.5")
    parser.add_argument("--list", action="store_true", help="list the jobs and their state, run nothing")
    parser.add_argument("--report", metavar="DIR",
                        help="run nothing: analyse the series again from the finished runs and write "
                             "the results folder DIR (e.g. results)")
    parser.add_argument("--comparison", action="append", default=[], metavar="DIR",
                        help="with --report: a reference/run_comparison.sh output folder to include "
                             "(repeatable)")
    parser.add_argument("--run-var", action="append", default=[], metavar="GLOB:NAME=VALUE",
                        help="deck variable for the runs whose name matches GLOB only, after --var: e.g. runs "
                             "made again with another setting (repeatable)")
    parser.add_argument("--publish-unconverged", action="store_true",
                        help="with --report: publish runs with more than 0.1 %% of their steps unconverged "
                             "(flagged) instead of refusing them")
    parser.add_argument("--count-without-health", action="store_true",
                        help="with --report: count runs whose solver health is neither recorded nor inferred "
                             "(series health_evidence) in the fits and verdicts, flagged, instead of refusing")
    parser.add_argument("--dry-run", action="store_true", help="print the commands of the pending jobs")
    parser.add_argument("--progress-interval", type=float, default=60.0, help="seconds between progress lines")
    parser.add_argument("--poll", type=float, default=2.0, help=argparse.SUPPRESS)
    return parser


def run_variables_of(parser, items):
    """--run-var GLOB:NAME=VALUE items -> [(glob, {name: value})]."""
    pairs = []
    for item in items:
        if ":" not in item:
            parser.error(f"--run-var {item}: expected GLOB:NAME=VALUE")
        pattern, assignment = item.split(":", 1)
        pairs.append((pattern, deck_variables(parser, [assignment])))
    return pairs


def deck_variables(parser, items):
    """--var NAME=VALUE items -> {name: value}; the runner's own variables refused."""
    variables = {}
    for item in items:
        if "=" not in item:
            parser.error(f"--var {item}: expected NAME=VALUE")
        key, value = item.split("=", 1)
        if key in ("stage", "start", "duration"):
            parser.error(f"--var {key}: set by the runner (use --duration)")
        variables[key] = value
    return variables


def launcher(args):
    """The command put before lmp_cd: --launcher, else mpirun for --mpi > 1."""
    if args.launcher is not None:
        return shlex.split(args.launcher)
    return mpi_launcher("mpirun", args.mpi, oversubscribe=False) if args.mpi > 1 else []


def parse_args(argv):
    parser = argument_parser()
    args = parser.parse_args(argv)
    args.var = deck_variables(parser, args.var)
    args.run_var = run_variables_of(parser, args.run_var)
    if args.jobs < 1 or args.mpi < 1:
        parser.error("--jobs and --mpi must be >= 1")
    args.launcher = launcher(args)
    args.out = os.path.abspath(args.out)
    args.lmp = os.path.abspath(args.lmp)
    args.max_duration = max(args.max_duration, args.duration)
    if not os.access(args.lmp, os.X_OK) and not (args.list or args.dry_run or args.report):
        parser.error(f"--lmp {args.lmp}: not an executable (build it: make -C build lmp_cd)")
    if args.comparison and not args.report:
        parser.error("--comparison goes with --report")
    for folder in args.comparison:
        if not os.path.isdir(folder):
            parser.error(f"--comparison {folder}: not a folder")
    args.argv = list(argv)
    return args


def main(args):
    if args.report:
        return write_results(args)
    jobs = build_jobs(args)
    if args.list:
        list_jobs(jobs)
        return 0
    return run_campaign(jobs, args)


if __name__ == "__main__":
    sys.exit(main(parse_args(sys.argv[1:])))
