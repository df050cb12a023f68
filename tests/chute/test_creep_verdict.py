#!/usr/bin/env python3
"""Checks of studies/creep_verdict.py on synthetic runs, run by ctest (no simulation; cdpost
series stood in for by a script that reads each run's first-decade length from its results.csv).

    tests/chute/test_creep_verdict.py

The power law: lambda = c L^0.93 with 5 % noise gives a within two of its errors of 0.93, the
cell's (within three in the whole tool, whose noise is drawn otherwise); lambda constant with
noise gives the grains'. The whole tool on a synthetic repository and campaign: the published L
series and some creep runs read, the others listed as missing with no number for them, the
unresolved runs left out of their estimator's fit and named, the runs of a campaign folder
preferred to the published ones, the 45 d mu 2 run never read from results/runs (capped), the
walls' differences in combined errors, the coherence verdicts (independent regions at mu 0.5,
one mode at mu 2) and the page marked partial.
Standard library only.
"""

import csv
import math
import os
import random
import sys
import tempfile

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir)
sys.path.insert(0, os.path.join(TOP, "studies"))

import creep_verdict  # studies/creep_verdict.py
from study_test import check

FAKE_CDPOST = """#!{python}
import csv, os, sys
manifest, out = sys.argv[2], sys.argv[sys.argv.index("--out") + 1]
os.makedirs(out, exist_ok=True)
rows = [r for r in csv.DictReader(line for line in open(manifest) if not line.startswith("#"))]
with open(os.path.join(out, "runs.csv"), "w") as dst:
    dst.write("run,creep_lambda_first_decade,creep_lambda_first_decade_error\\n")
    for r in rows:
        value = ""
        for line in open(os.path.join(r["run"], "results.csv")):
            if line.startswith("test_first_decade,"):
                value = line.split(",")[1]
        dst.write(r["run"] + "," + value + "," + ("0.01" if value else "") + "\\n")
"""


def power_law_recovered(tool):
    rng = random.Random(63)
    lengths = [12, 22, 22, 22, 32, 45, 45, 45, 52, 72, 72, 72, 102, 152]
    law = tool.power_law([(L, 0.08 * L ** 0.93 * (1 + 0.05 * rng.gauss(0, 1))) for L in lengths])
    a, error, c, n = law
    check(n == len(lengths) and abs(a - 0.93) <= 2 * error and error < 0.05, f"a of c L^0.93: {law}")
    check(tool.verdict_of(a, error) == "cell's", f"verdict of {law}")
    flat = tool.power_law([(L, 2.1 * (1 + 0.05 * rng.gauss(0, 1))) for L in lengths])
    check(abs(flat[0]) <= 2 * flat[1] and tool.verdict_of(flat[0], flat[1]) == "grains'", f"constant: {flat}")
    check(tool.verdict_of(-0.5, 0.1).startswith("neither"), "a falling beyond two errors")
    check(tool.power_law([(22, 1.0), (22, 1.1), (22, 0.9)]) is None, "one length: no law")
    exact = tool.power_law([(10, 1.0), (100, 10.0), (1000, 100.0)])
    check(abs(exact[0] - 1) < 1e-12 and exact[1] < 1e-9 and abs(exact[2] - 0.1) < 1e-12, f"exact law {exact}")


def results_csv(folder, rows):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "results.csv"), "w") as out:
        out.write("name,value,error,unit,description\n")
        for name, value, error in rows:
            out.write(f"{name},{value},{'' if error is None else error},,\n")


def synthetic_run(folder, L, rng, first=True, floor=True, coherence=None, lam=None):
    """A run's results: lambda_1 = 0.08 L^0.93, lambda_f = 0.07 L^0.9 (5 % noise), A = 0.3 / sqrt(L)."""
    noise = 1 + 0.05 * rng.gauss(0, 1)
    rows = [("A", 0.3 / math.sqrt(L) * noise, None), ("A_mean", 0.018 / math.sqrt(L), None)]
    if first:
        rows.append(("test_first_decade", lam or 0.08 * L ** 0.93 * noise, None))
    if floor:
        rows.append(("creep_lambda", 0.07 * L ** 0.9 * noise, 0.05))
    if coherence:
        pattern, plateau, xi = coherence
        rows += [("oscillation_pattern", pattern, None), ("coherence_plateau", plateau, 0.02),
                 ("coherence_far", plateau + 0.02, None), ("coherence_length", xi, 1.0)]
    results_csv(folder, rows)


def campaign_run(campaign, name, L, rng, **kw):
    folder = os.path.join(campaign, "runs", name)
    synthetic_run(os.path.join(folder, "post"), L, rng, **kw)
    open(os.path.join(folder, "DONE"), "w").close()


def read_csv(path):
    with open(path, newline="") as src:
        return list(csv.DictReader(src))


def whole_tool(tool, work):
    rng = random.Random(7)
    root, campaign = os.path.join(work, "repo"), os.path.join(work, "campaign")
    for L in (12, 22, 32, 45, 52, 72, 102, 152):
        # L 12 resolves neither length; 102 and 152 reach the floor nowhere (lambda_f unresolved)
        synthetic_run(os.path.join(root, "results", "runs", f"mu0.5_theta22_L{L}"), L, rng, first=L != 12,
                      floor=L not in (12, 102, 152))
    # the capped mu 2 run published: never read; the campaign's L 22 run read instead of the published
    synthetic_run(os.path.join(root, "results", "runs", "mu2_theta28_L45"), 45, rng, lam=99.0)
    results_csv(os.path.join(root, "results", "runs", "mu0.5_theta22_L22_seed20261124"), [("creep_lambda", 99, 1)])
    for L in (22, 45, 72):
        for seed in (20261124, 20261125):
            campaign_run(campaign, f"mu0.5_theta22_L{L}_seed{seed}", L, rng, coherence=(4, 0.05, 3.0))
    for seed in ("", "_seed20261123"):
        campaign_run(campaign, f"mu0.5_theta22_L45{seed}_wall15", 45, rng)
    for L, lam in ((22, 1.5), (45, 1.62), (102, 1.45)):    # no trend in L
        campaign_run(campaign, f"mu2_theta28_L{L}", L, rng, coherence=(1, 0.8, 8.0), lam=lam)
    os.makedirs(os.path.join(campaign, "runs", "mu0.5_theta22_L102_wall60", "legs"))   # running
    cdpost = os.path.join(work, "cdpost")
    with open(cdpost, "w") as out:
        out.write(FAKE_CDPOST.format(python=sys.executable))
    os.chmod(cdpost, 0o755)
    out = os.path.join(work, "out")
    status = tool.main(["--runs", campaign, "--root", root, "--cdpost", cdpost, "--out", out,
                        "--work", os.path.join(work, "cdpost-work")])
    check(status == 0, f"status {status}")

    runs = {r["run"]: r for r in read_csv(os.path.join(out, "verdict_runs.csv"))}
    check(runs["mu0.5_theta22_L22_seed20261124"]["source"] == campaign + "/runs/mu0.5_theta22_L22_seed20261124",
          "the campaign's run before the published one")
    check(runs["mu2_theta28_L45"]["source"].endswith("mu2_theta28_L45") and float(runs["mu2_theta28_L45"]["lambda_1"])
          < 2, "mu 2 at 45 d read from the campaign, not from results/runs")
    missing = [name for name, r in runs.items() if not r["source"]]
    check("mu0.5_theta22_L45_wall60" in missing and "mu0.5_theta22_L152_wall60" in missing
          and all(not runs[n]["lambda_1"] and not runs[n]["lambda_f"] for n in missing), f"missing {missing}")
    check(runs["mu0.5_theta22_L102_wall60"]["state"] == f"running or pending in {campaign}", "a running run's state")

    fits = {(r["mu"], r["estimator"]): r for r in read_csv(os.path.join(out, "verdict_fits.csv"))}
    first, floor = fits[("0.5", "lambda_1")], fits[("0.5", "lambda_f")]
    check(first["runs"] == "13" and abs(float(first["a"]) - 0.93) <= 3 * float(first["a_error"])
          and first["verdict"] == "cell's", f"mu 0.5 lambda_1 {first}")
    check(first["unresolved"] == "mu0.5_theta22_L12", f"lambda_1 unresolved {first['unresolved']}")
    check(floor["unresolved"].split() == ["mu0.5_theta22_L12", "mu0.5_theta22_L102", "mu0.5_theta22_L152"]
          and floor["runs"] == "11" and abs(float(floor["a"]) - 0.9) <= 3 * float(floor["a_error"]),
          f"lambda_f {floor}")
    check(first["missing"] == "", "every run of the fit found")
    mu2 = fits[("2", "lambda_1")]
    check(mu2["runs"] == "3" and mu2["verdict"] == "grains'", f"mu 2 constant lambda_1: {mu2}")

    walls = read_csv(os.path.join(out, "verdict_walls.csv"))
    w15 = next(w for w in walls if w["estimator"] == "lambda_1" and w["L"] == "45" and w["walls"] == "15")
    w30 = next(w for w in walls if w["estimator"] == "lambda_1" and w["L"] == "45" and w["walls"] == "30")
    combined = math.hypot(float(w15["se"]), float(w30["se"]))
    check(w15["runs"] == "2" and w30["runs"] == "3" and abs(float(w15["combined_error"]) - combined) < 1e-9
          and abs(float(w15["sigmas"]) - (float(w15["mean"]) - float(w30["mean"])) / combined) < 1e-6
          and abs(float(w15["sigmas"])) < 3, f"15 d walls against 30 d in combined errors: {w15}")
    w60 = next(w for w in walls if w["estimator"] == "lambda_1" and w["L"] == "45" and w["walls"] == "60")
    check(w60["runs"] == "0" and "mu0.5_theta22_L45_wall60" in w60["missing"], f"60 d walls missing: {w60}")

    verdicts = open(os.path.join(out, "verdict.md")).read()
    check(verdicts.startswith("# The creep length: grains or cell (partial)") and "runs missing" in verdicts
          and "mu0.5_theta22_L152_wall60" in verdicts, "the page says partial and lists the missing runs")
    check("| 0.5 | 22 | 22 45 72 |" in verdicts and "independent regions" in verdicts, "mu 0.5 independent regions")
    check("| 2 | 28 | 22 45 102 |" in verdicts and "| one mode |" in verdicts, "mu 2 one mode")
    coherence = read_csv(os.path.join(out, "verdict_coherence.csv"))
    check(all(r["kind"] == "" for r in coherence if r["run"].startswith("mu0.5_theta22_L") and "seed" not in r["run"]),
          "published runs carry no coherence")


def main():
    tool = creep_verdict
    power_law_recovered(tool)
    with tempfile.TemporaryDirectory() as work:
        whole_tool(tool, work)
    print("creep_verdict: all checks passed")


if __name__ == "__main__":
    main()
