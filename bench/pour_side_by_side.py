#!/usr/bin/env python3
"""LAMMPS's 2D pour, soft (inputs/examples/in.pour_granular: the original's gran/hertz/history at
k 4e5, dt 1e-4) and rigid (inputs/examples/in.pour_rigid), at matched restitution: the original's
damping (gamma_n 100, e 0.97-1.00 by its law) against rigid e 0.99, and gamma_n 6000 (e 0.5 for two
grains of the mean size at speed 3) against rigid e 0.5. Runs one after the other, REPEATS times:
CPU time (user + system) and wall time of each run, their medians, and the final packing of the
last run of each: grains, pile height h (twice the grains' mean height, exact for a uniformly
filled layer), packing fraction phi = sum pi r^2 / (box width x h), the largest and mean overlap of
touching pairs and of grains on the walls (in mean diameters), kinetic energy.

    bench/pour_side_by_side.py [--lmp build/lmp_cd] [--repeats 3] [--duration 25] [--out DIR]

Run it under one nice level for both (e.g. nice -n 15 bench/pour_side_by_side.py) on an otherwise
idle machine. Prints a Markdown table.
"""

import argparse
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "studies"))
from cdtools.lammps_files import read_dump  # noqa: E402

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir)
# (restitution, soft deck's -vars, rigid deck's -vars)
MATCHED = [("0.99", {"gamma_n": "100"}, {"e": "0.99"}),
           ("0.5", {"gamma_n": "6000"}, {"e": "0.5"})]
DECKS = {"soft": "in.pour_granular", "rigid": "in.pour_rigid"}
WIDTH = 100.0  # the decks' box width


def timed_run(lmp, deck, variables, duration, folder):
    """(CPU s, wall s, the run's printed POUR line) of one run in `folder`."""
    os.makedirs(folder, exist_ok=True)
    arguments = [word for name, value in dict(variables, duration=duration).items()
                 for word in ("-var", name, str(value))]
    before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
    result = subprocess.run([lmp, "-in", os.path.join(TOP, "inputs", "examples", deck)] + arguments +
                            ["-log", "log.lammps", "-screen", "none"], cwd=folder)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode != 0:
        sys.exit(f"pour_side_by_side.py: {deck} failed in {folder}")
    with open(os.path.join(folder, "log.lammps")) as log:
        pour = [line.split() for line in log if line.startswith("POUR ")][-1]
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, dict(zip(pour[1::2], map(float, pour[2::2])))


def overlaps(grains):
    """Overlaps (> 0) of touching pairs, found through a grid of cells one largest diameter wide."""
    cell = 2 * max(g["radius"] for g in grains)
    grid = {}
    for index, g in enumerate(grains):
        grid.setdefault((int(g["x"] // cell), int(g["y"] // cell)), []).append(index)
    found = []
    for (cx, cy), members in grid.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in grid.get((cx + dx, cy + dy), []):
                    for i in members:
                        if i < j:
                            a, b = grains[i], grains[j]
                            gap = math.hypot(a["x"] - b["x"], a["y"] - b["y"]) - a["radius"] - b["radius"]
                            if gap < 0:
                                found.append(-gap)
    return found


def packing(folder):
    grains = list(read_dump(os.path.join(folder, "pour.final"))[-1][2].values())
    mean_d = statistics.mean(2 * g["radius"] for g in grains)
    height = 2 * statistics.mean(g["y"] for g in grains)
    area = sum(math.pi * g["radius"] ** 2 for g in grains)
    pairs = overlaps(grains)
    walls = [w for g in grains for w in (g["radius"] - g["x"], g["x"] + g["radius"] - WIDTH, g["radius"] - g["y"])
             if w > 0]
    return {"grains": len(grains), "h": height, "h_d": height / mean_d, "phi": area / (WIDTH * height),
            "pair_max": max(pairs, default=0) / mean_d, "pair_mean": statistics.mean(pairs) / mean_d if pairs else 0,
            "contacts": len(pairs), "wall_max": max(walls, default=0) / mean_d}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lmp", default=os.path.join(TOP, "build", "lmp_cd"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--duration", type=float, default=25)
    parser.add_argument("--out", default=None)
    args = parser.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="pour_side_by_side.")
    runs = {}
    for repeat in range(args.repeats):
        for restitution, soft_vars, rigid_vars in MATCHED:
            for model, variables in (("soft", soft_vars), ("rigid", rigid_vars)):
                folder = os.path.join(out, f"{model}_e{restitution}.{repeat + 1}")
                result = timed_run(args.lmp, DECKS[model], variables, args.duration, folder) + (folder,)
                runs.setdefault((restitution, model), []).append(result)
                print(f"{model} e {restitution} run {repeat + 1}: CPU {result[0]:.2f} s, wall {result[1]:.1f} s",
                      flush=True)
    print(f"\n| e | run | -var | CPU s (median of {args.repeats}) | wall s | grains | h (d) | phi | "
          "largest overlap, pairs (d) | mean overlap (d) | largest on a wall (d) | kinetic energy |")
    print("|" + "---|" * 12)
    for restitution, soft_vars, rigid_vars in MATCHED:
        for model, variables in (("soft", soft_vars), ("rigid", rigid_vars)):
            results = runs[(restitution, model)]
            final = packing(results[-1][3])
            setting = " ".join(f"{k} {v}" for k, v in variables.items())
            print(f"| {restitution} | {model} | {setting} | {statistics.median(r[0] for r in results):.2f} | "
                  f"{statistics.median(r[1] for r in results):.1f} | {final['grains']} | {final['h_d']:.2f} | "
                  f"{final['phi']:.4f} | {final['pair_max']:.2e} | {final['pair_mean']:.2e} | "
                  f"{final['wall_max']:.2e} | {results[-1][2]['ke']:.3g} |")
    for restitution, _, _ in MATCHED:
        soft, rigid = (statistics.median(r[0] for r in runs[(restitution, m)]) for m in ("soft", "rigid"))
        print(f"e {restitution}: rigid / soft CPU time {rigid / soft:.3f}")
    print(f"(runs in {out})")


if __name__ == "__main__":
    main()
