#!/usr/bin/env python3
"""Checks of studies/cdtools, the tools' package, run by ctest (no simulation, a second).

    tests/chute/test_cdtools.py

The LAMMPS file readers on hand-written files: fix ave/time rows and a malformed row named by
its line, the head and tail of a file still being written; fix ave/chunk blocks, a block cut
by a kill dropped from the records and refused by the row reader; dump frames, plain and
gzip, a gzip stream cut by a kill read up to its last complete frame. The log parsers: summary
lines, the last one of a log, loop timers. The statistics and the text of numbers on
hand-computed cases. The -var arguments. The campaign's rule for a run started before a deck
variable existed. Standard library only.
"""

import gzip
import math
import os
import sys
import tempfile
import zlib

import argparse
import json

# cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies"))

from cdtools import lammps_files, logs, run, stats, text
from cdtools.campaign import plan, post, report

from study_test import check


def write(folder, name, content):
    path = os.path.join(folder, name)
    with open(path, "w") as out:
        out.write(content)
    return path


TIME_FILE = "# Time-averaged data for fix flowout\n# TimeStep v_time v_u_flow\n0 0 0.5\n50 0.001 0.75\n100 0.002 1\n"


def check_time_files(work):
    path = write(work, "flow.time", TIME_FILE)
    rows = lammps_files.read_time_file(path)
    check(rows == [dict(TimeStep=0, v_time=0, v_u_flow=0.5), dict(TimeStep=50, v_time=0.001, v_u_flow=0.75),
                   dict(TimeStep=100, v_time=0.002, v_u_flow=1)], f"ave/time rows {rows}")
    header, records = lammps_files.read_time_records(path)
    check(len(header) == 2 and [s for s, _ in records] == [0, 50, 100], f"ave/time records {records}")
    check(lammps_files.time_span(path) == (0.0, 0.002), f"time span {lammps_files.time_span(path)}")
    cut = write(work, "cut.time", TIME_FILE + "150 0.00")    # a row cut by a kill
    check(lammps_files.time_span(cut) == (0.0, 0.002), "the span counts a cut row")
    check(lammps_files.time_span(write(work, "empty.time", TIME_FILE[:60])) is None, "a span before the first row")
    bad = write(work, "bad.time", TIME_FILE + "150 0.003 x\n")
    try:
        lammps_files.read_time_file(bad)
        check(False, "a row with a word was read")
    except lammps_files.FileFormatError as error:
        check(f"{bad}:6:" in str(error), f"the error does not name the line: {error}")


CHUNK_HEADER = "# Chunk-averaged data\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Ncount vx\n"
CHUNK_BLOCKS = "100 2 30\n  1 0.5 10 0.1\n  2 1.5 20 0.2\n200 2 30\n  1 0.5 10 0.3\n  2 1.5 20 0.4\n"


def check_chunk_files(work):
    path = write(work, "profile.chunk", CHUNK_HEADER + CHUNK_BLOCKS)
    blocks = lammps_files.read_chunk_file(path)
    check([s for s, _ in blocks] == [100, 200] and blocks[1][1][1] == dict(Chunk=2, Coord1=1.5, Ncount=20, vx=0.4),
          f"ave/chunk blocks {blocks}")
    cut = write(work, "cut.chunk", CHUNK_HEADER + CHUNK_BLOCKS + "300 2 30\n  1 0.5 10 0.5\n")
    header, records = lammps_files.read_chunk_records(cut)
    check(len(header) == 3 and [s for s, _ in records] == [100, 200], "the cut block is among the records")
    check(records[1][1] == CHUNK_BLOCKS[CHUNK_BLOCKS.index("200"):], f"the record of step 200: {records[1][1]!r}")
    try:
        lammps_files.read_chunk_file(cut)
        check(False, "a cut block was read")
    except lammps_files.FileFormatError as error:
        check(cut in str(error) and "200" in str(error), f"the error does not say where: {error}")


def frame(step, atoms):
    rows = "".join(f"{i} 1 {0.1 * i} 0.2 0 {i % 2}\n" for i in range(1, atoms + 1))
    return (f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{atoms}\nITEM: BOX BOUNDS pp fm pp\n0 1\n0 2\n-0.1 0.1\n"
            f"ITEM: ATOMS id type x y vx ix\n{rows}")


def check_dumps(work):
    text_of_dump = frame(0, 3) + frame(100, 3)
    plain = write(work, "dump.plain", text_of_dump)
    frames = lammps_files.read_dump(plain)
    check([f[0] for f in frames] == [0, 100] and frames[0][1] == [(0, 1), (0, 2), (-0.1, 0.1)],
          f"dump frames {[(f[0], f[1]) for f in frames]}")
    check(frames[1][2][3] == dict(id=3, type=1, x=0.30000000000000004, y=0.2, vx=0, ix=1), f"atom 3: {frames[1][2][3]}")
    check(lammps_files.unwrapped(frames[0])[3] == (0.30000000000000004 + 1, 0.2), "atom 3 unwrapped by one box")
    packed = os.path.join(work, "dump.gz")
    with gzip.open(packed, "wt") as out:
        out.write(text_of_dump + frame(200, 3))
    # A kill leaves a gzip stream without its end: two frames and half of the third flushed.
    last = frame(200, 3)
    stream = zlib.compressobj(6, zlib.DEFLATED, 16 + zlib.MAX_WBITS)
    cut = os.path.join(work, "cut.gz")
    with open(cut, "wb") as out:
        for part in (text_of_dump, last[:len(last) // 2]):
            out.write(stream.compress(part.encode()) + stream.flush(zlib.Z_SYNC_FLUSH))
    _, records = lammps_files.read_dump_records(cut)
    check([s for s, _ in records] == [0, 100], f"frames of a cut gzip dump: {[s for s, _ in records]}")
    check(records[1][1] == frame(100, 3), f"the record of step 100: {records[1][1]!r}")
    check([f[0] for f in lammps_files.read_dump(packed)] == [0, 100, 200], "the whole gzip dump")


def check_logs(work):
    line = "CHUTE y_top_m 0.004 time_s 1.2000 U 1.5 state flowing"
    check(logs.parse_summary(line) == dict(y_top_m=0.004, time_s=1.2, U=1.5, state="flowing"), "summary line")
    check(logs.tagged_line(f"x\n{line}\nCHUTE U 2\n", "CHUTE")["U"] == 1.5, "the first CHUTE line of a text")
    check(logs.tagged_line("CHUTES U 2\n", "CHUTE") is None, "another tag was taken for CHUTE")
    log = write(work, "log.lammps", "Step Time\n  100 0.1\n  200 0.2\n"
                "Loop time of 4 on 1 procs for 100 steps with 60 atoms\n\n50.0% CPU use with 1 MPI tasks\n"
                f"Step Time\n  200 0.2\n  300 0.3\nLoop time of 6 on 2 procs for 100 steps with 60 atoms\n\n"
                f"100.0% CPU use with 2 MPI tasks x 1 OpenMP threads\n{line}\nCHUTE U 2\nERROR: one\nERROR: two\n")
    check(logs.log_summary(work, "CHUTE") == dict(U=2.0), "the last CHUTE line of a log")
    progress = logs.read_progress(log)
    check((progress.first_step, progress.last_step, progress.wall, progress.steps, progress.cpu, progress.summary)
          == (100, 300, 10.0, 200, 14.0, "CHUTE U 2"), f"progress {progress}")  # 4 x 50 % + 6 x 2 ranks
    check(logs.error_line(open(log).read()) == "ERROR: one", "the first ERROR line")
    try:
        logs.log_summary(work, "SOLVER")
        check(False, "a missing SOLVER line was found")
    except RuntimeError as error:
        check(log in str(error) and "SOLVER" in str(error), f"the error does not name the log and tag: {error}")


def check_statistics():
    mean, sd, error = stats.mean_sd_se([1.0, 2.0, 3.0, 6.0])
    check((mean, sd) == (3.0, math.sqrt(14 / 3)) and abs(error - sd / 2) < 1e-15, f"mean, sd, se {mean, sd, error}")
    check(stats.mean_sd_se([4.0])[0] == 4.0 and all(math.isnan(v) for v in stats.mean_sd_se([4.0])[1:]),
          "one value: its mean, no scatter")
    # Deviations from each group's mean: 1, 1 and 2, 2 -> (1 + 1 + 4 + 4) / (1 + 1) = 5;
    # a group of one has no deviation to give and is left out.
    check(abs(stats.pooled_sd([[1, 3], [10, 14], [99]]) - math.sqrt(5)) < 1e-12, "pooled sd of [1,3],[10,14]")
    check(math.isnan(stats.pooled_sd([[1], [2]])), "pooled sd without two values in a group is not nan")
    # Errors 0.3 and 0.4 combine to 0.5: 3.999 against 3 is 1.998 of it, 4.001 is 2.002.
    check(abs(stats.difference_in_errors(2.0, 0.4, 1.0, 0.3) - 2.0) < 1e-12, "a difference of two combined errors")
    check(stats.difference_in_errors(3.999, 0.4, 3.0, 0.3) <= 2 < stats.difference_in_errors(4.001, 0.4, 3.0, 0.3),
          "the boundary at twice the combined error")
    check(math.isnan(stats.difference_in_errors(1.0, 0.0, 1.1, 0.0)), "a difference without errors is not nan")
    slope, r2 = stats.least_squares_slope([0, 1, 2, 3], [1, 3, 5, 7])
    check(abs(slope - 2) < 1e-12 and abs(r2 - 1) < 1e-12, f"slope {slope}, R^2 {r2}")


def check_text():
    check(text.with_error(1.23456, 0.0123) == "1.235 ± 0.012", text.with_error(1.23456, 0.0123))
    check(text.with_error(1234.5, 56) == "1234 ± 56", text.with_error(1234.5, 56))
    check(text.with_error(1.23456, None) == "1.235", "a value without error: four digits")
    check([text.number(None), text.number(math.nan), text.number(0.012345, 2)] == ["–", "–", "0.012"], "numbers")
    check([text.parameter(2.0), text.parameter(0.5), text.parameter("1e-3")] == ["2", "0.5", "1e-3"], "parameters")
    check([text.duration(59), text.duration(3725), text.duration(90000), text.duration(None)]
          == ["0m59s", "1h02m", "1d01h", "?"], "durations")
    check(text.markdown_table(["a", "b"], [[1, 2]]) == "| a | b |\n|---|---|\n| 1 | 2 |\n", "Markdown table")


def check_arguments():
    check(run.name_value_pairs("L=10 order=shuffle") == dict(L="10", order="shuffle"), "name=value pairs")
    for bad, named in (("L=10 theta", "'theta'"), ("L=10 L=12", "'L' is given twice")):
        try:
            run.name_value_pairs(bad)
            check(False, f"'{bad}' accepted")
        except ValueError as error:
            check(named in str(error), f"'{bad}': {error}")
    check(run.lmp_command("lmp_cd", "in.chute", dict(stage="flow", dt=1e-4), screen="none", launcher=["mpirun"])
          == ["mpirun", "lmp_cd", "-in", "in.chute", "-log", "log.lammps", "-screen", "none", "-var", "stage", "flow",
              "-var", "dt", "0.0001"], "lmp_cd command line")


def check_runs_older_than_a_variable(work):
    """A run whose params.json lacks a deck variable (added to the deck after it started) goes
    on without it, so its parameters still match; one that --var sets is a change."""
    defaults = plan.deck_defaults()
    folder = os.path.join(work, "runs", "mu0.5_theta24_L45")
    os.makedirs(folder)
    older = dict(defaults, mu="0.5", theta="24", L="45")
    added = "acceleration"    # added to the deck during the first campaign
    del older[added]
    with open(os.path.join(folder, "params.json"), "w") as out:
        json.dump({"vars": older}, out)
    for given, differs in (({}, False), ({added: defaults[added]}, True)):
        args = argparse.Namespace(out=work, var=given)
        variables = dict(older)
        variables[added] = defaults[added]
        variables.update(given)
        job = plan.new_run(args, "mu0.5_theta24_L45", "mu0.5", variables, None)
        problem = plan.check_recorded_params(job)
        check((problem is not None) == differs and (added in job.vars) == differs,
              f"--var {given}: vars keep '{added}': {added in job.vars}, problem: {problem}")


def check_run_vars(work):
    """--run-var GLOB:NAME=VALUE sets a deck variable for the matching runs only, after --var."""
    args = argparse.Namespace(out=work, var={"max_iterations": "1000"}, series=["layer_mu2"], only=None,
                              duration=10.0, run_var=[("mu2_theta2[48]_*", {"max_iterations": "10000"})])
    caps = {job.name: job.vars["max_iterations"] for job in plan.build_jobs(args) if job.kind == "run"}
    check(caps["mu2_theta24_L45_layer"] == "10000" and caps["mu2_theta28_L45_layer"] == "10000"
          and caps["mu2_theta25_L45_layer"] == "1000", f"--run-var: {caps}")
    deposition = next(job for job in plan.build_jobs(args) if job.kind == "deposition")
    check("max_iterations" not in deposition.vars and deposition.vars["max_iterations_deposition"] == "1000",
          f"the rain's cap is its own: {deposition.vars}")
    # The health evidence: a run per friction and reading at the deck's defaults whatever --var says,
    # named apart from the published runs of the same point, in no analysis.
    evidence = [job for job in plan.build_jobs(argparse.Namespace(out=work, var={"max_iterations": "1000"},
                                                                  series=["health_evidence"], only=None, duration=10.0))
                if job.kind == "run"]
    defaults = plan.deck_defaults()
    check(sorted(job.name for job in evidence) == sorted(f"health_mu{mu}_theta{t}_L45{suffix}" for mu, t in
                                                         (("0.05", 20), ("0.5", 24), ("2", 28))
                                                         for suffix in ("", "_layer")), f"{[j.name for j in evidence]}")
    check(all(job.vars["max_iterations"] == defaults["max_iterations"] and job.vars["duration"] == "10"
              and not any(belongs(job) for belongs in plan.ANALYSES.values()) for job in evidence),
          "the evidence runs take the deck's defaults and join no analysis")
    check_creep_series(work)
    check_sign_series(work)


def check_sign_series(work):
    """The signs' rains (issue 63, item 5): two seeds no other series uses, in the layer reading at
    three angles per friction inside its published range, one packing per seed, joining the layer
    reading's flow rules alone."""
    args = argparse.Namespace(out=work, var={}, series=["layer_signs"], only=None, duration=10.0)
    jobs = plan.build_jobs(args)
    runs = {job.name: job for job in jobs if job.kind == "run"}
    other_seeds = {str(p.get("seed", "")) for name, points in plan.SERIES.items() if name != "layer_signs"
                   for p in points} | {plan.deck_defaults()["seed"]}
    check(len(runs) == 18 and not {str(s) for s in plan.SIGN_SEEDS} & other_seeds
          and "mu2_theta29_L45_seed20261127_layer" in runs, f"runs {sorted(runs)}")
    for mu, angles in plan.SIGN_ANGLES.items():
        published = [p["theta"] for p in plan.SERIES[f"layer_mu{mu}"]]
        check(len(angles) == 3 and min(published) < min(angles) and max(angles) < max(published),
              f"mu {mu}: angles {angles} inside {published}")
    check(sorted(job.name for job in jobs if job.kind == "deposition")
          == ["mu0.5_L45_seed20261126_layer", "mu0.5_L45_seed20261127_layer"], "one packing per seed")
    check(all([a for a, belongs in plan.ANALYSES.items() if belongs(job)] == ["layer_flow_rules"]
              and job.vars["reading"] == "layer" for job in runs.values()), "the layer reading's flow rules alone")


def check_creep_series(work):
    """The creep length's series (issue 63, item 3): names apart from the published runs (walls
    other than 30 d named), a deeper bed given the grains of the 30 d cell's layer plus the bed
    added, its own depositions, and the runs in the creep analysis only."""
    args = argparse.Namespace(out=work, var={}, series=list(plan.CREEP_SERIES), only=None, duration=10.0)
    jobs = plan.build_jobs(args)
    runs = {job.name: job for job in jobs if job.kind == "run"}
    check(len(runs) == 14 and "mu0.5_theta22_L45_seed20261123_wall60" in runs and "mu2_theta28_L102" in runs
          and "mu0.5_theta22_L152_wall60" in runs and "mu0.5_theta22_L72_seed20261125" in runs, f"runs {sorted(runs)}")
    # 3967 x 102/45 = 8992.1, plus 0.82 x 102 x 30 / (pi/4 x (1 + 0.4^2/12)) = 3152.5
    check(plan.grains_for_walls(102, 60) == 12145 and plan.grains_for_walls(45, 30) == 3967
          and plan.grains_for_walls(45, 15) == 3967 - 695, f"grains {plan.grains_for_walls(102, 60)}")
    check(runs["mu0.5_theta22_L102_wall60"].vars["grains"] == "12145", "the deep bed's grains")
    check(runs["mu0.5_theta22_L45_wall15"].deposition.name == "mu0.5_L45_seed20261122_wall15",
          "a bed between other walls rains its own packing")
    check(all([a for a, belongs in plan.ANALYSES.items() if belongs(job)] == ["creep_length"] for job in runs.values()),
          "a creep run joins the creep analysis alone")
    walls_by_var = argparse.Namespace(out=work, var={"wall_height": "4", "L": "8"}, series=["mu0.5"],
                                      only=["mu0.5_theta24_*"], duration=10.0)
    check([job.name for job in plan.build_jobs(walls_by_var)] == ["mu0.5_L8_seed20261122", "mu0.5_theta24_L8"],
          "walls set by --var name no run (chute.runner_resume's)")
    check(post.creep_depth_option(runs["mu0.5_theta22_L45_wall60"].vars) == ["--creep-depth", "60"]
          and post.creep_depth_option(runs["mu2_theta28_L22"].vars) == [], "the creep measure reads the whole bed")


def check_readings():
    """The layer reading's runs and packings carry its name, and a deck value written two ways
    (1e-4, 1.0e-4) is one setting for the resume check and the report."""
    defaults = plan.deck_defaults()
    point = dict(defaults, mu="0.5", theta="24", L="45", reading="layer")
    check(plan.run_name(point, defaults) == "mu0.5_theta24_L45_layer", plan.run_name(point, defaults))
    check(plan.run_name(dict(point, reading="count"), defaults) == "mu0.5_theta24_L45", "count reading's name")
    layer_points = plan.SERIES["layer_mu0.5"]
    check([p["theta"] for p in layer_points] == [p["theta"] for p in plan.SERIES["mu0.5"]]
          and all(p["reading"] == "layer" for p in layer_points), f"layer_mu0.5 series {layer_points}")
    args = argparse.Namespace(out="/tmp/campaign")
    depositions = {}
    plan.deposition_of(args, point, depositions)
    plan.deposition_of(args, dict(point, reading="count"), depositions)
    check(sorted(depositions) == ["mu0.5_L45_seed20261122", "mu0.5_L45_seed20261122_layer"],
          f"depositions {sorted(depositions)}")
    same = plan.changed_vars(dict(dt="1.0e-4", mu="0.5"), dict(dt="1e-4", mu="0.5"), ["dt", "mu"])
    check(same == "", f"1e-4 and 1.0e-4: {same}")
    check(plan.changed_vars(dict(order="fixed"), dict(order="shuffle"), ["order"]) == "order fixed -> shuffle",
          "a changed word")


def check_solver_health(work):
    line = ("Fix contact/dynamics cd solver: 2000 steps, 3 unconverged (0.15 %), largest final norm 0.00247, "
            "sweeps per step median 138, 99th percentile 900, max 1000, 4 rescued from a stall (1 started again "
            "from zero)\n")
    first = logs.solver_health(write(work, "first.log", "Step Time\n" + line.replace("2000 steps", "10 steps")
                                     + line))
    check(first == dict(steps=2000, unconverged=3, unconverged_fraction=0.0015, largest_final_norm=0.00247,
                        sweeps_median=138, sweeps_p99=900, sweeps_max=1000, rescued=4, restarted=1, block_solved=0),
          f"the last line: {first}")
    blocks = logs.solver_health(write(work, "blocks.log",
                                      line.replace("from zero)", "from zero, 3 by exact block solves)")))
    check(blocks["restarted"] == 1 and blocks["block_solved"] == 3, f"a line with block solves: {blocks}")
    older = logs.solver_health(write(work, "older.log", line.split(" (1 started")[0] + "\n"))
    check(older["rescued"] == 4 and older["restarted"] == 0, f"a line without restarts: {older}")
    check(logs.solver_health(write(work, "none.log", "Step Time\n")) is None, "a log without the line")
    second = dict(first, steps=6000, unconverged=0, unconverged_fraction=0.0, sweeps_median=200, sweeps_p99=300,
                  largest_final_norm=0.001, rescued=0, restarted=0)
    merged = logs.merged_solver_health([first, None, second])
    check((merged["steps"], merged["unconverged"], merged["unconverged_fraction"], merged["largest_final_norm"],
           merged["sweeps_median"], merged["sweeps_p99"], merged["legs"], merged["legs_unrecorded"])
          == (8000, 3, 3 / 8000, 0.00247, 200, 900, 2, 1), f"merged legs: {merged}")
    check(logs.merged_solver_health([None, None]) is None, "no leg recorded the line")
    record = argparse.Namespace(name="mu2_theta28", cost=dict(solver=first))
    refusal = report.publication_refusal(record, argparse.Namespace(publish_unconverged=False))
    check(refusal == "not publishing mu2_theta28: 0.15 % of its steps ended unconverged (more than 0.1 %); "
          "--publish-unconverged publishes it anyway, flagged", f"refusal: {refusal}")
    check(report.publication_refusal(record, argparse.Namespace(publish_unconverged=True)) is None, "told")
    check(report.publication_refusal(argparse.Namespace(name="old", cost={}), argparse.Namespace()) is None,
          "a run without a record is published (and shown as not recorded)")
    check(report.solver_cells(dict(solver=first)) == ["3 (0.15 %) ⚠", "138 / 900"], "the runs table's cells")

    def run(mu, cost, series="layer_mu2", name="r", which="layer"):
        return argparse.Namespace(name=name, series=series, results={"U": 1}, cost=cost,
                                  vars=dict(mu=mu, L="45", reading=which, theta="24"))
    records = [run("2", dict(solver=first)), run("2", {}), run("0.5", dict(solver=second), "layer_mu0.5")]
    check(report.health_refusal(records, argparse.Namespace(count_without_health=True)) is None,
          "--count-without-health counts a run without health")
    caveat = report.solver_caveat("pouliquen_curve_angle_mu2", "layer", records)
    check(caveat == " (⚠ 1 run(s) above 0.1 % unconverged; solver health not recorded for 1 of 2 runs)",
          f"a mu 2 row's caveat: {caveat}")
    check(report.solver_caveat("pouliquen_curve_angle_mu0.5", "layer", records) == "", "a mu 0.5 row's caveat")
    check("1 of 3 runs" in report.solver_caveat("phi_law_k", "layer", records), "a row of every friction")
    lengths = [argparse.Namespace(name=f"mu0.5_theta22_L{L}", series="L", results={"U": 1}, cost={},
                                  vars=dict(mu="0.5", L=L, reading="count", theta="22")) for L in ("12", "102")]
    caveat = report.solver_caveat("sign_f_vs_L", "count", records + lengths)
    check(caveat == " (solver health not recorded for 2 of 2 runs)", f"the cell length's rows count its runs: {caveat}")
    check_health_rule(run, first, second)


def check_health_rule(run, first, second):
    """A run a verdict counts needs its solver health, recorded or inferred from the evidence run of
    its friction and reading (at most 0.01 % unconverged); else --report refuses in one line naming it."""
    told, untold = argparse.Namespace(count_without_health=False), argparse.Namespace()
    old = run("2", {}, "mu2", "mu2_theta25_L45", "count")
    replica = run("2", {}, "replicas", "mu2_theta28_L45_seed20261123", "count")  # in no verdict
    refusal = report.health_refusal([old, replica, run("0.5", dict(solver=second), "mu0.5")], told)
    check(refusal is not None and "\n" not in refusal and refusal.startswith("refusing to count 1 runs without solver "
          "health (no evidence run of their friction and reading: mu2_theta25_L45)"), f"the refusal: {refusal}")
    layer_proof = run("2", dict(solver=second), "health_evidence", "health_mu2_theta28_L45_layer", "layer")
    check(report.health_refusal([old, layer_proof], untold) is not None, "evidence of the other reading counts not")
    clean = dict(second, unconverged=1, unconverged_fraction=0.5e-4)
    proof = run("2", dict(solver=clean), "health_evidence", "health_mu2_theta28_L45", "count")
    inferred = report.health_refusal([old, replica, proof], untold) is None
    check(inferred and old.inferred == ("health_mu2_theta28_L45", 0.5e-4), f"health inferred: {old.inferred}")
    check(replica.inferred == old.inferred, f"a replica's health is inferred too: {replica.inferred}")
    check(report.solver_cells({}, old.inferred)[0] == "inferred: ≤ 0.01 % (health_mu2_theta28_L45)",
          "the runs table shows the inferred health with its evidence")
    check(report.solver_caveat("phi_c_mu2", "count", [old, proof]) == " (solver health inferred for 1 of 1 runs)",
          "a verdict on inferred health says so (the evidence run counts in none)")
    dirty = run("2", dict(solver=first), "health_evidence", "health_mu2_theta28_L45", "count")  # 0.15 %
    refusal = report.health_refusal([old, dirty], untold)
    check(refusal is not None and "health_mu2_theta28_L45 0.15 % unconverged: mu2_theta25_L45" in refusal,
          f"evidence above 0.01 %: {refusal}")
    with tempfile.TemporaryDirectory() as destination:
        report.health_refusal([old, proof], untold)
        report.write_health_marks([old, proof], destination)
        with open(os.path.join(destination, "runs", report.HEALTH_MARKS)) as src:
            marks = [line for line in src if not line.startswith("#")]
        check(marks[1].strip() == "mu2_theta25_L45,2,count,health_mu2_theta28_L45,5e-05", f"the marks: {marks}")


def main():
    with tempfile.TemporaryDirectory() as work:
        check_solver_health(work)
        check_runs_older_than_a_variable(work)
        check_time_files(work)
        check_chunk_files(work)
        check_dumps(work)
        check_logs(work)
    check_statistics()
    check_text()
    check_arguments()
    check_readings()
    with tempfile.TemporaryDirectory() as work:
        check_run_vars(work)
    print("cdtools: ave/time, ave/chunk and dump readers (cut files included), logs, solver health, statistics, text, "
          "-var arguments, runs older than a deck variable, the two readings' names")


if __name__ == "__main__":
    main()
