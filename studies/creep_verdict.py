#!/usr/bin/env python3
"""The creep length: the grains' or the cell's (issue 63, item 3), the verdict that doc/creep.md
(*Grains or cell*) states before its runs, made from the runs of the campaign's analysis
`creep_length` (studies/cdtools/campaign/plan.py) that exist.

Per friction (mu 0.5 at 22 deg, mu 2 at 28 deg) and per estimator (lambda_1, cdpost series'
creep_lambda_first_decade; lambda_f, cdpost run's creep_lambda): ln lambda = ln c + a ln L by
least squares over every run, each rain a point, a's error from the scatter about the line; runs
whose lambda is unresolved are left out and named; the cell's if a > 2 errors, the grains' if
|a| <= 2 errors. The walls: lambda at L 45 between 15, 30 and 60 d walls (mean and scatter of the
rains), 15 - 30 and 60 - 30 in combined errors; at L 102 and 152 the 60 d bed against the 30 d
one. The coherence test (doc/creep.md, *The coherence test*): A sqrt(L/d) and the coherence of v
at the peak across the cell against L.

Where the runs are: a campaign folder given by --runs (RUNS/runs/<name>/post, a finished run
analysed by cdpost run), else the published runs of PUBLISHED (the L series and the 45 d mu 0.5
run from results/runs; the 45 d mu 2 run only from the count reading's converged re-run,
results/rerun/count_mu2, the published one being capped at 1000 sweeps; the creep series' runs
committed to results/rerun/creep_length). A run found nowhere is
listed as missing; no number stands in for it. lambda_1 is cdpost series' over the runs found
(a manifest and its outputs in --work).

    studies/creep_verdict.py --runs RUNS --cdpost build/postproc/cdpost --out results/series/creep_length

Writes OUT/verdict.md, OUT/verdict_runs.csv (every run of the analysis, found or missing),
OUT/verdict_fits.csv (a per friction and estimator), OUT/verdict_walls.csv and
OUT/verdict_coherence.csv. Standard library and cdpost.
"""

import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from cdtools.cdpost import find_cdpost, read_results
from cdtools.campaign.plan import ANALYSES, CREEP_SERIES, build_jobs
from cdtools.run import TOP
from cdtools.stats import mean_sd_se
from cdtools.text import markdown_table, number, with_error

FRICTIONS = ((0.5, 22.0), (2.0, 28.0))
ESTIMATORS = (("lambda_1", "creep_lambda_first_decade"), ("lambda_f", "creep_lambda"))
# Published runs read where no campaign folder holds the run: (folder under the repository, series).
PUBLISHED = (("results/runs", ("L", "mu0.5")), ("results/rerun/count_mu2", ("mu2",)),
             ("results/rerun/creep_length", CREEP_SERIES))
COHERENCE_ROWS = ("coherence_length", "coherence_plateau", "coherence_far", "oscillation_pattern", "A", "A_mean")
PATTERNS = {1: "uniform", 2: "standing", 3: "travelling", 4: "local"}
SOURCE_WALLS = 30.0
WALL_LENGTH = 45.0
DEEP_LENGTHS = (102.0, 152.0)


class Run:
    """One run of the analysis: its point, where it was found (None: missing) and its numbers."""

    def __init__(self, name, series, variables):
        self.name, self.series = name, series
        self.mu, self.theta, self.L = float(variables["mu"]), float(variables["theta"]), float(variables["L"])
        self.walls = float(variables.get("wall_height", SOURCE_WALLS))
        self.seed = variables.get("seed", "")
        self.folder, self.source, self.state = None, "", "not found in the folders given"
        self.values = {}          # name -> (value, error or None)

    def get(self, name):
        return self.values.get(name)


def expected_runs():
    """The runs of the analysis creep_length, as the campaign lists them (plan.py)."""
    args = argparse.Namespace(series=list(CREEP_SERIES) + ["L", "mu0.5", "mu2"], only=None, var={}, run_var=[],
                              duration=10, out=os.path.join(tempfile.gettempdir(), "creep-verdict-none"))
    belongs = ANALYSES["creep_length"]
    return [Run(job.name, job.series, job.vars) for job in build_jobs(args) if job.kind == "run" and belongs(job)]


def locate(run, campaigns, root):
    """Sets where the run's analysed results are: a finished run of a campaign folder, else its
    published run (PUBLISHED); else its state ('running or pending in RUNS', or not found)."""
    for campaign in campaigns:
        folder = os.path.join(campaign, "runs", run.name)
        if os.path.exists(os.path.join(folder, "DONE")) and os.path.exists(os.path.join(folder, "post", "results.csv")):
            run.folder, run.source, run.state = os.path.join(folder, "post"), folder, "analysed"
            return
        if os.path.isdir(os.path.join(folder, "legs")):
            run.state = "running or pending in " + campaign
    for published, series in PUBLISHED:
        folder = os.path.join(root, published, run.name)
        if run.series in series and os.path.exists(os.path.join(folder, "results.csv")):
            run.folder, run.source, run.state = folder, published, "published"
            return


def measure(runs, cdpost, work):
    """Each found run's numbers: its results.csv (creep_lambda, the coherence rows) and cdpost
    series' runs.csv over them all (creep_lambda_first_decade). Returns cdpost's failure or ''."""
    found = [r for r in runs if r.folder]
    for r in found:
        results = read_results(os.path.join(r.folder, "results.csv"))
        r.values = {k: (v[0], v[1]) for k, v in results.items() if math.isfinite(v[0])}
    if len(found) < 1:
        return ""
    os.makedirs(work, exist_ok=True)
    manifest = os.path.join(work, "manifest.csv")
    with open(manifest, "w") as out:
        out.write("# creep_length: the runs the verdict found\nrun,mu,theta,L,stopped,h_stop\n")
        for r in found:
            out.write(f"{os.path.abspath(r.folder)},{r.mu:g},{r.theta:g},{r.L:g},0,\n")
    series = os.path.join(work, "series")
    result = subprocess.run([cdpost, "series", manifest, "--out", series], capture_output=True, text=True)
    with open(os.path.join(work, "cdpost.log"), "w") as log:
        log.write(result.stdout + result.stderr)
    if result.returncode != 0:
        return "cdpost series failed: " + (result.stderr.strip().splitlines() or [""])[-1]
    with open(os.path.join(series, "runs.csv"), newline="") as src:
        rows = {os.path.normpath(row["run"]): row for row in csv.DictReader(src)}
    for r in found:
        row = rows.get(os.path.normpath(os.path.abspath(r.folder)), {})
        value, error = row.get("creep_lambda_first_decade", ""), row.get("creep_lambda_first_decade_error", "")
        r.values.pop("creep_lambda_first_decade", None)
        if value:
            r.values["creep_lambda_first_decade"] = (float(value), float(error) if error else None)
    return ""


def power_law(points):
    """ln y = ln c + a ln x by least squares over (x, y): (a, error of a, c, n); the error from
    the scatter about the line (None with fewer than 3 points or x all equal)."""
    n = len(points)
    if n < 3 or len({x for x, _ in points}) < 2:
        return None
    xs, ys = [math.log(x) for x, _ in points], [math.log(y) for _, y in points]
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    a = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    residual = sum((y - my - a * (x - mx)) ** 2 for x, y in zip(xs, ys))
    return a, math.sqrt(residual / (n - 2) / sxx), math.exp(my - a * mx), n


def verdict_of(a, error):
    """The verdict's form of doc/creep.md."""
    if a > 2 * error:
        return "cell's"
    if abs(a) <= 2 * error:
        return "grains'"
    return "neither: falls with L beyond two errors"


def friction_runs(runs, mu, theta):
    return [r for r in runs if r.mu == mu and r.theta == theta]


def fits(runs):
    """[dict] per friction and estimator: the law in L over the runs between the source's 30 d walls
    (the other walls are tested apart, walls())."""
    rows = []
    for mu, theta in FRICTIONS:
        cell = [r for r in friction_runs(runs, mu, theta) if r.walls == SOURCE_WALLS]
        for label, name in ESTIMATORS:
            found = [r for r in cell if r.folder]
            used = [r for r in found if r.get(name) and r.get(name)[0] > 0]
            unresolved = [r.name for r in found if r not in used]
            missing = [r.name for r in cell if not r.folder]
            law = power_law([(r.L, r.get(name)[0]) for r in used])
            row = dict(mu=mu, theta=theta, estimator=label, result=name, runs=len(used),
                       lengths=len({r.L for r in used}), unresolved=" ".join(unresolved), missing=" ".join(missing))
            if law:
                a, error, c, n = law
                row.update(a=a, a_error=error, c=c, verdict=verdict_of(a, error),
                           sigmas=a / error if error > 0 else math.inf)
            else:
                row.update(a=None, a_error=None, c=None, verdict="not decided: fewer than 3 runs at 2 lengths",
                           sigmas=None)
            rows.append(row)
    return rows


def group(runs, name):
    """(mean, sd, se, n) of `name` over the found runs that resolve it."""
    values = [r.get(name)[0] for r in runs if r.folder and r.get(name) and r.get(name)[0] > 0]
    mean, sd, se = mean_sd_se(values)
    return mean, sd, se, len(values)


def walls(runs):
    """[dict]: at L 45 (mu 0.5, 22 deg) lambda between 15, 30 and 60 d walls and the differences to
    30 d in combined errors (standard errors of the rains); at L 102 and 152 the 60 d bed against
    the 30 d one (one run each: the fits' own errors)."""
    rows = []
    at45 = [r for r in friction_runs(runs, *FRICTIONS[0]) if r.L == WALL_LENGTH]
    for label, name in ESTIMATORS:
        groups = {w: group([r for r in at45 if r.walls == w], name) for w in (15.0, SOURCE_WALLS, 60.0)}
        for w, (mean, sd, se, n) in groups.items():
            reference = groups[SOURCE_WALLS]
            combined = math.hypot(se, reference[2]) if w != SOURCE_WALLS else math.nan
            difference = mean - reference[0] if w != SOURCE_WALLS else math.nan
            rows.append(dict(estimator=label, L=WALL_LENGTH, walls=w, runs=n, mean=mean, sd=sd, se=se,
                             difference=difference, combined_error=combined,
                             sigmas=difference / combined if combined > 0 else math.nan,
                             missing=" ".join(r.name for r in at45 if r.walls == w and not r.folder)))
        for length in DEEP_LENGTHS:
            pair = {w: [r for r in friction_runs(runs, *FRICTIONS[0]) if r.L == length and r.walls == w]
                    for w in (SOURCE_WALLS, 60.0)}
            for w in (SOURCE_WALLS, 60.0):
                run = pair[w][0] if pair[w] else None
                value = run.get(name) if run and run.folder else None
                row = dict(estimator=label, L=length, walls=w, runs=int(bool(value)),
                           mean=value[0] if value else math.nan, sd=math.nan,
                           se=(value[1] or math.nan) if value else math.nan, difference=math.nan,
                           combined_error=math.nan, sigmas=math.nan,
                           missing=run.name if run and not run.folder else "",
                           resolved="" if not (run and run.folder) else ("yes" if value else "no"))
                if w == 60.0 and value and pair[SOURCE_WALLS] and pair[SOURCE_WALLS][0].get(name):
                    ref = pair[SOURCE_WALLS][0].get(name)
                    combined = math.hypot(value[1] or 0, ref[1] or 0)
                    row.update(difference=value[0] - ref[0], combined_error=combined,
                               sigmas=(value[0] - ref[0]) / combined if combined > 0 else math.nan)
                rows.append(row)
    return rows


# The coherence test's thresholds (doc/creep.md, *The coherence test*).
ONE_MODE_PLATEAU = 0.5


def coherence(runs):
    """(rows, verdicts): per found run its A sqrt(L/d), A_mean sqrt(L/d) and coherence rows; per
    friction the exponents of A and A_mean on L and the verdict of doc/creep.md."""
    rows, verdicts = [], []
    for mu, theta in FRICTIONS:
        found = [r for r in friction_runs(runs, mu, theta) if r.folder and r.walls == SOURCE_WALLS]
        for r in sorted(found, key=lambda r: (r.L, r.name)):
            a, a_mean = r.get("A"), r.get("A_mean")
            xi, plateau, far, pattern = (r.get(k) for k in COHERENCE_ROWS[:4])
            rows.append(dict(run=r.name, mu=mu, theta=theta, L=r.L, A=a[0] if a else math.nan,
                             A_sqrt_L=a[0] * math.sqrt(r.L) if a else math.nan,
                             A_mean=a_mean[0] if a_mean else math.nan,
                             A_mean_sqrt_L=a_mean[0] * math.sqrt(r.L) if a_mean else math.nan,
                             coherence_length=xi[0] if xi else math.nan,
                             coherence_length_error=(xi[1] or math.nan) if xi else math.nan,
                             xi_over_L=xi[0] / r.L if xi else math.nan,
                             coherence_plateau=plateau[0] if plateau else math.nan,
                             coherence_far=far[0] if far else math.nan,
                             pattern=PATTERNS.get(int(pattern[0]), "") if pattern else "",
                             kind=coherence_kind(r)))
        laws = {name: power_law([(r.L, r.get(name)[0]) for r in found if r.get(name) and r.get(name)[0] > 0])
                for name in ("A", "A_mean")}
        verdicts.append(coherence_verdict(mu, theta, found, laws))
    return rows, verdicts


def coherence_kind(run):
    """'regions' (cdpost's pattern local: the coherence decays within the cell), 'one mode'
    (uniform, standing or travelling with the coherence left across the cell, the plateau, at
    least ONE_MODE_PLATEAU), 'between', or '' without columns.chunk analysed."""
    pattern, plateau = run.get("oscillation_pattern"), run.get("coherence_plateau")
    far = run.get("coherence_far")
    if not pattern:
        return ""
    if int(pattern[0]) == 4:
        return "regions"
    across = plateau[0] if plateau else (far[0] if far else math.nan)
    return "one mode" if across >= ONE_MODE_PLATEAU else "between"


def coherence_verdict(mu, theta, found, laws):
    kinds = {r.L: coherence_kind(r) for r in found if coherence_kind(r)}
    law = laws["A"]
    half = law is not None and abs(law[0] + 0.5) <= 2 * law[1]
    exponent = (f"A ∝ L^({with_error(law[0], law[1])}), {len(found)} runs" if law
                else "A against L: fewer than 3 runs at 2 lengths")
    if laws["A_mean"]:
        exponent += f"; A_mean ∝ L^({with_error(laws['A_mean'][0], laws['A_mean'][1])})"
    lengths = sorted(kinds)
    if len(lengths) < 2:
        verdict = (f"not decided: the coherence across the cell is analysed at {len(lengths)} cell length(s) "
                   "(columns.chunk; it needs 2)")
    elif all(kinds[L] == "regions" for L in lengths) and half:
        verdict = "independent regions"
    elif all(kinds[L] == "one mode" for L in lengths):
        verdict = "one mode"
    else:
        verdict = "neither: " + ", ".join(f"L {L:g} {kinds[L]}" for L in lengths) + \
            ("" if half else "; A not as L^-1/2")
    return dict(mu=mu, theta=theta, lengths_with_coherence=" ".join(f"{L:g}" for L in lengths),
                A_exponent=law[0] if law else math.nan, A_exponent_error=law[1] if law else math.nan,
                A_minus_half_consistent=half, text=exponent, verdict=verdict)


def estimate(value, error):
    """'value ± error' ('–' without a value; the value alone without a finite error)."""
    if value is None or not math.isfinite(value):
        return "–"
    return with_error(value, error if error is not None and math.isfinite(error) else None)


def cell(value, digits=4):
    return number(value, digits) if isinstance(value, (int, float)) and value is not None else (value or "–")


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(columns)
        for row in rows:
            writer.writerow(["" if row.get(c) is None or (isinstance(row.get(c), float) and not math.isfinite(row[c]))
                             else (f"{row[c]:.10g}" if isinstance(row[c], float) else row[c]) for c in columns])


def run_rows(runs):
    rows = []
    for r in runs:
        row = dict(run=r.name, series=r.series, mu=r.mu, theta=r.theta, L=r.L, walls=r.walls, seed=r.seed,
                   state=r.state, source=r.source)
        for label, name in ESTIMATORS:
            value = r.get(name)
            row[label] = value[0] if value else None
            row[label + "_error"] = value[1] if value else None
            row[label + "_resolved"] = "" if not r.folder else ("yes" if value else "no")
        rows.append(row)
    return rows


RUN_COLUMNS = ("run", "series", "mu", "theta", "L", "walls", "seed", "state", "source", "lambda_1", "lambda_1_error",
               "lambda_1_resolved", "lambda_f", "lambda_f_error", "lambda_f_resolved")
FIT_COLUMNS = ("mu", "theta", "estimator", "result", "runs", "lengths", "a", "a_error", "sigmas", "c", "verdict",
               "unresolved", "missing")
WALL_COLUMNS = ("estimator", "L", "walls", "runs", "mean", "sd", "se", "difference", "combined_error", "sigmas",
                "resolved", "missing")
COHERENCE_COLUMNS = ("run", "mu", "theta", "L", "A", "A_sqrt_L", "A_mean", "A_mean_sqrt_L", "coherence_length",
                     "coherence_length_error", "xi_over_L", "coherence_plateau", "coherence_far", "pattern", "kind")


def meaning(fit_rows, wall_rows, complete):
    """What the verdicts say of the source's 2.5 d (doc/creep.md, *The verdict's form*)."""
    first = [row for row in fit_rows if row["estimator"] == "lambda_1"]
    verdicts = {row["verdict"] for row in first}
    moved = [row for row in wall_rows if row["estimator"] == "lambda_1" and row["L"] == WALL_LENGTH
             and math.isfinite(row["sigmas"]) and abs(row["sigmas"]) > 2]
    walls_known = all(math.isfinite(row["sigmas"]) for row in wall_rows
                      if row["estimator"] == "lambda_1" and row["L"] == WALL_LENGTH and row["walls"] != SOURCE_WALLS)
    prefix = "" if complete else "Partial (runs missing, listed below): "
    if verdicts == {"grains'"} and walls_known and not moved:
        return prefix + ("λ_1 is the grains' at both frictions and the walls do not move it: the source's 2.5 d is "
                         "a material length, set against ours.")
    if verdicts == {"cell's"}:
        return prefix + ("λ_1 grows as L^a at both frictions: the comparison with the source holds at its 45 d cell "
                         "and 30 d walls only, and the source's 2.5 d is its cell's.")
    return prefix + ("the verdicts do not yet decide what the source's 2.5 d is: " +
                     "; ".join(f"mu {row['mu']:g} {row['verdict']}" for row in first) +
                     ("" if walls_known else "; the walls not yet measured") +
                     ("; the walls move λ_1" if moved else "") + ".")


def write_outputs(out, runs, fit_rows, wall_rows, coherence_rows, coherence_verdicts, command, failure=""):
    os.makedirs(out, exist_ok=True)
    write_csv(os.path.join(out, "verdict_runs.csv"), run_rows(runs), RUN_COLUMNS)
    write_csv(os.path.join(out, "verdict_fits.csv"), fit_rows, FIT_COLUMNS)
    write_csv(os.path.join(out, "verdict_walls.csv"), wall_rows, WALL_COLUMNS)
    write_csv(os.path.join(out, "verdict_coherence.csv"), coherence_rows, COHERENCE_COLUMNS)
    missing = [r for r in runs if not r.folder]
    complete = not missing and not failure
    text = ["# The creep length: grains or cell" + ("" if complete else " (partial)"), "",
            "Made by", "", "    " + command, "",
            "from the runs of the analysis `creep_length` (`studies/cdtools/campaign/plan.py`) found "
            f"({len(runs) - len(missing)} of {len(runs)}); the test and its verdict's form: `doc/creep.md`, *Grains or "
            "cell*. Errors are one standard error.", ""]
    if failure:
        text += ["**" + failure + "**", ""]
    if missing:
        text += [f"**Partial: {len(missing)} runs missing**, no number stands in for them: "
                 + ", ".join(f"{r.name} ({r.state})" for r in missing) + ".", ""]
    text += ["## ln λ = ln c + a ln L, per friction and estimator", "",
             "Least squares over every run between 30 d walls (each rain a point), a's error from the scatter "
             "about the line; the cell's if a > 2 errors, the grains' if |a| ≤ 2 errors.", "",
             markdown_table(["mu", "θ (°)", "estimator", "runs (lengths)", "a", "a / error", "c (d)", "verdict",
                             "unresolved, left out", "missing"],
                            [[f"{r['mu']:g}", f"{r['theta']:g}", r["estimator"], f"{r['runs']} ({r['lengths']})",
                              estimate(r["a"], r["a_error"]),
                              number(r["sigmas"], 3) if r["sigmas"] is not None else "–",
                              number(r["c"], 3) if r["c"] is not None else "–", r["verdict"],
                              r["unresolved"] or "–", r["missing"] or "–"] for r in fit_rows]),
             "**What it means for the source's 2.5 d.** " + meaning(fit_rows, wall_rows, complete), "",
             "## The walls", "",
             "At L 45 d (mu 0.5, 22°) the mean ± standard error of the rains between each wall height and its "
             "difference to 30 d in combined errors; at L 102 and 152 d the 60 d bed against the 30 d one (one run "
             "each, the fits' own errors).", "",
             markdown_table(["estimator", "L (d)", "walls (d)", "runs", "λ (d)", "sd of the rains",
                             "difference to 30 d", "in errors", "resolved", "missing"],
                            [[w["estimator"], f"{w['L']:g}", f"{w['walls']:g}", w["runs"],
                              estimate(w["mean"], w["se"]), cell(w["sd"], 3),
                              estimate(w["difference"], w["combined_error"]), cell(w["sigmas"], 3),
                              w.get("resolved") or "–", w["missing"] or "–"] for w in wall_rows]),
             "## The coherence test", "",
             "Per run with columns.chunk analysed (`doc/postproc_method.md`, *Along the cell*): A √(L/d), the "
             "coherence length ξ, the plateau (the coherence left across the cell) and the pattern; runs published "
             "without them show '–'. Per friction, A ∝ L^b over every run between 30 d walls, and the verdict of "
             "`doc/creep.md`, *The coherence test*.", "",
             markdown_table(["run", "L (d)", "A (√(gd))", "A √(L/d)", "A_mean √(L/d)", "ξ (d)", "ξ / L", "plateau",
                             "far", "pattern", "reads"],
                            [[c["run"], f"{c['L']:g}", cell(c["A"]), cell(c["A_sqrt_L"]), cell(c["A_mean_sqrt_L"]),
                              estimate(c["coherence_length"], c["coherence_length_error"]),
                              cell(c["xi_over_L"], 3), cell(c["coherence_plateau"], 3), cell(c["coherence_far"], 3),
                              c["pattern"] or "–", c["kind"] or "–"] for c in coherence_rows]),
             markdown_table(["mu", "θ (°)", "lengths with coherence", "A against L", "verdict"],
                            [[f"{v['mu']:g}", f"{v['theta']:g}", v["lengths_with_coherence"] or "–", v["text"],
                              v["verdict"]] for v in coherence_verdicts])]
    with open(os.path.join(out, "verdict.md"), "w") as page:
        page.write("\n".join(text))
    return complete


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", action="append", default=[], metavar="RUNS",
                        help="a campaign folder (its runs/<name>/post), repeatable, searched in order")
    parser.add_argument("--root", default=TOP, help="the repository, whose published runs are read (default: this one)")
    parser.add_argument("--cdpost", default=None, help="cdpost (default build/postproc/cdpost or PATH)")
    parser.add_argument("--out", default=os.path.join("results", "series", "creep_length"),
                        help="where the verdict's files go (default results/series/creep_length)")
    parser.add_argument("--work", default=None, help="cdpost series' manifest and outputs (default OUT/../work)")
    args = parser.parse_args(argv)
    cdpost = find_cdpost(args.cdpost)
    if cdpost is None:
        print("creep_verdict: no cdpost (build/postproc/cdpost, --cdpost)", file=sys.stderr)
        return 2
    runs = expected_runs()
    for r in runs:
        locate(r, args.runs, args.root)
    work = args.work or os.path.join(tempfile.gettempdir(), "creep_verdict_work")
    failure = measure(runs, cdpost, work)
    coherence_rows, coherence_verdicts = coherence(runs)
    fit_rows, wall_rows = fits(runs), walls(runs)
    command = " ".join(["studies/creep_verdict.py"] + (argv if argv is not None else sys.argv[1:]))
    complete = write_outputs(args.out, runs, fit_rows, wall_rows, coherence_rows, coherence_verdicts, command, failure)
    for row in fit_rows:
        a = estimate(row["a"], row["a_error"])
        print(f"mu {row['mu']:g} {row['estimator']}: a = {a} over {row['runs']} runs: {row['verdict']}")
    missing = [r.name for r in runs if not r.folder]
    print(f"{args.out}/verdict.md: " + ("complete" if complete else f"partial, {len(missing)} runs missing: "
                                        + ", ".join(missing)))
    if failure:
        print(failure, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
