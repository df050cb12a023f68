#!/usr/bin/env python3
"""studies/chute_campaign.py --report on a synthetic campaign, run by ctest.

    test_report.py --cdpost build/postproc/cdpost --work DIR

The campaign folder is written here as the runner leaves it (run folders with their spliced
outputs and legs, DONE), for the mu = 0.5 series, its replica and three runs of its layer
reading (a thinner layer), with flows that follow a known mu(I) rule, phi(U) law and
oscillation; one run of the series is left unstarted. The report must analyse every finished
run with cdpost (from its chute.params, or the campaign's variables for a run made before the
deck wrote one), recover the laws from the series fit, show both readings side by side (each
reading's fits as its own series made them), measure the replica scatter, list the unstarted
run, hold no dump or restart, read a run whose raw outputs are gone back from what it
published, use no run (its own or published) made with other deck variables than the report's,
keep a hand-written discussion when it is made again, and show a rigid/soft comparison's table; a
run without its solver health is refused in one line unless --count-without-health counts it.
Standard library only.
"""

import argparse
import csv
import gzip
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
RUNNER = os.path.join(TOP, "studies", "chute_campaign.py")
# The pages --report writes: the README, then the pages holding the runs', series' and soft tables.
PAGES = ("README.md", "runs/README.md", "series/README.md", "soft/README.md")

D, G = 5.0e-4, 9.81
SQRT_GD = math.sqrt(G * D)
Y_TOP = 30 * D                          # the deck's wall tops
H = 40.0                                # flowing-layer thickness (d)
H_LAYER = 30.0                          # and of the layer reading's runs
THETA1, THETA2, I0 = 20.0, 32.0, 0.3    # the mu(I) rule the flows follow
PHI_C, K = 0.82, 0.002                  # phi = PHI_C - K U/sqrt(g d)
SAMPLE_RATE, DURATION, DT = 1000, 4.0, 1.0e-4
REPLICA_SHIFT = 0.2                     # U of the replica run minus the original (sqrt(g d))
STOPPED_U, H_STOP = 0.02, 30.0          # a layer that stopped (it creeps), and its thickness (d)
UNRECORDED = "mu0.5_theta24_L45_seed20261123"  # a run made before the deck wrote chute.params
SERIES_ARGS = ["--series", "mu0.5", "--series", "replicas", "--series", "layer_mu0.5", "--only", "mu0.5_*"]
LAYER_ANGLES = (23, 25, 27)             # the layer reading's finished runs


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def flow_velocity(theta, h=H):
    """U/sqrt(g d) of the mu(I) rule at this tilt and thickness h (d)."""
    t, t1, t2 = (math.tan(math.radians(a)) for a in (theta, THETA1, THETA2))
    inertial = I0 * (t - t1) / (t2 - t)
    return inertial * h ** 1.5


def write_flow_time(folder, u, frequency, rng, h):
    amplitude = 0.002 * max(u, 1.0) * SQRT_GD
    with open(os.path.join(folder, "flow.time"), "w") as out:
        out.write("# synthetic chute flow\n# TimeStep v_time v_u_all v_u_flow v_v_flow v_phi_flow v_h v_n_flow\n")
        for k in range(int(DURATION * SAMPLE_RATE) + 1):
            t = k / SAMPLE_RATE
            u_flow = u * SQRT_GD * (1 + 0.005 * rng.gauss(0, 1))
            v = amplitude * math.sin(2 * math.pi * frequency * t) + 0.1 * amplitude * rng.gauss(0, 1)
            phi = PHI_C - K * u + 1e-4 * rng.gauss(0, 1)
            out.write(f"{int(round(t / DT))} {t:.10g} {0.6 * u_flow:.8g} {u_flow:.8g} {v:.8g} {phi:.8g} "
                      f"{h * D:.8g} 2500\n")


def write_profile(folder, u):
    """u(z): Bagnold in the layer, exponential creep (lambda 2 d) below the wall tops."""
    bins = int(Y_TOP / D + H + 5)
    a = 0.5 * u / H ** 1.5
    with open(os.path.join(folder, "profile.chunk"), "w") as out:
        out.write("# synthetic profile\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Ncount vx vy\n")
        for block in range(int(DURATION * 10)):
            out.write(f"{(block + 1) * 1000} {bins} {bins * 40}\n")
            for b in range(bins):
                z = (b + 0.5) - Y_TOP / D
                if z < 0:
                    vx = 0.5 * u * math.exp(z / 2.0)
                elif z <= H:
                    vx = 0.5 * u + a * (H ** 1.5 - (H - z) ** 1.5)
                else:
                    vx = 0.0
                count = 40 if z <= H else 0
                out.write(f"  {b + 1} {(b + 0.5) * D:.6g} {count} {vx * SQRT_GD:.6g} 0\n")


def write_layers(folder, frequency):
    layers = int(H / 5)
    with open(os.path.join(folder, "layers.chunk"), "w") as out:
        out.write("# synthetic layers\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Ncount vy\n")
        for k in range(int(DURATION * SAMPLE_RATE) + 1):
            t = k / SAMPLE_RATE
            out.write(f"{int(round(t / DT))} {layers} {layers * 200}\n")
            for n in range(layers):
                z = 2.5 + 5 * n
                vy = 0.05 * math.exp((z - H) / 10.0) * math.sin(2 * math.pi * frequency * t)
                out.write(f"  {n + 1} {Y_TOP + z * D:.6g} 200 {vy:.6g}\n")


def write_dump(folder):
    with gzip.open(os.path.join(folder, "dump.chute.gz"), "wt") as out:
        out.write(f"ITEM: TIMESTEP\n{int(DURATION / DT)}\nITEM: NUMBER OF ATOMS\n20\nITEM: BOX BOUNDS pp fm pp\n"
                  f"0 {45 * D}\n0 {Y_TOP + 2 * H * D}\n-3e-4 3e-4\nITEM: ATOMS id type x y vx vy radius ix\n")
        for n in range(20):
            out.write(f"{n + 1} 1 {(n + 0.5) * 2.2 * D:.6g} {Y_TOP + D:.6g} 0.1 0 {D / 2} 0\n")


def write_record(folder):
    """chute.params as inputs/in.chute writes it (the wall tops, sample rate, d, g, ...)."""
    with open(os.path.join(folder, "chute.params"), "w") as out:
        out.write(f"# inputs/in.chute: chute parameters, one name and value a line (SI)\ny_top_m {Y_TOP}\n"
                  f"sample_rate_hz {SAMPLE_RATE}\nd_m {D}\ng_mps2 {G}\nL_d 45\nwall_height_d 30\n")


# The fix's end-of-run solver line: the run's solver health.
SOLVER_LINE = ("Fix contact/dynamics cd solver: 40000 steps, 0 unconverged (0 %), largest final norm 0.001, "
               "sweeps per step median 120, 99th percentile 400, max 900, 0 rescued from a stall\n")


def write_run(campaign, name, theta, seed_shift, frequency, u=None, h=H, record=True, health=True):
    """A finished run folder as the runner leaves it, with one leg and its timers (and the solver's
    health unless told), and its chute.params unless made before the deck wrote one; the layer
    flows by the mu(I) rule unless u (sqrt(g d)) is given."""
    folder = os.path.join(campaign, "runs", name)
    leg = os.path.join(folder, "legs", "00")
    os.makedirs(leg)
    rng = random.Random(name)
    u = flow_velocity(theta, h) + seed_shift if u is None else u
    write_flow_time(folder, u, frequency, rng, h)
    write_profile(folder, u)
    write_layers(folder, frequency)
    write_dump(folder)
    if record:
        write_record(folder)
    for restart in ("chute.restart", os.path.join("legs", "00", "chute.restart")):
        open(os.path.join(folder, restart), "w").write("a restart the report must not copy\n")
    shutil.copy(os.path.join(folder, "flow.time"), leg)
    with open(os.path.join(leg, "log.lammps"), "w") as out:
        out.write("Loop time of 400 on 1 procs for 40000 steps with 3967 atoms\n\n100.0% CPU use with 1 MPI tasks\n"
                  + (SOLVER_LINE if health else ""))
    with open(os.path.join(leg, "command.sh"), "w") as out:
        out.write(f"#!/bin/sh\n# synthetic leg of {name}\n")
    open(os.path.join(folder, "DONE"), "w").close()


def write_campaign(campaign):
    # theta 22: the layer stopped (it creeps); theta 28 is left unstarted.
    write_run(campaign, "mu0.5_theta22_L45", 22, 0.0, 15.0, u=STOPPED_U, h=H_STOP)
    for theta in range(23, 28):
        write_run(campaign, f"mu0.5_theta{theta}_L45", theta, 0.0, 15.0 + theta - 22)
    write_run(campaign, UNRECORDED, 24, REPLICA_SHIFT, 17.0, record=False)
    # The layer reading: a thinner layer on the same rule (the others of its series are unstarted).
    for theta in LAYER_ANGLES:
        write_run(campaign, f"mu0.5_theta{theta}_L45_layer", theta, 0.0, 15.0 + theta - 22, h=H_LAYER)


def read_csv(path):
    with open(path, newline="") as src:
        return {row["name"]: row for row in csv.DictReader(src)}


def write_comparison(folder):
    """A rigid/soft comparison as reference/run_comparison.sh leaves it: cdref's table.csv, each
    value column followed by its error column."""
    os.makedirs(os.path.join(folder, "comparison"))
    with open(os.path.join(folder, "comparison", "table.csv"), "w") as out:
        out.write("run,label,code,overlap_target_d,error,U_sqrt(g d),error,phi,error,f_Hz,error,"
                  "cpu_per_physical_s_s/s,error\n")
        out.write("runs/rigid,rigid tol 1e-3,lmp_cd,,,24.67146,0.04768,0.75299,0.00046,21.64,4.39,184.06,\n")
        out.write("runs/soft,granular hooke 1e-3,lammps-granular,0.001,,27.8237,0.0513,0.74780,0.00039,19.07,4.14,"
                  "364.8,\n")


def report(cdpost, campaign, results, *more):
    cmd = [sys.executable, RUNNER, "--out", campaign, "--cdpost", cdpost, "--report", results, *more] + SERIES_ARGS
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    check(done.returncode == 0, "--report failed:\n" + done.stdout + done.stderr)
    return "\n".join(open(os.path.join(results, page)).read() for page in PAGES)


def run_folders(results):
    """The published runs' folders of results/runs (beside its README.md)."""
    folder = os.path.join(results, "runs")
    return sorted(name for name in os.listdir(folder) if os.path.isdir(os.path.join(folder, name)))


def check_within(fits, name, truth, sigmas=3.0):
    check(name in fits, f"fits.csv has no {name}")
    value, error = float(fits[name]["value"]), float(fits[name]["error"] or 0)
    check(abs(value - truth) <= sigmas * error + 1e-3 * abs(truth),
          f"{name} = {value} ± {error}, expected {truth}")


def check_readings(results, readme):
    """Both readings side by side: each reading's fits as its own series analysis made them, the
    difference in units of the combined error, and the comparison's figures in the README."""
    fits = {name: read_csv(os.path.join(results, "series", analysis, "fits.csv"))
            for name, analysis in (("count", "flow_rules"), ("layer", "layer_flow_rules"))}
    with open(os.path.join(results, "series", "readings", "compared_fits.csv"), newline="") as src:
        compared = {row["name"]: row for row in csv.DictReader(src)}
    for reading, own in fits.items():
        check(set(own) <= set(compared), f"the comparison lacks {reading} fits: {sorted(set(own) - set(compared))}")
        for name, row in own.items():
            check(float(compared[name][reading]) == float(row["value"]),
                  f"{name}: {reading} {compared[name][reading]} in the comparison, {row['value']} alone")
    # The layer's runs follow the same phi(U) law: k within the errors of both.
    row = compared["phi_k"]
    count, layer = float(row["count"]), float(row["layer"])
    combined = math.hypot(float(row["count_error"]), float(row["layer_error"]))
    difference = (layer - count) / combined
    rounding = 1e-9 * (abs(count) + abs(layer)) / combined      # of values written to 10 digits
    check(abs(float(row["difference_sigma"]) - difference) < rounding and abs(difference) < 3,
          f"phi_k differs by {row['difference_sigma']} sigma, expected {difference!r} (same law)")
    section = readme[readme.find("## Two readings of the 45 d cell"):]
    line = next((r for r in section.splitlines() if r.startswith("| phi_k |")), "")
    check(f"| {difference:+.1f} |" in line, "the readings' table has no phi_k with its difference:\n" + section[:1500])
    check("![U_vs_theta](readings/figures/U_vs_theta.png)" in section
          and "![phi_vs_I](readings/figures/phi_vs_I.png)" in section,
          "the readings' figures are not shown:\n" + section[:1500])
    # Per friction, the layer's thickness in each reading and their difference at the same angles:
    # H_LAYER - H at each of LAYER_ANGLES, with the standard error of those differences.
    h_of = {name: float(read_csv(os.path.join(results, "runs", name, "results.csv"))["h"]["value"])
            for name in run_folders(results)}
    differences = [h_of[f"mu0.5_theta{t}_L45_layer"] - h_of[f"mu0.5_theta{t}_L45"] for t in LAYER_ANGLES]
    mean = sum(differences) / len(differences)
    error = math.sqrt(sum((d - mean) ** 2 for d in differences) / (len(differences) - 1) / len(differences))
    check(abs(mean - (H_LAYER - H)) < 0.05 * (H - H_LAYER), f"h differs by {mean} between readings, expected "
          f"{H_LAYER - H}")
    line = next((r for r in section.splitlines() if r.startswith("| h (d) | 0.5 |")), "")
    shown = re.search(r"\| (-?[0-9.]+)(?: ± ([0-9.]+))? \((\d+) angles\) \|$", line)   # no ± when all agree
    check(shown and int(shown.group(3)) == len(LAYER_ANGLES)
          and abs(float(shown.group(1)) - mean) <= 1e-3 * abs(mean) + error
          and abs(float(shown.group(2) or 0) - error) <= 0.05 * error,
          f"the readings' h difference is not {mean} ± {error} over {LAYER_ANGLES}:\n{line}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cdpost", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    campaign, results = os.path.join(work, "campaign"), os.path.join(work, "results")
    try:
        write_campaign(campaign)
        os.makedirs(results)
        shutil.copy(os.path.join(TOP, "results", "source.csv"), results)
        readme = report(os.path.abspath(args.cdpost), campaign, results)

        analysed = run_folders(results)
        check(len(analysed) == 10, f"results/runs holds {analysed}, expected the 10 finished runs")
        for name in analysed:
            check(os.path.exists(os.path.join(results, "runs", name, "results.csv")), f"{name}: no results.csv")
        check("| mu0.5_theta28_L45 |" in readme and "not started" in readme,
              "the unstarted run is not listed with its state")
        # cdpost reads a run's chute.params; a run without one gets the campaign's variables.
        log = open(os.path.join(campaign, "runs", "mu0.5_theta23_L45", "cdpost.log")).read()
        check("--z0" not in log.splitlines()[0] and "parameters: z0 0.015 m, sample rate 1000 Hz, d 0.0005 m, g 9.81 "
              "m/s^2, L 45 d from " in log, "cdpost did not take the run's chute.params:\n" + log[:400])
        log = open(os.path.join(campaign, "runs", UNRECORDED, "cdpost.log")).read()
        check("parameters: z0 0.015 m from --z0; sample rate 1000 Hz from --sample-rate; d 0.0005 m from --d; "
              "g 9.81 m/s^2 from --g" in log, "the run without chute.params did not get the campaign's variables:\n"
              + log[:400])
        big = [os.path.join(d, f) for d, _, files in os.walk(results) for f in files
               if "restart" in f or f.startswith("dump") or os.path.getsize(os.path.join(d, f)) > 2_000_000]
        check(not big, f"results/ holds restarts, dumps or large files: {big}")

        manifest = open(os.path.join(results, "series", "flow_rules", "manifest.csv")).read()
        check(f"/mu0.5_theta22_L45,0.5,22,1,{H_STOP:g}\n" in manifest,
              "the stopped run is not a stopped row with its h_stop:\n" + manifest)
        check(manifest.count(",0,\n") == 5, "the five flowing runs are not flowing rows:\n" + manifest)
        fits = read_csv(os.path.join(results, "series", "flow_rules", "fits.csv"))
        check_within(fits, "muI_I0", I0)
        check_within(fits, "muI_theta1_mu0.5", THETA1)
        check_within(fits, "muI_theta2_mu0.5", THETA2)
        check_within(fits, "phi_k", K)
        check_within(fits, "phi_c_mu0.5", PHI_C)
        check("![U_vs_theta](flow_rules/figures/U_vs_theta.png)" in readme, "the flow-rule figure is not shown")
        # The source's numbers (results/source.csv) compared by cdpost series --source, in the README.
        source = readme[readme.find("## Against the source"):]
        check("## Against the source" in readme and "(source.csv)" in source
              and "\n| phi_c of phi = phi_c - k U, mu 0.5 | 0.826 | " in source
              and "\n| Pouliquen's rule (beta = 0.136) as a curve, mu 0.5 | 0 deg | theta - theta_source(I): " in source
              and os.path.exists(os.path.join(results, "series", "readings", "source_comparison.csv")),
              "the comparison with the source is not in the README:\n" + source[:1500])

        check_readings(results, readme)

        # The replica pair differs by REPLICA_SHIFT in U (each run's own noise is ~1e-3 of it).
        line = next((row for row in readme.splitlines() if row.startswith("| U |")), None)
        check(line is not None, "no replica scatter of U in the README")
        scatter = float(line.split("|")[2])
        expected = REPLICA_SHIFT / math.sqrt(2)
        check(abs(scatter - expected) < 0.05 * expected, f"replica scatter of U {scatter}, expected {expected:.3g}")

        # A run a verdict counts without its solver health: --report refuses, in one line naming it,
        # and writes nothing; --count-without-health counts it, flagged.
        unhealthy = "mu0.5_theta26_L45"
        shutil.rmtree(os.path.join(campaign, "runs", unhealthy))
        write_run(campaign, unhealthy, 26, 0.0, 19.0, health=False)
        before = open(os.path.join(results, "README.md")).read()
        cmd = [sys.executable, RUNNER, "--out", campaign, "--cdpost", os.path.abspath(args.cdpost), "--report",
               results] + SERIES_ARGS
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        lines = done.stderr.strip().splitlines()
        check(done.returncode == 2 and len(lines) == 1 and lines[0].startswith("refusing to count 1 runs without "
              f"solver health (no evidence run of their friction and reading: {unhealthy})"),
              "a run without health was not refused in one line:\n" + done.stdout + done.stderr)
        check(open(os.path.join(results, "README.md")).read() == before, "a refused report wrote its README")
        flagged = report(os.path.abspath(args.cdpost), campaign, results, "--count-without-health")
        check("solver health not recorded for 1 of" in flagged and f"| {unhealthy} |" in flagged,
              "--count-without-health did not count the run, flagged")
        shutil.rmtree(os.path.join(campaign, "runs", unhealthy))
        write_run(campaign, unhealthy, 26, 0.0, 19.0)
        report(os.path.abspath(args.cdpost), campaign, results)

        # A run whose raw outputs are gone is read back from results/runs: same table, same fits.
        lost = "mu0.5_theta25_L45"
        shutil.rmtree(os.path.join(campaign, "runs", lost))
        fits_before = open(os.path.join(results, "series", "flow_rules", "fits.csv")).read()
        readme = report(os.path.abspath(args.cdpost), campaign, results)
        check(f"| {lost} |" in readme and "published (raw outputs not here)" in readme,
              "the run without raw outputs is not listed as published")
        check(open(os.path.join(results, "series", "flow_rules", "fits.csv")).read() == fits_before,
              "the series fits changed when a run was read back from its published results")
        check("## Changed by this report" not in readme, "an unchanged re-analysis reported changes")
        # A published number that the analysis does not reproduce (an earlier cdpost, say) is
        # replaced, and the report says which, with the value it had.
        fits_path = os.path.join(results, "series", "flow_rules", "fits.csv")
        published = fits_before.replace("\nmuI_I0,", "\nmuI_I0,9", 1)
        check(published != fits_before, "no muI_I0 row to alter")
        open(fits_path, "w").write(published)
        changed = report(os.path.abspath(args.cdpost), campaign, results)
        changes_page = open(os.path.join(results, "changes.md")).read()
        rows = [r for r in changes_page.splitlines() if r.startswith("| series/flow_rules/fits.csv | muI_I0 | 9")]
        check("## Changed by this report" in changed and "[changes.md](changes.md)" in changed and len(rows) == 1,
              "a changed published fit was not reported:\n" + changed[:1500] + "\n" + changes_page[:1500])
        check(open(fits_path).read() == fits_before, "the altered fit was not replaced by the analysis")
        manifest = open(os.path.join(results, "series", "flow_rules", "manifest.csv")).read()
        check(f"\n../../runs/{lost},0.5,25,0,\n" in manifest, "the manifest does not list the published run:\n"
              + manifest)

        # A finished run whose params.json records other deck variables than the report's is
        # not used, and says why; a run that records none is analysed with the report's.
        recorded = os.path.join(campaign, "runs", "mu0.5_theta23_L45", "params.json")
        shutil.copy(os.path.join(results, "runs", "mu0.5_theta23_L45", "params.json"), recorded)
        other = report(os.path.abspath(args.cdpost), campaign, os.path.join(work, "results_other"),
                       "--var", "tolerance=1e-4")
        rows = {}                       # the runs table: each run's first row
        for line in other.splitlines():
            if line.startswith("| mu0.5_"):
                rows.setdefault(line.split("|")[1].strip(), line)
        check("analysed run not used: tolerance 1.0e-3 -> 1e-4" in rows["mu0.5_theta23_L45"],
              "a run made with another tolerance was used:\n" + rows["mu0.5_theta23_L45"])
        check(rows["mu0.5_theta24_L45"].rstrip().endswith("| analysed |"),
              "a run that records no deck variables was not analysed:\n" + rows["mu0.5_theta24_L45"])

        # A stationary window shorter than --min-window-seconds reopens the run, longer by --extend.
        cmd = [sys.executable, RUNNER, "--out", campaign, "--cdpost", "none", "--lmp", "/bin/false",
               "--min-window-seconds", "5", "--max-duration", "12"] + SERIES_ARGS
        rerun = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        check("mu0.5_theta24_L45: stationary window 4.00 s, extended to 12 s" in rerun.stdout,
              "a run with a 4 s window was not extended:\n" + rerun.stdout + rerun.stderr)
        params = json.load(open(os.path.join(campaign, "runs", "mu0.5_theta24_L45", "params.json")))
        check(params["vars"]["duration"] == "12", f"duration after the extension: {params['vars']['duration']}")

        path = os.path.join(results, "README.md")
        text = open(path).read().replace("(no discussion yet)", "The flows follow the rule they were made with.")
        open(path, "w").write(text)
        comparison = os.path.join(work, "mu0.5-theta24")
        write_comparison(comparison)
        again = report(os.path.abspath(args.cdpost), campaign, results, "--comparison", comparison)
        check("The flows follow the rule they were made with." in again, "the discussion was lost on regeneration")
        # The comparison's chosen columns, values with their errors, a column it lacks as '–'.
        check("| rigid tol 1e-3 | – | – | 24.671 ± 0.048 | 0.75299 ± 0.00046 | – | 21.6 ± 4.4 |" in again
              and "| granular hooke 1e-3 | 0.001 |" in again,
              "the rigid/soft table is not in the README:\n" + again[again.find("## Rigid against soft"):][:800])
        # A published run made with other deck variables is not taken for this one.
        other = report(os.path.abspath(args.cdpost), campaign, results, "--var", "tolerance=1e-4")
        check("published run not used: tolerance 1.0e-3 -> 1e-4" in other,
              "a published run with another tolerance was used:\n" + other[other.find("## The runs"):][:1500])
        check("| granular hooke 1e-3 | 0.001 |" in other,
              "a comparison published by an earlier report is no longer shown when --comparison is not given")
    except Failure as failure:
        print(f"FAILED report: {failure}")
        return 1
    print("report: 10 runs analysed, mu(I) and phi(U) recovered, both readings compared, replica scatter measured, "
          "discussion kept, rigid/soft table shown")
    return 0


if __name__ == "__main__":
    sys.exit(main())
