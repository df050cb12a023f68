#!/usr/bin/env python3
"""The chute's local rheology against plane shear's (results/README.md, *Local rheology*): each run
of the two readings' flow-rule series at its mid-layer point (I_local, phi_local of `cdpost series`,
runs.csv: GDR MiDi's I = gamma_dot d / sqrt(P / rho) from the measured shear rate and the weight of
the grains above) against fits of plane shear's mu(I) and phi(I) of the same grains at its friction
(results/plane_shear/plane_shear_mu*_1e-4.csv, doc/plane_shear_results.md).

In a steady flow uniform along x the shear stress over the pressure is tan theta at every depth, so
a run's local point is (I_local, mu = tan theta). Plane shear's points are fitted per friction with

    mu(I)  = mu_s + (mu_2 - mu_s) / (1 + I0 / I)     (GDR MiDi, Jop et al.; least squares in mu)
    phi(I) = phi_c - b I                              (least squares in phi)

and each run gives theta - arctan mu_ps(I_local) in degrees and phi_local - phi_ps(I_local); the
fits' own rms residual about plane shear's points (in degrees and in phi) is the resolution of
that comparison. A run whose I_local lies beyond plane shear's range of I is read on the fit's
extension and flagged.

Re-runs replace published runs: the count reading's mu 2 runs re-run converged
(results/rerun/count_mu2/, its README) are read instead of the published ones where present, each
row saying which it used ('published' or 'rerun'). Their I_local and phi_local come from
`cdpost series` over the re-run folders (RERUNS/manifest.csv, RERUNS/runs.csv, made by --cdpost);
besides, the same analysis with phi(z) taken from the grain counts (as the count reading's
published runs, whose profile.csv has no phi column, are read) gives phi_local_from_counts.

    studies/local_rheology.py                                   # the tables, to stdout
    studies/local_rheology.py --out results/series/local_rheology
    studies/local_rheology.py --out results/series/local_rheology --cdpost build/postproc/cdpost
                                                                # the re-runs analysed again first

Standard library, gnuplot for the figure, cdpost for --cdpost.
"""

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.run import TOP
from cdtools.stats import least_squares_line, mean_sd_se
from cdtools.text import markdown_table, number, with_error
from packing_against_plane_shear import PLANE_SHEAR, gnuplot_data, read_rows

SERIES = os.path.join(TOP, "results", "series")
READINGS = (("count", os.path.join(SERIES, "flow_rules", "runs.csv")),
            ("layer", os.path.join(SERIES, "layer_flow_rules", "runs.csv")))
# Folders of re-runs that replace a reading's published runs of the same name.
RERUNS = {"count": os.path.join(TOP, "results", "rerun", "count_mu2")}
OUT = os.path.join(SERIES, "local_rheology")
RERUN_TABLE = "reruns"  # OUT/reruns/manifest.csv and runs.csv: cdpost series over the re-run folders


# Plane shear's fits.

def _two_linear(basis, ys):
    """Least-squares (a, b) of y = a f0 + b f1 over the basis rows (f0, f1)."""
    s00 = sum(f0 * f0 for f0, _ in basis)
    s01 = sum(f0 * f1 for f0, f1 in basis)
    s11 = sum(f1 * f1 for _, f1 in basis)
    t0 = sum(f0 * y for (f0, _), y in zip(basis, ys))
    t1 = sum(f1 * y for (_, f1), y in zip(basis, ys))
    det = s00 * s11 - s01 * s01
    return (t0 * s11 - t1 * s01) / det, (s00 * t1 - s01 * t0) / det


def _mu_residual(inertial, mus, i0):
    """(sum of squares, mu_s, mu_2) of the best mu(I) at a given I0."""
    basis = [(1.0, 1.0 / (1.0 + i0 / i)) for i in inertial]
    mu_s, rise = _two_linear(basis, mus)
    squares = sum((mu_s + rise * f1 - m) ** 2 for (_, f1), m in zip(basis, mus))
    return squares, mu_s, mu_s + rise


def fit_mu_of_i(inertial, mus):
    """{mu_s, mu_2, I0, rms}: mu(I) = mu_s + (mu_2 - mu_s)/(1 + I0/I) by least squares in mu; I0 by
    a scan in log I0 over 1e-3..10, refined by golden section; rms over n - 3 degrees of freedom."""
    if len(inertial) < 4:
        raise ValueError(f"a mu(I) fit of 3 parameters needs 4 points or more, got {len(inertial)}")
    logs = [math.log(1e-3) + k * math.log(1e4) / 400 for k in range(401)]
    best = min(range(len(logs)), key=lambda k: _mu_residual(inertial, mus, math.exp(logs[k]))[0])
    low, high = logs[max(best - 1, 0)], logs[min(best + 1, len(logs) - 1)]
    golden = (math.sqrt(5) - 1) / 2
    for _ in range(80):
        a, b = high - golden * (high - low), low + golden * (high - low)
        if _mu_residual(inertial, mus, math.exp(a))[0] < _mu_residual(inertial, mus, math.exp(b))[0]:
            high = b
        else:
            low = a
    i0 = math.exp((low + high) / 2)
    squares, mu_s, mu_2 = _mu_residual(inertial, mus, i0)
    return {"mu_s": mu_s, "mu_2": mu_2, "I0": i0, "rms": math.sqrt(squares / (len(inertial) - 3))}


def mu_at(fit, inertial):
    return fit["mu_s"] + (fit["mu_2"] - fit["mu_s"]) / (1.0 + fit["I0"] / inertial)


def fit_phi_of_i(inertial, phis):
    """{phi_c, b, rms}: phi(I) = phi_c - b I by least squares in phi; rms over n - 2."""
    phi_c, slope = least_squares_line(inertial, phis)
    squares = sum((phi_c + slope * i - p) ** 2 for i, p in zip(inertial, phis))
    return {"phi_c": phi_c, "b": -slope, "rms": math.sqrt(squares / (len(inertial) - 2))}


def phi_at(fit, inertial):
    return fit["phi_c"] - fit["b"] * inertial


def plane_shear_fits(tables):
    """{mu: {'points': [(I, mu, phi)], 'mu': fit, 'phi': fit, 'I_range': (low, high),
    'rms_deg': the mu fit's rms in degrees at its points}} of {mu: plane-shear csv path}."""
    fits = {}
    for mu, path in sorted(tables.items()):
        points = sorted((float(r["I"]), float(r["mu"]), float(r["phi"])) for r in read_rows(path))
        inertial = [p[0] for p in points]
        mu_fit = fit_mu_of_i(inertial, [p[1] for p in points])
        degrees = [math.degrees(math.atan(p[1]) - math.atan(mu_at(mu_fit, p[0]))) for p in points]
        fits[mu] = {"points": points, "mu": mu_fit, "phi": fit_phi_of_i(inertial, [p[2] for p in points]),
                    "I_range": (inertial[0], inertial[-1]),
                    "rms_deg": math.sqrt(sum(d * d for d in degrees) / (len(points) - 3))}
    return fits


# The chute's points.

def chute_rows(path):
    """{run name: (mu, theta, I_local, I_local error, phi_local)} of a series' runs.csv (runs without
    I_local left out)."""
    rows = {}
    for row in read_rows(path):
        if row.get("I_local") and row.get("phi_local"):
            rows[os.path.basename(row["run"])] = (float(row["mu"]), float(row["theta_deg"]), float(row["I_local"]),
                                                  float(row["I_local_error"]) if row.get("I_local_error") else None,
                                                  float(row["phi_local"]))
    return rows


def rerun_rows(folder):
    """{run name: row} of FOLDER/runs.csv (cdpost series over the re-runs, with
    phi_local_from_counts); {} where there is none."""
    path = os.path.join(folder, "runs.csv")
    return {os.path.basename(r["run"]): r for r in read_rows(path)} if os.path.exists(path) else {}


def rerun_folders(folder):
    """The names of the finished re-runs (folders with results.json) of a re-run folder."""
    if not os.path.isdir(folder):
        return []
    return sorted(n for n in os.listdir(folder) if os.path.exists(os.path.join(folder, n, "results.json")))


def points(readings, reruns):
    """[(reading, run, used, mu, theta, I_local, I error, phi_local)]: each reading's series runs,
    a run replaced by its re-run where the reading's re-run table has it ('rerun'), else
    'published'. readings: [(reading, {run: (mu, theta, I, I error, phi)})]; reruns: {reading: {run:
    row of the re-run table}}."""
    rows = []
    for reading, runs in readings:
        replaced = reruns.get(reading, {})
        for name, (mu, theta, inertial, error, phi) in runs.items():
            if name in replaced:
                r = replaced[name]
                rows.append((reading, name, "rerun", mu, theta, float(r["I_local"]),
                             float(r["I_local_error"]) if r.get("I_local_error") else None, float(r["phi_local"])))
            else:
                rows.append((reading, name, "published", mu, theta, inertial, error, phi))
    return rows


def compared(chute, fits):
    """Each chute point with plane shear's at its friction: dicts with the point's fields and
    mu_ps, theta_ps, dtheta (deg), phi_ps, dphi, inside (I within plane shear's range)."""
    rows = []
    for reading, run, used, mu, theta, inertial, error, phi in chute:
        if mu not in fits:
            continue
        fit = fits[mu]
        mu_ps, phi_ps = mu_at(fit["mu"], inertial), phi_at(fit["phi"], inertial)
        theta_ps = math.degrees(math.atan(mu_ps))
        low, high = fit["I_range"]
        rows.append({"reading": reading, "run": run, "used": used, "mu": mu, "theta": theta, "I_local": inertial,
                     "I_local_error": error, "phi_local": phi, "mu_ps": mu_ps, "theta_ps": theta_ps,
                     "dtheta": theta - theta_ps, "phi_ps": phi_ps, "dphi": phi - phi_ps,
                     "inside": low <= inertial <= high})
    return rows


def summary(rows):
    """{(reading, mu): {runs, reruns, outside, dtheta: (low, high, mean, se), dphi: (...)}}, mu 'all'
    over every friction of the reading."""
    groups = {}
    for r in rows:
        for key in ((r["reading"], r["mu"]), (r["reading"], "all")):
            groups.setdefault(key, []).append(r)
    result = {}
    for key, members in groups.items():
        entry = {"runs": len(members), "reruns": sum(m["used"] == "rerun" for m in members),
                 "outside": sum(not m["inside"] for m in members)}
        for quantity in ("dtheta", "dphi"):
            values = [m[quantity] for m in members]
            mean, _, se = mean_sd_se(values)
            entry[quantity] = (min(values), max(values), mean, se)
        result[key] = entry
    return result


def load(reruns_table=None):
    """(plane-shear fits, compared rows) from the committed tables; reruns_table: the folder of the
    re-runs' runs.csv (default OUT/reruns)."""
    folder = reruns_table or os.path.join(OUT, RERUN_TABLE)
    readings = [(reading, chute_rows(path)) for reading, path in READINGS]
    fits = plane_shear_fits(PLANE_SHEAR)
    return fits, compared(points(readings, {"count": rerun_rows(folder)}), fits)


def unanalysed_reruns(reruns_table=None):
    """[(reading, run)] of re-run folders that the re-runs' runs.csv does not hold (analyse them with
    --cdpost)."""
    held = rerun_rows(reruns_table or os.path.join(OUT, RERUN_TABLE))
    return [(reading, name) for reading, folder in RERUNS.items() for name in rerun_folders(folder) if name not in held]


# The re-runs through cdpost series.

def write_manifest(folder, rerun_folder, names):
    """folder/manifest.csv of the re-runs, paths relative to it, mu and theta from params.json."""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "manifest.csv")
    with open(path, "w", newline="") as out:
        out.write("# re-runs read by studies/local_rheology.py: run folders relative to this file\n")
        writer = csv.writer(out)
        writer.writerow(["run", "mu", "theta", "stopped", "h_stop"])
        for name in names:
            with open(os.path.join(rerun_folder, name, "params.json")) as src:
                variables = json.load(src)["vars"]
            writer.writerow([os.path.relpath(os.path.join(rerun_folder, name), folder), variables["mu"],
                             variables["theta"], 0, ""])
    return path


def series_runs(cdpost, manifest, scratch):
    """{run name: row} of runs.csv of `cdpost series MANIFEST --out scratch`."""
    done = subprocess.run([cdpost, "series", manifest, "--out", scratch], capture_output=True, text=True)
    if done.returncode != 0:  # its warnings (fits that two runs cannot make) are not this tool's
        sys.exit(f"local_rheology: cdpost series {manifest} failed: {done.stderr.strip()}")
    with open(os.path.join(scratch, "runs.csv"), newline="") as src:
        return {os.path.basename(r["run"]): r for r in csv.DictReader(src)}


def without_phi_column(rerun_folder, names, scratch):
    """Copies of the re-runs in scratch whose profile.csv lacks its phi column: cdpost then takes
    phi(z) from the grain counts. Returns their manifest."""
    for name in names:
        shutil.copytree(os.path.join(rerun_folder, name), os.path.join(scratch, name))
        profile = os.path.join(scratch, name, "profile.csv")
        rows = read_rows(profile)
        with open(profile, "w", newline="") as out:
            writer = csv.writer(out)
            writer.writerow(["z_d", "u_sqrt_gd", "count"])
            writer.writerows([r["z_d"], r["u_sqrt_gd"], r["count"]] for r in rows)
    return write_manifest(scratch, scratch, names)


def analyse_reruns(cdpost, folder, rerun_folder):
    """folder/manifest.csv and folder/runs.csv: I_local, phi_local (profile's phi column) and
    phi_local_from_counts of every finished re-run."""
    names = rerun_folders(rerun_folder)
    if not names:
        return
    manifest = write_manifest(folder, rerun_folder, names)
    with tempfile.TemporaryDirectory() as scratch:
        measured = series_runs(cdpost, manifest, os.path.join(scratch, "measured"))
        counts = series_runs(cdpost, without_phi_column(rerun_folder, names, os.path.join(scratch, "copies")),
                             os.path.join(scratch, "counts"))
    columns = ["run", "mu", "theta_deg", "I_local", "I_local_error", "phi_local", "phi_local_from_counts"]
    with open(os.path.join(folder, "runs.csv"), "w", newline="") as out:
        out.write(f"# cdpost series {os.path.relpath(manifest, TOP)}: I_local and phi_local at mid-layer; "
                  "phi_local_from_counts the same with phi(z) from the grain counts (no phi column)\n")
        writer = csv.writer(out)
        writer.writerow(columns)
        for name in names:
            row = measured[name]
            writer.writerow([name, row["mu"], row["theta_deg"], row["I_local"], row["I_local_error"],
                             row["phi_local"], counts[name]["phi_local"]])


# Tables, figure, page.

def fits_table(fits):
    return markdown_table(
        ["mu", "points", "I range", "mu_s", "mu_2", "I0", "rms of mu (deg)", "phi_c", "b", "rms of phi"],
        [[number(mu), str(len(f["points"])), f"{number(f['I_range'][0])}–{number(f['I_range'][1])}",
          f"{f['mu']['mu_s']:.4f}", f"{f['mu']['mu_2']:.4f}", f"{f['mu']['I0']:.4f}", f"{f['rms_deg']:.2f}",
          f"{f['phi']['phi_c']:.4f}", f"{f['phi']['b']:.4f}", f"{f['phi']['rms']:.4f}"]
         for mu, f in sorted(fits.items())])


def summary_table(groups):
    rows = []
    for (reading, mu), s in sorted(groups.items(), key=lambda item: (item[0][0], str(item[0][1]))):
        t, p = s["dtheta"], s["dphi"]
        rows.append([reading, mu if mu == "all" else number(mu), str(s["runs"]), str(s["reruns"]), str(s["outside"]),
                     f"{t[0]:+.2f} to {t[1]:+.2f}", with_error(t[2], t[3]),
                     f"{p[0]:+.4f} to {p[1]:+.4f}", with_error(p[2], p[3])])
    return markdown_table(["reading", "mu", "runs", "re-runs", "beyond plane shear's I", "θ − arctan μ_ps(I) (deg)",
                           "mean ± s.e.", "φ − φ_ps(I)", "mean ± s.e."], rows)


def runs_table(rows):
    return markdown_table(
        ["reading", "run", "used", "mu", "θ (deg)", "I_local", "arctan μ_ps(I) (deg)", "θ − arctan μ_ps",
         "φ_local", "φ_ps(I)", "φ − φ_ps", "inside plane shear's I"],
        [[r["reading"], r["run"], r["used"], number(r["mu"]), number(r["theta"]), f"{r['I_local']:.4f}",
          f"{r['theta_ps']:.2f}", f"{r['dtheta']:+.2f}", f"{r['phi_local']:.4f}", f"{r['phi_ps']:.4f}",
          f"{r['dphi']:+.4f}", "yes" if r["inside"] else "no"] for r in rows])


def write_csv(path, rows):
    columns = ["reading", "run", "used", "mu", "theta", "I_local", "I_local_error", "phi_local", "mu_ps", "theta_ps",
               "dtheta", "phi_ps", "dphi", "inside"]
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(columns)
        for r in rows:
            writer.writerow(["" if r[c] is None else (int(r[c]) if c == "inside" else r[c]) for c in columns])


def figure(fits, rows, stem):
    """stem.png: mu = tan theta and phi against I_local, both readings (a colour per friction; count
    circles, re-runs filled, layer triangles), plane shear's points (squares) and fits (lines)."""
    frictions = sorted(fits)
    panels = []
    for quantity, label, ps_column, ps_curve in (
            ("mu", "mu = tan theta (chute), -P_xy/P_yy (plane shear)", 1,
             lambda f: "{mu_s!r} + ({mu_2!r} - {mu_s!r}) / (1 + {I0!r} / x)".format(**f["mu"])),
            ("phi", "phi", 2, lambda f: f"{f['phi']['phi_c']!r} - {f['phi']['b']!r} * x")):
        plots, data = [], []
        for c, mu in enumerate(frictions):
            for reading, used, pt in (("count", "published", 6), ("count", "rerun", 7), ("layer", "published", 8),
                                      ("layer", "rerun", 9)):
                chosen = [r for r in rows if r["mu"] == mu and r["reading"] == reading and r["used"] == used]
                if not chosen:
                    continue
                y = (lambda r: math.tan(math.radians(r["theta"]))) if quantity == "mu" else (lambda r: r["phi_local"])
                title = f"{reading}{' re-run' if used == 'rerun' else ''}, mu {number(mu)}"
                plots.append(f"'-' using 1:2 with points pt {pt} ps 1.3 lc {c + 1} title '{title}'")
                data.append(gnuplot_data([(r["I_local"], y(r)) for r in chosen]))
            plots.append(f"'-' using 1:2 with points pt 5 lc {c + 1} title 'plane shear, mu {number(mu)}'")
            data.append(gnuplot_data([(p[0], p[ps_column]) for p in fits[mu]["points"]]))
            plots.append(f"({ps_curve(fits[mu])}) with lines lc {c + 1} notitle")
        panels.append(f"set ylabel '{label}'\nplot " + ", ".join(plots) + "\n" + "".join(data))
    script = (f"set terminal pngcairo size 1300,560 noenhanced\nset output '{stem}.png'\n"
              "set multiplot layout 1,2\nset grid\nset xlabel 'I (chute: at mid-layer; plane shear: of the cell)'\n"
              "set xrange [0:0.65]\nset samples 400\nset key bottom right font ',9'\n"
              + panels[0] + "set key top right font ',9'\nset yrange [0.68:0.84]\n" + panels[1] + "unset multiplot\n")
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def report(fits, rows):
    return ("Plane shear's fits (mu(I) = mu_s + (mu_2 − mu_s)/(1 + I0/I), phi(I) = phi_c − b I; rms about "
            "plane shear's own points):\n\n" + fits_table(fits) + "\nPer reading and friction:\n\n"
            + summary_table(summary(rows)) + "\nEvery run:\n\n" + runs_table(rows))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", metavar="DIR", help="write DIR/local_rheology.md, .csv and .png")
    parser.add_argument("--cdpost", metavar="PATH",
                        help="analyse the re-runs first (OUT/reruns/manifest.csv and runs.csv)")
    args = parser.parse_args(argv)
    table = os.path.join(args.out or OUT, RERUN_TABLE)
    if args.cdpost:
        for reading, folder in RERUNS.items():
            analyse_reruns(args.cdpost, table, folder)
    for reading, name in unanalysed_reruns(table):
        print(f"local_rheology: the re-run {name} ({reading} reading) is not in {table}/runs.csv: its published run "
              "is read; analyse it with --cdpost", file=sys.stderr)
    fits, rows = load(table)
    text = report(fits, rows)
    print(text)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        write_csv(os.path.join(args.out, "local_rheology.csv"), rows)
        figure(fits, rows, os.path.join(args.out, "local_rheology"))
        command = "studies/local_rheology.py --out results/series/local_rheology [--cdpost build/postproc/cdpost]"
        with open(os.path.join(args.out, "local_rheology.md"), "w") as out:
            out.write("# The chute's local rheology against plane shear\n\nMade by `" + command + "` (its docstring "
                      "says how). Figure: [local_rheology.png](local_rheology.png); every run: "
                      "[local_rheology.csv](local_rheology.csv).\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
