"""cdpost on the campaign: each finished run, and the series analyses over the analysed runs."""

import os
import shlex
import subprocess

from .plan import ANALYSES


def wall_top(variables):
    """Height of the wall tops (m): cdpost's z0."""
    return float(variables["wall_height"]) * float(variables["d"])


def run_logged(cmd, log):
    """Runs cmd; its command line and output go to `log`. Returns (ok, last line of its
    standard error)."""
    result = subprocess.run(cmd, capture_output=True, text=True)
    with open(log, "w") as out:
        out.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + result.stdout + result.stderr)
    return result.returncode == 0, (result.stderr.strip().splitlines() or [""])[-1]


def postprocess_run(job, cdpost, args):
    """cdpost run on a finished run. Returns (ok, message); 'not stationary' is reported."""
    cmd = [cdpost, "run", job.folder, "--d", job.vars["d"], "--g", job.vars["g"],
           "--z0", repr(wall_top(job.vars)), "--dump", os.path.join(job.folder, "dump.chute.gz")]
    return run_logged(cmd + args.cdpost_option, os.path.join(job.folder, "cdpost.log"))


def analysed(job):
    return job.kind == "run" and job.done and os.path.exists(os.path.join(job.folder, "post", "results.csv"))


def write_manifest(folder, analysis, runs):
    """series/<analysis>/manifest.csv: the runs' folders relative to it, mu, theta (and L where
    it varies: cdpost correlates the results with L when it is given)."""
    with_length = len({j.vars["L"] for j in runs}) > 1
    manifest = os.path.join(folder, "manifest.csv")
    with open(manifest, "w") as out:
        out.write(f"# {analysis}: run folders relative to this file\n")
        out.write("run,mu,theta" + (",L" if with_length else "") + "\n")
        for j in runs:
            rel = os.path.relpath(j.folder, folder)
            out.write(f"{rel},{j.vars['mu']},{j.vars['theta']}" + (f",{j.vars['L']}" if with_length else "") + "\n")
    return manifest


def postprocess_series(jobs, cdpost, args):
    """cdpost series on every analysis (ANALYSES) that has two analysed runs."""
    for analysis, belongs in ANALYSES.items():
        runs = [j for j in jobs if analysed(j) and belongs(j)]
        if len(runs) < 2:
            continue
        folder = os.path.join(args.out, "series", analysis)
        os.makedirs(folder, exist_ok=True)
        manifest = write_manifest(folder, analysis, runs)
        cmd = [cdpost, "series", manifest, "--z0", repr(wall_top(runs[0].vars))] + args.cdpost_option
        ok, message = run_logged(cmd, os.path.join(folder, "cdpost.log"))
        print(f"series {analysis}: {len(runs)} runs, cdpost series {'done' if ok else 'failed: ' + message}",
              flush=True)
