#!/usr/bin/env python3
"""The numbers of the results pages' prose against the committed data, run by ctest (no simulation).

    tests/chute/test_page_numbers.py

Every `<!-- check: KEY -->` marker of results/README.md, results/runs/README.md,
results/series/README.md and doc/source.md (studies/cdtools/page_numbers.py says how a marker
reads the numbers before it) is recomputed from the committed runs and series files with the
estimators the tables use, and each printed number must be its value rounded as printed. A run
re-analysed or re-run changes those files: the sentence that quotes it then fails here, named by
its page, line and key. Besides, on a synthetic page: a stale number, a wrong sign, too few
numbers and an unknown family each fail, and the update rewrites a stale number as printed
(decimals, sign, exponent form) and leaves a number two markers disagree on; the command refuses
a folder without the pages in one line; the estimators on
hand-computed cases. The signs of the
committed comparison tables on mu and on L (f on mu and A on mu in both readings, f on L) are each
the one weighted slope the prose quotes: the table's 'weighted: slope ± error, chi2/dof' is the
estimator's own (page_numbers.f_mu, A_mu, f_L, cdpost's fit_weighted_slope). Standard library
only.
"""

import contextlib
import io
import math
import os
import sys
import tempfile

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir)
sys.path.insert(0, os.path.join(TOP, "studies"))

from cdtools import page_numbers  # noqa: E402
from cdtools.text import with_error  # noqa: E402
from study_test import check, load_study  # noqa: E402


class Synthetic:
    """A Data whose fits are given."""

    def __init__(self, fits):
        self._fits = fits

    def fits(self, series):
        return self._fits


def synthetic_cases():
    data = Synthetic({"a": (0.12345, 0.0312), "b": (-0.5, None)})
    ok = "A rises, 0.123 ± 0.031<!-- check: fit:s:a -->, and b is −0.50<!-- check: fit:s:b -->."
    check(page_numbers.check_text(ok, data) == [], f"a page that agrees: {page_numbers.check_text(ok, data)}")
    stale = "A rises, 0.109 ± 0.030<!-- check: fit:s:a -->."
    check(len(page_numbers.check_text(stale, data)) == 1, "a stale number fails")
    sign = "b is 0.50<!-- check: fit:s:b -->."
    check(len(page_numbers.check_text(sign, data)) == 1, "a number of the wrong sign fails")
    few = "<!-- check: fit:s:a -->"
    check("expected" in page_numbers.check_text(few, data)[0][3], "too few numbers fail")
    unknown = "3<!-- check: nothing:s:a -->"
    check("cannot compute" in page_numbers.check_text(unknown, data)[0][3], "an unknown family fails")
    other_paragraph = "0.123 ± 0.031\n\nthe next paragraph<!-- check: fit:s:a -->"
    check(len(page_numbers.check_text(other_paragraph, data)) == 1, "a marker reads its own paragraph only")
    # signs and ranges as the pages write them
    numbers = page_numbers.printed_numbers("f ∝ L^(−0.102 ± 0.046), 12.5–35.8 Hz, mu0.5_theta22, +0.004 to -0.01")
    check(numbers == [(-0.102, 3), (0.046, 3), (12.5, 1), (35.8, 1), (0.004, 3), (-0.01, 2)],
          f"numbers read: {numbers}")
    check(page_numbers.agrees(0.13, 2, 0.1349) and not page_numbers.agrees(0.13, 2, 0.1351), "rounding")
    wrong_unit = "6.3<!-- check: run_as:mu0.5_theta22_L152:t_start:h -->"
    problem = page_numbers.check_text(wrong_unit, page_numbers.Data(TOP))[0][3]
    check("unit 'h' is neither 's' nor '%'" in problem, f"an unknown unit: {problem}")


def update_cases():
    """--update rewrites a disagreeing number in the decimals and sign style it was printed in,
    leaves agreeing ones and everything else as written, and the text then checks clean."""
    data = Synthetic({"a": (0.12345, 0.0312), "b": (-0.5, None), "p": (0.00204, None), "c": (0.25, None),
                      "d": (0.7, None)})
    stale = ("A rises, 0.109 ± 0.031<!-- check: fit:s:a -->; b is +0.50<!-- check: fit:s:b -->, "
             "p = 1e-06<!-- check: fit:s:p -->, c 0.25<!-- check: fit:s:c -->.")
    text, changes = page_numbers.update_text(stale, data)
    expected = ("A rises, 0.123 ± 0.031<!-- check: fit:s:a -->; b is −0.50<!-- check: fit:s:b -->, "
                "p = 2e-03<!-- check: fit:s:p -->, c 0.25<!-- check: fit:s:c -->.")
    check(text == expected, f"updated text: {text}")
    check([(old, new) for _, _, old, new in changes] == [("0.109", "0.123"), ("+0.50", "−0.50"), ("1e-06", "2e-03")],
          f"changes listed: {changes}")
    check(page_numbers.check_text(text, data) == [], "the updated text checks clean")
    twice = "x 0.3<!-- check: fit:s:b --><!-- check: fit:s:d -->"
    text, changes = page_numbers.update_text(twice, data)
    check(text == twice and changes[0][3].startswith("conflict"), f"two markers on one number: {changes}")


def estimator_cases():
    # y = 1 + 2 x exactly: slope 2, chi2 0, error sqrt(S/det) unscaled
    xs, ys, sigmas = [0.0, 1.0, 2.0, 3.0], [1.0, 3.0, 5.0, 7.0], [1.0, 1.0, 1.0, 1.0]
    slope, error, chi2 = page_numbers.weighted_slope(xs, ys, sigmas)
    check(abs(slope - 2) < 1e-12 and chi2 < 1e-20 and abs(error - math.sqrt(4 / 20)) < 1e-12,
          f"weighted slope of a line: {slope}, {error}, {chi2}")
    # scatter beyond the errors scales the error by sqrt(chi2/dof)
    slope, error, chi2 = page_numbers.weighted_slope(xs, [1.0, 4.0, 4.0, 7.0], [0.1] * 4)
    check(chi2 > 1 and abs(error - math.sqrt(4 / 20) * 0.1 * math.sqrt(chi2)) < 1e-12, "scaled error")
    intercept, slope = page_numbers.least_squares([1.0, 2.0, 3.0], [2.0, 4.0, 6.0])
    check(abs(slope - 2) < 1e-12 and abs(intercept) < 1e-12, "least squares")


def one_estimator():
    """f on mu, A on mu and f on L of the committed tables: the one weighted slope."""
    data = page_numbers.Data(TOP)
    cases = [("readings", "sign_f_vs_mu", column, lambda s=series: page_numbers.f_mu(data, s))
             for column, series in (("count", "flow_rules"), ("layer", "layer_flow_rules"))]
    cases += [("readings", "sign_A_vs_mu", column, lambda s=series: page_numbers.A_mu(data, s))
              for column, series in (("count", "flow_rules"), ("layer", "layer_flow_rules"))]
    cases.append(("L_series", "sign_f_vs_L", "ours", lambda: page_numbers.f_L(data)))
    for folder, key, column, estimator in cases:
        rows = page_numbers.read_rows(os.path.join(TOP, "results", "series", folder, "source_comparison.csv"))
        text = next(row[column] for row in rows if row["key"] == key)
        slope, error, chi2 = estimator()
        expected = f"weighted: {with_error(slope, error).replace(chr(0x2212), '-')}, chi2/dof {chi2:.2g}"
        sign = "rises" if slope - 2 * error > 0 else "falls" if slope + 2 * error < 0 else "no dependence"
        check(expected in text and text.startswith(sign), f"{folder} {key} {column}: '{text}' is not '{sign} ... "
              f"{expected}'")
    print(f"{len(cases)} signs on mu and L read by the one weighted slope")


def committed_pages():
    problems = page_numbers.check_pages(TOP)
    for page, line, key, problem in problems:
        print(f"{page}:{line}: {key}: {problem}")
    check(not problems, f"{len(problems)} numbers of the pages disagree with the data")
    counted = 0
    for page in page_numbers.PAGES:
        with open(os.path.join(TOP, page)) as src:
            counted += len(page_numbers.markers(src.read()))
    check(counted >= 100, f"only {counted} markers on the pages")
    print(f"{counted} marked numbers agree with the committed data")


def command_refuses_another_folder():
    """studies/page_numbers.py --root on a folder without the pages: one line naming them, status 2."""
    tool = load_study("page_numbers")
    error = io.StringIO()
    with tempfile.TemporaryDirectory() as scratch, contextlib.redirect_stderr(error):
        try:
            tool.main(["--root", scratch])
            status = 0
        except SystemExit as stop:
            status = stop.code
    last = error.getvalue().strip().splitlines()[-1]
    check(status == 2 and "no results/README.md" in last, f"status {status}, said {last!r}")


def main():
    synthetic_cases()
    command_refuses_another_folder()
    update_cases()
    estimator_cases()
    one_estimator()
    committed_pages()
    print("PASSED")
    return 0


if __name__ == "__main__":
    sys.exit(main())
