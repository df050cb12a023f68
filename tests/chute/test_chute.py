#!/usr/bin/env python3
"""Deck-level tests of inputs/in.chute and studies/chute_campaign.py, run by ctest.

    tests/chute/test_chute.py CASE --lmp build/lmp_cd --work DIR

Each case runs lmp_cd (or the runner) on a tiny erodible-bed cell (10 d long, 200 grains,
walls 8 d high, so the flowing layer is about 12 d thick) and checks physics on its output.
The packing made by the case 'deposition' is the start of the cases that need one (a ctest
fixture). Standard library only.
"""

import argparse
import csv
import math
import gzip
import os
import shutil
import signal
import subprocess
import sys
import time

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies"))

import rank_solutions
from cdtools.lammps_files import read_chunk_file, read_dump, read_time_file, unwrapped
from cdtools.logs import tagged_line
from cdtools.run import DECK, TOP, lmp_command, mpi_launcher

RUNNER = os.path.join(TOP, "studies", "chute_campaign.py")

D = 5.0e-4                      # mean diameter (m), the deck's default
G = 9.81
SQRT_GD = math.sqrt(G * D)
# The tiny cell at the solver settings its assertions were measured at (the deck's defaults
# before they followed the 45 d study: doc/accuracy.md).
CELL = dict(L="10", grains="200", wall_height="8", dt="2e-5", tolerance="1e-3", skin="0.6", acceleration="none",
            full_sweep_every="1")
WALL_TOP = 8 * D


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def run_lmp(lmp, folder, variables, expect_ok=True, launcher=()):
    """Run in.chute in folder with -var NAME VALUE (behind `launcher`, e.g. mpirun -np 2);
    returns (exit status, screen text)."""
    os.makedirs(folder, exist_ok=True)
    result = subprocess.run(lmp_command(lmp, DECK, variables, launcher=launcher), cwd=folder, capture_output=True,
                            text=True)
    output = result.stdout + result.stderr
    if expect_ok and result.returncode != 0:
        errors = [line for line in output.splitlines() if "ERROR" in line]
        raise Failure(f"lmp_cd failed in {folder}: {errors[:1] or output[-500:]}")
    return result.returncode, output


def summary(output, tag):
    """The 'TAG key value ...' line the deck prints, as a dict."""
    values = tagged_line(output, tag)
    check(values is not None, f"no {tag} line in the output")
    return values


def check_record(folder, wall_height, grains, theta):
    """chute.params, the record in.chute writes for cdpost as a chute stage starts: the wall tops
    z is measured from, the sample rate (the deck's default), d, g, the grains and the tilt."""
    path = os.path.join(folder, "chute.params")
    check(os.path.exists(path), f"no chute.params in {folder}")
    with open(path) as src:
        record = {name: float(value) for name, value in
                  (line.split() for line in src if line.strip() and not line.startswith("#"))}
    expected = dict(y_top_m=wall_height * D, sample_rate_hz=1000, d_m=D, g_mps2=G, grains=grains, theta_deg=theta)
    wrong = {k: record.get(k) for k, v in expected.items() if record.get(k) is None or abs(record[k] - v) > 1e-9 * v}
    check(not wrong, f"{path}: {wrong}, expected {expected}")


def mean(values):
    values = list(values)
    return sum(values) / len(values)


# ----------------------------------------------------------------------------------------
# Cases
# ----------------------------------------------------------------------------------------

def largest_overlap(atoms, box):
    """Largest interpenetration r_i + r_j - |x_i - x_j| over all pairs (m), x periodic."""
    length = box[0][1] - box[0][0]
    grains = list(atoms.values())
    worst = -math.inf
    for i, a in enumerate(grains):
        for b in grains[i + 1:]:
            dx = a["x"] - b["x"]
            dx -= length * round(dx / length)
            worst = max(worst, a["radius"] + b["radius"] - math.hypot(dx, a["y"] - b["y"]))
    return worst


def surface_height(atoms, box, column_width=2 * D):
    """Mean over columns of the top of the highest grain whose centre is in the column (m)."""
    length = box[0][1] - box[0][0]
    columns = max(1, int(length / column_width))
    tops = [0.0] * columns
    for a in atoms.values():
        c = int((a["x"] - box[0][0]) / length * columns) % columns
        tops[c] = max(tops[c], a["y"] + a["radius"])
    return mean(tops)


def case_deposition(args):
    """The rain settles (kinetic energy criterion) into a packing with no interpenetration
    above 0.005 d, a packing fraction of a random 2D polydisperse deposit, and a surface at
    the height its grain area and packing fraction imply."""
    folder = os.path.join(args.work, "deposition")
    shutil.rmtree(folder, ignore_errors=True)
    _, output = run_lmp(args.lmp, folder, dict(CELL, stage="deposition"))
    result = summary(output, "DEPOSITION")
    for name in ("deposition.restart", "deposition.data", "deposition.dump"):
        check(os.path.exists(os.path.join(folder, name)), f"{name} not written")
    check(not os.path.exists(os.path.join(folder, "chute.params")), "the deposition wrote a chute's chute.params")
    check(result["grains"] == 200, f"{result['grains']} grains, expected 200")
    check(result["ke_per_grain"] < 1e-4, f"not settled: KE per grain {result['ke_per_grain']} m g d")
    check(result["max_interpenetration_d"] < 0.005,
          f"the fix reports an interpenetration of {result['max_interpenetration_d']} d")

    (_, box, atoms), = read_dump(os.path.join(folder, "deposition.dump"))
    overlap = largest_overlap(atoms, box) / D
    check(overlap < 0.005, f"two grains interpenetrate by {overlap:.4f} d")
    check(0.78 <= result["phi_bed"] <= 0.86,
          f"packing fraction of the bed {result['phi_bed']}, expected 0.78-0.86 for a random deposit")
    # Expected height: total grain area / (L phi_bed), computed here from the dump.
    area = sum(math.pi * a["radius"] ** 2 for a in atoms.values())
    length = box[0][1] - box[0][0]
    expected = area / (length * result["phi_bed"]) / D
    surface = surface_height(atoms, box) / D
    check(abs(surface - expected) < 1.5,
          f"surface at {surface:.2f} d, expected {expected:.2f} d from the packing fraction")
    check(surface > 8 + 5, f"the bed top {surface:.2f} d is not well above the 8 d walls")
    # Below the floor: deeper into it than the interpenetration the rigid model keeps between
    # grains at the deposition's tolerance (checked above).
    low = [a for a in atoms.values() if a["y"] - a["radius"] < -0.005 * D]
    check(not low, f"{len(low)} grains below the floor")
    print(f"deposition: phi_bed {result['phi_bed']:.4f}, surface {surface:.2f} d, expected "
          f"{expected:.2f} d, largest overlap {overlap:.2e} d, settled at {result['time_s']} s")


def case_reproducible(args):
    """The same seed gives the same packing; another seed another one."""
    reference = read_dump(os.path.join(args.work, "deposition", "deposition.dump"))[0][2]
    again = os.path.join(args.work, "deposition_again")
    other = os.path.join(args.work, "deposition_other_seed")
    for folder in (again, other):
        shutil.rmtree(folder, ignore_errors=True)
    run_lmp(args.lmp, again, dict(CELL, stage="deposition"))
    run_lmp(args.lmp, other, dict(CELL, stage="deposition", seed=12345))
    same = read_dump(os.path.join(again, "deposition.dump"))[0][2]
    different = read_dump(os.path.join(other, "deposition.dump"))[0][2]
    moved = max(math.hypot(same[i]["x"] - a["x"], same[i]["y"] - a["y"]) for i, a in reference.items())
    check(moved == 0.0, f"same seed, but a grain is {moved / D:.3g} d away")
    shifted = mean(math.hypot(different[i]["x"] - a["x"], different[i]["y"] - a["y"])
                   for i, a in reference.items())
    check(shifted > 0.5 * D, f"another seed moved the grains by only {shifted / D:.3g} d on average")
    print(f"reproducible: identical with the same seed; mean shift {shifted / D:.1f} d with another")


def chute(args, name, theta, duration, launcher=(), **extra):
    folder = os.path.join(args.work, name)
    shutil.rmtree(folder, ignore_errors=True)
    start = os.path.join(args.work, "deposition", "deposition.restart")
    variables = dict(CELL, stage="flow", start=start, theta=theta, duration=duration)
    variables.update(extra)
    _, output = run_lmp(args.lmp, folder, variables, launcher=launcher)
    return folder, output


FLOW_THETA, FLOW_DURATION, FLOW_FRAME = 24, 1.2, 0.004


def case_flow_run(args):
    """The flow that steady_flow and walls_trap analyse: 24 degrees (the thin layer stops at
    23) for 1.2 s, a dump frame every 4 ms. Its chute.params, and that of the same cell in stage
    all (deposition and chute in one process, 4 ms of flow at 26 degrees)."""
    folder, _ = chute(args, "flow", FLOW_THETA, FLOW_DURATION, snapshot_interval=FLOW_FRAME)
    check_record(folder, 8, 200, FLOW_THETA)
    in_one = os.path.join(args.work, "stage_all")
    shutil.rmtree(in_one, ignore_errors=True)
    run_lmp(args.lmp, in_one, dict(CELL, stage="all", theta=26, duration=0.004))
    check_record(in_one, 8, 200, 26)
    print("flow run written; chute.params right from a deposition and in stage all")


def dump_frames(path):
    """[(timestep, column names, rows)] of a gzip dump custom or dump local."""
    frames, lines = [], gzip.open(path, "rt").read().splitlines()
    for k, line in enumerate(lines):
        if line == "ITEM: TIMESTEP":
            count = int(lines[k + 3])
            columns = lines[k + 8].split()[2:]
            frames.append((int(lines[k + 1]), columns, lines[k + 9:k + 9 + count]))
    return frames


def check_fields_dumps(folder, steps):
    """fields.dump.gz and fields.contacts.gz (-var fields_every) hold a frame at each step, the
    grains with masses, the contacts with the fix's seven columns, each naming dumped grains."""
    atoms = dump_frames(os.path.join(folder, "fields.dump.gz"))
    contacts = dump_frames(os.path.join(folder, "fields.contacts.gz"))
    check([f[0] for f in atoms] == steps and [f[0] for f in contacts] == steps,
          f"fields dumps at steps {[f[0] for f in atoms]} and {[f[0] for f in contacts]}, expected {steps}")
    check(atoms[0][1] == ["id", "type", "x", "y", "vx", "vy", "radius", "mass"], f"atom columns {atoms[0][1]}")
    check(contacts[-1][1] == [f"f_cd[{k}]" for k in range(1, 8)] and contacts[-1][2],
          f"contact columns {contacts[-1][1]}, {len(contacts[-1][2])} rows")
    ids = {float(row.split()[0]) for row in atoms[-1][2]}
    named = {float(v) for row in contacts[-1][2] for v in row.split()[:2] if float(v) != 0}
    check(named <= ids, f"contacts name {len(named - ids)} atoms absent from the dump")


def case_dt_change(args):
    """A chute restart continued at another fixed time step (adapt_dt no) keeps its chute time
    (the step count is rescaled), and the solver -vars reach the fix: 10 ms from the 1.2 s flow
    at dt = 1e-5 s with the maximum norm, no warm start and a shuffled order. With fields_every
    100 it dumps grains (with masses) and the fix's contacts (seven columns) at the same 11 steps."""
    folder = os.path.join(args.work, "dt_change")
    shutil.rmtree(folder, ignore_errors=True)
    start = os.path.join(args.work, "flow", "chute.restart")
    end = FLOW_DURATION + 0.01
    _, output = run_lmp(args.lmp, folder, dict(CELL, stage="flow", start=start, theta=FLOW_THETA,
                                               duration=end, dt="1e-5", adapt_dt="no", norm="maximum", warm_start="no",
                                               order="shuffle", max_iterations=200, fields_every=100))
    rows = read_time_file(os.path.join(folder, "flow.time"))
    times = [r["v_time"] for r in rows]
    # fix ave/time also writes the run's first step: 11 samples from the start's 1.2 s.
    check(abs(times[0] - FLOW_DURATION) < 1e-9 and abs(times[-1] - end) < 1e-9 and len(rows) == 11,
          f"flow.time covers {times[0]}..{times[-1]} s in {len(rows)} rows, expected {FLOW_DURATION}..{end} in 11")
    steps = [r["TimeStep"] for r in rows]
    check(all(abs(s * 1e-5 - t) < 1e-9 for s, t in zip(steps, times)), "steps are not chute time / 1e-5 s")
    with open(os.path.join(folder, "log.lammps")) as f:
        fix_lines = [line for line in f if line.startswith("fix cd all contact/dynamics")]
    solver_vars = ("norm maximum", "warm_start no", "acceleration none", "order shuffle")
    check(any(all(v in line for v in solver_vars) for line in fix_lines),
          f"the chute's fix line lacks the solver -vars {solver_vars}: {fix_lines[-1:]}")
    extremes = summary(output, "SOLVER")
    check(1 <= extremes["max_sweeps_per_step"] <= 200, f"largest sweeps per step {extremes['max_sweeps_per_step']}")
    check_fields_dumps(folder, [round(s) for s in steps])
    print(f"dt change: 1.2 s restart continued at dt 1e-5 s to {times[-1]} s (steps {steps[0]:.0f}..{steps[-1]:.0f}); "
          f"largest sweeps {extremes['max_sweeps_per_step']:.0f}")


def case_walls_trap(args):
    """Grains that stay below the wall tops never cross the periodic boundary; grains of the
    flowing layer do, and only with their centre above the wall tops."""
    folder = os.path.join(args.work, "flow")
    frames = [f[2] for f in read_dump(os.path.join(folder, "dump.chute.gz"))]
    expected = int(round(FLOW_DURATION / FLOW_FRAME)) + 1
    check(len(frames) == expected, f"{len(frames)} frames, expected {expected}")
    first = frames[0]
    buried = [i for i in first if all(f[i]["y"] < WALL_TOP for f in frames)]
    crossed = [i for i in first if any(f[i]["ix"] != first[i]["ix"] for f in frames)]
    check(len(buried) > 50, f"only {len(buried)} grains stayed below the wall tops")
    trapped_crossers = sorted(set(buried) & set(crossed))
    check(not trapped_crossers, f"grains below the wall tops crossed the boundary: {trapped_crossers[:10]}")
    check(len(crossed) > 20, f"only {len(crossed)} grains crossed the boundary: no flow above the walls")
    lowest = math.inf
    for before, after in zip(frames, frames[1:]):
        for i in before:
            if before[i]["ix"] != after[i]["ix"]:
                lowest = min(lowest, before[i]["y"], after[i]["y"])
    check(lowest > WALL_TOP, f"a grain crossed with its centre {(lowest - WALL_TOP) / D:.3f} d from the wall top")
    print(f"walls: {len(buried)} grains stayed below the wall tops and none crossed; {len(crossed)} "
          f"grains crossed, the lowest at z = {(lowest - WALL_TOP) / D:.2f} d")


def case_columns(args):
    """columns.chunk holds the flowing layer's v(x, t): at every sample round(L/column_width)
    columns tile the cell, their counts add up to the layer's grains (flow.time's n_flow), and
    their count-weighted mean vy is the layer's mean v_flow."""
    folder = os.path.join(args.work, "flow")
    rows = {round(r["v_time"] * 1000): r for r in read_time_file(os.path.join(folder, "flow.time"))}
    blocks = read_chunk_file(os.path.join(folder, "columns.chunk"))
    columns = round(float(CELL["L"]) / 1.5)
    check(len(blocks) >= len(rows) - 1, f"{len(blocks)} blocks of columns.chunk for {len(rows)} samples")
    compared = 0
    for step, chunks in blocks:
        check(len(chunks) == columns, f"step {step}: {len(chunks)} columns, expected {columns}")
        centres = [c["Coord1"] for c in chunks]
        check(all(abs(x - (k + 0.5) / columns) < 1e-6 for k, x in enumerate(centres)), f"column centres {centres}")
        count = sum(c["Ncount"] for c in chunks)
        row = next((r for r in rows.values() if r["TimeStep"] == step), None)
        if row is None or count == 0:
            continue
        check(count == row["v_n_flow"], f"step {step}: {count} grains in the columns, {row['v_n_flow']} in the layer")
        v = sum(c["Ncount"] * c["vy"] for c in chunks) / count
        check(abs(v - row["v_v_flow"]) <= 1e-6 * max(1.0, abs(row["v_v_flow"])) + 1e-9,
              f"step {step}: columns' mean vy {v}, the layer's {row['v_v_flow']}")
        compared += 1
    check(compared > 10, f"only {compared} samples compared")
    print(f"columns: {columns} columns tile the cell; at {compared} samples their grains and mean vy are the layer's")


def case_reading(args):
    """-var reading selects the source's count per 45 d (3967) or the count of a 40-49 d layer
    (3290), scaled with L; -var grains wins. The deposition stops right after creating its
    grains (settle_max shorter than the fall), so each count costs a fraction of a second."""
    folder = os.path.join(args.work, "reading")
    cases = ((dict(reading="count"), round(3967 * 9 / 45)), (dict(reading="layer"), round(3290 * 9 / 45)),
             (dict(reading="layer", grains="700"), 700))
    for given, expected in cases:
        variables = dict(given, stage="deposition", L="9", wall_height="3", settle_max="0.001")
        status, output = run_lmp(args.lmp, folder, variables, expect_ok=False)
        created = [line for line in output.splitlines() if line.strip().startswith("Created") and "atoms" in line]
        check(status == 1 and created, f"{given}: status {status}, no 'Created N atoms' line")
        count = int(created[-1].split()[1])
        check(count == expected, f"{given}: {count} grains, expected {expected}")
    print("reading: count 3967 and layer 3290 grains per 45 d, scaled with L; -var grains wins")


def case_steady_flow(args):
    """Tilted by 24 degrees, the layer above the walls flows and its mean velocity stops
    growing: U over the last 0.2 s exceeds U over the 0.2 s before by less than 15 % (it grew
    from 0 to ~1.5 sqrt(g d) in the first 0.4 s; over 0.2 s it fluctuates by up to ~20 % from
    one realisation to another, so a drop is not a failure), far below the frictionless
    acceleration g sin(theta) t, and at least twice its mean over the first 0.1 s."""
    folder = os.path.join(args.work, "flow")
    rows = read_time_file(os.path.join(folder, "flow.time"))

    def u_flow(a, b):
        return mean(r["v_u_flow"] for r in rows if a <= r["v_time"] < b) / SQRT_GD
    end = FLOW_DURATION
    early, late = u_flow(end - 0.4, end - 0.2), u_flow(end - 0.2, end + 1)
    start = u_flow(0.0, 0.1)
    check(late > 0.5, f"U = {late:.3f} sqrt(g d) over the last 0.2 s: the layer does not flow")
    check(late > 2 * start, f"U = {start:.3f} in the first 0.1 s, {late:.3f} at the end: no acceleration phase")
    check(late - early < 0.15 * late, f"U = {early:.3f} then {late:.3f} sqrt(g d): still accelerating")
    free = G * math.sin(math.radians(FLOW_THETA)) * FLOW_DURATION / SQRT_GD
    check(late < 0.2 * free, f"U = {late:.3f} sqrt(g d) is not far below free acceleration ({free:.1f})")
    h = mean(r["v_h"] for r in rows if r["v_time"] >= end - 0.4) / D
    check(8 < h < 16, f"flowing layer {h:.1f} d thick, expected about 12 d")
    diagnostics = read_time_file(os.path.join(folder, "solver.time"))
    capped = 1 - mean(r["f_cd[7]"] for r in diagnostics)
    check(capped < 0.05, f"{capped:.1%} of the steps hit the iteration cap")
    print(f"steady flow: U = {start:.3f}, {early:.3f}, {late:.3f} sqrt(g d) over the first 0.1 s and "
          f"the two last 0.2 s; h = {h:.1f} d; "
          f"{capped:.2%} capped steps")


# Scatter of U (sqrt(g d)), phi and h (d) over the last 0.4 s of the 1.2 s test flow between
# realisations from the same start (1-rank runs in plain full sweeps differing only in contact
# order, -var order shuffle -var seed 2..5, and the fixed order: sd of 5 runs, measured again
# with the code of full_sweep_every; doc/benchmarks.md, MPI section). Two runs from one start
# then differ by sqrt(2) times these.
REALISATION_SD = dict(U=0.27, phi=0.0098, h=0.14)


def solver_summary(folder):
    """SOLVER and CHUTE lines of a finished chute's log, as one dict of floats."""
    with open(os.path.join(folder, "log.lammps")) as log:
        text = log.read()
    return {**summary(text, "SOLVER"), **summary(text, "CHUTE")}


def compare_realisations(args, other, label):
    """flow_run against another realisation of the same flow (folder `other`): U, phi and h over
    the last 0.4 s within 4 standard deviations of the difference of two realisations from one
    start (REALISATION_SD; this cell's U scatters by 16 %, so that check only catches gross
    errors); the solver's sharper checks: the deepest interpenetration stays below twice
    flow_run's, and at most 5 % of the steps hit the iteration cap."""
    one = os.path.join(args.work, "flow")
    report = []

    def late(rows):
        return [r for r in rows if r["v_time"] >= FLOW_DURATION - 0.4]
    rows_one = late(read_time_file(os.path.join(one, "flow.time")))
    rows_other = late(read_time_file(os.path.join(other, "flow.time")))
    for column, scale, name in (("v_u_flow", SQRT_GD, "U"), ("v_phi_flow", 1.0, "phi"), ("v_h", D, "h")):
        m1 = mean(r[column] / scale for r in rows_one)
        m2 = mean(r[column] / scale for r in rows_other)
        bound = 4 * math.sqrt(2) * REALISATION_SD[name]
        check(abs(m1 - m2) < bound, f"{name} = {m1:.4f} in flow_run, {m2:.4f} {label} (bound {bound:.3g})")
        report.append(f"{name} {m1:.4f} / {m2:.4f} ({abs(m1 - m2) / bound:.2f} of the bound)")
    solver_one, solver_other = solver_summary(one), solver_summary(other)
    deepest_one, deepest_other = solver_one["max_interpenetration_d"], solver_other["max_interpenetration_d"]
    check(deepest_other < 2 * deepest_one,
          f"deepest interpenetration {deepest_other:.3g} d {label}, {deepest_one:.3g} d in flow_run")
    capped = solver_other["steps_capped"] / solver_other["steps_solved"]
    check(capped < 0.05, f"{capped:.1%} of the steps {label} hit the iteration cap")
    return "; ".join(report) + f"; deepest interpenetration {deepest_one:.3g} / {deepest_other:.3g} d; " \
        f"{capped:.2%} capped steps"


def case_flow_two_ranks(args):
    """The flow of flow_run, domain-decomposed along x on 2 ranks (--ranks). The decompositions
    order the sweep differently and a frictional packing's impulses are not unique, so the runs
    part after a few ms (a grain is 3.5e-3 d away after 4 ms, 0.07 d after 20 ms): they are two
    realisations of one flow, compared as compare_realisations says (the interpenetration was
    1.2-1.8e-3 d in 19 runs on 1, 2 and 4 ranks). Independent starts on 1, 2 and 4 ranks:
    studies/rank_replicas.py."""
    launcher = mpi_launcher(args.mpirun, args.ranks)
    folder, output = chute(args, f"flow_np{args.ranks}", FLOW_THETA, FLOW_DURATION, launcher=launcher)
    check(f"{args.ranks} by 1 by 1 MPI processor grid" in output,
          f"lmp_cd did not split the cell along x on {args.ranks} ranks")
    print(f"{args.ranks} ranks vs 1: " + compare_realisations(args, folder, f"on {args.ranks} ranks"))


def case_default_sweeps_flow(args):
    """The flow of flow_run with the deck's default sweeps, conjugate acceleration in cycles of
    8 (the other cases run plain full sweeps, at which their numbers were measured): another
    realisation of the same flow, compared as compare_realisations says; and the fix's local
    solves per contact (f_cd[11]) equal the sweeps in flow_run and fall well below them here."""
    folder, _ = chute(args, "flow_default_sweeps", FLOW_THETA, FLOW_DURATION, acceleration="conjugate",
                      full_sweep_every="8")
    print("default vs plain sweeps: " + compare_realisations(args, folder, "with the default sweeps"))
    # The fix's f_cd[11], the local solves per contact: the sweep count in full sweeps (less
    # only by the contacts a step promotes between solves), far below it in cycles.
    full = read_time_file(os.path.join(args.work, "flow", "solver.time"))
    work_full = mean(r["f_cd[11]"] for r in full) / mean(r["f_cd[1]"] for r in full)
    check(0.99 <= work_full <= 1.0 and all(r["f_cd[11]"] <= r["f_cd[1]"] * (1 + 1e-5) for r in full),
          f"full sweeps: local solves per contact {work_full:.4f} x the sweeps, expected 1")
    cycles = read_time_file(os.path.join(folder, "solver.time"))
    work_cycles = mean(r["f_cd[11]"] for r in cycles) / mean(r["f_cd[1]"] for r in cycles)
    check(work_cycles < 0.8, f"cycles: local solves per contact {work_cycles:.2f} x the sweeps: no contact skipped")
    print(f"local solves per contact / sweeps: {work_full:.3f} in full sweeps, {work_cycles:.2f} in cycles")


def case_solve_two_ranks(args):
    """One step from two snapshots of flow_run (1.1 and 1.2 s), solved at tolerance 1e-9 on 1
    and on 2 ranks (studies/rank_solutions.py): the decomposed Gauss-Seidel must reach the 1-rank
    solution (relative error of the velocities < SAME_SOLUTION; measured 1e-9 here, < 1e-4 in
    18 of 20 snapshots of independent flows on 2 and 4 ranks) or, where the frictional problem
    has several solutions, one that a 1-rank solve with another contact order or a cold start
    reaches too. At the deck's tolerance (1e-3) the 2-rank solve must stop no further from its
    solution than 2x the 1-rank one (ratios measured at 1e-3: 0.6-1.4 on 2 and 4 ranks)."""
    flow = os.path.join(args.work, "flow")
    work = os.path.join(args.work, "solve_two_ranks")
    shutil.rmtree(work, ignore_errors=True)
    cell = " ".join(f"{k}={v}" for k, v in CELL.items() if k not in ("dt", "tolerance")) + f" theta={FLOW_THETA}"
    options = rank_solutions.options(["--out", work, "--ranks", "1", "2", "--tolerances", "1e-3", "--cell", cell,
                                      "--lmp", args.lmp, "--mpirun", args.mpirun, "--snapshots",
                                      os.path.join(flow, "restart.a"), os.path.join(flow, "chute.restart")])
    report = []
    for index, snapshot in enumerate(options.snapshots):
        try:
            rows = {(r["ranks"], r["tolerance"]): r for r in rank_solutions.study_snapshot(options, index, snapshot)}
        except RuntimeError as error:
            raise Failure(str(error))
        exact, loose, loose_one = rows[(2, 1e-9)], rows[(2, 1e-3)], rows[(1, 1e-3)]
        check(exact["converged"] and rows[(1, 1e-9)]["converged"], f"{snapshot}: a 1e-9 solve hit the sweep cap")
        check(exact["error"] < rank_solutions.SAME_SOLUTION or exact["other_solution"].startswith("yes"),
              f"{snapshot}: 2 ranks reach a solution {exact['error']:.3g} from the 1-rank one, "
              "which no 1-rank order reaches")
        check(loose["error"] < 2 * loose_one["error"],
              f"{snapshot}: at tolerance 1e-3 the 2-rank solve is {loose['error']:.3g} from its solution, "
              f"the 1-rank one {loose_one['error']:.3g}")
        report.append(f"{os.path.basename(snapshot)}: 2-rank solution {exact['error']:.2g} from the 1-rank one "
                      f"({exact['other_solution'] or 'same'}); at 1e-3 {loose['error']:.3g} / {loose_one['error']:.3g}")
    print("; ".join(report))


def case_static(args):
    """Without tilt the packing stays at rest: 99 % of the grains move less than 0.02 d in 0.1 s,
    none more than 0.5 d, and the mean velocities stay below 0.01 sqrt(g d) (the solver's noise
    is ~ g dt). Rigid disks have no rolling resistance: a rattler on the curved floor of its
    cage, or a grain rolling on the floor, may roll on (which ones depends on the deposition)."""
    folder, output = chute(args, "static", 0, 0.1)
    frames = read_dump(os.path.join(folder, "dump.chute.gz"))
    first, last = frames[0][2], frames[-1][2]
    check(frames[-1][0] > frames[0][0], "a single dump frame")
    displacements = sorted(math.hypot(last[i]["x"] - a["x"], last[i]["y"] - a["y"]) / D for i, a in first.items())
    moved, typical = displacements[-1], displacements[int(0.99 * (len(displacements) - 1))]
    check(typical < 0.02, f"1 % of the grains moved more than {typical:.4f} d without tilt")
    check(moved < 0.5, f"a grain moved {moved:.4f} d without tilt")
    rows = read_time_file(os.path.join(folder, "flow.time"))
    u_all = max(abs(r["v_u_all"]) for r in rows) / SQRT_GD
    u_flow = max(abs(r["v_u_flow"]) for r in rows) / SQRT_GD
    v_flow = max(abs(r["v_v_flow"]) for r in rows) / SQRT_GD
    check(max(u_all, u_flow, v_flow) < 0.01,
          f"mean velocities {u_all:.2e}, {u_flow:.2e}, {v_flow:.2e} sqrt(g d) without tilt")
    print(f"static: 99th percentile displacement {typical:.2e} d, largest {moved:.2e} d, largest mean velocity "
          f"{max(u_all, u_flow, v_flow):.2e} sqrt(g d)")


def case_size_law(args):
    """size_law area: the same rain as chute.deposition's (the same seed draws the same number
    r in [0, 1) for each grain) with d = d0 sqrt((1 - s/2)^2 + 2 s r) (s the dispersity 0.4)
    instead of d0 (1 - s/2 + s r): each grain's diameter follows from its diameter-law one,
    d^2/d0^2 = 0.64 + 2 (d_diameter/d0 - 0.8), within 5e-5 (the dump's six digits of each radius
    leave ~1.5e-5; the diameter law itself is off the area law by up to 0.04); the rain settles."""
    folder = os.path.join(args.work, "size_law")
    shutil.rmtree(folder, ignore_errors=True)
    _, output = run_lmp(args.lmp, folder, dict(CELL, stage="deposition", size_law="area"))
    check(summary(output, "DEPOSITION")["ke_per_grain"] < 1e-4, "the area-law rain did not settle")
    by_diameter = read_dump(os.path.join(args.work, "deposition", "deposition.dump"))[0][2]
    by_area = read_dump(os.path.join(folder, "deposition.dump"))[0][2]
    check(sorted(by_area) == sorted(by_diameter), "the two rains hold other grains")
    worst = max(abs((2 * a["radius"] / D) ** 2 - (0.64 + 2 * (2 * by_diameter[i]["radius"] / D - 0.8)))
                for i, a in by_area.items())
    check(worst < 5e-5, f"a diameter is off the area law by {worst:.2e} (in d^2)")
    print(f"size law area: every grain's diameter from its diameter-law draw within {worst:.1e} d^2")


def case_frozen_bed(args):
    """frozen_depth 4: the grains deeper than 4 d below the wall tops at the tilt are obstacles:
    over 0.05 s of flow at 24 degrees they do not move at all (position and velocity exactly as
    dumped at the start) while the layer above flows (its mean velocity > 0.1 sqrt(g d))."""
    folder, output = chute(args, "frozen_bed", FLOW_THETA, 0.05, frozen_depth=4, snapshot_interval=0.01)
    frames = read_dump(os.path.join(folder, "dump.chute.gz"))
    first, last = frames[0][2], frames[-1][2]
    frozen = [i for i, a in first.items() if a["y"] < WALL_TOP - 4 * D]
    check(len(frozen) > 20, f"only {len(frozen)} grains deeper than 4 d")
    moved = [i for i in frozen if (last[i]["x"], last[i]["y"], last[i]["vx"], last[i]["vy"]) !=
             (first[i]["x"], first[i]["y"], 0.0, 0.0)]
    check(not moved, f"{len(moved)} frozen grains moved, e.g. {moved[:3]}")
    check(f"{len(frozen)} atoms in group frozen" in output, "the deck's frozen group is not the grains below 4 d")
    above = [a["vx"] for i, a in last.items() if a["y"] > WALL_TOP]
    u_layer = sum(above) / len(above) / SQRT_GD
    check(u_layer > 0.1, f"the layer above the frozen bed flows at {u_layer:.3f} sqrt(g d)")
    print(f"frozen bed: {len(frozen)} grains held exactly; the layer flows at {u_layer:.2f} sqrt(g d)")


def case_solve_error_by_depth(args):
    """bench/solve_error_by_depth.py on the packing at rest, tilted by 12 degrees (the frozen
    bed): one step from the deposition at tolerances 1e-2, 1e-4 and at the reference's own
    1e-8. The solve at the reference's tolerance is the reference (error exactly 0 in every
    band); the error falls from 1e-2 to 1e-4 in the bed as a whole (rms over its bands); every
    band below the surface holds grains, and the bands tile the packing."""
    work = os.path.join(args.work, "solve_error_by_depth")
    shutil.rmtree(work, ignore_errors=True)
    script = os.path.join(TOP, "bench", "solve_error_by_depth.py")
    cell = " ".join(f"{k}={v}" for k, v in CELL.items() if k not in ("dt", "tolerance")) + f" theta={STATIC_TILT}"
    done = subprocess.run([sys.executable, script, "--out", work, "--lmp", args.lmp, "--cell", cell, "--dt", "2e-5",
                           "--snapshots", os.path.join(args.work, "deposition", "deposition.restart"),
                           "--tolerances", "1e-2", "1e-4", "1e-8", "--reference-tolerance", "1e-8",
                           "--max-iterations", "200000", "--band", "2"], capture_output=True, text=True)
    check(done.returncode == 0, f"solve_error_by_depth.py failed: {done.stderr.strip()[-300:]}")
    with open(os.path.join(work, "error_by_depth.csv")) as src:
        rows = list(csv.DictReader(src))
    by_tolerance = {}
    for r in rows:
        by_tolerance.setdefault(float(r["tolerance"]), []).append(r)
    check(all(float(r["rms_error"]) == 0.0 for r in by_tolerance[1e-8]),
          "the solve at the reference's own tolerance is not the reference")
    grains = sum(int(r["grains"]) for r in by_tolerance[1e-2])
    check(grains == 200, f"the bands hold {grains} grains, not the cell's 200")

    def bed_error(tolerance):
        bed = [float(r["rms_error"]) for r in by_tolerance[tolerance] if float(r["z_low"]) < 0]
        return math.sqrt(sum(e * e for e in bed) / len(bed))
    loose, tight = bed_error(1e-2), bed_error(1e-4)
    check(tight < loose, f"the bed's error at 1e-4 ({tight:.3g}) is not below 1e-2's ({loose:.3g})")
    print(f"solve error by depth: bed rms error {loose:.2e} at 1e-2, {tight:.2e} at 1e-4 (sqrt(g d))")


STATIC_TILT, STATIC_DURATION, SETTLE_TIME = 12, 0.4, 0.1


def case_static_tilt(args):
    """Tilted by 12 degrees, well below the 23 degrees at which the flow of this layer stops
    (mu = 0.5), the packing stays at rest after a short readjustment (0.1 s), without creeping:
    over T = 0.3 s the mean downslope displacement stays below 1e-3 d and no grain moves 0.01 d.
    (A creep at the solver's velocity noise g dt, e.g. a restitution or contact-detection error,
    would carry grains g dt T = 0.12 d.) The mean velocities stay below g dt = 0.0028 sqrt(g d)
    over the last 0.1 s. Solved at tolerance 1e-4: at the chute's 1e-3 the solver's errors add
    up from step to step in a fixed contact order, and the packing creeps 0.5-4.2e-3 d over
    six other rains of this cell; at 1e-4 at most 1.2e-4 d on those rains."""
    folder, _ = chute(args, "static_tilt", STATIC_TILT, STATIC_DURATION, snapshot_interval=0.05,
                      tolerance="1e-4", max_iterations=5000)
    frames = read_dump(os.path.join(folder, "dump.chute.gz"))
    settled = unwrapped(next(f for f in frames if f[0] * 2e-5 >= SETTLE_TIME - 1e-9))
    last = unwrapped(frames[-1])
    moved = max(math.hypot(last[i][0] - x, last[i][1] - y) for i, (x, y) in settled.items()) / D
    creep = mean(last[i][0] - x for i, (x, _) in settled.items()) / D
    check(moved < 0.01, f"a grain moved {moved:.4f} d in {STATIC_DURATION - SETTLE_TIME:g} s at {STATIC_TILT} degrees")
    check(abs(creep) < 1e-3, f"the packing crept {creep:.2e} d downslope")
    rows = [r for r in read_time_file(os.path.join(folder, "flow.time")) if r["v_time"] > STATIC_DURATION - 0.1]
    speed = max(max(abs(r["v_u_all"]), abs(r["v_u_flow"]), abs(r["v_v_flow"])) for r in rows) / SQRT_GD
    noise = G * 2e-5 / SQRT_GD
    check(speed < noise, f"mean velocity {speed:.2e} sqrt(g d) at rest, above g dt = {noise:.2e}")
    print(f"static tilt {STATIC_TILT} deg: largest displacement {moved:.2e} d, mean downslope {creep:.2e} d "
          f"over {STATIC_DURATION - SETTLE_TIME:g} s; largest mean velocity {speed:.2e} sqrt(g d)")


RUNAWAY_MU, RUNAWAY_THETA, RUNAWAY_DURATION = 0.05, 40, 0.4


def case_runaway(args):
    """At mu = 0.05 and 40 degrees, far beyond the angles at which such flows are steady
    (16-22 degrees), the layer accelerates without bound: its mean velocity grows in every
    0.05 s window, at a rate below the frictionless g sin(theta) and still at least half the
    early rate at the end (no approach to a steady state); the dilute flow stays finite and
    the fix's largest interpenetration stays below 0.005 d."""
    folder, output = chute(args, "runaway", RUNAWAY_THETA, RUNAWAY_DURATION, mu=RUNAWAY_MU)
    rows = read_time_file(os.path.join(folder, "flow.time"))
    windows = [mean(r["v_u_flow"] for r in rows if k * 0.05 < r["v_time"] <= (k + 1) * 0.05)
               for k in range(int(round(RUNAWAY_DURATION / 0.05)))]
    check(all(math.isfinite(u) for u in windows), f"non-finite mean velocity: {windows}")
    check(all(b > a for a, b in zip(windows, windows[1:])), f"U does not grow in every window: {windows}")
    free = G * math.sin(math.radians(RUNAWAY_THETA))
    early = (windows[3] - windows[0]) / 0.15
    late = (windows[-1] - windows[-4]) / 0.15
    check(early < free, f"early acceleration {early:.2f} m/s^2 above g sin(theta) = {free:.2f}")
    check(late > 0.5 * early, f"acceleration fell from {early:.2f} to {late:.2f} m/s^2: not a runaway")
    diagnostics = read_time_file(os.path.join(folder, "solver.time"))
    overlap = max(r["f_cd[5]"] for r in diagnostics)
    check(overlap < 0.005, f"interpenetration up to {overlap:.4f} d")
    result = summary(output, "CHUTE")
    check(result["phi"] < 0.75, f"packing fraction {result['phi']:.3f}: the flow is not dilute")
    print(f"runaway: U = {windows[0] / SQRT_GD:.2f} ... {windows[-1] / SQRT_GD:.2f} sqrt(g d), acceleration "
          f"{early:.2f} then {late:.2f} m/s^2 (g sin(theta) = {free:.2f}); phi {result['phi']:.3f}; "
          f"largest interpenetration {overlap:.2e} d")


def case_start_mismatch(args):
    """A continuation whose cell differs from its start file's stops with one ERROR line naming
    the variable before the run: another L, or walls higher than those the bed was rained
    between (grains lie where the walls would be)."""
    start = os.path.join(args.work, "deposition", "deposition.restart")
    folder = os.path.join(args.work, "start_mismatch")
    problems = []
    for name, value in (("L", "12"), ("wall_height", "16")):
        variables = dict(CELL, stage="flow", start=start, duration="0.01")
        variables[name] = value
        status, output = run_lmp(args.lmp, folder, variables, expect_ok=False)
        errors = [line for line in output.splitlines() if line.startswith("ERROR")]
        if status == 0 or len(errors) != 1 or f"-var {name} {value}" not in errors[0] or "Setting up" in output:
            problems.append(f"-var {name} {value}: status {status}, errors {errors}")
    check(not problems, "; ".join(problems))
    run_lmp(args.lmp, folder, dict(CELL, stage="flow", start=start, duration="0.01"))
    print("start file: another L and higher walls refused, the matching cell runs")


BAD_VARS = [
    ("mu", "-0.1", "-var mu -0.1"),
    ("mu", "abc", "-var mu abc: not a number"),
    ("theta", "95", "-var theta 95"),
    ("L", "2", "-var L 2"),
    ("dt", "0", "-var dt 0"),
    ("e", "1.5", "-var e 1.5"),
    ("grains", "10.5", "-var grains 10.5"),
    ("tolerance", "0.1x", "-var tolerance 0.1x: not a number"),
    ("sample_rate", "3000", "-var sample_rate 3000"),
    ("stage", "chute", "-var stage chute"),
    ("adapt_dt", "maybe", "-var adapt_dt maybe"),
    ("travel", "0.7", "-var travel 0.7"),
    ("restart_interval", "0.015", "-var restart_interval 0.015"),
    ("norm", "l2", "-var norm l2"),
    ("warm_start", "1", "-var warm_start 1"),
    ("norm", "2", "-var norm 2"),
    ("order", "random", "-var order random"),
    ("join", "before", "-var join before"),
    ("acceleration", "anderson", "-var acceleration anderson"),
    ("full_sweep_every", "0", "-var full_sweep_every 0"),
    ("full_sweep_every", "2.5", "-var full_sweep_every 2.5"),
    ("reading", "both", "-var reading both"),
    ("column_width", "0", "-var column_width 0"),
    ("frozen_depth", "31", "-var frozen_depth 31: must be in [0, wall_height]"),
    ("size_law", "volume", "-var size_law volume: must be diameter or area"),
    ("frozen_depth", "deep", "-var frozen_depth deep: not a number"),
    ("frozen_depth", "abc", "-var frozen_depth abc: not a number"),
    ("mu_wall", "1e-x", "-var mu_wall 1e-x: not a number"),
    ("thta", "30", "-var thta: the deck has no such variable (the nearest is theta)"),
    ("frozen_dept", "2", "-var frozen_dept: the deck has no such variable (the nearest is frozen_depth)"),
    ("grains", "100", "-var grains 100: too few to cover the wall tops (at least 1425"),
    ("fields_every", "2.5", "-var fields_every 2.5: must be a whole number of steps >= 0"),
    ("fields_every", "1", "-var fields_every 1: needs -var adapt_dt no"),
]


def case_bad_var(args):
    """Every bad -var value stops lmp_cd with exit status 1 and one ERROR line naming it."""
    folder = os.path.join(args.work, "bad_var")
    problems = []
    for name, value, expected in BAD_VARS:
        status, output = run_lmp(args.lmp, folder, {name: value, "stage": "flow"} if name != "stage"
                                 else {name: value}, expect_ok=False)
        errors = [line for line in output.splitlines() if line.startswith("ERROR")]
        if status == 0 or len(errors) != 1 or expected not in errors[0] or "Setting up" in output:
            problems.append(f"-var {name} {value}: status {status}, errors {errors}")
    # The default scene includes in.chute: the names of both decks are known (its own `inputs`
    # passes, and the stage check after it speaks), a name of neither is refused.
    scene = os.path.join(TOP, "inputs", "in.default_scene")
    inputs = os.path.join(TOP, "inputs")
    for variables, expected in (({"inputs": inputs, "stage": "chute"}, "-var stage chute: must be"),
                                ({"inputs": inputs, "thta": "30"}, "-var thta: the deck has no such variable "
                                 "(the nearest is theta)")):
        result = subprocess.run(lmp_command(args.lmp, scene, variables, log="none"), cwd=folder, capture_output=True,
                                text=True)
        errors = [line for line in (result.stdout + result.stderr).splitlines() if line.startswith("ERROR")]
        if result.returncode == 0 or len(errors) != 1 or expected not in errors[0]:
            problems.append(f"in.default_scene {variables}: status {result.returncode}, errors {errors}")
    check(not problems, "; ".join(problems))
    print(f"bad -var: {len(BAD_VARS) + 2} values stopped with one ERROR line naming the variable")


def case_restart_between_samples(args):
    """With the step that follows the flow, a periodic restart may be written between two samples
    (at a refined level, 0.25 ms steps against 1 ms samples); continued from there, the run keeps
    the level and its position in the period: it starts from the state the straight run had at
    that step, takes the same steps at the same chute times up to the end of the period, and
    samples every whole millisecond after it; it records the chute in its chute.params. Small skin
    and dt 1e-4 s, so that the 0.3 s flow refines the step; a restart every 2 ms, so that the
    last two restarts fall within a few ms of the end. (Later values are not compared: rebuilt
    neighbour lists may reorder the contacts, and the flow amplifies differences within the
    solver's tolerance.)"""
    work = os.path.join(args.work, "restart_between_samples")
    shutil.rmtree(work, ignore_errors=True)
    start = os.path.join(args.work, "deposition", "deposition.restart")
    duration = 0.3
    settings = dict(CELL, stage="flow", theta=24, dt="1e-4", skin="0.03", restart_interval="0.002",
                    profile_interval="0.002", solver_interval="0.001")
    straight = os.path.join(work, "straight")
    run_lmp(args.lmp, straight, dict(settings, start=start, duration=duration))
    rows_straight = {r["TimeStep"]: r for r in read_time_file(os.path.join(straight, "flow.time"))}

    def whole_ms(t):
        return abs(t * 1000 - round(t * 1000)) < 1e-6

    between = []
    for name in ("restart.a", "restart.b"):
        folder = os.path.join(work, "from_" + name)
        run_lmp(args.lmp, folder, dict(settings, start=os.path.join(straight, name), duration=duration + 0.01))
        rows = [r for r in read_time_file(os.path.join(folder, "flow.time")) if r["v_time"] <= duration + 1e-9]
        check_record(folder, 8, 200, 24)
        first = rows[0]
        if not whole_ms(first["v_time"]):
            between.append(f"{name} at {first['v_time']} s")
        twin = rows_straight.get(first["TimeStep"])
        check(twin is not None and twin == first,
              f"from {name}: the first sample {first} is not the straight run's at that step {twin}")
        period_end = next((k for k, r in enumerate(rows) if whole_ms(r["v_time"]) and k > 0), len(rows) - 1)
        for row in rows[:period_end + 1]:
            twin = rows_straight.get(row["TimeStep"])
            check(twin is not None and abs(twin["v_time"] - row["v_time"]) < 1e-12,
                  f"from {name}: step {row['TimeStep']:.0f} at {row['v_time']} s, straight on: {twin}")
        sampled = {round(r["v_time"] * 1000) for r in rows[period_end:] if whole_ms(r["v_time"])}
        expected = set(range(round(rows[period_end]["v_time"] * 1000), round(duration * 1000) + 1))
        check(sampled == expected, f"from {name}: whole milliseconds {sorted(expected - sampled)} not sampled")
    check(between, "neither restart sits between samples: the flow no longer refines the step; lower the skin")
    print(f"restarts between samples continued the straight run's steps and times: {', '.join(between)}")


def case_runner_resume(args):
    """The runner, killed in the middle of a run, continues it from its restart when started
    again; the spliced outputs are continuous, the legs' chute.params is carried into the run's
    folder; a finished run is not run again."""
    out = os.path.join(args.work, "campaign")
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sys.executable, RUNNER, "--out", out, "--lmp", args.lmp, "--cdpost", "none",
           "--series", "mu0.5", "--only", "mu0.5_theta24_*", "--var", "L=8", "--var", "grains=80",
           "--var", "wall_height=4", "--var", "restart_interval=0.02", "--var", "profile_interval=0.01",
           "--var", "dt=2e-5", "--var", "tolerance=1e-3", "--var", "skin=0.6",
           "--duration", "0.6", "--progress-interval", "2"]
    run = os.path.join(out, "runs", "mu0.5_theta24_L8")
    runner = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + 120
    leg0 = os.path.join(run, "legs", "00")
    while time.time() < deadline and not os.path.exists(os.path.join(leg0, "restart.b")):
        time.sleep(0.05)
    check(os.path.exists(os.path.join(leg0, "restart.b")), "no periodic restart within 120 s")
    runner.send_signal(signal.SIGTERM)
    first_output = runner.communicate(timeout=60)[0]
    check("interrupted" in first_output, "the runner did not report the interruption:\n" + first_output)
    check(not os.path.exists(os.path.join(leg0, "chute.restart")),
          "the run reached its end before the interruption: lengthen --duration")

    second = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    check(second.returncode == 0, "second invocation failed:\n" + second.stdout + second.stderr)
    check("restart." in second.stdout, "the run did not continue from a restart:\n" + second.stdout)
    check(os.path.exists(os.path.join(run, "DONE")), "the run is not finished")
    legs = sorted(os.listdir(os.path.join(run, "legs")))
    check(len(legs) == 2, f"legs {legs}, expected 2")

    rows = read_time_file(os.path.join(run, "flow.time"))
    steps = [int(r["TimeStep"]) for r in rows]
    every = steps[1] - steps[0]
    check(steps[0] == 0 and steps[-1] == int(round(0.6 / 2e-5)),
          f"flow.time covers steps {steps[0]}..{steps[-1]}")
    check(all(b - a == every for a, b in zip(steps, steps[1:])), "flow.time has gaps or repeats")
    times = [r["v_time"] for r in rows]
    check(abs(times[-1] - 0.6) < 1e-9, f"flow.time ends at {times[-1]} s")
    for name in ("params.json", "cost.json", "chute.restart", "profile.chunk", "layers.chunk",
                 "packing.chunk", "solver.time", "dump.chute.gz"):
        check(os.path.exists(os.path.join(run, name)), f"{name} missing from the run folder")
    check_record(run, 4, 80, 24)

    third = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    check(third.returncode == 0 and "start run" not in third.stdout,
          "a finished run was started again:\n" + third.stdout)
    check(sorted(os.listdir(os.path.join(run, "legs"))) == legs, "a new leg appeared")
    print(f"runner: interrupted, continued in leg 01, {len(steps)} samples without gap; finished run skipped")


CASES = {
    "deposition": case_deposition,
    "reproducible": case_reproducible,
    "flow_run": case_flow_run,
    "dt_change": case_dt_change,
    "walls_trap": case_walls_trap,
    "steady_flow": case_steady_flow,
    "flow_two_ranks": case_flow_two_ranks,
    "default_sweeps_flow": case_default_sweeps_flow,
    "solve_two_ranks": case_solve_two_ranks,
    "static": case_static,
    "static_tilt": case_static_tilt,
    "runaway": case_runaway,
    "bad_var": case_bad_var,
    "frozen_bed": case_frozen_bed,
    "size_law": case_size_law,
    "solve_error_by_depth": case_solve_error_by_depth,
    "columns": case_columns,
    "reading": case_reading,
    "start_mismatch": case_start_mismatch,
    "runner_resume": case_runner_resume,
    "restart_between_samples": case_restart_between_samples,
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--lmp", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--mpirun", default="mpirun", help="MPI launcher of the multi-rank cases")
    parser.add_argument("--ranks", type=int, default=2, help="ranks of flow_two_ranks (4: by hand, ~7 min)")
    args = parser.parse_args()
    args.lmp = os.path.abspath(args.lmp)
    args.work = os.path.abspath(args.work)
    os.makedirs(args.work, exist_ok=True)
    try:
        CASES[args.case](args)
    except Failure as failure:
        print(f"FAILED {args.case}: {failure}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
