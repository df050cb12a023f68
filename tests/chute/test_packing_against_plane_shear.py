#!/usr/bin/env python3
"""Checks of studies/packing_against_plane_shear.py on synthetic tables, run by ctest (no
simulation, no figure).

    tests/chute/test_packing_against_plane_shear.py

The plane-shear phi at a run's I is linear between the two points around it (worked by hand),
none outside them; a run's offset is its phi minus that; runs of a friction plane shear lacks,
or without I_local, are left out; the per-friction summary gives the mean and standard error.
Standard library only.
"""

import math
import os
import tempfile

from study_test import check, load_study


RUNS_CSV = """run,mu,theta_deg,L_d,phi_local,phi_local_error,I_local,I_local_error
../../runs/a,0.5,22,,0.785,,0.10,0.002
../../runs/b,0.5,24,,0.760,,0.20,0.003
../../runs/c,2,26,,0.75,,0.15,0.002
../../runs/d,0.5,25,,0.70,,,
"""


def main():
    tool = load_study("packing_against_plane_shear")
    plane_shear = [(0.0, 0.0, 0.80), (0.2, 0.001, 0.76), (0.4, 0.002, 0.70)]
    # 0.80 + (0.76 - 0.80) x 0.05 / 0.2 = 0.79; 0.76 + (0.70 - 0.76) x 0.1 / 0.2 = 0.73.
    check(abs(tool.phi_at(0.05, plane_shear) - 0.79) < 1e-12, f"phi at 0.05: {tool.phi_at(0.05, plane_shear)}")
    check(abs(tool.phi_at(0.3, plane_shear) - 0.73) < 1e-12, f"phi at 0.3: {tool.phi_at(0.3, plane_shear)}")
    check(tool.phi_at(0.5, plane_shear) is None, "a phi outside the plane-shear range")
    with tempfile.TemporaryDirectory() as top:
        path = os.path.join(top, "runs.csv")
        with open(path, "w") as out:
            out.write("# a series' runs\n" + RUNS_CSV)
        points = tool.chute_points(path)
        check([p[0] for p in points] == ["a", "b", "c"], f"runs read: {[p[0] for p in points]}")
    rows = tool.offsets([("layer", points)], {0.5: plane_shear})
    # a: 0.785 - (0.80 - 0.02) = 0.005; b: 0.760 - 0.76 = 0; c has no plane shear at mu 2.
    check([r[1] for r in rows] == ["a", "b"], f"compared runs: {[r[1] for r in rows]}")
    check(abs(rows[0][6] - 0.005) < 1e-12 and abs(rows[1][6]) < 1e-12, f"offsets {[r[6] for r in rows]}")
    (reading, mu, runs, low, high, mean, se), = tool.summary(rows)
    check((reading, mu, runs) == ("layer", 0.5, 2) and abs(mean - 0.0025) < 1e-12, f"summary {mean}")
    # standard deviation sqrt(2 x 0.0025^2 / 1), over sqrt(2): 0.0025.
    check(abs(se - math.sqrt(2 * 0.0025 ** 2) / math.sqrt(2)) < 1e-12 and abs(low) < 1e-12
          and abs(high - 0.005) < 1e-12, f"standard error {se}, range {low} to {high}")
    print("packing_against_plane_shear: every check passed")


if __name__ == "__main__":
    main()
