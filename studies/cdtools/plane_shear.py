"""Plane shear's measured rheology (results/plane_shear/, doc/plane_shear_results.md): the table of
one friction and a quantity read at a given inertial number."""

import csv
import math
import os

from .run import TOP


def table_path(mu, tolerance="1e-4"):
    """The plane-shear table of contact friction mu solved to `tolerance` (the three frictions of
    the chute have one at 1e-4)."""
    return os.path.join(TOP, "results", "plane_shear", f"plane_shear_mu{mu:g}_{tolerance}.csv")


def read_table(path):
    """[(I, row)] of a plane-shear CSV ('#' lines are its provenance), sorted by I; every column
    a float."""
    with open(path, newline="") as src:
        table = csv.DictReader(line for line in src if not line.startswith("#"))
        rows = [{k: float(v) for k, v in r.items()} for r in table]
    if not rows:
        raise ValueError(f"{path}: no rows")
    return sorted(((r["I"], r) for r in rows), key=lambda pair: pair[0])


def at_inertial(table, inertial, column):
    """`column` at inertial number I, linear in log I between the two measured points around it;
    None outside the measured range."""
    for (i0, r0), (i1, r1) in zip(table, table[1:]):
        if i0 <= inertial <= i1:
            return r0[column] + (r1[column] - r0[column]) * math.log(inertial / i0) / math.log(i1 / i0)
    return None
