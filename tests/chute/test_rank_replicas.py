#!/usr/bin/env python3
"""Checks of studies/rank_replicas.py's own logic, run by ctest (no simulation).

    tests/chute/test_rank_replicas.py

Seed lists and their bad forms; the paired differences on synthetic replicas whose beds
scatter ten times more than their flows: pairing must recover the rank-count shift with the
flows' scatter only; a truncated cdpost table is refused with the file named, and so is a
--beds folder without the seed's bed; --against pairs with another study's runs, or with the
mean of several studies' runs; a -var given twice (--solver over --cell, or one the study
sets) is refused, and so is an analysis with no finished run. --timeline bins the flows' time
series and pairs them the same way, and refuses a cut or malformed flow.time with its name.
Standard library only.
"""

import argparse
import math
import os
import random
import subprocess
import sys
import tempfile

STUDIES = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies")
# the study and cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, STUDIES)

import rank_replicas as replicas  # noqa: E402
from study_test import check  # noqa: E402
from cdtools.stats import mean_sd_se

# The tool's command line.
TOOL = [sys.executable, os.path.join(STUDIES, "rank_replicas.py")]
ENV = dict(os.environ, PYTHONPATH=STUDIES)


def check_seeds():
    check(replicas.parse_seeds("1-3,7") == [1, 2, 3, 7], "'1-3,7' is not [1, 2, 3, 7]")
    for bad in ("3-1", "a", "1-"):
        try:
            replicas.parse_seeds(bad)
            check(False, f"--seeds {bad} accepted")
        except argparse.ArgumentTypeError:
            pass
    done = subprocess.run([*TOOL, "--out", "unused", "--seeds", "3-1"],
                          capture_output=True, text=True, env=ENV)
    lines = done.stderr.strip().splitlines()
    check(done.returncode == 2 and "--seeds" in lines[-1] and "3-1" in lines[-1],
          f"--seeds 3-1: exit {done.returncode}, '{lines[-1:]}'")


def check_pairing():
    # Bed offsets sd 1, flow noise sd 0.1, a shift of 0.05 on 2 ranks, 400 seeds. Paired: the
    # mean difference within 4 of its standard errors (0.1 sqrt(2) / 20 = 0.007) of 0.05 and
    # the sd of the differences within 15 % of 0.1 sqrt(2) (its own scatter: 3.5 %), where
    # the unpaired means could not separate the shift (sd 1, SE 0.07 on each side).
    rng = random.Random(11)
    seeds, shift, noise = list(range(1, 401)), 0.05, 0.1
    table = {}
    for s in seeds:
        bed = rng.gauss(0, 1)
        for ranks, offset in ((1, 0.0), (2, shift)):
            table[(s, ranks)] = {q: bed + offset + rng.gauss(0, noise) for q in replicas.QUANTITIES}
    differences = replicas.paired_differences(table, seeds, 1, [2])[2]
    for q in replicas.QUANTITIES:
        mean, sd, error = mean_sd_se(differences[q])
        check(abs(mean - shift) < 4 * error, f"{q}: paired shift {mean:.4f} ± {error:.4f}, expected {shift}")
        check(abs(sd / (noise * math.sqrt(2)) - 1) < 0.15, f"{q}: sd of the differences {sd:.4f}")
    table[(7, 2)] = None                                     # a run not done: no pair
    check(len(replicas.paired_differences(table, seeds, 1, [2])[2]["U"]) == 399, "an unfinished run was paired")


def check_truncated_table():
    with tempfile.TemporaryDirectory() as out:
        post = os.path.join(out, "seed1", "np1", "post")
        os.makedirs(post)
        with open(os.path.join(post, "results.csv"), "w") as table:
            table.write("name,value,error\nU,1.9,0.05\n")
        try:
            replicas.results(out, 1, 1)
            check(False, "a results.csv without phi, h, f was accepted")
        except RuntimeError as error:
            check("results.csv" in str(error) and "phi" in str(error), f"message '{error}'")


def check_missing_bed():
    # --beds names another study's folder: a seed it has no bed for stops the study before any run.
    with tempfile.TemporaryDirectory() as work:
        beds = os.path.join(work, "other")
        done = subprocess.run([*TOOL, "--out", os.path.join(work, "out"), "--beds", beds,
                               "--seeds", "3", "--ranks", "1", "--lmp", "/bin/false"],
                              capture_output=True, text=True, env=ENV)
        last = "".join(done.stderr.strip().splitlines()[-1:])
        check(done.returncode == 1 and "--beds" in last and "seed 3" in last, f"--beds without the bed: '{last}'")


def write_run(study, seed, values, ranks=1, u_flow=None):
    """A finished run as the study leaves it: cdpost's table, the deck's summary line and, given
    u_flow(t), the deck's flow.time sampled every 0.01 s over 2 s."""
    folder = replicas.run_folder(study, seed, ranks)
    os.makedirs(os.path.join(folder, "post"))
    with open(os.path.join(folder, "post", "results.csv"), "w") as table:
        table.write("name,value,error\n" + "".join(f"{q},{values[q]},0\n" for q in replicas.CDPOST_QUANTITIES))
    with open(os.path.join(folder, "log.lammps"), "w") as log:
        log.write(f"CHUTE steps_solved 100 sweeps {100 * values['sweeps']}\n")
    if u_flow:
        with open(os.path.join(folder, "flow.time"), "w") as series:
            series.write("# chute flow\n# TimeStep v_time v_u_all v_u_flow v_v_flow\n")
            series.write("".join(f"{500 * k} {k / 100:g} 0 {u_flow(k / 100)!r} 0\n" for k in range(201)))


def check_against():
    # Another setting from the same two beds, 0.1 and 0.3 faster: paired with --against, dU = +0.2.
    with tempfile.TemporaryDirectory() as work:
        base, other = os.path.join(work, "base"), os.path.join(work, "other")
        for seed, u in ((1, 1.5), (2, 2.5)):
            write_run(base, seed, dict(U=u, phi=0.78, h=12, f=40, sweeps=160))
            write_run(other, seed, dict(U=u + 0.1 * (2 * seed - 1), phi=0.78, h=12, f=40, sweeps=160))
        done = subprocess.run([*TOOL, "--out", other, "--against", base, "--seeds", "1-2",
                               "--ranks", "1", "--analyse-only"], capture_output=True, text=True, env=ENV)
        row = [line for line in done.stdout.splitlines() if line.startswith("| 1 | 2 |")]
        check(done.returncode == 0 and row and row[-1].split("|")[3].strip().startswith("+0.2 "),
              f"--against: {row or done.stdout + done.stderr}")
        # With two studies the bed's baseline is their mean: base2 has U 1.3 and 2.3, so the
        # baselines are 1.4 and 2.4 and the differences 0.2 and 0.4: +0.3. Seed 3 has no run in
        # base2 and drops out.
        base2 = os.path.join(work, "base2")
        for seed, u in ((1, 1.3), (2, 2.3)):
            write_run(base2, seed, dict(U=u, phi=0.78, h=12, f=40, sweeps=160))
        write_run(base, 3, dict(U=9.0, phi=0.78, h=12, f=40, sweeps=160))
        write_run(other, 3, dict(U=1.0, phi=0.78, h=12, f=40, sweeps=160))
        done = subprocess.run([*TOOL, "--out", other, "--against", base, base2, "--seeds", "1-3",
                               "--ranks", "1", "--analyse-only"], capture_output=True, text=True, env=ENV)
        row = [line for line in done.stdout.splitlines() if line.startswith("| 1 | 2 |")]
        check(done.returncode == 0 and row and row[-1].split("|")[3].strip().startswith("+0.3 "),
              f"--against two studies: {row or done.stdout + done.stderr}")


def check_clashing_variables():
    # LAMMPS keeps the first -var of a name, so a repeated one would be dropped silently.
    for flags, named in ((["--solver", "theta=23 order=shuffle"], "theta"),
                         (["--cell", "L=10 duration=5"], "duration"),
                         (["--cell", "L=10 seed=4"], "seed")):
        done = subprocess.run([*TOOL, "--out", "unused", "--analyse-only", *flags],
                              capture_output=True, text=True, env=ENV)
        last = done.stderr.strip().splitlines()[-1:]
        check(done.returncode == 2 and named in "".join(last), f"{flags}: exit {done.returncode}, {last}")


def check_nothing_to_analyse():
    with tempfile.TemporaryDirectory() as work:
        done = subprocess.run([*TOOL, "--out", work, "--analyse-only"], capture_output=True, text=True, env=ENV)
        lines = done.stderr.strip().splitlines()
        check(done.returncode == 1 and len(lines) == 1 and work in lines[0] and "no finished run" in lines[0],
              f"--analyse-only of an empty folder: exit {done.returncode}, {lines}")


def check_timeline():
    # Two beds whose 4-rank flows run 0.01 and 0.02 m/s faster from 1 s on: the 0.5 s bins
    # before 1 s show +0, those after +0.015, t = 0.015 / (0.00707 / sqrt 2) = 3.0.
    with tempfile.TemporaryDirectory() as work:
        values = dict(U=1.9, phi=0.78, h=12, f=40, sweeps=160)
        for seed in (1, 2):
            write_run(work, seed, values, 1, lambda t: 0.1 * t)
            write_run(work, seed, values, 4, lambda t, seed=seed: 0.1 * t + (0.01 * seed if t >= 1 else 0))
        command = [*TOOL, "--out", work, "--seeds", "1-2", "--ranks", "1", "4", "--analyse-only",
                   "--timeline", "0.5"]
        done = subprocess.run(command, capture_output=True, text=True, env=ENV)
        bins = ("| 0-", "| 0.5-", "| 1-", "| 1.5-")
        rows = [line.split("|") for line in done.stdout.splitlines() if line.startswith(bins)]
        expected = {"0-0.5": "+0 ", "0.5-1": "+0 ", "1-1.5": "+0.015 ± 0.005 (t +3.0)",
                    "1.5-2": "+0.015 ± 0.005 (t +3.0)"}
        got = {row[1].strip(): row[3].strip() for row in rows}
        check(done.returncode == 0 and set(got) == set(expected)
              and all(got[span].startswith(expected[span]) for span in expected),
              f"--timeline 0.5: {got or done.stderr}")
        check(abs(float(rows[0][2]) - 0.0245) < 1e-9, f"baseline of 0-0.5 s: {rows[0][2]} (mean of 0.1 t)")
        # A flow.time cut at 1.2 s leaves the last bin empty; a row of text is refused with its line.
        series = os.path.join(work, "seed2", "np4", "flow.time")
        lines = open(series).readlines()
        for broken, named in ((lines[:123], "no sample in 1.5-2 s"), (lines[:50] + ["50 0.48 0 x 0\n"], ":51:")):
            with open(series, "w") as out:
                out.writelines(broken)
            done = subprocess.run(command, capture_output=True, text=True, env=ENV)
            last = done.stderr.strip().splitlines()
            check(done.returncode == 1 and len(last) == 1 and "flow.time" in last[0] and named in last[0],
                  f"broken flow.time: exit {done.returncode}, {last}")
    for flags in (["--timeline", "0"], ["--timeline", "0.5", "--ranks", "1"]):    # no bin; nothing to pair
        done = subprocess.run([*TOOL, "--out", "unused", "--analyse-only", *flags],
                              capture_output=True, text=True, env=ENV)
        check(done.returncode == 2 and "--timeline" in done.stderr, f"{flags}: exit {done.returncode}")


def main():
    check_seeds()
    check_pairing()
    check_truncated_table()
    check_missing_bed()
    check_against()
    check_clashing_variables()
    check_nothing_to_analyse()
    check_timeline()
    print("rank_replicas logic: seeds, pairing, truncated table, missing bed, --against, "
          "clashing -vars, nothing to analyse, timeline")


if __name__ == "__main__":
    main()
