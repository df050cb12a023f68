#!/usr/bin/env python3
"""Checks of scripts/accuracy_study.py's own logic, run by ctest (no simulation).

    test_accuracy_study.py

batch_means on synthetic AR(1) series of known variance of the mean; within_noise on the
boundary cases; --dry-run lists every setting with the deck variables it changes.
Standard library only.
"""

import math
import os
import random
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(TOP, "scripts"))
import accuracy_study as study  # noqa: E402


def ar1(n, rho, rng):
    """AR(1) series of unit marginal variance and correlation rho per sample."""
    x, out = rng.gauss(0, 1), []
    for _ in range(n):
        x = rho * x + math.sqrt(1 - rho * rho) * rng.gauss(0, 1)
        out.append(x)
    return out


def check_batch_means():
    # For AR(1) the variance of the mean of n samples is (1/n)(1+rho)/(1-rho) for n >> the
    # correlation time. Over 400 series of 20000 samples (rho 0.9: 19x the white-noise
    # variance), the root mean square of the batch-means error must match the true standard
    # error within 10 % (the RMS of 400 estimates with 9 degrees of freedom each scatters by
    # about 1/sqrt(2*9*400) = 1.2 %; blocks of 2000 samples bias it low by about 1 %), and the
    # naive error of independent samples must be far too small (a check that can fail).
    rng = random.Random(7)
    n, rho, batches = 20000, 0.9, 10
    true_se = math.sqrt((1 + rho) / (1 - rho) / n)
    squares, hits = [], 0
    for _ in range(400):
        series = ar1(n, rho, rng)
        mean, err = study.batch_means(series, batches)
        squares.append(err * err)
        hits += abs(mean) < 2 * true_se
    rms = math.sqrt(sum(squares) / len(squares))
    assert abs(rms / true_se - 1) < 0.10, f"batch-means error {rms:.4g} against the true {true_se:.4g}"
    naive = 1 / math.sqrt(n)
    assert naive < 0.5 * true_se, "the test series is not correlated enough to test anything"
    assert 0.90 < hits / 400 < 0.99, f"{hits}/400 means within 2 true standard errors"
    try:
        study.batch_means([1.0] * 5, 10)
    except ValueError:
        pass
    else:
        raise AssertionError("batch_means accepted 5 values for 10 batches")
    print(f"batch_means: RMS error {rms:.4g}, true {true_se:.4g}; {hits}/400 within 2 sigma")


def check_within_noise():
    # The criterion |x - x_ref| < 2 sqrt(s^2 + s_ref^2): 3 and 4 (bars 0.3, 0.4: 2 x 0.5 = 1)
    # sit on the boundary; a hair inside is noise, a hair outside differs.
    assert study.within_noise(3.0, 0.3, 3.999, 0.4)
    assert not study.within_noise(3.0, 0.3, 4.001, 0.4)
    assert not study.within_noise(1.0, 0.0, 1.1, 0.0)
    assert abs(study.significance(1.0, 0.3, 2.0, 0.4) - 2.0) < 1e-12
    print("within_noise: boundary at twice the combined error bar")


def check_dry_run():
    out = subprocess.run([sys.executable, os.path.join(TOP, "scripts", "accuracy_study.py"),
                          "--out", "/nonexistent/study", "--dry-run", "--lmp", "lmp_cd"],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    names = [line.split(":")[0] for line in out]
    expected = (["deposition", "spinup", "reference", "default"] + [v[0] for v in study.VARIATIONS]
                + [f"reference seed {seed}" for seed in study.REFERENCE_REPLICA_SEEDS]
                + ["reference half-dt"] + [f"reference half-dt seed {seed}" for seed in study.REFERENCE_REPLICA_SEEDS[:3]])
    assert names == expected, f"dry run lists {names}"
    lines = dict(line.split(": ", 1) for line in out)
    assert "-var dt 4e-5 -var tolerance 1e-3" in lines["dt=4e-5"], lines["dt=4e-5"]
    assert "-var order shuffle" in lines["order=shuffle"]
    assert "-var stage deposition" in lines["deposition"]
    assert "-var start /nonexistent/study/spinup/chute.restart" in lines["tol=1e-4"]
    assert "-var dt 1e-5 -var tolerance 1e-4 -var max_iterations 10000" in lines["reference seed 3"]
    assert "-var dt 5e-06 -var tolerance 1e-4 -var max_iterations 10000" in lines["reference half-dt seed 2"]
    assert "-var order shuffle -var seed 3" in lines["reference seed 3"]
    print(f"dry run: {len(names)} jobs listed with their variables")


if __name__ == "__main__":
    check_batch_means()
    check_within_noise()
    check_dry_run()
