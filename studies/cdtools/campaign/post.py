"""cdpost on the campaign: each finished run, and the series analyses over the analysed runs."""

import math
import os
import shlex
import subprocess

from ..cdpost import RUN_RECORD, read_results
from .plan import ANALYSES

# A run whose flowing layer moves slower than this (sqrt(g d)) has stopped: it enters the
# series as a stopped row, its h the h_stop of its tilt (the flow rules' beta-free fit), not as a
# flowing point with I ~ 0. Flowing layers of the scene move at several sqrt(g d) or more.
STOPPED_U = 0.1


def wall_top(variables):
    """Height of the wall tops (m): cdpost's z0."""
    return float(variables["wall_height"]) * float(variables["d"])


def recorded_options(folders, variables):
    """cdpost's options for what a run folder's chute.params records: none when every folder
    holds one (cdpost reads them), else the deck variables the runs were made with (runs made
    before the deck wrote the record, or published runs, which do not need it)."""
    if all(os.path.exists(os.path.join(folder, RUN_RECORD)) for folder in folders):
        return []
    return ["--d", variables["d"], "--g", variables["g"], "--sample-rate", variables["sample_rate"],
            "--z0", repr(wall_top(variables)), "--cell-length", variables["L"]]


def creep_depth_option(variables):
    """cdpost's --creep-depth for a bed between walls other than its default 30 d: the creep
    measure then reads the whole bed (doc/creep.md)."""
    walls = variables.get("wall_height", "30")
    return [] if float(walls) == 30 else ["--creep-depth", str(walls)]


def run_logged(cmd, log):
    """Runs cmd; its command line and output go to `log`. Returns (ok, last line of its
    standard error)."""
    result = subprocess.run(cmd, capture_output=True, text=True)
    with open(log, "w") as out:
        out.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + result.stdout + result.stderr)
    return result.returncode == 0, (result.stderr.strip().splitlines() or [""])[-1]


def postprocess_run(job, cdpost, args):
    """cdpost run on a finished run. Returns (ok, message); 'not stationary' is reported."""
    # The run's wall tops and sample rate (the spectra's grid even where a leg ran at a refined step
    # throughout) come from its chute.params, or from its variables.
    cmd = [cdpost, "run", job.folder] + recorded_options([job.folder], job.vars) + \
        ["--dump", os.path.join(job.folder, "dump.chute.gz")] + creep_depth_option(job.vars)
    return run_logged(cmd + args.cdpost_option, os.path.join(job.folder, "cdpost.log"))


def window_bounds(results, variables):
    """(start, end) in s of the stationary window in cdpost's results (given in sqrt(d/g)),
    or None."""
    start, end = results.get("t_start"), results.get("t_end")
    if not start or not end:
        return None
    unit = math.sqrt(float(variables["d"]) / float(variables["g"]))
    return start[0] * unit, end[0] * unit


def window_seconds(job):
    """Length (s) of the stationary window cdpost found in an analysed run, or None."""
    bounds = window_bounds(read_results(os.path.join(job.folder, "post", "results.csv")), job.vars)
    return bounds[1] - bounds[0] if bounds else None


def analysed(job):
    return job.kind == "run" and job.done and os.path.exists(os.path.join(job.folder, "post", "results.csv"))


def stopped_thickness(results_csv):
    """h (in d) of a run whose layer stopped (U < STOPPED_U), else None."""
    results = read_results(results_csv)
    u, h = results.get("U"), results.get("h")
    return h[0] if u and h and abs(u[0]) < STOPPED_U else None


def write_manifest(folder, analysis, runs):
    """<folder>/manifest.csv for cdpost series: one row per run given as (the folder cdpost reads:
    raw outputs or published results, its results.csv, its deck variables), the folder relative to
    the manifest, mu, theta (and L where it varies: cdpost correlates the results with L when it is
    given), and whether the layer stopped, with its thickness then."""
    with_length = len({variables["L"] for _, _, variables in runs}) > 1
    manifest = os.path.join(folder, "manifest.csv")
    with open(manifest, "w") as out:
        out.write(f"# {analysis}: run folders relative to this file\n")
        out.write("run,mu,theta" + (",L" if with_length else "") + ",stopped,h_stop\n")
        for run_folder, results_csv, variables in runs:
            h_stop = stopped_thickness(results_csv)
            out.write(f"{os.path.relpath(run_folder, folder)},{variables['mu']},{variables['theta']}"
                      + (f",{variables['L']}" if with_length else "")
                      + (f",1,{h_stop:.6g}" if h_stop is not None else ",0,") + "\n")
    return manifest


def source_options(args):
    """--source for cdpost series: the source study's numbers, DIR/source.csv of --report when it
    holds one (as a path relative to the working directory, which the reports name)."""
    source = os.path.join(args.report, "source.csv") if getattr(args, "report", None) else None
    return ["--source", os.path.relpath(source)] if source and os.path.exists(source) else []


def run_series(analysis, manifest_folder, runs, cdpost, args, out=None):
    """cdpost series on `runs` (as write_manifest takes them), its manifest in manifest_folder and
    its outputs and log in `out` (default series-post beside the manifest). Returns whether it
    succeeded."""
    out = out or os.path.join(manifest_folder, "series-post")
    for folder in (manifest_folder, out):
        os.makedirs(folder, exist_ok=True)
    manifest = write_manifest(manifest_folder, analysis, runs)
    cmd = [cdpost, "series", manifest] + recorded_options([folder for folder, _, _ in runs], runs[0][2]) + \
        ["--out", out] + source_options(args) + args.cdpost_option
    ok, message = run_logged(cmd, os.path.join(out, "cdpost.log"))
    print(f"series {analysis}: {len(runs)} runs, cdpost series {'done' if ok else 'failed: ' + message}", flush=True)
    return ok


def run_comparison(manifests, labels, cdpost, args, out):
    """cdpost series on the first manifest with --compare the second (the two series side by side,
    each fitted as alone), labelled `labels`, its outputs and log in `out`. Returns whether it
    succeeded."""
    os.makedirs(out, exist_ok=True)
    cmd = [cdpost, "series", manifests[0], "--compare", manifests[1], "--labels", ",".join(labels),
           "--out", out] + source_options(args) + args.cdpost_option
    ok, message = run_logged(cmd, os.path.join(out, "cdpost.log"))
    print(f"comparison {' / '.join(labels)}: cdpost series --compare {'done' if ok else 'failed: ' + message}",
          flush=True)
    return ok


def postprocess_series(jobs, cdpost, args):
    """cdpost series on every analysis (ANALYSES) that has two analysed runs, from their raw
    outputs (the campaign's own progress view; --report makes the published series)."""
    for analysis, belongs in ANALYSES.items():
        runs = [(j.folder, os.path.join(j.folder, "post", "results.csv"), j.vars)
                for j in jobs if analysed(j) and belongs(j)]
        if len(runs) >= 2:
            run_series(analysis, os.path.join(args.out, "series", analysis), runs, cdpost, args)
