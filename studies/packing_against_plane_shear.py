#!/usr/bin/env python3
"""The chute's packing against plane shear and published 2D packings (doc/source.md, "The packing
law's offset"): each run's phi at mid-layer against its own inertial number there (phi_local and
I_local of `cdpost series`, runs.csv: GDR MiDi's I = gamma_dot d / sqrt(P / rho) with the measured
shear rate and the weight of the grains above), over the plane-shear phi(I) of rigid disks
(results/plane_shear/, doc/plane_shear.md) and the published values of
results/plane_shear/packing_literature.csv.

Plane shear measures phi and I of a homogeneous sheared bulk, so the chute's counterpart is the
local phi and I at one height, not the layer's mean phi against the stated I. Where plane shear
has the chute's friction, each run's phi is compared with the plane-shear phi at the run's I
(linear in I between the two plane-shear points around it).

    studies/packing_against_plane_shear.py                      # the table, to stdout
    studies/packing_against_plane_shear.py --out DIR            # and DIR/phi_vs_I.png, DIR/packing.md

Standard library and gnuplot.
"""

import argparse
import csv
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools import plane_shear
from cdtools.run import TOP
from cdtools.stats import mean_sd_se
from cdtools.text import markdown_table, number, with_error

SERIES = os.path.join(TOP, "results", "series")
READINGS = (("count", os.path.join(SERIES, "flow_rules", "runs.csv")),
            ("layer", os.path.join(SERIES, "layer_flow_rules", "runs.csv")))
# The plane-shear phi(I) at each of the chute's frictions, solved to 1e-4 (doc/plane_shear_results.md).
PLANE_SHEAR = {mu: plane_shear.table_path(mu) for mu in (0.05, 0.5, 2.0)}
LITERATURE = os.path.join(TOP, "results", "plane_shear", "packing_literature.csv")
SOURCE = os.path.join(TOP, "results", "source.csv")


def read_rows(path):
    """The rows of a CSV whose '#' lines are its provenance."""
    with open(path, newline="") as src:
        return list(csv.DictReader(line for line in src if not line.startswith("#")))


def chute_points(path):
    """[(run, mu, theta, phi_local, I_local, I_local error)] of a series' runs.csv (runs without
    I_local are left out)."""
    points = []
    for row in read_rows(path):
        if row.get("I_local"):
            points.append((os.path.basename(row["run"]), float(row["mu"]), float(row["theta_deg"]),
                           float(row["phi_local"]), float(row["I_local"]),
                           float(row["I_local_error"]) if row.get("I_local_error") else None))
    return points


def plane_shear_points(path):
    """[(I, I standard error, phi)] ascending in I."""
    return sorted((float(r["I"]), float(r["I_se"]), float(r["phi"])) for r in read_rows(path))


def phi_at(inertial, points):
    """The plane-shear phi at I, linear in I between the two points around it; None outside them."""
    for (i0, _, phi0), (i1, _, phi1) in zip(points, points[1:]):
        if i0 <= inertial <= i1:
            return phi0 + (phi1 - phi0) * (inertial - i0) / (i1 - i0)
    return None


def offsets(readings, plane_shear):
    """[(reading, run, mu, theta, I, phi, phi - plane-shear phi at I)] of the runs whose friction
    plane shear has and whose I lies inside its range."""
    rows = []
    for reading, points in readings:
        for run, mu, theta, phi, inertial, _ in points:
            reference = phi_at(inertial, plane_shear[mu]) if mu in plane_shear else None
            if reference is not None:
                rows.append((reading, run, mu, theta, inertial, phi, phi - reference))
    return rows


def summary(rows):
    """Per reading and friction: (reading, mu, runs, smallest, largest, mean and standard error of
    the offsets)."""
    groups = {}
    for reading, _, mu, _, _, _, offset in rows:
        groups.setdefault((reading, mu), []).append(offset)
    result = []
    for (reading, mu), values in sorted(groups.items()):
        mean, _, se = mean_sd_se(values)
        result.append((reading, mu, len(values), min(values), max(values), mean, se))
    return result


def markdown(rows):
    per_run = markdown_table(["reading", "run", "mu", "theta (deg)", "I_local", "phi_local",
                              "phi - plane shear's phi(I)"],
                             [[r[0], r[1], number(r[2]), number(r[3]), number(r[4]), number(r[5], 4),
                               f"{r[6]:+.4f}"] for r in rows])
    per_friction = markdown_table(["reading", "mu", "runs", "offset: smallest to largest", "mean ± standard error"],
                                  [[s[0], number(s[1]), str(s[2]), f"{s[3]:+.4f} to {s[4]:+.4f}",
                                    with_error(s[5], s[6])] for s in summary(rows)])
    return per_run + "\n" + per_friction


def gnuplot_data(points):
    return "\n".join(" ".join("nan" if v is None else repr(v) for v in p) for p in points) + "\ne\n"


def source_phi_c(path):
    """{mu: phi_c} of the source's phi(U) law (results/source.csv): its phi at U = 0, that is I = 0."""
    return {float(r["name"][len("phi_c_mu"):]): float(r["source_low"]) for r in read_rows(path)
            if r["name"].startswith("phi_c_mu")}


def figure(readings, plane_shear, literature, source, stem):
    """stem.png: phi_local against I_local of both readings (a colour per friction), the plane-shear
    phi(I), the source's phi_c at I = 0 and the published packings as short lines at small I."""
    frictions = sorted({p[1] for _, points in readings for p in points} | set(source))
    plots, data = [], []
    for r, (reading, points) in enumerate(readings):
        for c, mu in enumerate(frictions):
            plots.append(f"'-' using 1:2 with points pt {6 + r} lc {c + 1} title '{reading}: mu = {number(mu)}'")
            data.append(gnuplot_data([(p[4], p[3]) for p in points if p[1] == mu]))
    for mu, points in sorted(plane_shear.items()):
        colour = frictions.index(mu) + 1 if mu in frictions else "'black'"
        plots.append(f"'-' using 1:3:2 with xerrorbars pt 5 lc {colour} title 'plane shear, mu = {number(mu)}'")
        data.append(gnuplot_data(points))
        plots.append(f"'-' using 1:3 with lines lc {colour} notitle")
        data.append(gnuplot_data(points))
    for c, mu in enumerate(frictions):
        if mu in source:
            plots.append(f"'-' using 1:2 with points pt 3 ps 2 lc {c + 1} title 'source: phi_c, mu = {number(mu)}'")
            data.append(gnuplot_data([(0.0, source[mu])]))
    for row in literature:
        plots.append(f"'-' using 1:2 with lines dt 2 lw 2 lc 'gray30' title '{row['label'][:60]}...: "
                     f"{row['phi']}'")
        data.append(gnuplot_data([(0.0, float(row["phi"])), (0.05, float(row["phi"]))]))
    script = (f"set terminal pngcairo size 900,650 noenhanced\nset output '{stem}.png'\n"
              "set xlabel 'I at mid-layer (chute) or of the cell (plane shear)'\nset ylabel 'phi'\n"
              "set key top right\nset grid\nset xrange [-0.005:0.4]\nset yrange [0.68:0.87]\n"
              "plot " + ", ".join(plots) + "\n" + "".join(data))
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", metavar="DIR", help="write DIR/phi_vs_I.png and DIR/packing.md")
    args = parser.parse_args(argv)
    readings = [(reading, chute_points(path)) for reading, path in READINGS]
    plane_shear = {mu: plane_shear_points(path) for mu, path in PLANE_SHEAR.items()}
    text = markdown(offsets(readings, plane_shear))
    print(text)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        figure(readings, plane_shear, read_rows(LITERATURE), source_phi_c(SOURCE), os.path.join(args.out, "phi_vs_I"))
        with open(os.path.join(args.out, "packing.md"), "w") as out:
            out.write("# The chute's phi against plane shear\n\nMade by `studies/packing_against_plane_shear.py "
                      "--out results/series/packing` (its docstring says how). Figure: "
                      "[phi_vs_I.png](phi_vs_I.png).\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
