#!/usr/bin/env python3
"""Run the stability matrix of fix contact/dynamics and write a Markdown results table.

    studies/stability_matrix.py --out /work/stab-runs [--lmp build/lmp_cd] [--jobs 1]
                                [--only PATTERN] [--list]

Every case is one lmp_cd process in its own folder under --out (deck, log, screen output).
Each case either runs with bounded interpenetration and finite velocities, or stops with an
ERROR line naming the limit it exceeded; the table reports which, with the largest and mean
interpenetration, Gauss-Seidel sweeps per step and the case's own check (doc/stability.md).

Families (all SI, d = 5e-4 m, grains of density 2500 kg/m^3):
  fe_*     friction x restitution: a rain of 144 disks on a floor (20 d cell), 150 ms
  dt_*     time step: the same rain thrown down at 1 m/s, 20 ms, dt 1e-6 s .. 0.4 d per step
  size_*   size ratio: large disks dropped onto a rain of small ones (40 d cell), 60 ms
  long_*   gravity off, e = 1: a periodic gas of 144 disks, 1 s (momentum, energy drift)
  tilt_*   inputs/in.chute, 20 d cell, 400 grains, 10 d walls: static and runaway tilts, 0.4 s
  L*       inputs/in.chute, L = 12 .. 152 d, 15 grains per d of length, 6 d walls,
           mu 0.5, 24 degrees, 0.2 s
The chute cases start from a deposition of the same cell (cases dep_*), run first.

Results: --out/results.md (the table) and --out/results.json. Standard library only.
"""

import argparse
import fnmatch
import json
import math
import os
import shutil
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools.lammps_files import read_dump, read_time_file, unwrapped
from cdtools.logs import error_line, has_non_finite, tagged_line, thermo_rows
from cdtools.run import BUILT_LMP_CD, DECK as CHUTE_DECK, lmp_command, run_timed
from cdtools.stats import least_squares_slope
from cdtools.text import markdown_table, number

D = 5.0e-4          # mean diameter (m)
G = 9.81            # gravity (m/s^2)
SQRT_GD = math.sqrt(G * D)
CASE_TIMEOUT = 900  # s of wall time before a case is killed and reported as such

PREAMBLE = """units si
dimension 2
atom_style sphere
atom_modify map array
comm_modify vel yes
neigh_modify delay 0 every 1 check yes
"""

# Appended to the generic decks before their measured run: every step's largest and mean
# interpenetration (fix vector), and a summary line with the run's extremes.
MEASURE = """fix overlaps all vector 1 f_cd[5] f_cd[6]
compute ke_translational all ke
compute ke_disk_spin all erotate/sphere
variable ke_total equal c_ke_translational+1.25*c_ke_disk_spin
compute extent all reduce max x y vx vy
compute extent_low all reduce min x y vx vy
"""
# The summary's computes must be current at the last step: the thermo rows invoke them.
EXTREMES = ("v_ke_total c_extent[1] c_extent[2] c_extent[3] c_extent[4] "
            "c_extent_low[1] c_extent_low[2] c_extent_low[3] c_extent_low[4]")

SUMMARY = ('print "SUMMARY overlap_max $(max(f_overlaps[1])) overlap_mean $(ave(f_overlaps[2])) '
           'sweeps $(f_cd[8]) steps $(f_cd[10]) capped $(f_cd[9]) ke_total $(v_ke_total) '
           'xmax $(c_extent[1]) ymax $(c_extent[2]) vxmax $(c_extent[3]) vymax $(c_extent[4]) '
           'xmin $(c_extent_low[1]) ymin $(c_extent_low[2]) vxmin $(c_extent_low[3]) vymin $(c_extent_low[4]) '
           'grains $(atoms) mass $(mass(all))"\n')


def fmt(value):
    return f"{value:.6g}"


# ---------------------------------------------------------------------------------------
# Decks of the generic families
# ---------------------------------------------------------------------------------------

def rain_deck(mu, e, dt, duration, throw=0.0, skin=0.2, seed=77):
    """144 disks (diameters uniform in [0.8, 1.2] d) dropped from a 1.5 d lattice onto a
    floor in a 20 d x-periodic cell; `throw` (m/s) is an initial downward velocity."""
    steps = int(round(duration / dt))
    throw_line = f"velocity all set NULL {-throw} 0 units box\n" if throw else ""
    return PREAMBLE + f"""boundary p fm p
region box block 0 {fmt(20 * D)} 0 {fmt(40 * D)} -{fmt(0.6 * D)} {fmt(0.6 * D)}
create_box 1 box
lattice sq {fmt(1.5 * D)}
region fill block {fmt(0.7 * D)} {fmt(18.8 * D)} {fmt(2 * D)} {fmt(19.9 * D)} -{fmt(0.6 * D)} {fmt(0.6 * D)} units box
create_atoms 1 region fill
variable diameter atom {fmt(0.8 * D)}+{fmt(0.4 * D)}*random(0,1,{seed})
variable sideways atom 0.05*normal(0,1,{seed + 1})
set group all diameter v_diameter
set group all density/disc 2500
set group all vx v_sideways
{throw_line}neighbor {fmt(skin * D)} bin
timestep {fmt(dt)}
fix grav all gravity {G} vector 0 -1 0
fix cd all contact/dynamics {fmt(mu)} {fmt(e)} tolerance 1e-4 wall yplane 0.0 {fmt(mu)} {fmt(e)}
fix 2d all enforce2d
{MEASURE}thermo_style custom step time f_cd[1] f_cd[5] f_cd[9] {EXTREMES}
thermo_modify norm no flush yes
thermo {max(1, steps // 20)}
run {steps}
{SUMMARY}"""


def size_ratio_deck(ratio, duration=0.06, dt=1e-5):
    """Large disks of diameter ratio*d dropped onto a rain of small disks ([0.8, 1.2] d) in a
    40 d x-periodic cell: the small rain fills 1-16 d, the large disks start above it."""
    length = 40 * D
    count = max(1, int(40 // (1.2 * ratio)))
    spacing = length / count
    y_big = (17 + 0.6 * ratio) * D
    height = y_big + ratio * D
    bigs = "".join(f"create_atoms 1 single {fmt((k + 0.5) * spacing)} {fmt(y_big)} 0\n" for k in range(count))
    steps = int(round(duration / dt))
    return PREAMBLE + f"""boundary p fm p
region box block 0 {fmt(length)} 0 {fmt(height)} -{fmt(0.6 * ratio * D)} {fmt(0.6 * ratio * D)}
create_box 1 box
{bigs}group big id <= {count}
set group big diameter {fmt(ratio * D)}
lattice sq {fmt(1.3 * D)}
region rain block {fmt(0.5 * D)} {fmt(length - 0.8 * D)} {fmt(D)} {fmt(16 * D)} -{fmt(0.1 * D)} {fmt(0.1 * D)} units box
create_atoms 1 region rain
group small subtract all big
variable diameter atom {fmt(0.8 * D)}+{fmt(0.4 * D)}*random(0,1,91)
set group small diameter v_diameter
set group all density/disc 2500
neighbor {fmt(0.3 * D)} bin
timestep {fmt(dt)}
fix grav all gravity {G} vector 0 -1 0
fix cd all contact/dynamics 0.5 0.5 tolerance 1e-4 max_contacts 40 wall yplane 0.0 0.5 0.5
fix 2d all enforce2d
{MEASURE}thermo_style custom step time f_cd[1] f_cd[5] f_cd[9] {EXTREMES}
thermo_modify norm no flush yes
thermo {steps // 20}
run {steps}
{SUMMARY}"""


def gas_deck(mu, spacing, duration=1.0, dt=1e-5):
    """Gravity off, e = 1: 144 disks ([0.8, 1.2] d) on a square lattice of the given spacing
    (in d) in a fully periodic box, random velocities of 0.1 m/s rms. The thermo rows every
    1000 steps carry the momentum and the total (translational + disk spin) kinetic energy."""
    side = 12 * spacing * D
    steps = int(round(duration / dt))
    return PREAMBLE + f"""boundary p p p
region box block 0 {fmt(side)} 0 {fmt(side)} -{fmt(0.6 * D)} {fmt(0.6 * D)}
create_box 1 box
lattice sq {fmt(spacing * D)}
create_atoms 1 box
variable diameter atom {fmt(0.8 * D)}+{fmt(0.4 * D)}*random(0,1,5)
set group all diameter v_diameter
set group all density/disc 2500
variable vx atom 0.1*normal(0,1,9)
variable vy atom 0.1*normal(0,1,10)
set group all vx v_vx
set group all vy v_vy
variable px equal mass(all)*vcm(all,x)
variable py equal mass(all)*vcm(all,y)
variable momentum_of_grain atom mass*sqrt(vx*vx+vy*vy)
compute momentum_scale all reduce sum v_momentum_of_grain
neighbor {fmt(0.3 * D)} bin
timestep {fmt(dt)}
fix cd all contact/dynamics {fmt(mu)} 1.0 tolerance 1e-6
fix 2d all enforce2d
{MEASURE}thermo_style custom step v_px v_py c_momentum_scale f_cd[1] f_cd[5] f_cd[8] {EXTREMES}
thermo_modify norm no flush yes format float %.17g
thermo 1000
run {steps}
{SUMMARY}"""


# ---------------------------------------------------------------------------------------
# Running
# ---------------------------------------------------------------------------------------

def run_process(args, folder, command, deck=None):
    """Runs command in a fresh folder (with `deck` written to in.case) under nice, stdout and
    stderr in folder/screen.txt; returns (exit status or 'timeout', CPU seconds, screen text).
    With --reuse a folder holding a finished screen.txt is read instead (CPU time None)."""
    screen_path = os.path.join(folder, "screen.txt")
    if args.reuse and os.path.exists(screen_path):
        with open(screen_path, errors="replace") as screen:
            text = screen.read()
        if "Total wall time" in text or "ERROR" in text:
            return (0 if "Total wall time" in text else 1), None, text
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    if deck is not None:
        with open(os.path.join(folder, "in.case"), "w") as out:
            out.write(deck)
    status, cpu = run_timed(["nice", "-n", "19"] + command, folder, screen_path, CASE_TIMEOUT)
    with open(screen_path, errors="replace") as screen:
        return status, cpu, screen.read()


# ---------------------------------------------------------------------------------------
# Cases
# ---------------------------------------------------------------------------------------

class Case:
    def __init__(self, name, family, describe, run, needs=None):
        self.name, self.family, self.describe, self.run, self.needs = name, family, describe, run, needs


def result(status, overlap_max=None, overlap_mean=None, finite=None, sweeps=None, check="", cpu=None):
    return dict(status=status, overlap_max=overlap_max, overlap_mean=overlap_mean, finite=finite,
                sweeps=sweeps, check=check, cpu=cpu)


def stopped(status, text, **fields):
    """The result of a case that did not finish: its ERROR line, else its exit status."""
    error = error_line(text)
    return result(f"stopped: {error}" if error else f"exit {status}", **fields)


def generic_case(args, folder, deck, specific):
    """Runs a generic deck; `specific(summary, text)` gives the case's own check text."""
    status, cpu, text = run_process(args, folder, lmp_command(args.lmp, "in.case", {}), deck)
    summary = tagged_line(text, "SUMMARY")
    finite = not has_non_finite("\n".join(line for line in text.splitlines() if not line.startswith("ERROR")))
    if status != 0 or summary is None:
        return stopped(status, text, finite=finite, cpu=cpu, check="timeout" if status == "timeout" else "")
    finite = finite and all(math.isfinite(v) for v in summary.values())
    return result("ok", summary["overlap_max"], summary["overlap_mean"], finite,
                  summary["sweeps"] / summary["steps"], specific(summary, text), cpu)


def ke_per_grain(summary):
    """Kinetic energy (translation + spin) per grain over m g d, m the mean grain mass."""
    return summary["ke_total"] / (summary["mass"] * G * D)


def friction_restitution_case(mu, e):
    def run(args, folder):
        deck = rain_deck(mu, e, dt=1e-5, duration=0.15)
        return generic_case(args, folder, deck, lambda s, _: f"KE/grain {ke_per_grain(s):.2g} m g d at 150 ms")
    return Case(f"fe_mu{mu:g}_e{e:g}", "friction x restitution",
                f"rain of 144 disks, mu = {mu:g}, e = {e:g}, dt 1e-5 s, 150 ms", run)


def time_step_case(dt, skin):
    travel = 1.0 * dt / D    # d per step at the throw velocity

    def run(args, folder):
        deck = rain_deck(0.5, 0.5, dt=dt, duration=0.02, throw=1.0, skin=skin)

        def check(summary, _):
            fastest = max(abs(summary[k]) for k in ("vxmax", "vymax", "vxmin", "vymin"))
            return (f"{travel:.3g} d/step thrown; fastest grain at the end {fastest * dt / D:.3g} d/step; "
                    f"lowest centre {summary['ymin'] / D:.3f} d")
        return generic_case(args, folder, deck, check)
    return Case(f"dt_{dt:g}", "time step",
                f"rain thrown down at 1 m/s, dt {dt:g} s ({travel:.3g} d per step), skin {skin:g} d, 20 ms", run)


def size_ratio_case(ratio):
    def run(args, folder):
        return generic_case(args, folder, size_ratio_deck(ratio), lambda s, _: (
            f"KE/grain {ke_per_grain(s):.2g} m g d at 60 ms; lowest centre {s['ymin'] / D:.3f} d"))
    return Case(f"size_{ratio:g}", "size ratio",
                f"disks of {ratio:g} d dropped onto a rain of [0.8, 1.2] d disks, 40 d cell, 60 ms", run)


def gas_case(mu, spacing, dt=1e-5, duration=1.0):
    def run(args, folder):
        def check(summary, text):
            rows = thermo_rows(text)
            p0 = (rows[0]["v_px"], rows[0]["v_py"])
            scale = rows[0]["c_momentum_scale"]
            drift = max(math.hypot(r["v_px"] - p0[0], r["v_py"] - p0[1]) for r in rows) / scale
            ke0 = rows[0]["v_ke_total"]
            ke_peak = max(r["v_ke_total"] for r in rows) / ke0
            ke_end = rows[-1]["v_ke_total"] / ke0
            return (f"|P - P0|/sum m|v| <= {drift:.1e}; KE max/KE0 = 1{ke_peak - 1:+.1e}, "
                    f"KE end/KE0 = {ke_end:.4f}; {int(rows[-1]['f_cd[8]'])} sweeps in {int(rows[-1]['Step'])} steps")
        return generic_case(args, folder, gas_deck(mu, spacing, duration, dt), check)
    steps = int(round(duration / dt))
    suffix = "" if duration == 1.0 else f"_{duration:g}s_dt{dt:g}"
    return Case(f"long_mu{mu:g}_spacing{spacing:g}{suffix}", "long run, gravity off, e = 1",
                f"periodic gas of 144 disks, lattice {spacing:g} d, mu = {mu:g}, e = 1, 0.1 m/s rms, "
                f"dt {dt:g} s, {duration:g} s ({steps:.0e} steps)", run)


def chute_deposition_case(name, variables):
    def run(args, folder):
        command = lmp_command(args.lmp, CHUTE_DECK, {"stage": "deposition", **variables})
        status, cpu, text = run_process(args, folder, command)
        summary = tagged_line(text, "DEPOSITION")
        if status != 0 or summary is None:
            return stopped(status, text, cpu=cpu)
        rows = thermo_rows(text)
        overlaps = [r["f_cd[5]"] for r in rows if "f_cd[5]" in r]
        sweeps = [r["f_cd[1]"] for r in rows if "f_cd[1]" in r]
        finite = not has_non_finite(text)
        return result("ok", max(overlaps), None, finite, sum(sweeps) / len(sweeps),
                      f"settled at {summary['time_s']:g} s, phi_bed {summary['phi_bed']:.3f}, "
                      f"{int(summary['grains'])} grains", cpu)
    text = ", ".join(f"{k} {v}" for k, v in variables.items())
    return Case(name, "chute deposition", f"in.chute deposition, {text} (overlap: thermo rows every 0.01 s)", run)


def chute_flow(args, folder, deposition, variables):
    """Runs in.chute stage flow with per-step solver.time rows; returns (result or None,
    status, cpu, text)."""
    start = os.path.join(args.out, deposition, "deposition.restart")
    variables = {**CHUTE_SOLVER, **variables}
    every_step = dict(solver_interval=variables["dt"], snapshot_interval=0.1, restart_interval=0.1)
    command = lmp_command(args.lmp, CHUTE_DECK, {"stage": "flow", "start": start, **every_step, **variables})
    status, cpu, text = run_process(args, folder, command)
    chute = tagged_line(text, "CHUTE")
    if status != 0 or chute is None:
        return stopped(status, text, cpu=cpu, finite=not has_non_finite(text)), None
    solver = read_time_file(os.path.join(folder, "solver.time"))
    finite = not has_non_finite(text) and all(math.isfinite(v) for v in chute.values())
    base = result("ok", max(r["f_cd[5]"] for r in solver), sum(r["f_cd[6]"] for r in solver) / len(solver),
                  finite, chute["sweeps"] / chute["steps_solved"], cpu=cpu)
    return base, chute


def tilt_case(mu, theta, duration, deposition, cell):
    def run(args, folder):
        base, chute = chute_flow(args, folder, deposition,
                                 dict(cell, mu=mu, theta=theta, duration=duration))
        if chute is None:
            return base
        flow = read_time_file(os.path.join(folder, "flow.time"))
        frames = [(frame[0], unwrapped(frame)) for frame in read_dump(os.path.join(folder, "dump.chute.gz"))]
        half = duration / 2
        late = [r for r in flow if r["v_time"] >= half]
        ts = [r["v_time"] for r in late]
        slope_flow, r2 = least_squares_slope(ts, [r["v_u_flow"] for r in late])
        slope_all, _ = least_squares_slope(ts, [r["v_u_all"] for r in late])
        gs = G * math.sin(math.radians(theta))
        u_end = flow[-1]["v_u_flow"] / SQRT_GD
        # Displacement over the second half: the frames at duration/2 and at the end; the mean
        # downslope displacement in each frame interval (0.1 s).
        start = min(frames, key=lambda f: abs(f[0] * CHUTE_SOLVER["dt"] - half))[1]
        end = frames[-1][1]
        moved = sorted(math.hypot(end[i][0] - p[0], end[i][1] - p[1]) for i, p in start.items())
        creep = [sum(b[i][0] - a[i][0] for i in a) / len(a) / D
                 for (_, a), (_, b) in zip(frames, frames[1:])]
        rate = (lambda a: f"{a / gs:.3f} g sin(theta)") if theta else (lambda a: f"{a:.2g} m/s^2")
        base["check"] = (f"2nd half: du_flow/dt = {rate(slope_flow)} (R^2 {r2:.2f}), "
                         f"du_all/dt = {rate(slope_all)}; U end {u_end:.3g} sqrt(g d); "
                         f"displacement max {moved[-1] / D:.3g} d, median {moved[len(moved) // 2] / D:.3g} d; "
                         f"mean downslope per 0.1 s: {', '.join(f'{c:.2g}' for c in creep)} d")
        base["acceleration_flow"] = slope_flow    # m/s^2
        base["displacement_max_d"] = moved[-1] / D
        return base
    return Case(f"tilt_mu{mu:g}_theta{theta:g}", "tilt",
                f"in.chute flow, 20 d cell, mu = {mu:g}, theta = {theta:g} deg, {duration:g} s", run,
                needs=deposition)


def length_case(length, duration, deposition, cell):
    def run(args, folder):
        base, chute = chute_flow(args, folder, deposition, dict(cell, theta=24, duration=duration))
        if chute is None:
            return base
        base["check"] = (f"U end {chute['U_sqrt_gd']:.3g} sqrt(g d), h {chute['h_d']:.1f} d, "
                         f"{int(chute['steps_capped'])} capped steps of {int(chute['steps_solved'])}")
        return base
    return Case(f"L{length:g}", "cell length",
                f"in.chute flow, L = {length:g} d, {cell['grains']} grains, mu 0.5, 24 deg, {duration:g} s",
                run, needs=deposition)


TILT_CELL = dict(L=20, grains=400, wall_height=10)
# The chute cases run at a fixed step with every step's solver row: the settings the matrix
# of doc/stability.md was measured at (the deck's defaults before the step followed the flow).
CHUTE_SOLVER = dict(dt=2e-5, adapt_dt="no", tolerance=1e-3, skin=0.6)
TILT_DURATION = 0.4
LENGTHS = (12, 22, 45, 152)
LENGTH_DURATION = 0.2


def length_cell(length):
    return dict(L=length, grains=15 * length, wall_height=6)


def all_cases():
    # The depositions first: the chute flows wait for them.
    cases = [chute_deposition_case("dep_tilt", TILT_CELL)]
    cases += [chute_deposition_case(f"dep_L{n}", length_cell(n)) for n in LENGTHS]
    cases += [friction_restitution_case(mu, e) for mu in (0, 0.05, 0.5, 2, 10, 1e6) for e in (0, 0.5, 1)]
    # 1 m/s for dt: 1e-6 s is 0.002 d per step, 1e-4 s 0.2 d, 2e-4 s 0.4 d > skin/2 = 0.25 d.
    cases += [time_step_case(dt, 0.5) for dt in (1e-6, 1e-5, 5e-5, 1e-4, 2e-4)]
    cases += [size_ratio_case(ratio) for ratio in (1.5, 3, 10)]
    cases += [gas_case(0, 1.25), gas_case(0.5, 1.25), gas_case(0, 2.5)]
    # The dissipation at e = 1 against the time step: the dense gas for 0.1 s at 1e-5 and 1e-6 s.
    cases += [gas_case(0, 1.25, dt, 0.1) for dt in (1e-5, 1e-6)]
    for theta in (0, 10, 20, 30, 45, 60):
        cases.append(tilt_case(0.5, theta, TILT_DURATION, "dep_tilt", TILT_CELL))
    for theta in (10, 20, 30, 45, 60):
        cases.append(tilt_case(0.05, theta, TILT_DURATION, "dep_tilt", TILT_CELL))
    cases += [length_case(n, LENGTH_DURATION, f"dep_L{n}", length_cell(n)) for n in LENGTHS]
    return cases


# ---------------------------------------------------------------------------------------
# Table
# ---------------------------------------------------------------------------------------

TABLE_HEADINGS = ["case", "what", "status", "max overlap (d)", "mean overlap (d)", "finite", "sweeps/step", "check",
                  "CPU s"]


def table(cases, results):
    rows = []
    for case in cases:
        r = results.get(case.name)
        if r is None:
            continue
        finite = "–" if r["finite"] is None else ("yes" if r["finite"] else "**NO**")
        status, check = (r[k].replace("|", "\\|") for k in ("status", "check"))
        rows.append([case.name, case.describe, status, number(r["overlap_max"], 2), number(r["overlap_mean"], 2),
                     finite, number(r["sweeps"], 3), check, number(r["cpu"], 3)])
    return markdown_table(TABLE_HEADINGS, rows)


def options():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="scratch folder for the runs and the results")
    parser.add_argument("--lmp", default=os.environ.get("LMP_CD", BUILT_LMP_CD))
    parser.add_argument("--jobs", type=int, default=1, help="cases run at once (each under nice -n 19)")
    parser.add_argument("--only", action="append", help="run only cases matching this glob (repeatable)")
    parser.add_argument("--list", action="store_true", help="list the cases and exit")
    parser.add_argument("--reuse", action="store_true",
                        help="analyse the finished runs already in --out again instead of running them")
    args = parser.parse_args()
    args.lmp, args.out = os.path.abspath(args.lmp), os.path.abspath(args.out)
    return args


def selected_cases(args):
    """The cases --only selects, and the depositions they need (implied: reused if finished)."""
    cases = all_cases()
    if not args.only:
        return cases, set()
    wanted = {c.name for c in cases if any(fnmatch.fnmatch(c.name, p) for p in args.only)}
    implied = {c.needs for c in cases if c.name in wanted and c.needs} - wanted
    return [c for c in cases if c.name in wanted | implied], implied


class CaseRunner:
    """Runs cases on threads, each after the case it needs; keeps and prints their results."""

    def __init__(self, args, implied, previous):
        self.args, self.implied, self.previous = args, implied, previous
        self.results, self.lock = {}, threading.Lock()
        self.started = time.time()

    def run_all(self, cases):
        futures = {}
        with ThreadPoolExecutor(max_workers=self.args.jobs) as pool:
            for case in cases:    # dependencies are listed, hence submitted and started, first
                futures[case.name] = pool.submit(self.run_case, case, futures.get(case.needs))
        for future in futures.values():
            future.result()
        return len(futures)

    def run_case(self, case, dependency):
        if dependency is not None:
            dependency.result()
        outcome = self.outcome(case)
        if outcome["cpu"] is None and case.name in self.previous:
            outcome["cpu"] = self.previous[case.name]["cpu"]
        with self.lock:
            self.results[case.name] = outcome
            print(f"[{time.time() - self.started:7.0f} s] {case.name}: {outcome['status']} "
                  f"(max overlap {number(outcome['overlap_max'], 2)} d, {number(outcome['cpu'], 3)} CPU s) "
                  f"{outcome['check']}", flush=True)

    def outcome(self, case):
        if case.needs and self.results[case.needs]["status"] != "ok":
            return result(f"skipped: {case.needs} did not finish")
        # A deposition added only because a chosen case needs it is reused when finished.
        case_args = argparse.Namespace(**dict(vars(self.args), reuse=self.args.reuse or case.name in self.implied))
        try:
            return case.run(case_args, os.path.join(self.args.out, case.name))
        except Exception as failure:    # a broken analysis must not lose the other cases
            return result(f"analysis failed: {failure!r}")


def write_results(args, runner, count):
    """results.md and results.json: this invocation's cases and those of earlier invocations
    in the same folder that it did not run again."""
    results = dict(runner.results)
    every_case = all_cases()
    for case in every_case:
        if case.name not in results and case.name in runner.previous:
            results[case.name] = {k: v for k, v in runner.previous[case.name].items() if k != "describe"}
    cases = [c for c in every_case if c.name in results]
    cpu_total = sum(r["cpu"] for r in results.values() if r.get("cpu"))
    header = (f"Stability matrix: {len(results)} cases, {cpu_total:.0f} CPU s in all, lmp_cd {args.lmp}, "
              f"table made {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} "
              f"(this invocation: {count} cases, {time.time() - runner.started:.0f} s wall, --jobs {args.jobs})\n\n")
    with open(os.path.join(args.out, "results.md"), "w") as out:
        out.write(header + table(cases, results))
    with open(os.path.join(args.out, "results.json"), "w") as out:
        json.dump({c.name: dict(results[c.name], describe=c.describe) for c in cases}, out, indent=1)
    print(header + table(cases, results))


def main():
    args = options()
    cases, implied = selected_cases(args)
    if args.list:
        for case in cases:
            print(f"{case.name:28s} {case.describe}")
        return 0
    if not os.access(args.lmp, os.X_OK):
        print(f"ERROR: no lmp_cd at {args.lmp} (--lmp or LMP_CD)")
        return 1
    os.makedirs(args.out, exist_ok=True)
    previous_path = os.path.join(args.out, "results.json")
    previous = json.load(open(previous_path)) if os.path.exists(previous_path) else {}
    runner = CaseRunner(args, implied, previous)
    count = runner.run_all(cases)
    write_results(args, runner, count)
    return 0


if __name__ == "__main__":
    sys.exit(main())
