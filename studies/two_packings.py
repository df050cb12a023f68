#!/usr/bin/env python3
"""Two readings, two packings (results/series/packing/two_packings.md): why the count reading's
phi lies above plane shear's phi(I) by more than the layer reading's, measured three ways on the
same runs.

- phi_local, the tables' measure (`cdpost series`, mid-layer z = h/2 +- h/10): from the profile's
  phi column where the run has one (the layer reading, today's count runs), else from its grain
  counts times the mean grain area of the size law (the count reading's published runs).
- phi_bulk, the area fraction the deck measures itself (packing.chunk: the grains' areas, binned
  at their centres) over 0.2 h <= z <= 0.8 h: the same measure in every run of both readings.
- the size mix at mid-layer, from a run's snapshots (--dumps, the last 70 %): the mean area of the grains whose
  centres lie in h/2 +- h/10 over the cell's own, and the cell's over the size law's. Counts times
  the law's mean area read phi times (law's mean / mid-layer's mean): the counts move with it.

Each is set against plane shear's phi(I) fit at the run's I_local (studies/local_rheology.py's
fits, same friction). The runs: both readings' published flow-rule series
(results/series/*/runs.csv) and the count reading's runs at today's solver settings
(results/rerun/count_mu2/, the count runs of results/rerun/health_evidence/), whose I_local,
phi_local and phi_local_from_counts come from `cdpost series` over them (--cdpost writes
OUT/today/runs.csv).

    studies/two_packings.py                                           # the tables, to stdout
    studies/two_packings.py --out results/series/packing [--cdpost build/postproc/cdpost] \\
        [--dumps RUNS/runs]                    # the size mix of the runs of RUNS with dump.chute.gz

Standard library (cdpost for --cdpost).
"""

import argparse
import csv
import gzip
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

import local_rheology
from cdtools.run import TOP
from cdtools.stats import mean_sd_se
from cdtools.text import markdown_table
from packing_against_plane_shear import read_rows

OUT = os.path.join(TOP, "results", "series", "packing")
TODAY_TABLE = "today"  # OUT/today/manifest.csv, runs.csv: cdpost series over today's count runs
SIZE_MIX = "size_mix.csv"
# Plane shear at mu 0.5 at the deck's tolerance and at 1e-4 (doc/plane_shear_results.md).
PLANE_SHEAR_LOOSE = (0.5, os.path.join(TOP, "results", "plane_shear", "plane_shear_mu0.5.csv"))
# Count-reading runs at today's solver settings (cap 1e4, the stall rescue), each a folder of runs.
TODAY_FOLDERS = (os.path.join(TOP, "results", "rerun", "count_mu2"),
                 os.path.join(TOP, "results", "rerun", "health_evidence"))
MID_LAYER, BAND = 0.5, 0.1  # z = h/2 +- h/10, as cdpost series' I_local and phi_local
# Snapshots that count for the size mix: the last 70 % of a run's (its flow is steady by 2 s of 10;
# the dump is written every fixed number of steps, so with adapt_dt a frame's time is not known).
STEADY_FRACTION = 0.7


def _results(folder):
    """{name: value} of a run folder's results.csv."""
    return {r["name"]: float(r["value"]) for r in read_rows(os.path.join(folder, "results.csv")) if r["value"]}


def today_runs():
    """{name: folder} of the count reading's runs at today's settings (health runs of the count
    reading only: the layer reading's phi_local was measured already)."""
    runs = {}
    for folder in TODAY_FOLDERS:
        for name in local_rheology.rerun_folders(folder):
            with open(os.path.join(folder, name, "params.json")) as src:
                if json.load(src)["vars"].get("reading", "count") == "count":
                    runs[name] = os.path.join(folder, name)
    return runs


def analyse_today(cdpost, table):
    """table/manifest.csv and runs.csv of today's count runs (local_rheology's analysis)."""
    runs = today_runs()
    os.makedirs(table, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        for name, folder in runs.items():  # one folder of links: the manifest reads one place
            os.symlink(folder, os.path.join(scratch, name))
        local_rheology.analyse_reruns(cdpost, table, scratch)
    manifest = os.path.join(table, "manifest.csv")  # paths relative to the table, not the scratch
    with open(manifest, newline="") as src:
        lines = src.read().splitlines()
    with open(manifest, "w") as out:
        out.write("# today's count runs read by studies/two_packings.py: run folders relative to this file\n"
                  + lines[1] + "\n")
        for line in lines[2:]:
            name = os.path.basename(line.split(",")[0])
            out.write(",".join([os.path.relpath(runs[name], table)] + line.split(",")[1:]) + "\n")


def rows(table, fits):
    """One dict per run: reading, solver ('published' or 'today'), run, mu, theta, I_local,
    phi_local and its measure ('counts' or 'area'), phi_bulk, and the offsets from plane shear's
    phi(I) at I_local (dphi_local, dphi_bulk); today's runs add phi_local_from_counts."""
    result = []

    def add(reading, solver, run, mu, theta, inertial, phi_local, measure, phi_bulk, counts=None):
        if mu not in fits:
            return
        phi_ps = local_rheology.phi_at(fits[mu]["phi"], inertial)
        result.append({"reading": reading, "solver": solver, "run": run, "mu": mu, "theta": theta,
                       "I_local": inertial, "phi_local": phi_local, "measure": measure, "phi_bulk": phi_bulk,
                       "phi_ps": phi_ps, "dphi_local": phi_local - phi_ps, "dphi_bulk": phi_bulk - phi_ps,
                       "phi_local_from_counts": counts})

    for reading, path in local_rheology.READINGS:
        for r, profile in first_published(reading, path):
            if not (r.get("I_local") and r.get("phi_local") and r.get("phi_bulk")):
                continue
            run = os.path.basename(r["run"])
            with open(profile) as src:
                measure = "area" if "phi" in src.readline().strip().split(",") else "counts"
            add(reading, "published", run, float(r["mu"]), float(r["theta_deg"]), float(r["I_local"]),
                float(r["phi_local"]), measure, float(r["phi_bulk"]))
    folders = today_runs()
    for name, r in local_rheology.rerun_rows(table).items():
        if name in folders:
            add("count", "today", name, float(r["mu"]), float(r["theta_deg"]), float(r["I_local"]),
                float(r["phi_local"]), "area", _results(folders[name])["phi_bulk"],
                float(r["phi_local_from_counts"]))
    return result


def first_published(reading, path):
    """[(row of the series' runs.csv, its profile.csv)] of a reading's published runs as first
    published: a run a re-run has replaced since is read from the copy the re-run set kept
    (studies/rerun_tables.py --supersede), so that 'published' stays the runs the study explains."""
    kept = local_rheology.RERUNS.get(reading)
    result = []
    for r in read_rows(path):
        superseded = os.path.join(kept, os.path.basename(r["run"]), "superseded") if kept else None
        if superseded and os.path.isdir(superseded):
            result.append((read_rows(os.path.join(superseded, "series_row.csv"))[0],
                           os.path.join(superseded, "profile.csv")))
        else:
            result.append((r, os.path.join(os.path.dirname(path), r["run"], "profile.csv")))
    return result


def groups(table_rows):
    """{(reading, solver, mu): {runs, dphi_local: (mean, se), dphi_bulk: (mean, se), measure}}."""
    grouped = {}
    for r in table_rows:
        grouped.setdefault((r["reading"], r["solver"], r["mu"]), []).append(r)
    summary = {}
    for key, members in sorted(grouped.items()):
        entry = {"runs": len(members), "measure": "/".join(sorted({m["measure"] for m in members}))}
        for quantity in ("dphi_local", "dphi_bulk"):
            mean, _, se = mean_sd_se(m[quantity] for m in members)
            entry[quantity] = (mean, se)
        local_minus_bulk = mean_sd_se(m["phi_local"] - m["phi_bulk"] for m in members)
        entry["local_minus_bulk"] = (local_minus_bulk[0], local_minus_bulk[2])
        summary[key] = entry
    return summary


def counts_against_area(table_rows):
    """(mean, sd, se, n) of phi_local from counts minus from area over the runs that have both."""
    differences = [r["phi_local_from_counts"] - r["phi_local"] for r in table_rows
                   if r["phi_local_from_counts"] is not None]
    mean, sd, se = mean_sd_se(differences)
    return mean, sd, se, len(differences)


def paired(table_rows, against):
    """[(run, mu, theta, today's dphi_bulk minus the published run's)] for each of today's count runs
    with a published run of the same friction and angle, against 'count' (the run it re-runs) or
    'layer' (the layer reading's)."""
    published = {(r["reading"], r["mu"], r["theta"]): r for r in table_rows
                 if r["solver"] == "published" and "_seed" not in r["run"]}
    pairs = []
    for r in table_rows:
        other = published.get((against, r["mu"], r["theta"])) if r["solver"] == "today" else None
        if other:
            pairs.append((r["run"], r["mu"], r["theta"], r["dphi_bulk"] - other["dphi_bulk"]))
    return pairs


def paired_mean(table_rows, against):
    """(mean, se, n) of paired()'s differences."""
    differences = [p[3] for p in paired(table_rows, against)]
    mean, _, se = mean_sd_se(differences)
    return mean, se, len(differences)


def tolerance_shift(loose_table, tight_table, tight_fit):
    """[(phi, I loose, I tight, shift)] at each packing both plane-shear tables hold (plane shear is
    run at fixed phi): the looser tolerance's phi at its I minus the tighter one's phi at that I,
    read along the tighter table's phi(I) line through its own point, b (I_loose - I_tight)."""
    tight = {round(float(r["phi"]), 4): float(r["I"]) for r in read_rows(tight_table)}
    shifts = []
    for r in read_rows(loose_table):
        phi, inertial = round(float(r["phi"]), 4), float(r["I"])
        if phi in tight:
            shifts.append((phi, inertial, tight[phi], tight_fit["b"] * (inertial - tight[phi])))
    return shifts


def plane_shear_tolerance_shifts():
    """tolerance_shift of the committed plane-shear tables (PLANE_SHEAR_LOOSE against 1e-4)."""
    mu, loose = PLANE_SHEAR_LOOSE
    tight = local_rheology.PLANE_SHEAR[mu]
    return tolerance_shift(loose, tight, local_rheology.plane_shear_fits({mu: tight})[mu]["phi"])


# The size mix, from snapshots.

def snapshots(path):
    """(timestep, cell length, [(y, radius)]) of each snapshot of a dump.chute.gz."""
    with gzip.open(path, "rt") as src:
        while True:
            line = src.readline()
            if not line:
                return
            if not line.startswith("ITEM: TIMESTEP"):
                continue
            step = int(src.readline())
            src.readline()
            count = int(src.readline())
            src.readline()
            low, high = (float(v) for v in src.readline().split()[:2])
            src.readline(), src.readline()
            columns = src.readline().split()[2:]
            y, radius = columns.index("y"), columns.index("radius")
            grains = []
            for _ in range(count):
                fields = src.readline().split()
                if len(fields) != len(columns):
                    raise ValueError(f"{path}: snapshot at step {step} is truncated")
                grains.append((float(fields[y]), float(fields[radius])))
            yield step, high - low, grains


def size_mix(run_folder):
    """{run, frames, mid_over_cell, cell_over_law} of a campaign run folder with dump.chute.gz and
    post/results.csv: the mean grain area at mid-layer over the cell's, the cell's over the size
    law's (pi/4 d^2 (1 + dispersity^2/12))."""
    with open(os.path.join(run_folder, "params.json")) as src:
        variables = json.load(src)["vars"]
    d, dispersity = float(variables["d"]), float(variables["dispersity"])
    floor = float(variables["wall_height"]) * d  # z = 0 at the walls' tops, y = 0 at the floor
    results = _results(os.path.join(run_folder, "post"))
    h = results["h"]
    law = math.pi / 4 * d * d * (1 + dispersity ** 2 / 12)
    low, high = floor + (MID_LAYER - BAND) * h * d, floor + (MID_LAYER + BAND) * h * d
    ratios, cell = [], None
    for _, _, grains in snapshots(os.path.join(run_folder, "dump.chute.gz")):
        if cell is None:
            cell = sum(math.pi * r * r for _, r in grains) / len(grains)
        band = [math.pi * r * r for y, r in grains if low <= y < high]
        ratios.append(sum(band) / len(band) / cell)
    ratios = ratios[int(len(ratios) * (1 - STEADY_FRACTION)):]
    if not ratios:
        raise ValueError(f"{run_folder}: no snapshot")
    return {"run": os.path.basename(run_folder), "frames": len(ratios),
            "mid_over_cell": sum(ratios) / len(ratios), "cell_over_law": cell / law}


def read_size_mix(path):
    """{run: row} of a size-mix table; {} where there is none."""
    return {r["run"]: r for r in read_rows(path)} if os.path.exists(path) else {}


def write_size_mix(path, run_folders):
    """The size mix of every run folder with a dump, written to path (rows of runs not given kept)."""
    held = read_size_mix(path)
    for folder in run_folders:
        if os.path.exists(os.path.join(folder, "dump.chute.gz")) and os.path.exists(os.path.join(folder, "post")):
            held[os.path.basename(folder)] = size_mix(folder)
    with open(path, "w", newline="") as out:
        out.write("# studies/two_packings.py --dumps: mean grain area at mid-layer (h/2 +- h/10, the last "
                  f"{STEADY_FRACTION:.0%} of the snapshots) over the cell's; the cell's over the size law's\n")
        writer = csv.DictWriter(out, ["run", "frames", "mid_over_cell", "cell_over_law"])
        writer.writeheader()
        for name in sorted(held):
            writer.writerow({k: held[name][k] for k in writer.fieldnames})


# Tables and page.

def _signed(value, digits=4):
    return f"{value:+.{digits}f}".replace("-", "−")


def _mean_se(pair):
    mean, se = pair
    return _signed(mean) if math.isnan(se) else f"{_signed(mean)} ± {se:.4f}"


def report(table_rows, mix):
    summary = groups(table_rows)
    lines = ["Against plane shear's phi(I) at each run's I_local (mean ± standard error over the runs):", ""]
    lines += markdown_table(
        ["reading", "solver", "mu", "runs", "phi_local measure", "phi_local − plane shear", "phi_bulk − plane shear",
         "phi_local − phi_bulk"],
        [[reading, solver, f"{mu:g}", str(e["runs"]), e["measure"], _mean_se(e["dphi_local"]),
          _mean_se(e["dphi_bulk"]), _mean_se(e["local_minus_bulk"])]
         for (reading, solver, mu), e in summary.items()]).splitlines()
    mean, sd, se, n = counts_against_area(table_rows)
    lines += ["", f"phi_local from the grain counts minus from the area, on the {n} runs that have both (today's count "
              f"runs): {_signed(mean)} ± {se:.4f} (sd {sd:.4f}).", ""]
    lines += ["phi_bulk − plane shear of today's count runs minus the published run's of the same friction and "
              "angle:", ""]
    lines += markdown_table(
        ["run", "mu", "theta", "minus the count reading's published run", "minus the layer reading's"],
        [[run, f"{mu:g}", f"{theta:g}", _signed(count), _signed(layer)] for (run, mu, theta, count), (_, _, _, layer)
         in zip(paired(table_rows, "count"), paired(table_rows, "layer"))]).splitlines()
    lines += [""] + [f"Mean against the {against} reading's: {_mean_se(paired_mean(table_rows, against)[:2])} over "
                     f"{paired_mean(table_rows, against)[2]} runs." for against in ("count", "layer")
                     if paired_mean(table_rows, against)[2]] + [""]
    mu = PLANE_SHEAR_LOOSE[0]
    shifts = plane_shear_tolerance_shifts()
    lines += [f"Plane shear at mu {mu:g}, tolerance 1e-3 against 1e-4 at the same phi: phi(I) at 1e-3 minus at 1e-4, "
              "b (I at 1e-3 − I at 1e-4) with the 1e-4 line's b:", ""]
    lines += markdown_table(["phi", "I at 1e-3", "I at 1e-4", "shift of phi at fixed I"],
                            [[f"{phi:.2f}", f"{a:.4f}", f"{b:.4f}", _signed(shift)] for phi, a, b, shift in shifts]
                            ).splitlines()
    mean, _, se = mean_sd_se(shift for *_, shift in shifts)
    lines += ["", f"Mean shift {_mean_se((mean, se))} over {len(shifts)} packings.", ""]
    if mix:
        lines += ["The size mix (snapshots of today's count runs):", ""]
        lines += markdown_table(
            ["run", "snapshots", "mid-layer mean area / cell's", "cell's mean area / size law's",
             "counts' phi / area's, predicted", "measured (cdpost series)"],
            [[name, r["frames"], f"{float(r['mid_over_cell']):.4f}", f"{float(r['cell_over_law']):.4f}",
              f"{predicted_ratio(r):.4f}",
              _measured_ratio(table_rows, name)] for name, r in sorted(mix.items())]).splitlines()
    return "\n".join(lines) + "\n"


def predicted_ratio(mix_row):
    """The counts' phi over the area's that a size-mix row predicts: the law's mean area over the
    mid-layer's."""
    return 1 / (float(mix_row["mid_over_cell"]) * float(mix_row["cell_over_law"]))


def measured_ratio(table_rows, name):
    """phi_local from the counts over from the area of today's run `name` (cdpost series); None if
    not analysed."""
    for r in table_rows:
        if r["run"] == name and r["phi_local_from_counts"] is not None:
            return r["phi_local_from_counts"] / r["phi_local"]
    return None


def _measured_ratio(table_rows, name):
    ratio = measured_ratio(table_rows, name)
    return "not analysed" if ratio is None else f"{ratio:.4f}"


def write_csv(path, table_rows):
    columns = ["reading", "solver", "run", "mu", "theta", "I_local", "phi_local", "measure", "phi_bulk", "phi_ps",
               "dphi_local", "dphi_bulk", "phi_local_from_counts"]
    with open(path, "w", newline="") as out:
        writer = csv.DictWriter(out, columns)
        writer.writeheader()
        for r in table_rows:
            writer.writerow({k: "" if r[k] is None else r[k] for k in columns})


def load(out=OUT):
    """(rows, size mix) from the committed tables of out."""
    fits = local_rheology.plane_shear_fits(local_rheology.PLANE_SHEAR)
    return rows(os.path.join(out, TODAY_TABLE), fits), read_size_mix(os.path.join(out, SIZE_MIX))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", metavar="DIR", help="write DIR/two_packings.md and .csv")
    parser.add_argument("--cdpost", metavar="PATH", help="analyse today's count runs first (OUT/today/runs.csv)")
    parser.add_argument("--dumps", metavar="RUNS", action="append", default=[],
                        help="a campaign's runs folder: the size mix of its finished count runs (OUT/size_mix.csv)")
    args = parser.parse_args(argv)
    out = args.out or OUT
    if args.cdpost:
        analyse_today(args.cdpost, os.path.join(out, TODAY_TABLE))
    if args.dumps:
        wanted = set(today_runs())
        folders = [os.path.join(runs, name) for runs in args.dumps for name in sorted(os.listdir(runs))
                   if name in wanted]
        write_size_mix(os.path.join(out, SIZE_MIX), folders)
    table_rows, mix = load(out)
    text = report(table_rows, mix)
    print(text)
    if args.out:
        write_csv(os.path.join(args.out, "two_packings.csv"), table_rows)
        command = ("studies/two_packings.py --out results/series/packing [--cdpost build/postproc/cdpost] "
                   "[--dumps RUNS/runs]")
        with open(os.path.join(args.out, "two_packings.md"), "w") as page:
            page.write("# Two readings, two packings\n\nMade by `" + command + "` (its docstring says how); every "
                       "run: [two_packings.csv](two_packings.csv).\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
