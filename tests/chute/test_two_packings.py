#!/usr/bin/env python3
"""Checks of studies/two_packings.py on synthetic data, run by ctest (no simulation), and of its
committed tables against the run folders they read.

    tests/chute/test_two_packings.py

The size mix of a synthetic dump whose mid-layer grains are larger than the rest: the mid-layer's
mean area over the cell's and the cell's over the size law's, by hand, the early snapshots (which
differ) left out; the tolerance shift of two plane-shear tables by hand; a truncated snapshot
refused in one error naming the file; the pairing of today's runs with the published runs of
the same friction and angle (and not a replica's); a series run a re-run set kept read from the
kept copy; the committed today/runs.csv holds every
count run of the folders it reads, so a run committed without
`studies/two_packings.py --cdpost ...` fails here. Standard library only.
"""

import gzip
import json
import math
import os
import tempfile

from study_test import check, load_study


def write_run(folder, frames, truncate=False):
    """A run folder: params.json, post/results.csv (h 40 d) and dump.chute.gz of frames, each a list
    of (y, radius)."""
    os.makedirs(os.path.join(folder, "post"))
    with open(os.path.join(folder, "params.json"), "w") as out:
        json.dump({"vars": {"d": "1", "dispersity": "0.4", "wall_height": "30", "reading": "count"}}, out)
    with open(os.path.join(folder, "post", "results.csv"), "w") as out:
        out.write("name,value,error,unit,description\nh,40,,d,thickness\n")
    with gzip.open(os.path.join(folder, "dump.chute.gz"), "wt") as out:
        for step, grains in enumerate(frames):
            out.write(f"ITEM: TIMESTEP\n{step * 1000}\nITEM: NUMBER OF ATOMS\n{len(grains)}\n"
                      "ITEM: BOX BOUNDS pp fm pp\n0 10\n0 100\n-1 1\nITEM: ATOMS id type x y vx vy radius ix\n")
            shown = grains[:-1] if truncate and step == len(frames) - 1 else grains
            for k, (y, radius) in enumerate(shown):
                out.write(f"{k + 1} 1 0.5 {y} 0 0 {radius} 0\n")


def size_mix_by_hand(tool):
    # Floor at 30 (wall_height x d), h = 40: mid-layer 30 + 16 <= y < 30 + 24.
    steady = [(50.0, 0.6), (51.0, 0.6), (60.0, 0.4), (35.0, 0.4)]   # mid-layer grains larger
    early = [(50.0, 0.4), (51.0, 0.4), (60.0, 0.6), (35.0, 0.6)]    # the first 30 %: the other way
    frames = [early] * 3 + [steady] * 7
    with tempfile.TemporaryDirectory() as scratch:
        run = os.path.join(scratch, "count_run")
        write_run(run, frames)
        mix = tool.size_mix(run)
        cell = math.pi * (2 * 0.36 + 2 * 0.16) / 4  # the first snapshot's mean area
        law = math.pi / 4 * (1 + 0.4 ** 2 / 12)
        check(mix["frames"] == 7, f"frames {mix['frames']}, expected the last 7 of 10")
        check(abs(mix["mid_over_cell"] - math.pi * 0.36 / cell) < 1e-12, f"mid over cell {mix['mid_over_cell']}")
        check(abs(mix["cell_over_law"] - cell / law) < 1e-12, f"cell over law {mix['cell_over_law']}")
        broken = os.path.join(scratch, "broken_run")
        write_run(broken, frames, truncate=True)
        try:
            tool.size_mix(broken)
            check(False, "a truncated snapshot was read")
        except ValueError as error:
            check("dump.chute.gz" in str(error) and "truncated" in str(error), f"error says {error}")


def pairing(tool):
    def row(reading, solver, run, mu, theta, dphi_bulk, counts=None, phi_local=0.75):
        return {"reading": reading, "solver": solver, "run": run, "mu": mu, "theta": theta, "dphi_bulk": dphi_bulk,
                "phi_local_from_counts": counts, "phi_local": phi_local}
    rows = [row("count", "published", "mu2_theta24_L45", 2.0, 24.0, 0.007),
            row("count", "published", "mu2_theta24_L45_seed20261123", 2.0, 24.0, 0.020),  # a replica: not paired
            row("layer", "published", "mu2_theta24_L45_layer", 2.0, 24.0, 0.004),
            row("layer", "published", "mu2_theta25_L45_layer", 2.0, 25.0, 0.005),
            row("count", "today", "mu2_theta24_L45", 2.0, 24.0, 0.003, counts=0.754, phi_local=0.750),
            row("count", "today", "health_mu2_theta26_L45", 2.0, 26.0, 0.006, counts=0.748, phi_local=0.750)]
    against_count = tool.paired(rows, "count")
    check(len(against_count) == 1 and abs(against_count[0][3] + 0.004) < 1e-12, f"against count {against_count}")
    against_layer = tool.paired(rows, "layer")
    check(len(against_layer) == 1 and abs(against_layer[0][3] + 0.001) < 1e-12, f"against layer {against_layer}")
    mean, _, _, n = tool.counts_against_area(rows)
    check(n == 2 and abs(mean - 0.001) < 1e-12, f"counts against area {mean} over {n}")


def tolerance_by_hand(tool):
    # plane shear at fixed phi: the loose table's I is 0.01 above the tight one's at 0.77, equal at
    # 0.74; 0.80 is in the loose table alone. Along a tight line of slope b = 0.3 that is +0.003, 0.
    with tempfile.TemporaryDirectory() as scratch:
        loose, tight = os.path.join(scratch, "loose.csv"), os.path.join(scratch, "tight.csv")
        with open(loose, "w") as out:
            out.write("# loose\nphi,I\n0.7400,0.25\n0.7700,0.14\n0.8000,0.02\n")
        with open(tight, "w") as out:
            out.write("# tight\nphi,I\n0.7400,0.25\n0.7700,0.13\n")
        shifts = tool.tolerance_shift(loose, tight, {"phi_c": 0.8, "b": 0.3})
    check([s[0] for s in shifts] == [0.74, 0.77], f"packings {shifts}")
    check(abs(shifts[0][3]) < 1e-12 and abs(shifts[1][3] - 0.003) < 1e-12, f"shifts {shifts}")


def first_published_by_hand(tool):
    """A series run that a re-run set kept (superseded/) is read from the kept row and profile, the
    others from the series' runs.csv and their own folder."""
    with tempfile.TemporaryDirectory() as scratch:
        series = os.path.join(scratch, "series", "flow_rules")
        kept = os.path.join(scratch, "rerun", "count_mu2", "mu2_theta24_L45", "superseded")
        os.makedirs(series)
        os.makedirs(kept)
        path = os.path.join(series, "runs.csv")
        with open(path, "w") as out:
            out.write("# provenance\nrun,mu,I_local\n"
                      "../../runs/mu2_theta24_L45,2,0.30\n../../runs/mu2_theta25_L45,2,0.40\n")
        with open(os.path.join(kept, "series_row.csv"), "w") as out:
            out.write("run,mu,I_local\n../../runs/mu2_theta24_L45,2,0.10\n")
        saved = dict(tool.local_rheology.RERUNS)
        tool.local_rheology.RERUNS["count"] = os.path.dirname(os.path.dirname(kept))
        try:
            read = tool.first_published("count", path)
        finally:
            tool.local_rheology.RERUNS.clear()
            tool.local_rheology.RERUNS.update(saved)
    check([r["I_local"] for r, _ in read] == ["0.10", "0.40"], f"rows read: {read}")
    check(read[0][1] == os.path.join(kept, "profile.csv")
          and read[1][1] == os.path.join(series, "../../runs/mu2_theta25_L45", "profile.csv"), f"profiles: {read}")


def committed(tool):
    held = tool.local_rheology.rerun_rows(os.path.join(tool.OUT, tool.TODAY_TABLE))
    runs = tool.today_runs()
    check(sorted(held) == sorted(runs), f"today/runs.csv holds {sorted(held)}, the folders {sorted(runs)}")
    return len(runs)


def main():
    tool = load_study("two_packings")
    size_mix_by_hand(tool)
    pairing(tool)
    tolerance_by_hand(tool)
    first_published_by_hand(tool)
    count = committed(tool)
    print(f"two_packings: every check passed ({count} of today's count runs in the committed table)")


if __name__ == "__main__":
    main()
