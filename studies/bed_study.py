#!/usr/bin/env python3
"""The erodible bed against the solver's tolerance (doc/bed.md): the runs.

One layer-reading deposition (L 45 d, seed 20261122, the published series' own) serves every run
but the length/ jobs, which rain their own cells:

    floor/tol<T>_<order>        the packing at rest: mu 0.5, gravity tilted to 12 deg (below
                                the flow threshold), tolerance T, 0.6 s from the tilt (T 1e-3,
                                1e-4); at 1e-5 continued from 1e-4's end to 0.9 s, at 1e-6
                                from 1e-5's to 1.2 s
    start/mu<mu>_theta<theta>   a stationary flow: 6 s at tolerance 1e-2 from the tilt
    flow/mu<mu>_theta<theta>/tol<T>_<order>
                                continued from the start's chute.restart for 1.2 s at
                                tolerance T, the deck's defaults otherwise
    length/L<L>/start, length/L<L>/tol<T>_<order>
                                the creep against the cell length (doc/bed.md): the L
                                series' cell (count reading, mu 0.5, 22 deg) at L 45, 102 and 152 d,
                                each from its own deposition (seed 20261122), a start and
                                continuations as above

with <order> fixed, or shuffle<seed> (the contact order shuffled by that seed): replicas of one
setting from one state. Every job runs in legs (legs/NN, one lmp_cd each); started again with
the same options, finished jobs are skipped and an unfinished one continues from its newest
restart (the deck writes one every 0.1 s); a job whose origin is not finished waits for it
(another runner of the study may be running it on the other core). The outputs of the legs are spliced by time step
into the job's folder. --collect copies the small outputs of the finished jobs (and cdpost's
results of each continuation) into a folder of the repository; analysis: studies/bed_profiles.py.

    studies/bed_study.py --out runs/bed --core 0 --only 'floor/*1e-3*' --only 'start/*'
    studies/bed_study.py --out runs/bed --only '*' --collect results/bed

Standard library only.
"""

import argparse
import fnmatch
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.campaign.legs import LEG_OUTPUTS, splice_legs
from cdtools.lammps_files import time_span
from cdtools.logs import read_progress
from cdtools.run import BUILT_CDPOST, BUILT_LMP_CD, deck_copy, lmp_command

CELL = dict(reading="layer", L="45", seed="20261122")
FLOOR = dict(mu="0.5", theta="12", duration="0.6", max_iterations="100000")
FLOOR_CHAIN = (("1e-4", "1e-5", "0.9"), ("1e-5", "1e-6", "1.2"))   # (from, tolerance, to chute time)
FLOWS = (("0.5", "24"), ("0.05", "20"), ("2", "28"))
START = dict(tolerance="1e-2", duration="6")
CONTINUATION_SECONDS = 1.2
TOLERANCES = ("1e-3", "1e-4")
ORDERS = ("fixed", "shuffle1", "shuffle2")
LENGTH_FLOW = dict(reading="count", seed="20261122", mu="0.5", theta="22")
LENGTHS = ("102", "45", "152")


def order_variables(order):
    """'fixed' or 'shuffle<seed>' -> the deck's order and seed variables."""
    if order == "fixed":
        return dict(order="fixed")
    return dict(order="shuffle", seed=order[len("shuffle"):])


class Job:
    """One run of the study: its folder, deck variables, and the job whose end it starts from."""

    def __init__(self, name, variables, origin):
        self.name, self.vars, self.origin = name, variables, origin

    def folder(self, out):
        return os.path.join(out, self.name)

    def start_file(self, out):
        if self.origin == "deposition":
            return os.path.join(deposition_folder(out, self.vars), "deposition.restart")
        return os.path.join(out, self.origin, "chute.restart")


def deposition_folder(out, variables):
    """The study's own cell rains into deposition/, another cell into deposition_L<L>_<reading>/."""
    if all(variables[key] == value for key, value in CELL.items()):
        return os.path.join(out, "deposition")
    return os.path.join(out, f"deposition_L{variables['L']}_{variables['reading']}")


def cell_variables(variables):
    return {key: variables[key] for key in ("reading", "L", "seed")}


def plan():
    """Every job of the study, in the order they are run."""
    jobs = []
    for tolerance in TOLERANCES:
        for order in ORDERS:
            jobs.append(Job(f"floor/tol{tolerance}_{order}",
                            dict(CELL, **FLOOR, tolerance=tolerance, **order_variables(order)), "deposition"))
    # The tilt's transient costs ~1e4 sweeps a step at 1e-5; at rest a few: each tighter
    # tolerance continues the looser one's rest for 0.3 s.
    for looser, tolerance, end in FLOOR_CHAIN:
        for order in ORDERS:
            floor = dict(FLOOR, duration=end)
            jobs.append(Job(f"floor/tol{tolerance}_{order}",
                            dict(CELL, **floor, tolerance=tolerance, **order_variables(order)),
                            f"floor/tol{looser}_{order}"))
    for mu, theta in FLOWS:
        start = f"start/mu{mu}_theta{theta}"
        jobs.append(Job(start, dict(CELL, mu=mu, theta=theta, **START), "deposition"))
        end = float(START["duration"]) + CONTINUATION_SECONDS
        for tolerance in TOLERANCES + ("1e-5",):
            for order in ORDERS:
                variables = dict(CELL, mu=mu, theta=theta, tolerance=tolerance, duration=f"{end:g}",
                                 max_iterations="100000", **order_variables(order))
                jobs.append(Job(f"flow/mu{mu}_theta{theta}/tol{tolerance}_{order}", variables, start))
    for length in LENGTHS:
        flow = dict(LENGTH_FLOW, L=length)
        start = f"length/L{length}/start"
        jobs.append(Job(start, dict(flow, **START), "deposition"))
        end = float(START["duration"]) + CONTINUATION_SECONDS
        for tolerance in TOLERANCES:
            for order in ORDERS:
                variables = dict(flow, tolerance=tolerance, duration=f"{end:g}", max_iterations="100000",
                                 **order_variables(order))
                jobs.append(Job(f"length/L{length}/tol{tolerance}_{order}", variables, start))
    return jobs


def legs(folder):
    path = os.path.join(folder, "legs")
    return sorted(os.path.join(path, n) for n in os.listdir(path)) if os.path.isdir(path) else []


def newest_restart(folder):
    """The newest non-empty restart.a/b of the job's legs, or None."""
    files = [os.path.join(leg, n) for leg in legs(folder) for n in ("restart.a", "restart.b")]
    files = [f for f in files if os.path.exists(f) and os.path.getsize(f) > 0]
    return max(files, key=os.path.getmtime) if files else None


def splice(folder):
    """The legs' outputs joined by time step into the job's folder (later legs win)."""
    leg_dirs = legs(folder)
    starts = []
    for leg in leg_dirs:
        first = read_progress(os.path.join(leg, "log.lammps")).first_step
        starts.append(first if first is not None else math.inf)
    for name, kind in LEG_OUTPUTS:
        if name != "dump.chute.gz":
            splice_legs(leg_dirs, starts, name, kind, os.path.join(folder, name))
    shutil.copy2(os.path.join(leg_dirs[-1], "chute.restart"), os.path.join(folder, "chute.restart"))
    shutil.copy2(os.path.join(leg_dirs[-1], "chute.params"), os.path.join(folder, "chute.params"))


def cpu_seconds(folder):
    return sum(read_progress(os.path.join(leg, "log.lammps")).cpu for leg in legs(folder))


def run_deposition(out, variables, args):
    """The cell of variables rained once (a second runner waits for the first's)."""
    folder = deposition_folder(out, variables)
    if os.path.exists(os.path.join(folder, "deposition.restart")) or not claim(folder):
        return
    command = args.pin + lmp_command(args.lmp, deck_copy(out), dict(cell_variables(variables), stage="deposition"),
                                     screen="none")
    subprocess.run(command, cwd=folder, check=True)


def claim(folder):
    """True if this runner may run the job in folder: no other live runner holds its lock
    (two runners, one a core, share a study)."""
    os.makedirs(folder, exist_ok=True)
    lock = os.path.join(folder, "runner.pid")
    try:
        with open(lock) as src:
            holder = int(src.read())
        if holder != os.getpid() and os.path.exists(f"/proc/{holder}"):
            return False
    except (OSError, ValueError):
        pass
    with open(lock + ".tmp", "w") as out:
        out.write(f"{os.getpid()}\n")
    os.replace(lock + ".tmp", lock)
    return True


def run_job(job, args):
    """Legs until the job reaches its duration, then the splice; a failed leg stops the study.
    A job another live runner holds is skipped."""
    folder = job.folder(args.out)
    if os.path.exists(os.path.join(folder, "DONE")):
        return
    if not claim(folder):
        print(f"{job.name}: run by another runner", flush=True)
        return
    duration = float(job.vars["duration"])
    origin_done = job.start_file(args.out) if job.origin == "deposition" else os.path.join(args.out, job.origin, "DONE")
    while not os.path.exists(origin_done):    # run by another runner of the study (another core)
        print(f"{job.name}: waiting for {job.origin}", flush=True)
        time.sleep(60)
    while True:
        done = [time_span(os.path.join(leg, "flow.time")) for leg in legs(folder)]
        reached = max((span[1] for span in done if span), default=0.0)
        finished = legs(folder) and os.path.exists(os.path.join(legs(folder)[-1], "chute.restart"))
        if finished and reached >= duration - 1e-9:
            break
        start = newest_restart(folder) or job.start_file(args.out)
        leg = os.path.join(folder, "legs", f"{len(legs(folder)):02d}")
        os.makedirs(leg)
        variables = {**job.vars, **args.extra, "stage": "flow", "start": start}
        command = args.pin + lmp_command(args.lmp, deck_copy(args.out), variables, screen="none")
        with open(os.path.join(leg, "command.sh"), "w") as script:
            script.write("#!/bin/sh\ncd " + shlex.quote(leg) + " && " + shlex.join(command) + "\n")
        print(f"{job.name}: leg {os.path.basename(leg)} from {os.path.relpath(start, args.out)}", flush=True)
        if subprocess.run(command, cwd=leg).returncode != 0:
            raise RuntimeError(f"{job.name}: leg {leg} failed (see its log.lammps)")
    splice(folder)
    with open(os.path.join(folder, "DONE"), "w") as mark:
        mark.write(f"cpu_seconds {cpu_seconds(folder):.1f}\n")
    print(f"{job.name}: done, {cpu_seconds(folder):.0f} CPU s", flush=True)


KEPT_FILES = ("profile.chunk", "packing.chunk", "flow.time", "solver.time", "chute.params", "DONE")


def collect(job, args):
    """The small outputs of a finished job into --collect (the study's layout): its profiles,
    flow.time and solver.time, each leg's command and LAMMPS timers, and for a continuation
    cdpost's results over the windows studies/bed_profiles.py averages (--flow-from 0.4 s on)."""
    folder, kept = job.folder(args.out), os.path.join(args.collect, job.name)
    if not os.path.exists(os.path.join(folder, "DONE")) or "start" in job.name.split("/"):
        return
    os.makedirs(kept, exist_ok=True)
    for name in KEPT_FILES:
        shutil.copy2(os.path.join(folder, name), kept)
    for leg in legs(folder):
        os.makedirs(os.path.join(kept, "legs", os.path.basename(leg)), exist_ok=True)
        shutil.copy2(os.path.join(leg, "command.sh"), os.path.join(kept, "legs", os.path.basename(leg)))
        with open(os.path.join(leg, "log.lammps")) as log, \
                open(os.path.join(kept, "legs", os.path.basename(leg), "timers.txt"), "w") as timers:
            timers.writelines(line for line in log if re.match(r"Loop time of|.*% CPU use|Total wall time", line))
    if job.name.startswith(("flow/", "length/")) and args.cdpost:
        end = float(job.vars["duration"])
        command = [args.cdpost, "run", folder, "--t-start", f"{end - CONTINUATION_SECONDS + 0.4:g}",
                   "--t-end", f"{end:g}", "--segment", "0.4", "--cell-length", job.vars["L"],
                   "--out", os.path.join(folder, "post")]
        if subprocess.run(command, stdout=subprocess.DEVNULL).returncode == 0:
            os.makedirs(os.path.join(kept, "post"), exist_ok=True)
            shutil.copy2(os.path.join(folder, "post", "results.json"), os.path.join(kept, "post"))


def options(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="study folder (resumable)")
    parser.add_argument("--only", action="append", metavar="GLOB", required=True,
                        help="jobs to run, by name (repeatable), e.g. 'floor/tol1e-3_*'")
    parser.add_argument("--core", type=int, help="pin the runs to this CPU core (taskset)")
    parser.add_argument("--lmp", default=BUILT_LMP_CD)
    parser.add_argument("--list", action="store_true", help="list the jobs the globs select, run nothing")
    parser.add_argument("--collect", metavar="DIR",
                        help="run nothing: copy the small outputs of the finished jobs into DIR (e.g. results/bed)")
    parser.add_argument("--cdpost", default=BUILT_CDPOST, help="cdpost for --collect ('' for none)")
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="a deck variable of every flow leg, over the study's (repeatable), e.g. skin=2")
    args = parser.parse_args(argv)
    args.extra = {}
    for pair in args.var:
        name, sign, value = pair.partition("=")
        if not sign or not name or not value:
            parser.error(f"--var {pair}: must be NAME=VALUE")
        if name in ("stage", "start", "duration"):
            parser.error(f"--var {pair}: {name} is the study's own")
        args.extra[name] = value
    args.out = os.path.abspath(args.out)
    args.pin = ["taskset", "-c", str(args.core)] if args.core is not None else []
    return args


def main(argv=None):
    args = options(argv)
    jobs = [job for job in plan() if any(fnmatch.fnmatch(job.name, glob) for glob in args.only)]
    if not jobs:
        sys.exit(f"bed_study.py: --only {' '.join(args.only)}: no job of the study matches")
    if args.list:
        print("\n".join(job.name for job in jobs))
        return
    if args.collect:
        for job in jobs:
            collect(job, args)
        return
    for job in jobs:
        if job.origin == "deposition":
            run_deposition(args.out, job.vars, args)
        run_job(job, args)


if __name__ == "__main__":
    main()
