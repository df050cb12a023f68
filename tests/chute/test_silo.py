#!/usr/bin/env python3
"""Checks of studies/silo.py's measures on synthetic data, run by ctest (no simulation).

    tests/chute/test_silo.py

The Beverloo fit (W = C phi (D - k)^(3/2) through W^(2/3) linear in D) recovers C and k to 1e-9
from exact rates, and within three of its standard errors from rates with scatter of a known
size, whose errors it estimates to within a factor of two of the scatter of 200 such fits; the
flow rate of a discharge with clogged spells cut out is the rate it was made with, its block
error zero for a steady discharge; too few rates or samples are refused. Standard library only.
"""

import math
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies"))
import silo  # noqa: E402
from study_test import check  # noqa: E402

C, K, PHI = 0.62, 1.4, 0.81
WIDTHS = [4, 5, 6, 8, 11, 15, 20]


def law(D):
    return C * PHI * (D - K) ** 1.5


def exact_rates():
    fit = silo.beverloo_fit(WIDTHS, [law(D) for D in WIDTHS], [0.01 * law(D) for D in WIDTHS], PHI)
    check(abs(fit["C"] - C) < 1e-9 and abs(fit["k"] - K) < 1e-9, f"exact rates: C {fit['C']} k {fit['k']}")
    check(fit["chi2_red"] < 1e-12, f"exact rates: chi2 {fit['chi2_red']}")


def scattered_rates():
    rng = random.Random(61)
    fits = []
    for _ in range(200):
        rates = [law(D) * (1 + 0.03 * rng.gauss(0, 1)) for D in WIDTHS]
        fits.append(silo.beverloo_fit(WIDTHS, rates, [0.03 * law(D) for D in WIDTHS], PHI))
    for name, truth in (("C", C), ("k", K)):
        values = [f[name] for f in fits]
        mean = sum(values) / len(values)
        sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))
        quoted = sum(f[name + "_err"] for f in fits) / len(fits)
        check(abs(mean - truth) < 3 * sd / math.sqrt(len(values)) + 0.01 * abs(truth),
              f"{name}: mean of 200 fits {mean} against {truth}")
        check(0.5 < quoted / sd < 2.0, f"{name}: quoted error {quoted} against the fits' scatter {sd}")
        outside = sum(abs(f[name] - truth) > 3 * f[name + "_err"] for f in fits)
        check(outside <= 10, f"{name}: {outside} of 200 fits more than 3 errors from the truth")


def clogged_discharge():
    rate, stops = 7.5, [(20.0, 26.0), (40.0, 47.5)]
    samples = [(0.5 * i, rate * silo.flowing_time(0.5 * i, stops, 0.0)) for i in range(1, 201)]
    W, se, flowed = silo.flow_rate(samples, stops, 10.0)
    check(abs(W - rate) < 1e-9, f"clogged discharge: W {W}")
    check(se < 1e-9, f"clogged discharge: error {se}")
    check(abs(flowed - (100 - 10 - 6 - 7.5)) < 1e-9, f"clogged discharge: flowing time {flowed}")


def refusals():
    for call in (lambda: silo.beverloo_fit([4, 8], [1.0, 3.0], [0.1, 0.1], PHI),
                 lambda: silo.flow_rate([(t, t) for t in range(5)], [], 0.0)):
        try:
            call()
        except ValueError:
            continue
        sys.exit("FAILED: too few points accepted")


def main():
    exact_rates()
    scattered_rates()
    clogged_discharge()
    refusals()
    print("silo: Beverloo fit and flow rates recovered")


if __name__ == "__main__":
    main()
