#!/usr/bin/env python3
"""Run the erodible-bed chute series with inputs/in.chute (doc/chute.md).

The campaign is a set of runs, each a chute at one (mu, theta, L) started from a settled
packing deposited at the same (mu, L, seed). Every deposition and every run has its own
folder under --out:

    depositions/<name>/   deposition.restart, .data, .dump, log, params.json, result.json
    runs/<name>/          params.json; legs/NN/ (one lmp_cd process each); when finished the
                          spliced flow.time, profile.chunk, packing.chunk, layers.chunk,
                          solver.time, dump.chute.gz, chute.restart, cost.json, DONE, post/
    series/<series>/manifest.csv and the cdpost series analysis

A run is made of legs: each leg is one lmp_cd process started from the deposition or from
the newest restart of the previous legs, running up to the same chute time (run ... upto).
Interrupt the runner (Ctrl-C, kill, power cut) and start it again with the same options:
finished runs are skipped, unfinished ones continue from their newest restart. The legs'
output files are spliced by time step when the run finishes (later legs win).

Standard library only.
"""

import argparse
import fnmatch
import glob
import gzip
import json
import math
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(TOP, "inputs", "in.chute")

# The series of the scene (doc/chute.md). Angles in degrees, L in mean diameters d.
REPLICA_SEED = 20261123
SERIES = {
    "mu0.05": [dict(mu=0.05, theta=t, L=45) for t in range(16, 23)],
    "mu0.5": [dict(mu=0.5, theta=t, L=45) for t in range(22, 29)],
    "mu2": [dict(mu=2, theta=t, L=45) for t in range(26, 31)],
    "L": [dict(mu=0.5, theta=22, L=n) for n in (12, 22, 32, 52, 72, 102, 152)],
    # Another deposition (rain seed) at one point per friction: the scatter between two
    # realisations of a run, which the error bars of one run's windows understate.
    "replicas": [dict(mu=mu, theta=theta, L=45, seed=REPLICA_SEED)
                 for mu, theta in ((0.05, 20), (0.5, 24), (2, 28))],
}
# The cdpost series analyses: the flow rules need every mu together; the L series also takes
# the 45 d run at the same (mu, theta) from the mu = 0.5 series.
ANALYSES = {
    "flow_rules": lambda job: job.series in ("mu0.05", "mu0.5", "mu2"),
    "L_series": lambda job: float(job.vars["mu"]) == 0.5 and float(job.vars["theta"]) == 22,
}

# Deck variables that shape the deposition: one packing serves every run with the same
# values (by default one per L, deposited with mu_deposition = 0.5, for all three mu).
DEPOSITION_VARS = ("L", "grains", "wall_height", "mu_deposition", "e", "e_wall", "seed", "d",
                   "dispersity", "density", "g", "dt_deposition", "tolerance_deposition",
                   "rain_fill", "settle_ke", "settle_max", "max_iterations")

# Output files of one leg: (name, kind). Kind "time" is a fix ave/time file, "chunk" a fix
# ave/chunk file, "dump" a gzipped dump; all are spliced by time step.
LEG_OUTPUTS = (("flow.time", "time"), ("solver.time", "time"), ("profile.chunk", "chunk"),
               ("packing.chunk", "chunk"), ("layers.chunk", "chunk"), ("dump.chute.gz", "dump"))

# Prior cost model for the time-left estimate before any run has been measured: wall seconds
# per grain and per second of chute time at the deck's defaults (doc/accuracy.md gives the
# measured cost of the 45 d scene), and per grain and deposition step; replaced by the
# measured rate of finished and running legs as soon as there is one. Chute progress is
# counted in chute time, not steps: the step follows the flow (adapt_dt), so steps do not
# map to time.
PRIOR_SECONDS_PER_GRAIN_CHUTE_SECOND = 0.03
PRIOR_SECONDS_PER_GRAIN_DEPOSITION_STEP = 1.0e-6


def die_with_parent():
    """In the child: receive SIGTERM when the runner dies (Linux prctl PR_SET_PDEATHSIG), so
    that a killed runner does not leave simulations writing into folders it will resume."""
    try:
        import ctypes
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)
    except (OSError, AttributeError):
        pass


def fmt_number(value):
    """Short, stable text for a parameter value in names and -var arguments."""
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    return str(value)


def format_duration(seconds):
    if seconds is None or not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    days, rest = divmod(seconds, 86400)
    hours, rest = divmod(rest, 3600)
    minutes, secs = divmod(rest, 60)
    if days:
        return f"{days}d{hours:02d}h"
    if hours:
        return f"{hours}h{minutes:02d}m"
    return f"{minutes}m{secs:02d}s"


def write_json(path, data):
    tmp = path + ".tmp"
    with open(tmp, "w") as out:
        json.dump(data, out, indent=2, sort_keys=True)
        out.write("\n")
    os.replace(tmp, path)


def read_json(path, default=None):
    try:
        with open(path) as src:
            return json.load(src)
    except (OSError, ValueError):
        return default


def git_commit():
    try:
        return subprocess.run(["git", "-C", TOP, "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


# ---------------------------------------------------------------------------------------
# Reading LAMMPS output
# ---------------------------------------------------------------------------------------

def read_time_records(path):
    """fix ave/time file -> (header lines, [(timestep, line)])."""
    header, records = [], []
    with open(path) as src:
        for line in src:
            if line.startswith("#"):
                if not records:
                    header.append(line)
                continue
            fields = line.split()
            if fields:
                records.append((int(float(fields[0])), line))
    return header, records


def read_chunk_records(path):
    """fix ave/chunk file -> (header lines, [(timestep, block text)])."""
    header, records = [], []
    block, step, remaining = [], None, 0
    with open(path) as src:
        for line in src:
            if line.startswith("#"):
                if not records and step is None:
                    header.append(line)
                continue
            if not line.strip():
                continue
            if remaining == 0:
                fields = line.split()
                step, remaining = int(float(fields[0])), int(float(fields[1]))
                block = [line]
                if remaining == 0:
                    records.append((step, "".join(block)))
                continue
            block.append(line)
            remaining -= 1
            if remaining == 0:
                records.append((step, "".join(block)))
    return header, records   # a block cut by a kill is dropped (remaining > 0)


def read_dump_records(path):
    """gzipped dump -> ([], [(timestep, frame text)]); a frame cut by a kill is dropped."""
    records = []
    try:
        with gzip.open(path, "rt") as src:
            text = src.read()
    except (OSError, EOFError):
        # A gzip stream cut by a kill: keep what decompresses.
        text = read_truncated_gzip(path)
    frames = text.split("ITEM: TIMESTEP\n")[1:]
    for frame in frames:
        lines = frame.split("\n")
        try:
            step = int(lines[0])
            natoms = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
            start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS")) + 1
        except (ValueError, StopIteration, IndexError):
            continue
        atoms = [l for l in lines[start:] if l.strip()]
        if len(atoms) != natoms:
            continue
        records.append((step, "ITEM: TIMESTEP\n" + "\n".join(lines[:start] + atoms) + "\n"))
    return [], records


def read_truncated_gzip(path):
    import zlib
    out = []
    decompressor = zlib.decompressobj(16 + zlib.MAX_WBITS)
    with open(path, "rb") as src:
        data = src.read()
    while data:
        try:
            out.append(decompressor.decompress(data))
        except zlib.error:
            break
        data = decompressor.unused_data
        if data:
            decompressor = zlib.decompressobj(16 + zlib.MAX_WBITS)
    return b"".join(out).decode(errors="replace")


READERS = {"time": read_time_records, "chunk": read_chunk_records, "dump": read_dump_records}


def splice_legs(leg_dirs, starts, name, kind, destination):
    """Join one output file over the legs: the record of time step T is taken from the last
    leg that started at or before T and holds T (a later leg recomputed what an interrupted
    earlier one wrote past the restart it continues from)."""
    chosen, header = {}, None
    for leg_dir, start in zip(leg_dirs, starts):
        path = os.path.join(leg_dir, name)
        if not os.path.exists(path):
            continue
        leg_header, records = READERS[kind](path)
        if header is None and leg_header:
            header = leg_header
        for step, text in records:
            if step >= start:
                chosen[step] = text
    if not chosen:
        return False
    body = "".join(header or []) + "".join(chosen[s] for s in sorted(chosen))
    tmp = destination + ".tmp"
    if kind == "dump":
        with gzip.open(tmp, "wt") as out:
            out.write(body)
    else:
        with open(tmp, "w") as out:
            out.write(body)
    os.replace(tmp, destination)
    return True


def time_span(path):
    """(first, last) chute time of a flow.time file (its v_time column), or None before its
    first row. Only the head and the tail are read: a row cut by a kill is skipped."""
    try:
        with open(path, "rb") as src:
            head = src.read(8192).decode(errors="replace").splitlines()
            src.seek(max(0, os.path.getsize(path) - 8192))
            tail = src.read().decode(errors="replace").splitlines()
    except OSError:
        return None
    names = [l[1:].split() for l in head if l.startswith("#")]
    if not names or "v_time" not in names[-1]:
        return None
    column = names[-1].index("v_time")

    def time_of(line):
        fields = line.split()
        if line.startswith("#") or len(fields) != len(names[-1]):
            return None
        try:
            return float(fields[column])
        except ValueError:
            return None
    firsts = [t for t in map(time_of, head) if t is not None]
    lasts = [t for t in map(time_of, tail[1:]) if t is not None]   # tail[0] may be cut
    if not firsts:
        return None
    return firsts[0], (lasts[-1] if lasts else firsts[-1])


def leg_start_step(leg_dir):
    """The time step a leg started from: the first thermo row of its log (the run's setup)."""
    in_thermo = False
    try:
        with open(os.path.join(leg_dir, "log.lammps")) as src:
            for line in src:
                if line.startswith("Step "):
                    in_thermo = True
                    continue
                fields = line.split()
                if in_thermo and fields and fields[0].isdigit():
                    return int(fields[0])
    except OSError:
        pass
    return None


def leg_progress(leg_dir):
    """(last thermo step, loop wall seconds, loop steps, final line) of a leg's log."""
    return leg_timing(leg_dir)[:4]


def leg_timing(leg_dir):
    """leg_progress plus the CPU seconds of the loops (wall time x LAMMPS's '% CPU use')."""
    log = os.path.join(leg_dir, "log.lammps")
    last_step, wall, steps, finished, cpu = None, 0.0, 0, None, 0.0
    in_thermo, loop_wall = False, None
    try:
        with open(log) as src:
            for line in src:
                if line.startswith("Step "):
                    in_thermo = True
                    continue
                if line.startswith("Loop time of"):
                    in_thermo = False
                    match = re.match(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps", line)
                    if match:
                        loop_wall = float(match.group(1))
                        wall += loop_wall
                        steps += int(match.group(2))
                    continue
                match = re.match(r"([0-9.]+)% CPU use", line)
                if match and loop_wall is not None:
                    cpu += loop_wall * float(match.group(1)) / 100.0
                    loop_wall = None
                    continue
                if line.startswith("CHUTE ") or line.startswith("DEPOSITION "):
                    finished = line.strip()
                if in_thermo:
                    fields = line.split()
                    if fields and fields[0].isdigit():
                        last_step = int(fields[0])
    except OSError:
        pass
    return last_step, wall, steps, finished, cpu


def error_line(leg_dir):
    for name in ("log.lammps", "screen.txt"):
        try:
            with open(os.path.join(leg_dir, name)) as src:
                for line in src:
                    if line.startswith("ERROR"):
                        return line.strip()
        except OSError:
            pass
    return None


# ---------------------------------------------------------------------------------------
# Jobs
# ---------------------------------------------------------------------------------------

class Job:
    """One deposition or one chute run: a folder, its parameters, its legs."""

    def __init__(self, kind, name, folder, variables, deposition=None):
        self.kind = kind                  # "deposition" | "run"
        self.name = name
        self.folder = folder
        self.vars = variables             # deck variables (strings)
        self.deposition = deposition      # the Job this run starts from
        self.process = None
        self.leg_dir = None
        self.leg_started = None
        self.failed = None
        self.restart_candidates = []
        self.rate_samples = []            # (wall time, step)

    # -- state on disk --
    @property
    def done(self):
        return os.path.exists(os.path.join(self.folder, "DONE"))

    def grains(self):
        n = int(float(self.vars.get("grains", "0")))
        return n if n > 0 else int(round(3967 * float(self.vars["L"]) / 45))

    def total_work(self):
        """Deposition steps (at most settle_max), or the chute time of a run (s)."""
        if self.kind == "deposition":
            return int(round(float(self.vars["settle_max"]) / float(self.vars["dt_deposition"])))
        return float(self.vars["duration"])

    def expected_work(self):
        """total_work, except that most depositions settle within 0.6 s, not settle_max."""
        if self.kind == "deposition":
            return min(self.total_work(), int(0.6 / float(self.vars["dt_deposition"])))
        return self.total_work()

    def prior_seconds_per_work(self):
        if self.kind == "deposition":
            return self.grains() * PRIOR_SECONDS_PER_GRAIN_DEPOSITION_STEP
        return self.grains() * PRIOR_SECONDS_PER_GRAIN_CHUTE_SECOND

    def legs(self):
        return sorted(glob.glob(os.path.join(self.folder, "legs", "[0-9][0-9]")))

    def work_done(self):
        """Chute time already behind the newest usable restart (0 for a deposition): a
        finished leg's end, or an unfinished leg's last sample less one restart interval (its
        restarts come at least that often)."""
        if self.kind == "deposition":
            return 0
        best = 0.0
        for leg in self.legs():
            span = time_span(os.path.join(leg, "flow.time"))
            if span is None:
                continue
            if os.path.exists(os.path.join(leg, "chute.restart")):
                best = max(best, span[1])
            else:
                best = max(best, span[0], span[1] - float(self.vars["restart_interval"]))
        return best

    def restart_files(self):
        """Restart files to continue from, newest first."""
        files = []
        for leg in reversed(self.legs()):
            final = os.path.join(leg, "chute.restart")
            periodic = [os.path.join(leg, n) for n in ("restart.a", "restart.b")]
            periodic = [p for p in periodic if os.path.exists(p) and os.path.getsize(p) > 0]
            periodic.sort(key=os.path.getmtime, reverse=True)
            if os.path.exists(final):
                files.append(final)
            files.extend(periodic)
        return files

    # -- launching --
    @property
    def deck(self):
        """The job's own copy of in.chute, taken at its first launch: every leg of a run uses
        the same deck, and editing inputs/in.chute never changes a run under way."""
        return os.path.join(self.folder, "in.chute")

    def command(self, args, start_file):
        variables = dict(self.vars)
        if self.kind == "deposition":
            variables["stage"] = "deposition"
        else:
            variables["stage"] = "flow"
            variables["start"] = start_file
        cmd = list(args.launcher) + [args.lmp, "-in", self.deck, "-log", "log.lammps", "-screen", "screen.txt"]
        for key in sorted(variables):
            cmd += ["-var", key, str(variables[key])]
        return cmd

    def launch(self, args):
        os.makedirs(self.folder, exist_ok=True)
        if not os.path.exists(self.deck):
            shutil.copy2(DECK, self.deck + ".tmp")
            os.replace(self.deck + ".tmp", self.deck)
        if self.kind == "deposition":
            leg = self.folder
            start_file = None
            # A deposition is short: an interrupted one starts again from the rain.
            for stale in ("log.lammps", "screen.txt", "deposition.restart"):
                if os.path.exists(os.path.join(leg, stale)):
                    os.remove(os.path.join(leg, stale))
        else:
            if not self.restart_candidates:
                self.restart_candidates = self.restart_files() + [
                    os.path.join(self.deposition.folder, "deposition.restart")]
            start_file = self.restart_candidates.pop(0)
            leg = os.path.join(self.folder, "legs", f"{len(self.legs()):02d}")
            os.makedirs(leg)
        cmd = self.command(args, start_file)
        with open(os.path.join(leg, "command.sh"), "w") as out:
            out.write("#!/bin/sh\ncd " + shlex.quote(leg) + " && " + " ".join(shlex.quote(c) for c in cmd) + "\n")
        self.process = subprocess.Popen(cmd, cwd=leg, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL, start_new_session=True,
                                        preexec_fn=die_with_parent)
        with open(os.path.join(leg, "pid"), "w") as out:
            out.write(f"{self.process.pid}\n")
        self.leg_dir = leg
        self.leg_started = time.time()
        self.rate_samples = []
        return start_file

    def last_leg_complete(self):
        """True if the newest leg ran to the run's duration (finished but not spliced)."""
        legs = self.legs()
        if not legs or not os.path.exists(os.path.join(legs[-1], "chute.restart")):
            return False
        _, _, _, summary = leg_progress(legs[-1])
        if not summary:
            return False
        reached = parse_summary(summary).get("time_s", 0.0)
        return reached >= float(self.vars["duration"]) - 0.5 * float(self.vars["dt"])

    def live_leg(self):
        """A leg whose lmp_cd still runs (started by a runner that did not stop it), or None."""
        folders = self.legs() if self.kind == "run" else [self.folder]
        for leg in folders:
            try:
                with open(os.path.join(leg, "pid")) as src:
                    pid = int(src.read())
                if os.path.realpath(os.readlink(f"/proc/{pid}/cwd")) == os.path.realpath(leg):
                    return leg, pid
            except (OSError, ValueError):
                continue
        return None

    def poll_rate(self):
        """Work (deposition steps, chute seconds) per wall second of the running leg, None until
        it progressed twice."""
        last = self.current_work()
        if last is None:
            return None
        now = time.time()
        if not self.rate_samples or self.rate_samples[-1][1] != last:
            self.rate_samples.append((now, last))
        self.rate_samples = self.rate_samples[-20:]
        if len(self.rate_samples) < 2:
            return None
        (t0, s0), (t1, s1) = self.rate_samples[0], self.rate_samples[-1]
        return (s1 - s0) / (t1 - t0) if t1 > t0 else None

    def current_work(self):
        """Deposition step or chute time reached by the running leg, None before its first
        output."""
        if self.leg_dir is None:
            return None
        if self.kind == "deposition":
            return leg_progress(self.leg_dir)[0]
        span = time_span(os.path.join(self.leg_dir, "flow.time"))
        return span[1] if span else None


# ---------------------------------------------------------------------------------------
# Finishing a job
# ---------------------------------------------------------------------------------------

def parse_summary(line):
    """'DEPOSITION grains 3967 time_s 0.35 ...' -> dict of numbers."""
    fields = line.split()[1:]
    result = {}
    for key, value in zip(fields[0::2], fields[1::2]):
        try:
            result[key] = float(value)
        except ValueError:
            result[key] = value
    return result


def finish_deposition(job):
    _, wall, steps, summary = leg_progress(job.folder)
    if not summary or not os.path.exists(os.path.join(job.folder, "deposition.restart")):
        return error_line(job.folder) or "deposition ended without its restart"
    result = parse_summary(summary)
    result.update(wall_seconds=wall, steps=steps)
    write_json(os.path.join(job.folder, "result.json"), result)
    open(os.path.join(job.folder, "DONE"), "w").close()
    return None


def finish_run(job, args):
    legs = job.legs()
    final_leg = legs[-1]
    starts = []
    for leg in legs:
        start = leg_start_step(leg)
        starts.append(start if start is not None else math.inf)
    for name, kind in LEG_OUTPUTS:
        splice_legs(legs, starts, name, kind, os.path.join(job.folder, name))
    shutil.copy2(os.path.join(final_leg, "chute.restart"), os.path.join(job.folder, "chute.restart"))
    write_json(os.path.join(job.folder, "cost.json"), run_cost(job, legs))
    _, _, _, summary = leg_progress(final_leg)
    write_json(os.path.join(job.folder, "result.json"), parse_summary(summary))
    open(os.path.join(job.folder, "DONE"), "w").close()
    return None


def run_cost(job, legs):
    """Wall and CPU time per physical second over the chute legs, from LAMMPS's own loop
    timers. A leg killed before its end printed no timers, so the physical time is the chute
    time covered by the legs that did."""
    wall, steps, cpu = 0.0, 0, 0.0
    spans = []
    for leg in legs:
        _, leg_wall, leg_steps, _, leg_cpu = leg_timing(leg)
        wall += leg_wall
        steps += leg_steps
        cpu += leg_cpu
        span = time_span(os.path.join(leg, "flow.time"))
        if span and leg_steps > 0:
            spans.append(span)
    sweeps = None
    solver = os.path.join(job.folder, "solver.time")
    if os.path.exists(solver):
        _, records = read_time_records(solver)
        values = [float(text.split()[1]) for _, text in records]
        sweeps = sum(values) / len(values) if values else None
    physical = max(s[1] for s in spans) - min(s[0] for s in spans) if spans else 0.0
    return dict(grains=job.grains(), steps=steps, physical_seconds=physical, wall_seconds=wall,
                wall_per_physical_second=wall / physical if physical > 0 else None,
                cpu_seconds=cpu, cpu_per_physical_second=cpu / physical if physical > 0 else None,
                seconds_per_grain_step=wall / (steps * job.grains()) if steps else None,
                mean_sweeps_per_step=sweeps, legs=len(legs))


def find_cdpost(args):
    if args.cdpost == "none":
        return None
    candidates = [args.cdpost] if args.cdpost else [
        os.path.join(TOP, "build", "postproc", "cdpost"), shutil.which("cdpost") or ""]
    for candidate in candidates:
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    return None


def postprocess_run(job, cdpost, args):
    """cdpost run on a finished run. Returns (ok, message); 'not stationary' is reported."""
    y_top = float(job.vars["wall_height"]) * float(job.vars["d"])
    cmd = [cdpost, "run", job.folder, "--d", job.vars["d"], "--g", job.vars["g"],
           "--z0", repr(y_top), "--dump", os.path.join(job.folder, "dump.chute.gz")]
    cmd += args.cdpost_option
    result = subprocess.run(cmd, capture_output=True, text=True)
    with open(os.path.join(job.folder, "cdpost.log"), "w") as out:
        out.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + result.stdout + result.stderr)
    message = (result.stderr.strip().splitlines() or [""])[-1]
    return result.returncode == 0, message


def postprocess_series(jobs, cdpost, args):
    for analysis, belongs in ANALYSES.items():
        runs = [j for j in jobs if j.kind == "run" and belongs(j) and j.done
                and os.path.exists(os.path.join(j.folder, "post", "results.csv"))]
        if len(runs) < 2:
            continue
        folder = os.path.join(args.out, "series", analysis)
        os.makedirs(folder, exist_ok=True)
        manifest = os.path.join(folder, "manifest.csv")
        with open(manifest, "w") as out:
            out.write(f"# {analysis}: run folders relative to this file\n")
            # L only where it varies: cdpost correlates the results with L when it is given.
            with_length = len({j.vars["L"] for j in runs}) > 1
            out.write("run,mu,theta" + (",L" if with_length else "") + "\n")
            for j in runs:
                rel = os.path.relpath(j.folder, folder)
                out.write(f"{rel},{j.vars['mu']},{j.vars['theta']}" + (f",{j.vars['L']}" if with_length else "") + "\n")
        y_top = float(runs[0].vars["wall_height"]) * float(runs[0].vars["d"])
        cmd = [cdpost, "series", manifest, "--z0", repr(y_top)] + args.cdpost_option
        result = subprocess.run(cmd, capture_output=True, text=True)
        with open(os.path.join(folder, "cdpost.log"), "w") as out:
            out.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + result.stdout + result.stderr)
        status = "done" if result.returncode == 0 else "failed: " + (result.stderr.strip().splitlines() or [""])[-1]
        print(f"series {analysis}: {len(runs)} runs, cdpost series {status}", flush=True)


# ---------------------------------------------------------------------------------------
# The campaign
# ---------------------------------------------------------------------------------------

def build_jobs(args):
    base = dict(args.var)
    base.setdefault("duration", fmt_number(args.duration))
    defaults = deck_defaults()
    for key, value in defaults.items():
        base.setdefault(key, value)
    base["mu_wall"] = args.var.get("mu_wall", "")
    base["e_wall"] = args.var.get("e_wall", "")
    depositions, jobs = {}, []
    selected = args.series or list(SERIES)
    for series in selected:
        for point in SERIES[series]:
            variables = dict(base)
            for key, value in point.items():
                variables[key] = fmt_number(value)
            for key, value in args.var.items():       # --var wins over the series point
                if key not in ("mu_wall", "e_wall"):
                    variables[key] = value
            if not variables["mu_wall"]:
                variables["mu_wall"] = variables["mu"]
            if not variables["e_wall"]:
                variables["e_wall"] = variables["e"]
            name = f"mu{variables['mu']}_theta{variables['theta']}_L{variables['L']}"
            if variables["seed"] != defaults["seed"]:
                name += f"_seed{variables['seed']}"
            if args.only and not any(fnmatch.fnmatch(name, p) for p in args.only):
                continue
            dep_vars = {k: variables[k] for k in DEPOSITION_VARS}
            dep_name = f"mu{dep_vars['mu_deposition']}_L{dep_vars['L']}_seed{dep_vars['seed']}"
            if dep_name not in depositions:
                depositions[dep_name] = Job("deposition", dep_name,
                                            os.path.join(args.out, "depositions", dep_name), dep_vars)
            if any(j.name == name for j in jobs):
                continue
            folder = os.path.join(args.out, "runs", name)
            recorded = read_json(os.path.join(folder, "params.json"), {}).get("vars", {})
            if float(recorded.get("duration", 0)) > float(variables["duration"]):
                variables["duration"] = recorded["duration"]    # an extended run stays extended
            job = Job("run", name, folder, variables, depositions[dep_name])
            job.series = series
            jobs.append(job)
    return list(depositions.values()) + jobs


def deck_defaults():
    """The deck's index variables and their defaults (the deck is the one source)."""
    defaults = {}
    with open(DECK) as src:
        for line in src:
            match = re.match(r"variable\s+(\w+)\s+index\s+(\S+)", line)
            if match and "${" not in match.group(2):
                defaults[match.group(1)] = match.group(2)
    defaults.pop("stage", None)
    defaults.pop("start", None)
    return defaults


def check_recorded_params(job):
    """A run continues only with the parameters it was started with (duration may grow)."""
    path = os.path.join(job.folder, "params.json")
    recorded = read_json(path)
    if recorded is None:
        return None
    old = recorded.get("vars", {})
    changed = [k for k in set(old) | set(job.vars)
               if k != "duration" and str(old.get(k)) != str(job.vars.get(k))]
    if changed:
        return ("parameters differ from those recorded in " + path + ": "
                + ", ".join(f"{k} {old.get(k)} -> {job.vars.get(k)}" for k in sorted(changed)))
    return None


def record_params(job, args):
    path = os.path.join(job.folder, "params.json")
    os.makedirs(job.folder, exist_ok=True)
    data = read_json(path, {})
    data.update(name=job.name, kind=job.kind, vars=job.vars, deck=job.deck, deck_source=DECK, lmp=args.lmp,
                launcher=args.launcher, commit=data.get("commit", git_commit()),
                units="SI: m, s, kg; L, wall_height in d; theta in degrees",
                y_top=float(job.vars["wall_height"]) * float(job.vars["d"]),
                grains=job.grains())
    if job.kind == "run":
        data["deposition"] = job.deposition.folder
        data["series"] = job.series
    write_json(path, data)


def estimate_left(jobs, running, seconds_per_grain_chute_second, jobs_at_once):
    """Wall seconds left: running legs from their own rate, queued work from the cost model
    (runs: the measured rate, when there is one)."""
    left_running, queued = [], 0.0
    for job in jobs:
        if job.done or job.failed:
            continue
        per_work = job.prior_seconds_per_work()
        if job.kind == "run" and seconds_per_grain_chute_second:
            per_work = job.grains() * seconds_per_grain_chute_second
        if job in running:
            rate = job.poll_rate()
            reached = job.current_work()
            remaining = max(job.expected_work() - (reached if reached is not None else job.work_done()), 0)
            left_running.append(remaining / rate if rate else remaining * per_work)
        else:
            queued += max(job.expected_work() - job.work_done(), 0) * per_work
    busy = max(left_running) if left_running else 0.0
    return max(busy, (sum(left_running) + queued) / max(jobs_at_once, 1))


def measured_rate(jobs):
    """Wall seconds per grain and chute second over every chute leg so far, or None."""
    seconds, grain_seconds = 0.0, 0.0
    for job in jobs:
        if job.kind != "run":
            continue
        for leg in job.legs():
            span = time_span(os.path.join(leg, "flow.time"))
            if span:
                seconds += leg_progress(leg)[1]
                grain_seconds += (span[1] - span[0]) * job.grains()
    return seconds / grain_seconds if grain_seconds > 0 else None


def after_run(job, args, cdpost, pending):
    """Report a finished run, postprocess it, and extend it when it is not stationary."""
    line = f"done run {job.name}"
    cost = read_json(os.path.join(job.folder, "cost.json"), {})
    if cost.get("cpu_per_physical_second"):
        line += (f": {cost['cpu_per_physical_second']:.0f} CPU s ({cost['wall_per_physical_second']:.0f}"
                 " wall s) per physical second")
    if cdpost:
        ok, message = postprocess_run(job, cdpost, args)
        line += "; cdpost " + ("done" if ok else "failed: " + message)
        if not ok and "stationary" in message and args.max_duration > float(job.vars["duration"]) + 1e-9:
            new = min(float(job.vars["duration"]) + args.extend, args.max_duration)
            job.vars["duration"] = fmt_number(new)
            os.remove(os.path.join(job.folder, "DONE"))
            record_params(job, args)
            job.restart_candidates = []
            pending.insert(0, job)
            line += f"; extended to {fmt_number(new)} s"
    print(line, flush=True)


def run_campaign(args):
    if args.report:
        return write_results(args)
    jobs = build_jobs(args)
    if args.list:
        for job in jobs:
            state = "done" if job.done else ("started" if job.kind == "run" and job.legs() else "pending")
            extra = ""
            if job.kind == "run":
                reached = job.work_done()
                extra = f"  {reached:.3f}/{job.vars['duration']} s"
                if job.done and reached < float(job.vars["duration"]) - 1e-9:
                    state = "to extend"
            print(f"{job.kind:10s} {job.name:34s} {job.grains():6d} grains  {state}{extra}")
        return 0
    for job in jobs:
        problem = check_recorded_params(job)
        if problem and job.kind == "run":
            print(f"{job.name}: {problem}", file=sys.stderr)
            return 2
    cdpost = find_cdpost(args)
    if cdpost is None and args.cdpost != "none":
        print("cdpost not found (build/postproc/cdpost, --cdpost): runs are not postprocessed", flush=True)

    # Runs whose duration was raised since they finished are continued.
    for job in jobs:
        if job.kind == "run" and job.done:
            recorded = read_json(os.path.join(job.folder, "params.json"), {})
            old = float(recorded.get("vars", {}).get("duration", job.vars["duration"]))
            if float(job.vars["duration"]) > old + 1e-12:
                os.remove(os.path.join(job.folder, "DONE"))

    pending = []
    for job in jobs:
        if job.done:
            continue
        live = job.live_leg()
        if live:
            print(f"{job.name}: {live[0]} is still being run by pid {live[1]}; skipped "
                  "(stop that process or wait for it, then run again)", flush=True)
            continue
        pending.append(job)
    running = []
    print(f"{len(jobs)} jobs ({sum(j.kind == 'run' for j in jobs)} runs, "
          f"{sum(j.kind == 'deposition' for j in jobs)} depositions), {len(jobs) - len(pending)} done; "
          f"{args.jobs} at once, launcher: {' '.join(args.launcher) or '(none)'}", flush=True)
    if args.dry_run:
        for job in pending:
            print(" ".join(shlex.quote(c) for c in job.command(args, "<restart>")))
        return 0

    stop = {"signal": None}

    def on_signal(signum, _frame):
        stop["signal"] = signum
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)

    last_report = 0.0
    failures = 0
    while (pending or running) and stop["signal"] is None:
        # Start what can start.
        for job in list(pending):
            if len(running) >= args.jobs:
                break
            if job.kind == "run" and not job.deposition.done:
                blocked = job.deposition not in pending and job.deposition not in running
                if job.deposition.failed or blocked:
                    job.failed = "its deposition " + ("failed" if job.deposition.failed else "is not available")
                    print(f"FAILED run {job.name}: {job.failed}", flush=True)
                    pending.remove(job)
                    failures += 1
                continue
            if job.kind == "run" and job.last_leg_complete():
                # The runner stopped between the end of the last leg and the splicing.
                pending.remove(job)
                finish_run(job, args)
                after_run(job, args, cdpost, pending)
                continue
            record_params(job, args)
            start = job.launch(args)
            pending.remove(job)
            running.append(job)
            origin = f" from {os.path.relpath(start, args.out)}" if start else ""
            print(f"start {job.kind} {job.name} ({job.grains()} grains){origin}", flush=True)
        # Collect what ended.
        for job in list(running):
            code = job.process.poll()
            if code is None:
                continue
            running.remove(job)
            problem = None
            if code != 0:
                problem = error_line(job.leg_dir) or f"lmp_cd exit status {code}"
                never_ran = "Setting up Verlet run" not in open_text(job.leg_dir)
                if job.kind == "run" and never_ran and "restart" in problem.lower() \
                        and job.restart_candidates:
                    # The newest restart was cut by a kill: try the one before it.
                    print(f"{job.name}: {problem}; trying an older restart", flush=True)
                    shutil.rmtree(job.leg_dir)
                    pending.insert(0, job)
                    continue
            elif job.kind == "deposition":
                problem = finish_deposition(job)
            else:
                problem = finish_run(job, args)
            if problem:
                job.failed = problem
                failures += 1
                print(f"FAILED {job.kind} {job.name}: {problem}", flush=True)
                continue
            if job.kind == "run":
                after_run(job, args, cdpost, pending)
            else:
                result = read_json(os.path.join(job.folder, "result.json"), {})
                print(f"done deposition {job.name}: phi_bed {result.get('phi_bed')}, bed top "
                      f"{result.get('expected_height_d')} d, settled at {result.get('time_s')} s", flush=True)
        # Progress.
        now = time.time()
        if now - last_report >= args.progress_interval and (running or pending):
            last_report = now
            left = estimate_left(jobs, running, measured_rate(jobs), args.jobs)
            finished = sum(j.done for j in jobs)
            parts = []
            for job in running:
                reached = job.current_work() or 0
                parts.append(f"{job.name} {100.0 * reached / job.total_work():.0f}%")
            print(f"[{finished}/{len(jobs)} done, {len(running)} running, {len(pending)} queued] "
                  + ", ".join(parts) + f"; time left ~{format_duration(left)}", flush=True)
        time.sleep(args.poll)

    if stop["signal"] is not None:
        for job in running:
            try:
                os.killpg(job.process.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
        for job in running:
            try:
                job.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(job.process.pid, signal.SIGKILL)
        print("interrupted: run the same command again to continue", flush=True)
        return 130
    if cdpost and not args.only:
        postprocess_series(jobs, cdpost, args)
    print(f"finished: {sum(j.done for j in jobs)}/{len(jobs)} done, {failures} failed", flush=True)
    return 1 if failures else 0


def write_results(args):
    """--report: cdpost on the finished runs it has not analysed yet, the series analyses made
    again from every analysed run, then the results folder."""
    import chute_report
    cdpost = find_cdpost(args)
    if cdpost is None:
        print("--report needs cdpost (build/postproc/cdpost, --cdpost)", file=sys.stderr)
        return 2
    jobs = build_jobs(args)
    for job in jobs:
        if job.kind == "run" and job.done and not os.path.exists(os.path.join(job.folder, "post", "results.csv")):
            ok, message = postprocess_run(job, cdpost, args)
            print(f"cdpost run {job.name}: " + ("done" if ok else "failed: " + message), flush=True)
    postprocess_series(jobs, cdpost, args)
    records = [chute_report.RunRecord(job, run_cost(job, job.legs())) for job in jobs if job.kind == "run"]
    series = {analysis: os.path.join(args.out, "series", analysis) for analysis in ANALYSES}
    command = " ".join(shlex.quote(a) for a in ["scripts/chute_campaign.py"] + args.argv)
    readme = chute_report.write_report(records, series, args.comparison, args.report, command)
    analysed = sum(r.results is not None for r in records)
    print(f"{readme}: {analysed} of {len(records)} runs analysed", flush=True)
    return 0


def open_text(folder):
    text = []
    for name in ("log.lammps", "screen.txt"):
        try:
            with open(os.path.join(folder, name)) as src:
                text.append(src.read())
        except OSError:
            pass
    return "".join(text)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Series: " + "; ".join(
            f"{k}: " + ", ".join(f"mu {p['mu']} theta {p['theta']} L {p['L']}" for p in v[:1]) + f" ... ({len(v)} runs)"
            for k, v in SERIES.items()))
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
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="deck variable for every run, e.g. --var tolerance=1e-4 (repeatable)")
    parser.add_argument("--jobs", type=int, default=1, help="simulations at once (default 1)")
    parser.add_argument("--mpi", type=int, default=1,
                        help="MPI ranks per simulation (default 1; fix contact/dynamics runs on one rank for now)")
    parser.add_argument("--launcher", default=None,
                        help="command put before lmp_cd (default 'mpirun -np N' when --mpi N > 1)")
    parser.add_argument("--lmp", default=os.environ.get("LMP_CD", os.path.join(TOP, "build", "lmp_cd")),
                        help="lmp_cd executable (default build/lmp_cd, or $LMP_CD)")
    parser.add_argument("--cdpost", default=None, help="cdpost executable, or 'none' (default build/postproc/cdpost or PATH)")
    parser.add_argument("--cdpost-option", action="append", default=[], metavar="OPT",
                        help="extra cdpost option, e.g. --cdpost-option=--segment --cdpost-option=0.5")
    parser.add_argument("--list", action="store_true", help="list the jobs and their state, run nothing")
    parser.add_argument("--report", metavar="DIR",
                        help="run nothing: analyse the series again from the finished runs and write "
                             "the results folder DIR (e.g. results)")
    parser.add_argument("--comparison", action="append", default=[], metavar="DIR",
                        help="with --report: a reference/run_comparison.sh output folder to include "
                             "(repeatable)")
    parser.add_argument("--dry-run", action="store_true", help="print the commands of the pending jobs")
    parser.add_argument("--progress-interval", type=float, default=60.0, help="seconds between progress lines")
    parser.add_argument("--poll", type=float, default=2.0, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    variables = {}
    for item in args.var:
        if "=" not in item:
            parser.error(f"--var {item}: expected NAME=VALUE")
        key, value = item.split("=", 1)
        if key in ("stage", "start", "duration"):
            parser.error(f"--var {key}: set by the runner (use --duration)")
        variables[key] = value
    args.var = variables
    if args.jobs < 1 or args.mpi < 1:
        parser.error("--jobs and --mpi must be >= 1")
    if args.launcher is None:
        args.launcher = []
        if args.mpi > 1:
            args.launcher = ["mpirun", "-np", str(args.mpi)]
            if os.geteuid() == 0:
                args.launcher.append("--allow-run-as-root")    # Open MPI refuses root otherwise
    else:
        args.launcher = shlex.split(args.launcher)
    args.out = os.path.abspath(args.out)
    args.lmp = os.path.abspath(args.lmp)
    if args.max_duration < args.duration:
        args.max_duration = args.duration
    if not os.access(args.lmp, os.X_OK) and not (args.list or args.dry_run or args.report):
        parser.error(f"--lmp {args.lmp}: not an executable (build it: make -C build lmp_cd)")
    if args.comparison and not args.report:
        parser.error("--comparison goes with --report")
    for folder in args.comparison:
        if not os.path.isdir(folder):
            parser.error(f"--comparison {folder}: not a folder")
    args.argv = list(argv)
    return args


if __name__ == "__main__":
    sys.exit(run_campaign(parse_args(sys.argv[1:])))
