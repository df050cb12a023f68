#!/usr/bin/env python3
"""Checks of studies/drum.py's own measures, run by ctest (no simulation).

    tests/chute/test_drum.py

A packing of disks on a triangular lattice filling a drum of radius 25 d below a line tilted by
a known angle: the surface reading returns that angle and height within a bin's resolution
(0.5 degree on a crystal, whose rows the columns cut at the tilt), and the grains' own
overlaps are found (none, then one made on purpose). The layer's sign change is interpolated
between bins. Standard library only.
"""

import math
import os
import sys

STUDIES = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "studies")
sys.path.insert(0, STUDIES)

import drum  # noqa: E402
from study_test import check  # noqa: E402


def tilted_packing(angle_deg, height):
    """Unit disks on a triangular lattice whose rows run along the surface y = height + x
    tan(angle), as a settled slope's do, filling the drum below that line."""
    a = math.radians(angle_deg)
    along, normal = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
    origin = (-height * math.sin(a) * math.cos(a), height * math.cos(a) ** 2)  # the line's point nearest the axis
    grains = []
    for row in range(80):
        depth = 0.5 + row * math.sqrt(3.0) / 2.0
        for k in range(-60, 61):
            u = k + (0.5 if row % 2 else 0.0)
            x = origin[0] + u * along[0] - depth * normal[0]
            y = origin[1] + u * along[1] - depth * normal[1]
            if math.hypot(x, y) < drum.RADIUS - 0.5:
                grains.append((x, y, 0.0, 0.0, 0.5))
    return grains


def main():
    for angle in (15.0, 22.0, 30.0):
        grains = tilted_packing(angle, 2.0)
        height, measured = drum.frame_surface(grains)
        check(abs(measured - angle) < 0.5, f"surface angle {measured:.2f} for a packing tilted by {angle}")
        check(abs(height - 2.0) < 1.0, f"surface height {height:.2f} over the axis for 2.0")
    grains = tilted_packing(20.0, 0.0)
    overlap = drum.deepest_overlap(grains)
    check(overlap < 1e-9, f"a lattice of touching disks overlaps by {overlap}")
    x, y, vx, vy, r = grains[10]
    grains.append((x + 0.9, y, vx, vy, r))  # 0.1 d into its right-hand neighbour at most
    check(abs(drum.deepest_overlap(grains) - 0.1) < 1e-9 or drum.deepest_overlap(grains) > 0.1,
          "a disk placed 0.9 d from another is not found overlapping")
    profile = [(0.5, 1.0), (1.5, 0.5), (2.5, -0.5), (3.5, -1.0)]
    check(abs(drum.sign_change_depth(profile) - 2.0) < 1e-12, "the layer's depth is not interpolated to 2.0")
    check(drum.sign_change_depth([(0.5, 1.0), (1.5, 0.2)]) is None, "a layer that never turns gets a depth")
    print("drum measures: surface angles within 0.5 degree, overlaps found, sign change interpolated")


if __name__ == "__main__":
    main()
