#!/usr/bin/env python3
"""Checks of studies/rerun_tables.py, run by ctest: a synthetic re-run against its published run
(health cells, each quantity's difference in combined errors by hand, A without one), a run added
with its small files and refused without them, the published run kept by --supersede (with its
series row) and read by the table once the re-run is published in its place, a run a report
published as itself not compared with itself, a README
without the block refused naming it, and the committed tables of results/rerun/*/README.md made
again from their folders (a run added or changed without `studies/rerun_tables.py` fails here).

    tests/chute/test_rerun_tables.py

Standard library only.
"""

import json
import os
import shutil
import tempfile

from study_test import check, load_study


def write_run(folder, values, cost=None):
    os.makedirs(folder)
    with open(os.path.join(folder, "results.csv"), "w") as out:
        out.write("name,value,error,unit,description\n")
        for name, (value, error) in values.items():
            out.write(f"{name},{value},{'' if error is None else error},,\n")
    if cost:
        with open(os.path.join(folder, "cost.json"), "w") as out:
            json.dump(cost, out)


def synthetic(tool):
    solver = {"unconverged": 2, "unconverged_fraction": 2e-5, "steps": 100000, "legs_unrecorded": 0,
              "largest_final_norm": 0.0031, "sweeps_median": 120, "sweeps_p99": 480, "rescued": 1234}
    new = {"U": (20.3, 0.3), "phi": (0.7500, 0.0004), "h": (60.0, 0.04), "f": (25.0, 2.0), "A": (0.06, None)}
    old = {"U": (20.0, 0.4), "phi": (0.7503, 0.0003), "h": (60.0, 0.03), "f": (22.0, 2.0), "A": (0.07, None)}
    with tempfile.TemporaryDirectory() as scratch:
        tool.PUBLISHED = os.path.join(scratch, "published")
        write_run(os.path.join(scratch, "rerun", "mu2_theta28_L45"), new, {"physical_seconds": 10.0, "solver": solver})
        write_run(os.path.join(tool.PUBLISHED, "mu2_theta28_L45"), old)
        row = tool.table(os.path.join(scratch, "rerun")).splitlines()[2]
        cells = [c.strip() for c in row.strip("|").split("|")]
        expected = ["mu2_theta28_L45", "10 s", "2 of 100 000 (2.0e-05)", "0.0031", "120 / 480", "1 234",
                    "20.30 (20.00; +0.6 σ)", "0.7500 (0.7503; −0.6 σ)", "60.00 (60.00; +0.0 σ)",
                    "25.0 (22.0; +1.1 σ)", "0.060 (0.070)"]
        check(cells == expected, f"row {cells}, expected {expected}")
        run = os.path.join(scratch, "campaign", "mu2_theta29_L45")
        write_run(os.path.join(run, "post"), new)
        try:
            tool.add_run(run, os.path.join(scratch, "rerun"))
            check(False, "a run without cost.json was added")
        except FileNotFoundError as error:
            check("cost.json" in str(error), f"error says {error}")
        for name in ("cost.json", "params.json"):
            with open(os.path.join(run, name), "w") as out:
                json.dump({"physical_seconds": 10.0, "solver": solver}, out)
        for name in ("layers.csv", "profile.csv", "results.json", "spectrum.csv"):
            open(os.path.join(run, "post", name), "w").close()
        added = tool.add_run(run, os.path.join(scratch, "rerun"))
        check(sorted(os.listdir(added)) == sorted(tool.RUN_FILES + tool.POST_FILES), f"added {os.listdir(added)}")
        superseded_kept_and_read(tool, scratch, row)
    try:
        tool.rewritten("no block here", "", "README.md")
        check(False, "a README without the block was rewritten")
    except ValueError as error:
        check("README.md" in str(error), f"error says {error}")


def superseded_kept_and_read(tool, scratch, row):
    """--supersede keeps the published run with its series row; once the published folder holds the
    re-run itself, the table still compares against the kept run."""
    published = os.path.join(tool.PUBLISHED, "mu2_theta28_L45")
    for name in tool.SUPERSEDED_FILES:
        if not os.path.exists(os.path.join(published, name)):
            open(os.path.join(published, name), "w").close()
    tool.SERIES = os.path.join(scratch, "series")
    os.makedirs(os.path.join(tool.SERIES, "flow_rules"))
    with open(os.path.join(tool.SERIES, "flow_rules", "runs.csv"), "w") as out:
        out.write("# provenance\nrun,mu,I_local\n../../runs/mu2_theta29_L45,2,0.1\n../../runs/mu2_theta28_L45,2,0.2\n")
    rerun = os.path.join(scratch, "rerun")
    check(tool.supersede(rerun) == ["mu2_theta28_L45"], "only the re-run with a published run is kept")
    with open(os.path.join(rerun, "mu2_theta28_L45", "superseded", tool.SERIES_ROW)) as src:
        kept_row = src.read()
    check(kept_row == "run,mu,I_local\n../../runs/mu2_theta28_L45,2,0.2\n", f"series row kept: {kept_row!r}")
    check(tool.supersede(rerun) == [], "a kept run is kept once")
    shutil.rmtree(published)  # the report publishes the re-run in its place
    shutil.copytree(os.path.join(rerun, "mu2_theta28_L45"), published, ignore=shutil.ignore_patterns("superseded"))
    again = tool.table(rerun).splitlines()[2]
    check(again == row, f"after the report the table still reads the kept run: {again}")
    shutil.copytree(os.path.join(rerun, "mu2_theta29_L45"), os.path.join(tool.PUBLISHED, "mu2_theta29_L45"))
    itself = tool.table(rerun).splitlines()[3]
    check(itself.rstrip(" |").endswith("no published run"), f"a run published as itself is not compared: {itself}")


def main():
    tool = load_study("rerun_tables")
    synthetic(tool)
    tool = load_study("rerun_tables")  # the real folders again
    check(tool.main(["--check"]) == 0, "the committed re-run tables differ from their folders")
    print("rerun_tables: every check passed")


if __name__ == "__main__":
    main()
