#!/usr/bin/env python3
"""Speed/accuracy study of fix contact/dynamics on the chute (doc/accuracy.md).

One deposition, one common spin-up flow at the default settings to a restart, then one flow
window per solver setting, every window started from that same restart. The settings vary one
factor at a time around the default (time step, tolerance, iteration cap, convergence norm,
warm start, contact order) and are compared with a reference (the smallest time step and
tolerance the study affords). For each window the study records the cost (CPU seconds per
physical second, contact updates per CPU second), the solver's behaviour (mean and largest
sweeps per step, final norm, mean and largest interpenetration) and the scene's observables
(U, phi, h, f, A from cdpost, with error bars), then writes a CSV, a Markdown table and the
Pareto figures (cost against |difference from the reference| / its error bar).

    scripts/accuracy_study.py --out /work/pareto-runs           # the small cell (L = 20 d)
    scripts/accuracy_study.py --out DIR --scene full            # the 45 d scene
    scripts/accuracy_study.py --out DIR --dry-run               # list the settings and commands
    scripts/accuracy_study.py --out DIR --analyse-only          # tables and figures only

Started again with the same options it skips the stages and windows already done.
Standard library only.
"""

import argparse
import csv
import json
import math
import os
import shlex
import shutil
import subprocess
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(TOP, "inputs", "in.chute")

# The two cells: the default scene (inputs/in.default_scene) and the scene of doc/scene.md.
SCENES = {
    "small": dict(L="20", grains="400", wall_height="10", mu="0.5", theta="24"),
    "full": dict(L="45", grains="0", wall_height="30", mu="0.5", theta="24"),
}
DEFAULT = dict(dt="2e-5", tolerance="1e-3", max_iterations="1000", norm="quadratic",
               warm_start="yes", order="fixed")
# One factor at a time around DEFAULT: (setting name, factor, the values that differ).
VARIATIONS = [
    ("dt=5e-6", "dt", dict(dt="5e-6")),
    ("dt=1e-5", "dt", dict(dt="1e-5")),
    ("dt=4e-5", "dt", dict(dt="4e-5")),
    ("tol=1e-2", "tolerance", dict(tolerance="1e-2")),
    ("tol=3e-3", "tolerance", dict(tolerance="3e-3")),
    ("tol=1e-4", "tolerance", dict(tolerance="1e-4")),
    ("tol=1e-5", "tolerance", dict(tolerance="1e-5")),
    ("cap=10", "max_iterations", dict(max_iterations="10")),
    ("cap=30", "max_iterations", dict(max_iterations="30")),
    ("cap=100", "max_iterations", dict(max_iterations="100")),
    ("norm=maximum", "norm", dict(norm="maximum")),
    ("warm_start=no", "warm_start", dict(warm_start="no")),
    ("order=shuffle", "order", dict(order="shuffle")),
    # Replicas of the default up to the contact order (another shuffle seed: in stage flow the
    # seed only draws the order): their scatter is the noise of one realisation of the flow.
    ("replica seed 2", "replica", dict(order="shuffle", seed="2")),
    ("replica seed 3", "replica", dict(order="shuffle", seed="3")),
    ("replica seed 4", "replica", dict(order="shuffle", seed="4")),
]
# The settings that differ from the default only by the contact order.
REPLICA_FACTORS = ("default", "order", "replica")
# Replicas of the reference the same way: the scatter of the most accurate setting.
REFERENCE_REPLICA_SEEDS = ("2", "3", "4", "5")
OBSERVABLES = [  # cdpost result name, label, unit
    ("U", "U", "sqrt(g d)"), ("phi", "phi", ""), ("h", "h", "d"), ("f", "f", "Hz"),
    ("A", "A", "sqrt(g d)"), ("f_c", "f_c", "Hz"), ("A_mean", "A_mean", "sqrt(g d)"),
]
CENTROID_BAND = (10.0, 150.0)   # Hz: f_c, the power-weighted mean frequency of v(t) in this band


def settings(args):
    """The study's settings in run order: reference, default, then the variations."""
    reference = dict(DEFAULT, dt=args.ref_dt, tolerance=args.ref_tolerance,
                     max_iterations=args.ref_max_iterations)
    rows = [("reference", "reference", reference), ("default", "default", dict(DEFAULT))]
    rows += [(name, factor, dict(DEFAULT, **change)) for name, factor, change in VARIATIONS]
    rows += [(f"reference seed {seed}", "reference replica", dict(reference, order="shuffle", seed=seed))
             for seed in REFERENCE_REPLICA_SEEDS]
    # The reference at half its time step, with its replicas: is the reference converged in dt?
    finer = dict(reference, dt=f"{float(args.ref_dt) / 2:g}")
    rows.append(("reference half-dt", "reference half-dt", finer))
    rows += [(f"reference half-dt seed {seed}", "reference half-dt replica", dict(finer, order="shuffle", seed=seed))
             for seed in REFERENCE_REPLICA_SEEDS[:3]]
    # --replicas NAME ...: the same replicas of other settings (factor "NAME replica").
    by_name = {name: setting for name, _, setting in rows}
    for name in args.replicas or []:
        if name not in by_name:
            raise SystemExit(f"accuracy_study.py: --replicas {name}: no such setting")
        rows += [(f"{name} seed {seed}", f"{name} replica", dict(by_name[name], order="shuffle", seed=seed))
                 for seed in REFERENCE_REPLICA_SEEDS[:3]]
    return [r for r in rows if not args.only or r[0] in args.only]


# ---------------------------------------------------------------- statistics

def batch_means(values, batches):
    """Mean of a correlated series and its standard error from `batches` consecutive block
    means (the leftover samples at the end are dropped); error None below two batches."""
    n = len(values) // batches
    if batches < 2 or n < 1:
        raise ValueError(f"batch_means: {len(values)} values cannot make {batches} batches")
    means = [sum(values[i * n:(i + 1) * n]) / n for i in range(batches)]
    mean = sum(means) / batches
    variance = sum((m - mean) ** 2 for m in means) / (batches - 1)
    return mean, math.sqrt(variance / batches)


def within_noise(x, s, x_ref, s_ref):
    """True when x and x_ref differ by less than twice their combined error bar."""
    return abs(x - x_ref) < 2 * math.sqrt(s * s + s_ref * s_ref)


def significance(x, s, x_ref, s_ref):
    """|x - x_ref| in units of the combined error bar (inf when both bars are zero)."""
    bar = math.sqrt(s * s + s_ref * s_ref)
    return abs(x - x_ref) / bar if bar > 0 else math.inf


# ---------------------------------------------------------------- running lmp_cd

def deck_command(args, variables, log):
    # lmp_cd reads its input while it runs: the study runs its own copy of the deck.
    cmd = ["nice", "-n", "19", args.lmp, "-in", os.path.join(os.path.abspath(args.out), "in.chute"), "-log", log, "-screen", "none"]
    for key, value in variables.items():
        cmd += ["-var", key, str(value)]
    return cmd


def run_timed(cmd, folder, deadline=None):
    """Run cmd in folder; return (status, user + sys CPU seconds, wall seconds, stopped):
    a process still running at `deadline` (time.time()) is stopped by SIGTERM."""
    start = time.time()
    with open(os.path.join(folder, "stdout"), "w") as out:
        proc = subprocess.Popen(cmd, cwd=folder, stdout=out, stderr=subprocess.STDOUT)
        stopped = False
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if deadline is not None and time.time() > deadline and not stopped:
                proc.terminate()
                stopped = True
            time.sleep(1)
        proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_utime + usage.ru_stime, time.time() - start, stopped


class Job:
    """One lmp_cd process in its own folder; DONE holds its cost when it has finished, PARTIAL
    when the study's deadline stopped it (its files then end where it stopped)."""

    def __init__(self, name, folder, variables, args):
        self.name, self.folder, self.variables = name, folder, variables
        self.cmd = deck_command(args, variables, "log.lammps")
        self.deadline = args.deadline

    def done(self):
        return os.path.exists(os.path.join(self.folder, "DONE"))

    def partial(self):
        return os.path.exists(os.path.join(self.folder, "PARTIAL"))

    def run(self):
        if self.deadline is not None and time.time() > self.deadline:
            print(f"{self.name}: not started (deadline)", flush=True)
            return
        os.makedirs(self.folder, exist_ok=True)
        with open(os.path.join(self.folder, "command"), "w") as f:
            f.write(" ".join(shlex.quote(c) for c in self.cmd) + "\n")
        with open(os.path.join(self.folder, "variables.json"), "w") as f:
            json.dump(self.variables, f)
        status, cpu, wall, stopped = run_timed(self.cmd, self.folder, self.deadline)
        if stopped:
            with open(os.path.join(self.folder, "PARTIAL"), "w") as f:
                json.dump(dict(cpu_s=cpu, wall_s=wall), f)
            print(f"{self.name}: stopped at the deadline after {cpu:.0f} CPU s", flush=True)
            return
        if status != 0:
            raise RuntimeError(f"{self.name}: lmp_cd exit status {status}, see {self.folder}/log.lammps")
        with open(os.path.join(self.folder, "DONE"), "w") as f:
            json.dump(dict(cpu_s=cpu, wall_s=wall), f)
        print(f"{self.name}: {cpu:.0f} CPU s, {wall:.0f} s wall", flush=True)


def expected_cost(variables):
    """Rough cost of a window relative to the default: steps scale as 1/dt; sweeps per step
    (about 170 at the default) as tolerance^-1/2 up to the cap (measured: about 1500 at 1e-5);
    a cold start or the maximum norm costs more."""
    sweeps = min(170 * math.sqrt(1e-3 / float(variables["tolerance"])), float(variables["max_iterations"]))
    factor = {"no": 3.0}.get(variables["warm_start"], 1.0) * {"maximum": 2.0}.get(variables["norm"], 1.0)
    return 2e-5 / float(variables["dt"]) * sweeps / 170 * factor


def run_pool(jobs, parallel):
    """Run the jobs not yet done, `parallel` at a time (threads wait on the processes): the
    first job (the reference) at once, then the others cheapest first, so that a deadline
    leaves as many settings finished as possible."""
    import concurrent.futures
    pending = [j for j in jobs if not j.done() and not j.partial()]
    pending = pending[:1] + sorted(pending[1:], key=lambda j: expected_cost(j.variables))
    with concurrent.futures.ThreadPoolExecutor(max_workers=parallel) as pool:
        for future in [pool.submit(j.run) for j in pending]:
            future.result()


def common_variables(args):
    v = dict(SCENES[args.scene])
    v.update(dict(snapshot_interval="0.5", solver_interval="0.01", sample_rate="1000"))
    return v


def build_jobs(args):
    out = os.path.abspath(args.out)
    base = common_variables(args)
    deposition = Job("deposition", os.path.join(out, "deposition"),
                     dict(base, stage="deposition"), args)
    spinup = Job("spinup", os.path.join(out, "spinup"),
                 dict(base, stage="flow", start=os.path.join(deposition.folder, "deposition.restart"),
                      duration=args.spinup, **DEFAULT), args)
    end = f"{float(args.spinup) + float(args.window):.6g}"
    windows = []
    for name, factor, setting in settings(args):
        variables = dict(base, stage="flow", start=os.path.join(spinup.folder, "chute.restart"),
                         duration=end, **setting)
        windows.append((name, factor, setting, Job(name, os.path.join(out, "runs", name), variables, args)))
    return deposition, spinup, windows


# ---------------------------------------------------------------- reading a window

def read_table(path):
    """Rows of a fix ave/time file (the last '#' line names the columns) as dicts."""
    header, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                header = line[1:].split()
            elif line.strip():
                rows.append(dict(zip(header, map(float, line.split()))))
    return rows


def log_line(folder, key):
    """Words of the last log.lammps line starting with key, as {name: value}."""
    words = None
    with open(os.path.join(folder, "log.lammps")) as f:
        for line in f:
            if line.startswith(key + " "):
                words = line.split()[1:]
    if words is None:
        raise RuntimeError(f"{folder}/log.lammps: no line starting with {key}")
    return dict(zip(words[0::2], words[1::2]))


def solver_summary(folder, dt, window, finished):
    """Means of solver.time over the window, and the contact updates (sum over the
    solver_interval rows of mean sweeps x mean contacts x steps). The largest sweeps and
    interpenetration of any step come from the SOLVER line of a finished run; a stopped run
    has none, and the largest row mean (a lower bound) is given instead."""
    rows = read_table(os.path.join(folder, "solver.time"))
    steps_per_row = (rows[1]["TimeStep"] - rows[0]["TimeStep"]) if len(rows) > 1 else window / dt
    mean = lambda key: sum(r[key] for r in rows) / len(rows)
    updates = sum(r["f_cd[1]"] * r["f_cd[3]"] for r in rows) * steps_per_row
    if finished:
        extremes = log_line(folder, "SOLVER")
        sweeps_max, overlap_max = float(extremes["max_sweeps_per_step"]), float(extremes["max_interpenetration_d"])
    else:
        sweeps_max, overlap_max = max(r["f_cd[1]"] for r in rows), max(r["f_cd[5]"] for r in rows)
    return dict(sweeps_mean=mean("f_cd[1]"), sweeps_max=sweeps_max,
                residual=mean("f_cd[2]"), contacts=mean("f_cd[3]"),
                overlap_mean_d=mean("f_cd[6]"), overlap_max_d=overlap_max,
                converged=mean("f_cd[7]"), updates=updates)


def cdpost_results(args, folder, y_top, t_start, t_end):
    post = os.path.join(folder, "post")
    cmd = ["nice", "-n", "19", args.cdpost, "run", folder, "--z0", y_top, "--segment", str(args.segment),
           "--t-start", f"{t_start:.6g}", "--t-end", f"{t_end:.6g}", "--out", post]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    results = {}
    with open(os.path.join(post, "results.csv")) as f:
        for row in csv.DictReader(f):
            error = row["error"].strip()
            results[row["name"]] = (float(row["value"]), float(error) if error else None)
    return results


def amplitude_error(folder, f_hz, t_start, t_end, segment, g, d):
    """Standard error of the v(t) amplitude at f_hz over non-overlapping segments (each
    detrended and Hann-windowed as cdpost does), in sqrt(g d); None below two segments."""
    rows = [r for r in read_table(os.path.join(folder, "flow.time")) if t_start <= r["v_time"] <= t_end]
    rate = 1 / (rows[1]["v_time"] - rows[0]["v_time"])
    n = int(round(segment * rate))
    amplitudes = []
    for k in range(len(rows) // n):
        v = [r["v_v_flow"] for r in rows[k * n:(k + 1) * n]]
        mean_i, mean_v = (n - 1) / 2, sum(v) / n
        slope = sum((i - mean_i) * (x - mean_v) for i, x in enumerate(v)) / sum((i - mean_i) ** 2 for i in range(n))
        w = [0.5 - 0.5 * math.cos(2 * math.pi * i / n) for i in range(n)]
        y = [(x - mean_v - slope * (i - mean_i)) * w[i] for i, x in enumerate(v)]
        k_bin = round(f_hz * n / rate)
        re = sum(yi * math.cos(2 * math.pi * k_bin * i / n) for i, yi in enumerate(y))
        im = sum(yi * math.sin(2 * math.pi * k_bin * i / n) for i, yi in enumerate(y))
        amplitudes.append(2 * math.hypot(re, im) / sum(w) / math.sqrt(g * d))
    if len(amplitudes) < 2:
        return None
    return batch_means(amplitudes, len(amplitudes))[1]   # one segment per batch


def reached_time(folder):
    """Chute time of the last complete solver_interval in solver.time (s)."""
    rows = read_table(os.path.join(folder, "solver.time"))
    return rows[-1]["TimeStep"] * float(json.load(open(os.path.join(folder, "variables.json")))["dt"])


def spectral_centroid(post):
    """Power-weighted mean frequency of cdpost's spectrum.csv over CENTROID_BAND (Hz): unlike
    the peak, it does not jump between the bumps of a broad spectrum."""
    power = weighted = 0.0
    with open(os.path.join(post, "spectrum.csv")) as f:
        for row in csv.DictReader(f):
            freq, amp = float(row["f_Hz"]), float(row["A_sqrt_gd"])
            if CENTROID_BAND[0] <= freq <= CENTROID_BAND[1]:
                power += amp * amp
                weighted += freq * amp * amp
    return weighted / power


def analyse_window(args, name, factor, setting, job):
    finished = job.done()
    cost = json.load(open(os.path.join(job.folder, "DONE" if finished else "PARTIAL")))
    y_top = f"{float(SCENES[args.scene]['wall_height']) * 5e-4:.6g}"   # wall_height d, d = 5e-4 m
    t0 = float(args.spinup) + float(args.discard)
    t1 = float(args.spinup) + float(args.window) if finished else reached_time(job.folder)
    t1 = math.floor(t1 * 1000 + 1e-6) / 1000   # whole samples (1 kHz)
    window = t1 - float(args.spinup)
    solver = solver_summary(job.folder, float(setting["dt"]), window, finished)
    row = dict(setting=name, factor=factor, **setting, finished=finished, window_s=window,
               cpu_per_s=cost["cpu_s"] / window, wall_per_s=cost["wall_s"] / window,
               updates_per_cpu_s=solver.pop("updates") / cost["cpu_s"], **solver)
    if args.cost_only:
        return row
    res = cdpost_results(args, job.folder, y_top, t0, t1)
    res["f_c"] = (spectral_centroid(os.path.join(job.folder, "post")), None)
    res["A"] = (res["A"][0], amplitude_error(job.folder, res["f"][0], t0, t1, args.segment, 9.81, 5e-4))
    for key, _, _ in OBSERVABLES:
        value, error = res[key]
        row[key], row[key + "_err"] = value, error
    return row


# ---------------------------------------------------------------- reports

def replica_groups(rows):
    """The runs of the default's physics (differing only by the contact order) and those of
    the reference's."""
    return ([r for r in rows if r["factor"] in REPLICA_FACTORS],
            [r for r in rows if r["factor"] in ("reference", "reference replica")])


def group_stats(values):
    """Mean, standard deviation and standard error of the mean of a list (n >= 2)."""
    mean = sum(values) / len(values)
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))
    return mean, sd, sd / math.sqrt(len(values))


def replica_scatter(rows):
    """Per observable, the standard deviation of one run: pooled over the replica groups
    (deviations from each group's own mean) that have at least two runs; None when the
    groups hold fewer than three runs in all."""
    groups = [g for g in replica_groups(rows) if len(g) >= 2]
    if sum(len(g) for g in groups) < 3:
        return None
    scatter = {}
    for key, _, _ in OBSERVABLES:
        squares = dof = 0
        for g in groups:
            mean = sum(r[key] for r in g) / len(g)
            squares += sum((r[key] - mean) ** 2 for r in g)
            dof += len(g) - 1
        scatter[key] = math.sqrt(squares / dof)
    return scatter


def all_groups(rows):
    """Every replica group with at least two runs: {label: runs}, the default's physics and
    the reference's first, then each setting run with --replicas."""
    default, reference = replica_groups(rows)
    groups = {"default physics": default, "reference physics": reference}
    for r in rows:
        if r["factor"].endswith(" replica") and r["factor"] != "reference replica":
            name = r["factor"][:-len(" replica")]
            groups.setdefault(name, [x for x in rows if x["setting"] == name])
            groups[name].append(r)
    return {label: g for label, g in groups.items() if len(g) >= 2}


def group_table(rows):
    """Markdown: per replica group, mean ± standard error of each observable; each group
    against the reference's, in combined standard errors (**differs** from 2)."""
    groups = all_groups(rows)
    if "reference physics" not in groups or len(groups) < 2:
        return ""
    ref = groups["reference physics"]
    header = "| group (runs) | " + " | ".join(f"{label} ({unit})" if unit else label for _, label, unit in OBSERVABLES) + " |"
    lines = [header, "|---|" + "---|" * len(OBSERVABLES)]
    for label, g in groups.items():
        cells = []
        for key, _, _ in OBSERVABLES:
            m, _, e = group_stats([r[key] for r in g])
            cell = f"{fmt(m, 4)} ± {fmt(e, 2)}"
            if g is not ref:
                m_r, _, e_r = group_stats([r[key] for r in ref])
                cell += f" ({significance(m, e, m_r, e_r):.1f}{'' if within_noise(m, e, m_r, e_r) else ' **differs**'})"
            cells.append(cell)
        lines.append(f"| {label} ({len(g)}) | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def compare(rows):
    """Add, per observable, the difference from the reference, its size in error bars and
    whether it is noise: by the error bars (within_noise), and against the replicas' scatter
    (two runs differ by sqrt(2) times the scatter: within noise when below 2 sqrt(2) of it)."""
    ref = next(r for r in rows if r["setting"] == "reference")
    scatter = replica_scatter(rows)
    for r in rows:
        for key, _, _ in OBSERVABLES:
            s, s_ref = r[key + "_err"] or 0.0, ref[key + "_err"] or 0.0
            r[key + "_diff"] = r[key] - ref[key]
            has_bars = r[key + "_err"] is not None or ref[key + "_err"] is not None
            r[key + "_sig"] = significance(r[key], s, ref[key], s_ref) if has_bars else None
            r[key + "_noise"] = within_noise(r[key], s, ref[key], s_ref) if has_bars else None
            if scatter:
                bar = math.sqrt(2) * scatter[key]
                r[key + "_sig_replica"] = significance(r[key], bar, ref[key], 0.0)
                r[key + "_noise_replica"] = within_noise(r[key], bar, ref[key], 0.0)
    return rows, scatter


def fmt(x, digits=3):
    if x is None:
        return "–"
    if isinstance(x, str):
        return x
    return f"{x:.{digits}g}"


def write_csv(rows, path):
    keys = list(dict.fromkeys(k for r in rows for k in r))   # every column, first-seen order
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys, restval="")
        writer.writeheader()
        writer.writerows(rows)


def markdown_tables(rows, cost_only=False, scatter=None):
    cost = ["| setting | window (s) | CPU s / phys. s | contact updates / CPU s | sweeps/step mean | max | capped steps | final norm | overlap mean (d) | max (d) |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        mark = "" if r["finished"] else " (stopped)"
        cost.append(f"| {r['setting']} | {r['window_s']:.2f}{mark} | {r['cpu_per_s']:.0f} | {r['updates_per_cpu_s'] / 1e6:.1f} M | "
                    f"{r['sweeps_mean']:.0f} | {r['sweeps_max']:.0f} | {1 - r['converged']:.2%} | "
                    f"{r['residual']:.2g} | {r['overlap_mean_d']:.1e} | {r['overlap_max_d']:.1e} |")
    if cost_only:
        return "\n".join(cost) + "\n"
    obs = ["| setting | " + " | ".join(f"{label} ({unit})" if unit else label for _, label, unit in OBSERVABLES) + " |",
           "|---|" + "---|" * len(OBSERVABLES)]
    for r in rows:
        cells = []
        for key, _, _ in OBSERVABLES:
            cell = f"{fmt(r[key])} ± {fmt(r[key + '_err'], 2)}"
            if r["setting"] != "reference":
                marks = []
                if r[key + "_sig"] is not None:
                    marks.append(f"{r[key + '_sig']:.1f}σ{'' if r[key + '_noise'] else ' **differs**'}")
                if key + "_sig_replica" in r:
                    marks.append(f"{r[key + '_sig_replica']:.1f}σr{'' if r[key + '_noise_replica'] else ' **differs**'}")
                cell += f" ({'; '.join(marks)})" if marks else ""
            cells.append(cell)
        obs.append(f"| {r['setting']} | " + " | ".join(cells) + " |")
    if scatter:
        obs.append("| replica scatter (pooled sd of one run) | " + " | ".join(fmt(scatter[key], 2) for key, _, _ in OBSERVABLES) + " |")
    groups = group_table(rows)
    return "\n".join(cost) + "\n\n" + "\n".join(obs) + "\n" + ("\n" + groups if groups else "")


def gnuplot(script, folder):
    subprocess.run(["gnuplot"], input=script, text=True, cwd=folder, check=True)


def pareto_figure(rows, folder):
    """Cost against |difference| / error bar, one panel per observable; 2 = the noise line."""
    data = []
    for key, label, _ in OBSERVABLES:
        data.append(f"${key} << EOD")
        for r in rows:
            if r["setting"] != "reference":
                bars = r[key + "_sig"] if r[key + "_sig"] is not None else math.nan
                replica = r.get(key + "_sig_replica", math.nan)
                data.append(f"{r['cpu_per_s']:.6g} {max(bars, 0.01):.6g} {max(replica, 0.01):.6g} \"{'' if r['factor'] == 'replica' else r['setting']}\"")
        data.append("EOD")
    panels = []
    for i, (key, label, _) in enumerate(OBSERVABLES):
        panels.append(f"set title '{label}'\nplot ${key} using 1:2 with points pt 7 ps 0.8 lc 'black' title 'error bars', "
                      f"${key} using 1:3 with points pt 6 ps 0.9 lc 'red' title 'replica scatter', "
                      f"${key} using 1:($3 == $3 ? $3 : $2):4 with labels offset 0,0.6 font ',7' notitle, "
                      f"2 with lines dt 2 lc 'gray' notitle")
    script = "\n".join(data) + f"""
set terminal pngcairo size 1300,620 font ',9' noenhanced
set output 'accuracy_pareto.png'
set multiplot layout 2,4
set logscale xy
set xlabel 'CPU s per physical s'
set ylabel '|x - x_ref| / combined error bar'
set format x '%g'
set yrange [0.01:*]
set key bottom right font ',7'
""" + "\n".join(panels) + "\nunset multiplot\n"
    gnuplot(script, folder)


def convergence_figure(rows, folder, scatter):
    """f (peak ± half width) and f_c (spectral centroid ± the replicas' scatter) against dt and
    against tolerance; the band is the reference's f_c ± 2 sqrt(2) scatter (within noise)."""
    ref = next(r for r in rows if r["setting"] == "reference")
    sd = scatter["f_c"] if scatter else 0.0
    def series(factor, column):
        pts = sorted((r for r in rows if r["factor"] in (factor, "default")), key=lambda r: float(r[column]))
        return "\n".join(f"{float(r[column]):.6g} {r['f']:.6g} {r['f_err']:.6g} {r['f_c']:.6g} {sd:.6g}" for r in pts)
    plots = ("plot lo with lines dt 2 lc 'gray' notitle, hi with lines dt 2 lc 'gray' notitle, "
             "{0} using ($1*0.93):2:3 with yerrorbars pt 7 lc 'black' title 'f (peak, ± half width)', "
             "{0} using ($1*1.07):4:5 with yerrorbars pt 6 lc 'red' title 'f_c (centroid, ± replica sd)'")
    script = f"""$dt << EOD
{series('dt', 'dt')}
EOD
$tol << EOD
{series('tolerance', 'tolerance')}
EOD
set terminal pngcairo size 900,380 font ',9' noenhanced
set output 'accuracy_f_convergence.png'
set format x '%.0e'
set offsets graph 0.1, graph 0.1, 0, 0
set key top right font ',7'
set multiplot layout 1,2
set ylabel 'Hz'
set logscale x
lo = {ref['f_c'] - 2 * math.sqrt(2) * sd:.6g}; hi = {ref['f_c'] + 2 * math.sqrt(2) * sd:.6g}
set xlabel 'time step (s)'
set title 'against dt (tolerance 1e-3); band: reference f_c within noise'
{plots.format('$dt')}
set xlabel 'tolerance'
set title 'against tolerance (dt 2e-5 s)'
{plots.format('$tol')}
unset multiplot
"""
    gnuplot(script, folder)


# ---------------------------------------------------------------- main

def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", required=True, help="study folder (outside the repository)")
    p.add_argument("--scene", choices=sorted(SCENES), default="small", help="small: L = 20 d, 400 grains, 10 d walls; full: L = 45 d")
    p.add_argument("--lmp", default=os.path.join(TOP, "build", "lmp_cd"))
    p.add_argument("--cdpost", default=os.path.join(TOP, "build", "postproc", "cdpost"))
    p.add_argument("--spinup", default="0.7", help="chute time of the common restart (s)")
    p.add_argument("--window", default="0.4", help="flow window of each setting (s)")
    p.add_argument("--discard", default="0.05", help="start of each window left out of the analysis (s)")
    p.add_argument("--segment", type=float, default=0.175, help="cdpost spectrum segment (s)")
    p.add_argument("--ref-dt", default="1e-5")
    p.add_argument("--ref-tolerance", default="1e-4")
    p.add_argument("--ref-max-iterations", default="10000")
    p.add_argument("--replicas", nargs="*", help="also run three shuffled-order replicas of these settings")
    p.add_argument("--jobs", type=int, default=2, help="windows run at once")
    p.add_argument("--only", nargs="*", help="run only these settings")
    p.add_argument("--cost-only", action="store_true",
                   help="cost and solver columns only, no observables (for windows too short to analyse)")
    p.add_argument("--stop-at", default=None,
                   help="UTC time HH:MM at which running windows are stopped and analysed as far as they got")
    p.add_argument("--dry-run", action="store_true", help="list the settings and commands, run nothing")
    p.add_argument("--analyse-only", action="store_true", help="analyse the finished windows only")
    p.add_argument("--figures", default=None, help="also copy the figures into this folder")
    args = p.parse_args()
    # Every job runs in its own folder: a program given by a relative path is found from here.
    for name in ("lmp", "cdpost"):
        if os.sep in getattr(args, name):
            setattr(args, name, os.path.abspath(getattr(args, name)))
    for name, value in (("spinup", args.spinup), ("window", args.window), ("discard", args.discard)):
        if float(value) <= 0:
            p.error(f"--{name} {value}: must be > 0")
    if float(args.discard) >= float(args.window):
        p.error(f"--discard {args.discard}: must be shorter than --window {args.window}")

    args.deadline = None
    if args.stop_at:
        hour, minute = map(int, args.stop_at.split(":"))
        now = time.gmtime()
        args.deadline = time.time() + ((hour * 60 + minute) - (now.tm_hour * 60 + now.tm_min)) % 1440 * 60 - now.tm_sec
    deposition, spinup, windows = build_jobs(args)
    if args.dry_run:
        for job in [deposition, spinup] + [w[3] for w in windows]:
            print(f"{job.name}: {' '.join(shlex.quote(c) for c in job.cmd)}")
        return 0
    if not args.analyse_only:
        os.makedirs(args.out, exist_ok=True)
        copy = os.path.join(args.out, "in.chute")
        if not os.path.exists(copy) or open(copy).read() != open(DECK).read():
            shutil.copy(DECK, copy)
        for stage in (deposition, spinup):
            if not stage.done():
                stage.run()
        run_pool([w[3] for w in windows], args.jobs)
    rows = []
    for name, factor, setting, job in windows:
        if job.partial() and reached_time(job.folder) - float(args.spinup) - float(args.discard) < 2 * args.segment:
            print(f"{name}: stopped before two spectrum segments, left out", file=sys.stderr)
        elif job.done() or job.partial():
            rows.append(analyse_window(args, name, factor, setting, job))
        else:
            print(f"{name}: not finished, left out", file=sys.stderr)
    out = os.path.abspath(args.out)
    if args.cost_only:
        write_csv(rows, os.path.join(out, "accuracy_cost.csv"))
        with open(os.path.join(out, "accuracy_cost.md"), "w") as f:
            f.write(markdown_tables(rows, cost_only=True))
        print(f"wrote {out}/accuracy_cost.csv, accuracy_cost.md")
        return 0
    if not any(r["setting"] == "reference" for r in rows):
        print("the reference window has not finished: no comparison", file=sys.stderr)
        return 1
    rows, scatter = compare(rows)
    write_csv(rows, os.path.join(out, "accuracy.csv"))
    with open(os.path.join(out, "accuracy.md"), "w") as f:
        f.write(markdown_tables(rows, scatter=scatter))
    pareto_figure(rows, out)
    convergence_figure(rows, out, scatter)
    if args.figures:
        for name in ("accuracy_pareto.png", "accuracy_f_convergence.png"):
            shutil.copy(os.path.join(out, name), args.figures)
    print(f"wrote {out}/accuracy.csv, accuracy.md, accuracy_pareto.png, accuracy_f_convergence.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
