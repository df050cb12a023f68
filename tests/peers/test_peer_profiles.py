#!/usr/bin/env python3
"""bench/peer_profiles.py's second reading, on synthetic rows (no solver run): a solved answer over
F times its target at the problem's scale counts as 'inflated', one its second run did not solve
as 'not_reproduced', the others stay solved; an answer missing from the second run is refused in
one line naming it. Standard library only."""

import importlib.util
import os
import sys

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir)
spec = importlib.util.spec_from_file_location("peer_profiles", os.path.join(TOP, "bench", "peer_profiles.py"))
profiles = importlib.util.module_from_spec(spec)
spec.loader.exec_module(profiles)


def row(solver, status, target, scaled=""):
    return {"class": "stall_mu2_e0.5", "problem": "hard.1.hdf5", "solver": solver, "start": "warm",
            "target": str(target), "status": status, "seconds": "0.01", "error_at_problem_scale": scaled}


def check(condition, what):
    if not condition:
        print(f"FAILED: {what}")
        sys.exit(1)


def main():
    rows = [row("ours", "solved", 1e-6), row("grows", "solved", 1e-6), row("lost", "solved", 1e-6),
            row("edge", "solved", 1e-6), row("slow", "time_limit", 1e-6)]
    answers = [row("ours", "solved", 1e-6, "3e-7"), row("grows", "solved", 1e-6, "0.04"),
               row("lost", "time_limit", 1e-6, "nan"), row("edge", "solved", 1e-6, "1.1e-5"),
               row("slow", "time_limit", 1e-6, "nan")]
    marks = profiles.at_problem_scale(rows, answers, within=10)
    statuses = [r["status"] for r in rows]
    check(statuses == ["solved", "inflated", "not_reproduced", "inflated", "time_limit"], f"statuses {statuses}")
    check(marks["grows"]["inflated"] == 1 and marks["ours"]["solved"] == 1 and "slow" not in marks,
          f"marks {dict(marks)}")
    rows = [row("ours", "solved", 1e-6)]
    try:
        profiles.at_problem_scale(rows, [], within=10)
        check(False, "a solve missing from the answers was accepted")
    except SystemExit as stop:
        check("no answer in --answers for stall_mu2_e0.5 hard.1.hdf5 ours warm" in str(stop), f"said {stop}")
    print("PASSED")


if __name__ == "__main__":
    main()
