#!/usr/bin/env python3
"""Checks of studies/rank_solutions.py's own measures, run by ctest (no simulation).

    tests/chute/test_rank_solutions.py

The solve error and the mass-weighted bias on hand-computed velocities; a truncated velocity
dump and a missing snapshot are refused with the file named, a --cell that sets what the study
sets with the variable named; the search for a 1-rank order that reaches another solution
stops at the first that does. (Its runs are exercised by chute.solve_two_ranks.) Standard
library only.
"""

import os
import subprocess
import sys
import tempfile

STUDIES = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies")
# the study and cdtools, found from this file (studies/cdtools/__init__.py)
sys.path.insert(0, STUDIES)

import rank_solutions as solutions  # noqa: E402
from study_test import check  # noqa: E402

# The tool's command line.
TOOL = [sys.executable, os.path.join(STUDIES, "rank_solutions.py")]
ENV = dict(os.environ, PYTHONPATH=STUDIES)


# {id: (radius, vx, vy, spin)}: two grains, radii 1 and 2 (masses 1 : 4).
START = {1: (1.0, 0.0, 0.0, 0.0), 2: (2.0, 0.0, 0.0, 0.0)}
REFERENCE = {1: (1.0, 3.0, 0.0, 0.0), 2: (2.0, 0.0, 4.0, 9.0)}


def check_measures():
    # The step changed the velocities by |(3,0)|^2 + |(0,4)|^2 = 25; the solve is off by
    # (0.3, 0) and (0, -0.4): 0.25 -> error sqrt(0.25 / 25) = 0.1. Spins do not count.
    after = {1: (1.0, 3.3, 0.0, 5.0), 2: (2.0, 0.0, 3.6, 0.0)}
    check(abs(solutions.solve_error(START, after, REFERENCE) - 0.1) < 1e-12, "solve error of the hand example")
    check(solutions.solve_error(START, REFERENCE, REFERENCE) == 0.0, "a solve is no distance from itself")
    # vx off by +1 on the light grain and -0.5 on the heavy one: (1*1 + 4*(-0.5)) / 5 = -0.2,
    # in units of a gravity step of 0.1 -> -2.
    shifted = {1: (1.0, 4.0, 0.0, 0.0), 2: (2.0, -0.5, 4.0, 9.0)}
    check(abs(solutions.mean_vx_bias(shifted, REFERENCE, 0.1) + 2.0) < 1e-12, "mass-weighted vx bias")


def check_alternatives():
    tried = []

    def solve(k, extra):
        tried.append(k)
        return REFERENCE if k == 2 else START
    check(solutions.reached_by_one_rank(START, REFERENCE, solve) == "yes 2" and tried == [0, 1, 2],
          f"the search should stop at the third order, tried {tried}")
    check(solutions.reached_by_one_rank(START, REFERENCE, lambda k, extra: START) == "no",
          "no order reaches the target, yet the search reports one")


def check_bad_input():
    with tempfile.TemporaryDirectory() as work:
        dump = os.path.join(work, "after.dump")
        with open(dump, "w") as out:
            out.write("ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n2\nITEM: ATOMS id radius vx vy omegaz\n1 0.1 0.2\n")
        try:
            solutions.read_velocities(dump)
            check(False, "a truncated dump was read")
        except RuntimeError as error:
            check(dump in str(error), f"the error does not name the file: {error}")
        missing = os.path.join(work, "no.restart")
        done = subprocess.run([*TOOL, "--out", work, "--snapshots", missing],
                              capture_output=True, text=True, env=ENV)
        last = done.stderr.strip().splitlines()[-1:]
        check(done.returncode == 2 and missing in "".join(last), f"missing snapshot: exit {done.returncode}, {last}")
        snapshot = os.path.join(work, "some.restart")
        open(snapshot, "w").close()
        done = subprocess.run([*TOOL, "--out", work, "--snapshots", snapshot,
                               "--cell", "L=10 tolerance=1e-4", "--lmp", "false"],
                              capture_output=True, text=True, env=ENV)
        last = done.stderr.strip().splitlines()[-1:]
        check(done.returncode == 2 and "tolerance" in "".join(last),
              f"--cell tolerance: exit {done.returncode}, {last}")


def main():
    check_measures()
    check_alternatives()
    check_bad_input()
    print("rank_solutions measures: solve error, bias, order search, truncated dump, missing snapshot, "
          "--cell clash")


if __name__ == "__main__":
    main()
