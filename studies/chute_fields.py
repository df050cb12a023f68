#!/usr/bin/env python3
"""The 45 d chute's local rheology from its stresses: `cdpost fields` on a window of the steady
flow dumped every step (grains and the fix's contacts), across the flow; at each node of the
flowing layer mu = -sigma_yx / sigma_yy and I = gamma_dot d / sqrt(sigma_yy / rho_s) (plane
shear's definitions, doc/plane_shear_results.md), set against plane shear's mu(I) and phi(I) of the
same friction at 1e-4 (results/plane_shear/), read at the node's I (linear in log I).

A case is MU:THETA (the count reading, seed 20261122, the deck's defaults otherwise). Each runs
from the deposition to `--spin-up` s of chute time (skipped if MU:THETA=RUN names the folder of a
finished steady run, its chute.restart and flow.time), then a `--window` s more from there at a
fixed step (`--window-dt`) with `-var fields_every 1` (doc/fields.md).

    studies/chute_fields.py --run --deposition DEPOSITION.restart [--case 0.05:18 --case 0.5:24 \\
        --case 2:25=RUN] [--out runs/chute_fields]
    studies/chute_fields.py --analyse [--out runs/chute_fields] [--results results/chute_fields]

Writes RESULTS/nodes.csv (every node of every case), RESULTS/summary.csv and summary.md (per case:
the layer's nodes, the momentum balance, the angle and packing against plane shear's: at the
layer's mean, the nodes' least and largest) and RESULTS/local_rheology.png (gnuplot).
"""

import argparse
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools import lammps_files, plane_shear, run, stats  # noqa: E402

DEFAULT_CASES = ("0.05:18", "0.5:24", "2:25")
# A node is in the flowing layer when it is 2 d above the walls' tops (the grains below touch their
# ends), dense and 2 d below the free surface (the kernel reaches out of the grains there), and
# inside plane shear's measured range of I.
DENSE_PHI = 0.6
SURFACE_MARGIN_D = 2.0
BASE_MARGIN_D = 2.0
# The momentum balance is read in the bulk too: 10 d and more below the free surface, where the
# weight above is not a few grains'.
BULK_DEPTH_D = 10.0


def parse_case(text):
    """(mu, theta, a finished run's folder or None) of MU:THETA[=RUN]."""
    head, _, start = text.partition("=")
    try:
        mu, theta = (float(v) for v in head.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--case {text}: expected MU:THETA or MU:THETA=RUN")
    return mu, theta, start or None


def case_folder(out, mu, theta):
    return os.path.join(out, f"mu{mu:g}_theta{theta:g}")


def end_time(folder):
    """The chute time a finished run ended at: the last sample of its flow.time."""
    if not os.path.exists(os.path.join(folder, "chute.restart")):
        raise RuntimeError(f"{folder}: not a finished chute run (no chute.restart)")
    return lammps_files.time_span(os.path.join(folder, "flow.time"))[1]


def run_case(mu, theta, start_run, deposition, spin_up, window, window_dt, folder, lmp):
    """The spin-up (unless a finished run is given) and the dumped window, each skipped if done."""
    common = {"stage": "flow", "mu": f"{mu:g}", "theta": f"{theta:g}"}
    if start_run is None:
        start_run = os.path.join(folder, "spinup")
        if not os.path.exists(os.path.join(start_run, "chute.restart")):
            run.run_checked(run.lmp_command(lmp, run.deck_copy(start_run),
                                            dict(common, start=deposition, duration=f"{spin_up:g}"), screen="none"),
                            start_run)
    dumped = os.path.join(folder, "window")
    if not os.path.exists(os.path.join(dumped, "chute.restart")):
        variables = dict(common, start=os.path.abspath(os.path.join(start_run, "chute.restart")),
                         duration=f"{end_time(start_run) + window:g}", adapt_dt="no", dt=f"{window_dt:g}",
                         fields_every=1)
        run.run_checked(run.lmp_command(lmp, run.deck_copy(dumped), variables, screen="none"), dumped)


def read_params(folder):
    with open(os.path.join(folder, "chute.params")) as src:
        return {k: v for k, v in (line.split() for line in src if line.strip() and not line.startswith("#"))}


def profile(folder, params, cdpost):
    """`cdpost fields` across the flow of a window folder: [row of fields.csv as floats]. The
    window ran at the fixed step of its chute.params (the deck refuses fields_every with adapt_dt)."""
    out = os.path.join(folder, "profile")
    command = [cdpost, "fields", os.path.join(folder, "fields.dump.gz"), "--contacts",
               os.path.join(folder, "fields.contacts.gz"), "--along", "y", "--dt", params["dt_s"], "--out", out]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "fields.csv"), newline="") as src:
        rows = csv.DictReader(line for line in src if not line.startswith("#"))
        return [{k: float(v) if v else None for k, v in r.items()} for r in rows]


def free_surface(nodes, y_top):
    """The highest node above the walls' tops still dense."""
    dense = [n["y_m"] for n in nodes if n["y_m"] > y_top and n["phi"] is not None and n["phi"] >= DENSE_PHI]
    return max(dense) if dense else y_top


def weight_above(nodes, g):
    """g times the mass per area above each node: the profile's density integrated up to its top
    (trapezoids between nodes); {y: weight}."""
    ordered = sorted(nodes, key=lambda n: n["y_m"])
    weights, above = {}, 0.0
    for upper, lower in zip(reversed(ordered), list(reversed(ordered))[1:]):
        weights.setdefault(upper["y_m"], above)
        above += 0.5 * g * (upper["rho_kg/m^3"] + lower["rho_kg/m^3"]) * (upper["y_m"] - lower["y_m"])
        weights[lower["y_m"]] = above
    return weights


def layer_nodes(nodes, params, table):
    """The flowing layer's nodes with their local mu, I, plane shear's mu and phi at that I, and
    the momentum balance: sigma_yy and -sigma_yx over the weight above times cos and sin theta."""
    d, y_top = float(params["d_m"]), float(params["y_top_m"])
    rho_s = float(params["density_kgpm3"])
    theta = math.radians(float(params["theta_deg"]))
    weights = weight_above(nodes, float(params["g_mps2"]))
    surface = free_surface(nodes, y_top)
    top = surface - SURFACE_MARGIN_D * d
    layer = []
    for n in nodes:
        inside = y_top + BASE_MARGIN_D * d < n["y_m"] < top
        if not inside or n["phi"] < DENSE_PHI or not n["s_yy_Pa"] or n["s_yy_Pa"] <= 0:
            continue
        mu = -n["s_yx_Pa"] / n["s_yy_Pa"]    # compression positive: the layer above drags this one down the slope
        inertial = n["gamma_dot_1/s"] * d / math.sqrt(n["s_yy_Pa"] / rho_s)
        mu_ps = plane_shear.at_inertial(table, inertial, "mu")
        if mu_ps is None:
            continue
        layer.append({"z_d": (n["y_m"] - y_top) / d, "depth_d": (surface - n["y_m"]) / d, "phi": n["phi"],
                      "I": inertial, "mu": mu, "mu_ps": mu_ps,
                      "phi_ps": plane_shear.at_inertial(table, inertial, "phi"),
                      "dtheta_deg": math.degrees(math.atan(mu) - math.atan(mu_ps)),
                      "syy_over_weight": n["s_yy_Pa"] / (weights[n["y_m"]] * math.cos(theta)),
                      "syx_over_weight": -n["s_yx_Pa"] / (weights[n["y_m"]] * math.sin(theta))})
    return layer


def summary(mu, theta, layer, table):
    """One row per case: the layer's nodes, their means and spreads. The node-to-node scatter of
    I is mostly the window's noise in the shear rate: the layer's mean (mu, I, phi) against plane
    shear at the mean I is the comparison; the nodes' range bounds it."""
    def mean(key):
        return stats.mean_sd_se([n[key] for n in layer])[0]
    tan = math.tan(math.radians(theta))
    balance = [n["mu"] / tan - 1 for n in layer]
    dtheta, dphi = [n["dtheta_deg"] for n in layer], [n["phi"] - n["phi_ps"] for n in layer]
    mean_i = mean("I")
    bulk = [n for n in layer if n["depth_d"] >= BULK_DEPTH_D]
    return {"contact_mu": mu, "theta_deg": theta, "nodes": len(layer),
            "z_low_d": min(n["z_d"] for n in layer), "z_high_d": max(n["z_d"] for n in layer),
            "I_mean": mean_i, "I_low": min(n["I"] for n in layer), "I_high": max(n["I"] for n in layer),
            "mu_mean": mean("mu"), "phi_mean": mean("phi"),
            "balance_min": min(balance), "balance_max": max(balance),
            "syy_weight_min": min(n["syy_over_weight"] for n in layer) - 1,
            "syy_weight_max": max(n["syy_over_weight"] for n in layer) - 1,
            "syx_weight_min": min(n["syx_over_weight"] for n in layer) - 1,
            "syx_weight_max": max(n["syx_over_weight"] for n in layer) - 1,
            "bulk_syy_weight_min": min(n["syy_over_weight"] for n in bulk) - 1,
            "bulk_syy_weight_max": max(n["syy_over_weight"] for n in bulk) - 1,
            "bulk_syx_weight_min": min(n["syx_over_weight"] for n in bulk) - 1,
            "bulk_syx_weight_max": max(n["syx_over_weight"] for n in bulk) - 1,
            "dtheta_at_mean_deg": math.degrees(math.atan(mean("mu"))
                                               - math.atan(plane_shear.at_inertial(table, mean_i, "mu"))),
            "dphi_at_mean": mean("phi") - plane_shear.at_inertial(table, mean_i, "phi"),
            "dtheta_min_deg": min(dtheta), "dtheta_max_deg": max(dtheta), "dphi_min": min(dphi), "dphi_max": max(dphi)}


def write_csv(path, rows):
    with open(path, "w", newline="") as dst:
        writer = csv.DictWriter(dst, fieldnames=list(rows[0]))
        writer.writeheader()
        for row in rows:
            writer.writerow({k: f"{v:.6g}" if isinstance(v, float) else v for k, v in row.items()})


def write_markdown(path, rows):
    """The comparison as the table of doc/fields.md."""
    lines = ["| mu | θ (°) | layer z (d) | mean I | µ = −σ_yx/σ_yy | φ | σ_yy, −σ_yx against the weight above "
             "(10 d and more below the surface) | angle − plane shear's at the mean I (nodes) | "
             "φ − plane shear's (nodes) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(
            f"| {r['contact_mu']:g} | {r['theta_deg']:g} | {r['z_low_d']:.0f}–{r['z_high_d']:.0f} | "
            f"{r['I_mean']:.3f} | "
            f"{r['mu_mean']:.4f} (tan θ {math.tan(math.radians(r['theta_deg'])):.4f}) | {r['phi_mean']:.4f} | "
            f"{100 * r['bulk_syy_weight_min']:+.1f} to {100 * r['bulk_syy_weight_max']:+.1f} %, "
            f"{100 * r['bulk_syx_weight_min']:+.1f} to {100 * r['bulk_syx_weight_max']:+.1f} % | "
            f"{r['dtheta_at_mean_deg']:+.2f}° ({r['dtheta_min_deg']:+.2f} to {r['dtheta_max_deg']:+.2f}) | "
            f"{r['dphi_at_mean']:+.4f} ({r['dphi_min']:+.4f} to {r['dphi_max']:+.4f}) |")
    with open(path, "w") as dst:
        dst.write("\n".join(lines) + "\n")


def draw(results, cases):
    """RESULTS/local_rheology.png: mu(I) and phi(I), chute nodes over plane shear's tables
    (nodes.csv's columns: 1 contact_mu, 5 phi, 6 I, 7 mu)."""
    nodes = os.path.join(results, "nodes.csv")
    tables = " ".join(plane_shear.table_path(mu) for mu, _, _ in cases)
    script = f"""
set terminal pngcairo size 1100,450
set output '{results}/local_rheology.png'
set datafile separator ','
set multiplot layout 1,2
set logscale x
set xlabel 'I'
set key left top
set ylabel 'mu = -sigma_yx / sigma_yy'
plot for [m in "{' '.join(f'{mu:g}' for mu, _, _ in cases)}"] '{nodes}' every ::1 \\
       using (sprintf('%g', $1) eq m ? $6 : 1/0):7 pt 7 ps 0.5 title 'chute, mu '.m, \\
     for [f in "{tables}"] f using 2:4 with linespoints lt -1 dt 2 pt 6 notitle
set ylabel 'phi'
set key left bottom
plot for [m in "{' '.join(f'{mu:g}' for mu, _, _ in cases)}"] '{nodes}' every ::1 \\
       using (sprintf('%g', $1) eq m ? $6 : 1/0):5 pt 7 ps 0.5 title 'chute, mu '.m, \\
     for [f in "{tables}"] f using 2:1 with linespoints lt -1 dt 2 pt 6 notitle
unset multiplot
"""
    try:
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as failure:
        print(f"chute_fields.py: no figure ({failure})", file=sys.stderr)


def analyse(cases, out, results, cdpost):
    os.makedirs(results, exist_ok=True)
    all_nodes, rows = [], []
    for mu, theta, _ in cases:
        window = os.path.join(case_folder(out, mu, theta), "window")
        table = plane_shear.read_table(plane_shear.table_path(mu))
        params = read_params(window)
        layer = layer_nodes(profile(window, params, cdpost), params, table)
        if not layer:
            sys.exit(f"chute_fields.py: {window}: no node of the flowing layer within plane shear's range of I")
        all_nodes += [dict({"contact_mu": mu, "theta_deg": theta}, **n) for n in layer]
        rows.append(summary(mu, theta, layer, table))
    write_csv(os.path.join(results, "nodes.csv"), all_nodes)
    write_csv(os.path.join(results, "summary.csv"), rows)
    write_markdown(os.path.join(results, "summary.md"), rows)
    draw(results, cases)
    for r in rows:
        print(f"mu {r['contact_mu']:g}, {r['theta_deg']:g} deg: {r['nodes']} nodes, "
              f"z {r['z_low_d']:.1f}-{r['z_high_d']:.1f} d; mean I {r['I_mean']:.3g} (nodes {r['I_low']:.3g}-"
              f"{r['I_high']:.3g}), mu {r['mu_mean']:.4f}, phi {r['phi_mean']:.4f}; "
              f"-sigma_yx/sigma_yy / tan theta - 1 in [{r['balance_min']:+.3f}, {r['balance_max']:+.3f}]; "
              f"sigma_yy, -sigma_yx against the weight above: {r['syy_weight_min']:+.3f} to "
              f"{r['syy_weight_max']:+.3f}, {r['syx_weight_min']:+.3f} to {r['syx_weight_max']:+.3f} "
              f"(10 d and more below the surface {r['bulk_syy_weight_min']:+.3f} to {r['bulk_syy_weight_max']:+.3f}, "
              f"{r['bulk_syx_weight_min']:+.3f} to {r['bulk_syx_weight_max']:+.3f}); "
              f"against plane shear at the mean I: {r['dtheta_at_mean_deg']:+.2f} deg, phi {r['dphi_at_mean']:+.4f} "
              f"(nodes {r['dtheta_min_deg']:+.2f} to {r['dtheta_max_deg']:+.2f} deg, "
              f"phi {r['dphi_min']:+.4f} to {r['dphi_max']:+.4f})")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run", action="store_true", help="run the cases first")
    parser.add_argument("--analyse", action="store_true", help="coarse-grain the windows and compare")
    parser.add_argument("--case", type=parse_case, action="append", help="MU:THETA[=RUN] (repeatable)")
    parser.add_argument("--deposition", help="the deposition restart the spin-ups start from")
    parser.add_argument("--spin-up", type=float, default=10.0, help="chute time of the spin-up (s)")
    parser.add_argument("--window", type=float, default=0.2, help="chute time dumped every step (s)")
    parser.add_argument("--window-dt", type=float, default=1e-4,
                        help="the window's fixed step (s): at most the step the spin-up's adaptive step took")
    parser.add_argument("--out", default="runs/chute_fields")
    parser.add_argument("--results", default=os.path.join(run.TOP, "results", "chute_fields"))
    parser.add_argument("--lmp", default=run.BUILT_LMP_CD)
    parser.add_argument("--cdpost", default=run.BUILT_CDPOST)
    args = parser.parse_args(argv)
    cases = args.case or [parse_case(c) for c in DEFAULT_CASES]
    if not (args.run or args.analyse):
        parser.error("give --run, --analyse or both")
    if args.run:
        if any(start is None for _, _, start in cases) and not args.deposition:
            parser.error("--run: a case without =RUN spins up from --deposition, which is missing")
        for mu, theta, start in cases:
            deposition = args.deposition and os.path.abspath(args.deposition)
            folder = case_folder(args.out, mu, theta)
            run_case(mu, theta, start, deposition, args.spin_up, args.window, args.window_dt, folder, args.lmp)
    if args.analyse:
        analyse(cases, args.out, args.results, args.cdpost)


if __name__ == "__main__":
    main()
