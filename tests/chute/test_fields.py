#!/usr/bin/env python3
"""cdpost fields on LAMMPS runs of the fix (ctest label fields):

    tests/chute/test_fields.py pile|chute|shear --lmp build/lmp_cd --cdpost build/postproc/cdpost --work DIR

pile:  a pile at rest (in.fields_pile). A Gaussian and a Lucy kernel of 25 um, their range inside
       the gap between the floor and the lowest centres (radius 0.2 mm at least): there sigma_yy
       is the floor's force per width, which at rest carries the weight per width. The fix's
       tolerance (1e-4, relative) bounds the impulses' error: 1e-3 is allowed (measured ~1e-5).
       In the bulk (a kernel of d/2) sigma_yy(y) is g times the mass above y per width, computed
       from the same profile's density: 1e-3 allowed.
chute: a flowing chute on a fixed base (in.fields_chute, 22 degrees), dumped every step for
       0.4 s: in the bulk (phi >= 0.7, y >= 1.5 mm, 2 d above the base's top) sigma_yy and
       -sigma_yx are the weight above per width times cos and sin theta within 2 %.
shear: plane shear (inputs/examples/in.plane_shear, 12 x 12 grains, strain 2, phi 0.75) with the
       atoms and the fix's local array dumped every step of its averaging window: the profile's
       mean stress against the deck's averages over the same steps: its contact part against the
       fix's outputs 13-16 within 1e-4 (branch vectors at x_m, as the fix's), the whole (kinetic
       about the local mean velocity, the images across y moving at rate x ly) against compute
       pressure with compute temp/deform within 1 %.
Standard library only.
"""

import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81


def run(command, cwd):
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"failed ({done.returncode}): {' '.join(command)}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    return done.stdout


def read_fields(path):
    with open(path) as src:
        rows = list(csv.reader(line for line in src if not line.startswith("#")))
    names = rows[0]
    return {name: [float(r[k]) if r[k] else math.nan for r in rows[1:]] for k, name in enumerate(names)}


def weight_above(fields):
    """g times the mass above each node per width, from the profile's density (midpoint sums)."""
    y, rho = fields["y_m"], fields["rho_kg/m^3"]
    h = y[1] - y[0]
    above, total = [0.0] * len(y), 0.0
    for k in range(len(y) - 1, -1, -1):
        total += rho[k] * h
        above[k] = G * (total - 0.5 * rho[k] * h)
    return above


def fresh(work, name):
    folder = os.path.join(work, name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    return folder


def case_pile(args):
    folder = fresh(args.work, "fields_pile")
    run([args.lmp, "-in", os.path.join(HERE, "in.fields_pile"), "-log", "log.lammps", "-screen", "none"], folder)
    with open(os.path.join(folder, "pile.dump")) as src:
        lines = src.read().split("ITEM: ATOMS")[1].split("ITEM:")[0].splitlines()[1:]
    weight_per_width = G * sum(float(line.split()[7]) for line in lines) / 0.006  # the mass column
    common = [args.cdpost, "fields", "pile.dump", "--contacts", "pile.contacts", "--units", "si", "--dt", "1e-5",
              "--along", "y"]
    worst = 0.0
    for kernel in ("gauss", "lucy"):
        # One node at y = 0.1 mm; the kernel's range (75 and 81 um) stays within 0 < y < 0.2 mm.
        run(common + ["--kernel", kernel, "--width", "2.5e-5", "--range", "0:0.0002", "--cells", "1",
                      "--out", "floor_" + kernel], folder)
        floor = read_fields(os.path.join(folder, "floor_" + kernel, "fields.csv"))["s_yy_Pa"][0]
        error = abs(floor / weight_per_width - 1)
        print(f"pile, {kernel}: sigma_yy at the floor {floor:.6g} Pa, weight per width {weight_per_width:.6g} Pa, "
              f"relative difference {error:.2e}")
        worst = max(worst, error)
    if worst > 1e-3:
        sys.exit(f"pile: sigma_yy at the floor differs from the weight per width by {worst:.2e} (> 1e-3)")
    run(common + ["--width", "2.5e-4", "--cells", "120", "--out", "bulk"], folder)
    fields = read_fields(os.path.join(folder, "bulk", "fields.csv"))
    above = weight_above(fields)
    errors = [abs(s / w - 1) for s, w, phi, y in zip(fields["s_yy_Pa"], above, fields["phi"], fields["y_m"])
              if phi >= 0.7 and 1e-3 <= y]
    print(f"pile, bulk: {len(errors)} nodes, largest |sigma_yy / (g m_above) - 1| {max(errors):.2e}")
    if not errors or max(errors) > 1e-3:
        sys.exit("pile: sigma_yy in the bulk is not the weight above within 1e-3")


def case_chute(args):
    folder = fresh(args.work, "fields_chute")
    theta = 22.0
    run([args.lmp, "-in", os.path.join(HERE, "in.fields_chute"), "-log", "log.lammps", "-screen", "none",
         "-var", "theta", str(theta)], folder)
    run([args.cdpost, "fields", "chute.dump", "--contacts", "chute.contacts", "--units", "si", "--dt", "1e-4",
         "--along", "y", "--width", "2.5e-4", "--cells", "168", "--out", "profile"], folder)
    fields = read_fields(os.path.join(folder, "profile", "fields.csv"))
    above = weight_above(fields)
    cos, sin = math.cos(math.radians(theta)), math.sin(math.radians(theta))
    bulk = [k for k, (phi, y) in enumerate(zip(fields["phi"], fields["y_m"])) if phi >= 0.7 and y >= 1.5e-3]
    normal = [fields["s_yy_Pa"][k] / (above[k] * cos) - 1 for k in bulk]
    shear = [-fields["s_yx_Pa"][k] / (above[k] * sin) - 1 for k in bulk]
    y_low, y_high = fields['y_m'][bulk[0]] * 1e3, fields['y_m'][bulk[-1]] * 1e3
    print(f"chute: {len(bulk)} bulk nodes, y {y_low:.2f} to {y_high:.2f} mm;"
          f" sigma_yy / (W cos theta) - 1 from {min(normal):+.4f} to {max(normal):+.4f},"
          f" -sigma_yx / (W sin theta) - 1 from {min(shear):+.4f} to {max(shear):+.4f}")
    if len(bulk) < 20 or max(map(abs, normal + shear)) > 0.02:
        sys.exit("chute: the stress in the bulk is not the weight above times cos and sin theta within 2 %")


def case_shear(args):
    folder = fresh(args.work, "fields_shear")
    with open(os.path.join(HERE, os.pardir, os.pardir, "inputs", "examples", "in.plane_shear")) as src:
        deck = src.read()
    last = deck.rindex("run             ${half}")  # the averaging run
    dumps = ("dump atoms all custom 1 shear.dump id type x y vx vy radius mass\n"
             "dump contacts all local 1 shear.contacts f_cd[1] f_cd[2] f_cd[3] f_cd[4] f_cd[5] f_cd[6] f_cd[7]\n")
    with open(os.path.join(folder, "in.shear"), "w") as out:
        out.write(deck[:last] + dumps + deck[last:])
    run([args.lmp, "-in", "in.shear", "-log", "log.lammps", "-screen", "none", "-var", "side", "12", "-var", "strain",
         "2", "-var", "press_steps", "3000"], folder)
    with open(os.path.join(folder, "log.lammps")) as src:
        line = [line for line in src if line.startswith("SHEAR ")][-1].split()
    deck_values = dict(zip(line[1::2], map(float, line[2::2])))
    rate, dt = deck_values["rate"], 0.002 / deck_values["rate"]  # the deck's strain_step / rate
    steps = round(2 / rate / dt)
    # The deck averages steps half + 1 to steps; the dumps start at step half.
    run([args.cdpost, "fields", "shear.dump", "--contacts", "shear.contacts", "--units", "lj", "--dt", str(dt),
         "--t-start", str((steps // 2 + 0.5) * dt), "--along", "y", "--width", "0.5", "--image-velocity",
         str(rate * deck_values["ly"]), "--out", "profile"], folder)
    fields = read_fields(os.path.join(folder, "profile", "fields.csv"))
    unit = "_m/(sigma tau^2)"
    # The contact part is the fix's own sum, branch vectors at x_m: equal to round-off and the
    # frames' 10 significant digits; the kinetic part is a kernel's estimate: 1 %.
    pairs = [("sc_xx", "contact_xx", 1e-4), ("sc_yy", "contact_yy", 1e-4), ("sc_xy", "contact_xy", 1e-4),
             ("sc_yx", "contact_yx", 1e-4), ("s_xx", "pxx", 1e-2), ("s_yy", "pyy", 1e-2), ("s_xy", "pxy", 1e-2)]
    failures = []
    for name, deck_name, allowed in pairs:
        values = fields[name + unit]
        mean = sum(values) / len(values)
        error = mean / deck_values[deck_name] - 1
        print(f"shear: {name} {mean:.8g} against the deck's {deck_name} {deck_values[deck_name]:.8g}: {error:+.2e}")
        if abs(error) > allowed:
            failures.append(f"{name} differs from the deck's {deck_name} by {error:+.2e} (> {allowed:g})")
    if failures:
        sys.exit("shear: " + "; ".join(failures))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", choices=["pile", "chute", "shear"])
    parser.add_argument("--lmp", required=True)
    parser.add_argument("--cdpost", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    args.lmp, args.cdpost, args.work = (os.path.abspath(p) for p in (args.lmp, args.cdpost, args.work))
    os.makedirs(args.work, exist_ok=True)
    {"pile": case_pile, "chute": case_chute, "shear": case_shear}[args.case](args)


if __name__ == "__main__":
    main()
