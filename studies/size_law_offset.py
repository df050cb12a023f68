#!/usr/bin/env python3
"""The size law's shift of phi (doc/source.md, "The packing law's offset"): for each run of
results/size_law/ (diameters uniform in area) and the published layer-reading run of the same
friction, angle and seed (diameters uniform in diameter, results/runs/), the residual
phi - (phi_c - k U) about the layer reading's phi(U) law (results/series/layer_flow_rules/
fits.csv: k = phi_k, phi_c = phi_c_mu<mu>), and the shift, area minus diameter; then per
friction the mean shift with its standard error over the runs.

    studies/size_law_offset.py                 # the markdown tables
    studies/size_law_offset.py --csv FILE      # the per-run rows as CSV too

Standard library only.
"""

import argparse
import csv
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.cdpost import read_results
from cdtools.run import TOP
from cdtools.stats import mean_sd_se

SIZE_LAW_RUNS = os.path.join(TOP, "results", "size_law")
PUBLISHED_RUNS = os.path.join(TOP, "results", "runs")
LAW_FITS = os.path.join(TOP, "results", "series", "layer_flow_rules", "fits.csv")
# mu<mu>_theta<theta>_L<L>[_seed<seed>]_layer_area: the seed named unless it is the series' own
RUN_NAME = re.compile(r"mu(?P<mu>[0-9.]+)_theta(?P<theta>[0-9.]+)_L(?P<L>[0-9]+)"
                      r"(?P<seed>_seed[0-9]+)?_layer_area$")


def residual(results, fits, mu):
    """phi - (phi_c(mu) - k U) of one run's results."""
    k, phi_c = fits["phi_k"][0], fits[f"phi_c_mu{mu}"][0]
    return results["phi"][0] - (phi_c - k * results["U"][0])


def published_name(match):
    """The published (diameter-law) run of the same friction, angle, cell and seed."""
    return f"mu{match['mu']}_theta{match['theta']}_L{match['L']}{match['seed'] or ''}_layer"


def shift_rows(size_law_runs, published_runs, fits):
    """One row per size-law run: its name, mu, theta, U and residual, the published run's."""
    rows = []
    for name in sorted(os.listdir(size_law_runs)):
        match = RUN_NAME.match(name)
        if not match:
            continue
        published = os.path.join(published_runs, published_name(match), "results.csv")
        if not os.path.exists(published):
            sys.exit(f"size_law_offset.py: {name}: no published run {published}")
        area = read_results(os.path.join(size_law_runs, name, "results.csv"))
        diameter = read_results(published)
        mu = match["mu"]
        rows.append(dict(run=name, mu=mu, theta=match["theta"], U_area=area["U"][0],
                         U_diameter=diameter["U"][0], residual_area=residual(area, fits, mu),
                         residual_diameter=residual(diameter, fits, mu)))
        rows[-1]["shift"] = rows[-1]["residual_area"] - rows[-1]["residual_diameter"]
    return rows


def markdown(rows, fits):
    lines = [f"phi(U) law of the layer reading: k = {fits['phi_k'][0]:.6f}, "
             + ", ".join(f"phi_c(mu {mu}) = {fits[f'phi_c_mu{mu}'][0]:.4f}"
                         for mu in sorted({r['mu'] for r in rows}, key=float)),
             "",
             "| run | U area | U diameter | phi - (phi_c - k U): area | diameter | shift |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {r['run']} | {r['U_area']:.2f} | {r['U_diameter']:.2f} | {r['residual_area']:+.4f} "
              f"| {r['residual_diameter']:+.4f} | {r['shift']:+.4f} |" for r in rows]
    lines += ["", "| mu | runs | shift: mean | standard deviation | standard error |", "|---|---|---|---|---|"]
    for mu in sorted({r["mu"] for r in rows}, key=float):
        shifts = [r["shift"] for r in rows if r["mu"] == mu]
        mean, sd, se = mean_sd_se(shifts)
        lines.append(f"| {mu} | {len(shifts)} | {mean:+.4f} | {sd:.4f} | {se:.4f} |")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--size-law-runs", default=SIZE_LAW_RUNS, help="default: results/size_law")
    parser.add_argument("--published-runs", default=PUBLISHED_RUNS, help="default: results/runs")
    parser.add_argument("--fits", default=LAW_FITS, help="default: results/series/layer_flow_rules/fits.csv")
    parser.add_argument("--csv", metavar="FILE", help="write the per-run rows here")
    args = parser.parse_args(argv)
    fits = read_results(args.fits)
    rows = shift_rows(args.size_law_runs, args.published_runs, fits)
    if not rows:
        sys.exit(f"size_law_offset.py: no size-law run in {args.size_law_runs}")
    print(markdown(rows, fits))
    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
