#!/usr/bin/env python3
"""Checks of studies/size_law_offset.py on synthetic runs, run by ctest (no simulation).

    tests/chute/test_size_law_offset.py

Runs built on a phi(U) law with known residuals: every shift (area minus diameter residual,
paired by friction, angle and seed) comes back to 1e-9, each friction's mean and standard
error to the table's four decimals; a folder not named as a size-law run is skipped; a
size-law run without its published run stops with that run named. Standard library only.
"""

import csv
import math
import os
import subprocess
import sys
import tempfile

from study_test import check

TOOL = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies",
                    "size_law_offset.py")
K, PHI_C = 0.002, {"0.5": 0.80, "0.05": 0.83}
# (mu, theta, seed part, U area, residual area, U diameter, residual diameter)
RUNS = (("0.5", "22", "", 11.0, 0.003, 10.5, -0.001),
        ("0.5", "24", "", 16.0, 0.001, 15.5, 0.002),
        ("0.5", "24", "_seed7", 16.2, 0.004, 15.9, 0.000),
        ("0.05", "16", "", 9.0, 0.000, 8.5, 0.0015))


def write_results(folder, rows):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "results.csv"), "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["name", "value", "error", "unit", "description"])
        for name, value in rows:
            writer.writerow([name, repr(value), "", "", ""])


def run_results(mu, U, residual):
    return [("U", U), ("phi", PHI_C[mu] - K * U + residual)]


def build(top):
    write_results(os.path.join(top, "fits"), [("phi_k", K)] + [(f"phi_c_mu{m}", c) for m, c in PHI_C.items()])
    for mu, theta, seed, u_area, r_area, u_diameter, r_diameter in RUNS:
        write_results(os.path.join(top, "size_law", f"mu{mu}_theta{theta}_L45{seed}_layer_area"),
                      run_results(mu, u_area, r_area))
        write_results(os.path.join(top, "runs", f"mu{mu}_theta{theta}_L45{seed}_layer"),
                      run_results(mu, u_diameter, r_diameter))
    os.makedirs(os.path.join(top, "size_law", "not_a_run"))


def run_tool(top, csv_path):
    return subprocess.run([sys.executable, TOOL, "--size-law-runs", os.path.join(top, "size_law"),
                           "--published-runs", os.path.join(top, "runs"),
                           "--fits", os.path.join(top, "fits", "results.csv"), "--csv", csv_path],
                          capture_output=True, text=True)


def main():
    with tempfile.TemporaryDirectory() as top:
        build(top)
        csv_path = os.path.join(top, "shifts.csv")
        result = run_tool(top, csv_path)
        check(result.returncode == 0, f"the tool failed: {result.stderr}")
        with open(csv_path) as src:
            rows = {r["run"]: float(r["shift"]) for r in csv.DictReader(src)}
        check(len(rows) == len(RUNS), f"{len(rows)} rows for {len(RUNS)} runs")
        for mu, theta, seed, _, r_area, _, r_diameter in RUNS:
            name = f"mu{mu}_theta{theta}_L45{seed}_layer_area"
            check(abs(rows[name] - (r_area - r_diameter)) < 1e-9, f"{name}: shift {rows[name]}")
        shifts = [0.004, -0.001, 0.004]    # mu 0.5
        mean = sum(shifts) / 3
        se = math.sqrt(sum((s - mean) ** 2 for s in shifts) / 2 / 3)
        line = next(li for li in result.stdout.splitlines() if li.startswith("| 0.5 |"))
        cells = [c.strip() for c in line.strip("|").split("|")]
        check(cells[1] == "3" and abs(float(cells[2]) - mean) < 1e-4 and abs(float(cells[4]) - se) < 1e-4,
              f"mu 0.5 summary {line} against mean {mean:.4f}, standard error {se:.4f}")
        os.remove(os.path.join(top, "runs", "mu0.05_theta16_L45_layer", "results.csv"))
        result = run_tool(top, csv_path)
        check(result.returncode != 0 and "mu0.05_theta16_L45_layer_area" in result.stderr
              and len(result.stderr.strip().splitlines()) == 1,
              f"a missing published run: status {result.returncode}, {result.stderr!r}")
    print("size_law_offset: every check passed")


if __name__ == "__main__":
    main()
