"""results/ from a chute campaign (--report DIR): per run its cdpost results and commands, per
series the cdpost fits and figures, the two readings of the 45 d cell side by side, the replica
scatter, the rigid/soft comparisons, and README.md.

Every finished run is analysed (cdpost run) and published in results/runs/<name>; a run whose
raw outputs are not here is read back from what an earlier report published there. The series
analyses are then made from the published runs alone (results/series/<analysis>/manifest.csv
lists them), so results/ reproduces its fits without the raw outputs. Only small files are
written (CSV, JSON, Markdown, figures): no dumps, no restarts. A hand-written discussion between
the DISCUSSION markers of an existing README.md is kept; everything else is regenerated.
"""

import csv
import glob
import json
import math
import os
import re
import shlex
import shutil
import sys

from .. import page_numbers
from ..cdpost import read_results
from ..run import TOP
from ..stats import mean_sd_se, pooled_sd
from ..text import markdown_table, number, with_error
from .jobs import read_json
from .legs import run_cost
from .plan import ANALYSES, FLOW_SERIES, build_jobs, changed_vars, reading, same_value
from .post import postprocess_run, run_comparison, run_series, window_bounds
from .schedule import campaign_cdpost

DISCUSSION_BEGIN = "<!-- discussion: kept when the report is regenerated -->"
DISCUSSION_END = "<!-- end of discussion -->"

# Per-run files of cdpost run that results/ keeps (figures: the along-cell map and those the README shows).
RUN_FILES = ("results.csv", "results.json", "spectrum.csv", "profile.csv", "layers.csv", "coherence.csv",
             "figures/along_cell.png")   # space_time.csv (0.5 MB a run) stays with the raw outputs
SERIES_FILES = ("*.csv", "*.json", "report.md", "figures/*.png", "figures/*.svg")
COMPARISON_FILES = ("table.csv", "fits.csv", "report.md", "commands.txt", "figures/*.png", "figures/*.svg")
READINGS_FILES = ("compared_fits.csv", "source_comparison.csv", "report.md", "figures/*.png", "figures/*.svg")

# The per-run columns of the tables: (result name, heading).
FLOW_COLUMNS = (("U", "U (√(gd))"), ("phi", "φ"), ("h", "h (d)"), ("I", "I"))
OSCILLATION_COLUMNS = (("f", "f (Hz)"), ("A", "A (√(gd))"), ("A_mean", "A_mean (√(gd))"),
                       ("f_scale", "f_scale (Hz)"), ("shear_rate", "U/h (1/s)"))
PROFILE_COLUMNS = (("bagnold_slip", "slip (√(gd))"), ("bagnold_amplitude", "a (√(gd)/d^1.5)"),
                   ("bagnold_r2", "R²"), ("creep_lambda", "λ (d)"))
# Quantities whose scatter between two depositions the replicas measure.
REPLICA_QUANTITIES = ("U", "phi", "h", "f", "A", "A_mean", "creep_lambda")


def result_text(entry):
    """'value ± error' of a cdpost result (value, error, unit); '–' for none."""
    return "–" if entry is None else with_error(entry[0], entry[1])


def copy_matching(source, patterns, destination):
    """Copies the files of `source` matching `patterns` (relative globs) under `destination`;
    returns the relative paths copied."""
    copied = []
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(source, pattern))):
            relative = os.path.relpath(path, source)
            os.makedirs(os.path.dirname(os.path.join(destination, relative)), exist_ok=True)
            shutil.copy2(path, os.path.join(destination, relative))
            copied.append(relative)
    return copied


class RunRecord:
    """A run of the campaign as the report sees it: parameters, state, results, cost. Its results
    come from its own analysis (post/ of a finished run) or, when the raw outputs are not here
    (another machine, lost), from results/runs/<name> published by an earlier report, provided
    that run had the same deck variables."""

    def __init__(self, job, destination):
        self.name = job.name
        self.series = job.series
        self.folder = job.folder
        self.published = os.path.join(destination, "runs", job.name)
        self.source, self.state, recorded_in = self._choose_source(job)
        if self.source == self.published:
            self.cost = read_json(os.path.join(self.published, "cost.json"), {})
        else:
            self.cost = run_cost(job, job.legs())
        # The deck variables as the run recorded them (its duration may have grown).
        self.vars = (recorded_vars(recorded_in) if recorded_in else {}) or job.vars
        self.results = read_results(os.path.join(self.source, "results.csv")) if self.source else None

    def _choose_source(self, job):
        """(folder of the results, state, folder whose params.json recorded the run): the run's
        own analysis, else what an earlier report published; either only if the run was made
        with these deck variables."""
        post = os.path.join(job.folder, "post")
        if job.done and has_results(post):
            mismatch = recorded_mismatch(job.folder, job.vars)
            if not mismatch:
                return post, "analysed", job.folder
            state = f"analysed run not used: {mismatch}"
        else:
            state = self._state(job)
        if has_results(self.published):
            mismatch = recorded_mismatch(self.published, job.vars)
            if not mismatch:
                return self.published, "published (raw outputs not here)", self.published
            state += f"; published run not used: {mismatch}"
        return None, state, None

    @property
    def local(self):
        """Analysed here (its files go to results/), not read back from results/."""
        return self.source is not None and self.source != self.published

    def _state(self, job):
        if job.done:
            log = os.path.join(job.folder, "cdpost.log")
            reason = open(log).read().strip().splitlines()[-1] if os.path.exists(log) else "no cdpost result"
            return "finished, not analysed: " + reason
        return "running or pending" if job.legs() else "not started"

    def get(self, name):
        return self.results.get(name) if self.results else None

    def window_text(self):
        """The stationary window in s, '–' before the analysis."""
        bounds = window_bounds(self.results, self.vars) if self.results else None
        return f"{bounds[0]:.2f}–{bounds[1]:.2f}" if bounds else "–"


def has_results(folder):
    return os.path.exists(os.path.join(folder, "results.csv"))


def recorded_vars(folder):
    """The deck variables a run folder or a published run records ({} if none)."""
    return read_json(os.path.join(folder, "params.json"), {}).get("vars", {})


def recorded_mismatch(folder, variables):
    """Why the run recorded in `folder` (a run folder or a published run) is not the run of these
    deck variables ('' if it is, or if nothing is recorded). Its duration may differ (runs are
    extended); a variable it does not record did not exist when it ran."""
    recorded = recorded_vars(folder)
    return changed_vars(recorded, variables, set(recorded) & set(variables))


def changed_numbers(old, new):
    """[(name, old, new)] for every published number that a new analysis changes (beyond the
    10 significant digits cdpost writes), drops (new None) or adds to a published file (old None)."""
    def same(a, b):
        return (math.isnan(a) and math.isnan(b)) or abs(a - b) <= 1e-9 * max(abs(a), abs(b), 1e-300)
    changes = [(n, old[n][0], new[n][0] if n in new else None) for n in sorted(old)
               if n not in new or not same(old[n][0], new[n][0])]
    return changes + [(n, None, new[n][0]) for n in sorted(new) if n not in old and old]


def read_published(path):
    return read_results(path) if os.path.exists(path) else {}


# A run with more of its steps unconverged than this is not published unless told
# (--publish-unconverged), and the rows that rest on it are flagged.
UNCONVERGED_LIMIT = 0.001


def unconverged_share(cost):
    """The fraction of a run's steps that ended unconverged, or None if the run did not record it."""
    solver = (cost or {}).get("solver")
    return solver.get("unconverged_fraction") if solver else None


def publication_refusal(record, args):
    """One line saying why a run is not published, or None."""
    share = unconverged_share(record.cost)
    if share is None or share <= UNCONVERGED_LIMIT or getattr(args, "publish_unconverged", False):
        return None
    return (f"not publishing {record.name}: {100 * share:.3g} % of its steps ended unconverged (more than "
            f"{100 * UNCONVERGED_LIMIT:g} %); --publish-unconverged publishes it anyway, flagged")


# A run that did not record its solver health counts in a verdict only with its health inferred:
# the fresh run of its friction and reading at the deck's defaults (series health_evidence) ended
# with at most this fraction of its steps unconverged. The marks are results/runs/HEALTH_MARKS.
INFERRED_LIMIT = 1e-4
EVIDENCE_SERIES = "health_evidence"
HEALTH_MARKS = "health_inferred.csv"


def health_evidence(records):
    """{(mu, reading): record} of the analysed evidence runs that recorded their health."""
    return {(float(r.vars["mu"]), reading(r.vars)): r for r in records
            if r.series == EVIDENCE_SERIES and r.results and unconverged_share(r.cost) is not None}


def counted(record):
    """The run enters a series analysis, whose fits and verdicts count it."""
    return bool(record.results) and any(belongs(record) for belongs in ANALYSES.values())


def infer_health(records):
    """Marks every published run without recorded health (a replica too) whose friction and reading
    have evidence at most INFERRED_LIMIT unconverged: record.inferred = (evidence name, its
    unconverged fraction). Returns the counted runs left without health, each with why: [(name, why)]."""
    evidence = health_evidence(records)
    missing = []
    for r in records:
        r.inferred = None
        if not r.results or unconverged_share(r.cost) is not None:
            continue
        proof = evidence.get((float(r.vars["mu"]), reading(r.vars)))
        share = unconverged_share(proof.cost) if proof else None
        if proof and share <= INFERRED_LIMIT:
            r.inferred = (proof.name, share)
        elif counted(r):
            missing.append((r.name, f"{proof.name} {100 * share:.3g} % unconverged" if proof
                            else "no evidence run of their friction and reading"))
    return missing


def health_refusal(records, args):
    """One line naming the runs a verdict would count without solver health (recorded or
    inferred), or None; --count-without-health counts them, flagged."""
    missing = infer_health(records)
    if not missing or getattr(args, "count_without_health", False):
        return None
    by_why = {}
    for name, why in missing:
        by_why.setdefault(why, []).append(name)
    names = "; ".join(f"{why}: " + ", ".join(runs) for why, runs in by_why.items())
    return (f"refusing to count {len(missing)} runs without solver health ({names}); run the series "
            f"{EVIDENCE_SERIES} at the deck's defaults to infer it (at most {100 * INFERRED_LIMIT:g} % unconverged, "
            "doc/studies.md), or --count-without-health to count them flagged")


def write_health_marks(records, destination):
    """results/runs/HEALTH_MARKS: each run whose health is inferred, with its evidence (no file
    when none is)."""
    path = os.path.join(destination, "runs", HEALTH_MARKS)
    marked = [r for r in records if getattr(r, "inferred", None)]
    if not marked:
        if os.path.exists(path):
            os.remove(path)
        return
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as out:
        out.write(f"# runs whose solver health is inferred: the evidence run of their friction and reading, at the "
                  f"deck's defaults, ended with at most {100 * INFERRED_LIMIT:g} % of its steps unconverged "
                  "(studies/cdtools/campaign/report.py, infer_health)\n")
        writer = csv.writer(out)
        writer.writerow(["run", "mu", "reading", "evidence", "evidence_unconverged_fraction"])
        for r in marked:
            writer.writerow([r.name, r.vars["mu"], reading(r.vars), r.inferred[0], r.inferred[1]])


def add_solver_health(results_json, cost):
    """The run's solver health (cost.json's) beside cdpost's results in results.json."""
    if not os.path.exists(results_json) or not cost.get("solver"):
        return
    with open(results_json) as src:
        results = json.load(src)
    results["solver"] = cost["solver"]
    with open(results_json, "w") as out:
        json.dump(results, out, indent=2, sort_keys=True)


def write_run(record, destination, changes):
    """results/runs/<name>/: cdpost's results, the cost and every command that made them; what it
    changes of an earlier publication of the run goes to `changes` (file -> [(name, old, new)])."""
    folder = os.path.join(destination, "runs", record.name)
    os.makedirs(folder, exist_ok=True)
    published = os.path.join(folder, "results.csv")
    before = read_published(published)
    copy_matching(record.source, RUN_FILES, folder)
    add_solver_health(os.path.join(folder, "results.json"), record.cost)
    if changed_numbers(before, read_published(published)):
        changes[os.path.relpath(published, destination)] = changed_numbers(before, read_published(published))
    with open(os.path.join(folder, "cost.json"), "w") as out:
        json.dump(record.cost, out, indent=2, sort_keys=True)
    legs = sorted(glob.glob(os.path.join(record.folder, "legs", "*", "command.sh")))
    commands = [open(path).read().strip() for path in legs]
    log = os.path.join(record.folder, "cdpost.log")
    if os.path.exists(log):
        commands.append(open(log).readline().strip())
    with open(os.path.join(folder, "commands.txt"), "w") as out:
        out.write("\n".join(commands) + "\n")
    params = {k: record.vars[k] for k in sorted(record.vars)}
    with open(os.path.join(folder, "params.json"), "w") as out:
        json.dump(dict(name=record.name, series=record.series, vars=params), out, indent=2, sort_keys=True)


def replica_pairs(records):
    """(replica, original) pairs: a run of another seed and the run at the same mu, theta, L."""
    by_point = {}
    for r in (r for r in records if r.series in FLOW_SERIES):
        by_point.setdefault((r.vars["mu"], r.vars["theta"], r.vars["L"], reading(r.vars)), []).append(r)
    pairs = []
    for runs in by_point.values():
        analysed = [r for r in runs if r.results]
        seeds = sorted(analysed, key=lambda r: r.series.endswith("replicas"))
        if len(seeds) >= 2 and seeds[-1].series.endswith("replicas"):
            pairs.append((seeds[-1], seeds[0]))
    return pairs


def replica_scatter(pairs):
    """Per quantity: the standard deviation of one run pooled over the replica pairs,
    s = sqrt(sum d^2 / (2 n)) for n pairs differing by d, and n."""
    scatter = {}
    for name in REPLICA_QUANTITIES:
        groups = [(a.get(name)[0], b.get(name)[0]) for a, b in pairs if a.get(name) and b.get(name)]
        if groups:
            scatter[name] = (pooled_sd(groups), len(groups))
    return scatter


def solver_cells(cost, inferred=None):
    """The runs table's solver columns: unconverged steps (count, %, flagged above the limit), and
    sweeps per step (median / 99th percentile); '–' for runs that did not record them, their
    health 'inferred' with its evidence where it is."""
    solver = (cost or {}).get("solver")
    if not solver and inferred:
        return [f"inferred: ≤ {100 * INFERRED_LIMIT:g} % ({inferred[0]})", "–"]
    if not solver:
        return ["not recorded", "–"]
    share = solver["unconverged_fraction"]
    flag = " ⚠" if share > UNCONVERGED_LIMIT else ""
    return [f"{solver['unconverged']} ({100 * share:.3g} %){flag}",
            f"{solver['sweeps_median']} / {solver['sweeps_p99']}"]


def section_runs(records):
    rows = []
    for r in records:
        cost = r.cost.get("cpu_per_physical_second")
        rows.append([r.name, r.vars["mu"], r.vars["theta"], r.vars["L"], r.vars["seed"], r.vars["duration"],
                     r.window_text(), number(cost, 3) if cost else "–"]
                    + solver_cells(r.cost, getattr(r, "inferred", None)) + [r.state])
    return ("## The runs\n\nEach run rains its packing (seed), tilts gravity and flows for the chute time "
            "given; cdpost finds the stationary window of each. CPU s per physical s from LAMMPS's own "
            "timers over the chute time the runs covered. Unconverged: the steps whose solve met the "
            f"iteration cap (the fix's end-of-run line), ⚠ above {100 * UNCONVERGED_LIMIT:g} % of the run's "
            "steps; runs made before the fix printed that line show 'not recorded', or 'inferred' with the "
            "evidence run of their friction and reading"
            + (f" ([{HEALTH_MARKS}]({HEALTH_MARKS}))" if any(getattr(r, "inferred", None) for r in records) else "")
            + ". Sweeps: per step, median / 99th percentile.\n\n"
            + markdown_table(["run", "mu", "θ (°)", "L (d)", "seed", "chute time (s)", "window (s)",
                              "CPU s / phys s", "unconverged steps", "sweeps", "state"], rows))


def section_quantities(title, text, records, columns):
    analysed = [r for r in records if r.results]
    if not analysed:
        return ""
    rows = [[r.name] + [result_text(r.get(name)) for name, _ in columns] for r in analysed]
    return f"## {title}\n\n{text}\n\n" + markdown_table(["run"] + [h for _, h in columns], rows)


def read_fits(folder):
    path = os.path.join(folder, "fits.csv")
    return read_results(path) if os.path.exists(path) else {}


def section_fits(title, folder, prefixes, figures, destination):
    fits = read_fits(folder)
    rows = [[name, result_text(entry), entry[2]] for name, entry in sorted(fits.items())
            if name.startswith(prefixes)]
    shown = [f for f in figures if os.path.exists(os.path.join(folder, "figures", f + ".png"))]
    if not rows and not shown:
        return ""
    relative = os.path.relpath(folder, destination)
    text = f"## {title}\n\n"
    if rows:
        text += markdown_table(["fit parameter", "value", "unit"], rows) + "\n"
    text += "".join(f"![{f}]({relative}/figures/{f}.png) " for f in shown) + "\n"
    return text


# The series analysis of each reading of the 45 d cell (doc/scene.md), in the order compared.
READINGS = (("count", "flow_rules"), ("layer", "layer_flow_rules"))
# The comparison's figures shown, and the per-run quantities shown per friction beside its table.
READING_FIGURES = ("U_vs_theta", "phi_vs_U", "phi_vs_I", "f_vs_scale", "f_vs_shear_rate", "A_vs_phi")
READING_MEANS = (("h", "h (d)"), ("phi", "φ"), ("f", "f (Hz)"), ("A", "A (√(gd))"),
                 ("creep_lambda", "creep length λ (d)"), ("bagnold_amplitude", "Bagnold a (√(gd)/d^1.5)"))


def publish_readings(copied_series, cdpost, args):
    """results/series/readings/: both readings' series side by side (cdpost series --compare on
    their published manifests), when both series analyses are published. Returns (its folder,
    whether the comparison succeeded), or None without both series."""
    folders = [copied_series.get(analysis, os.path.join(args.report, "series", analysis)) for _, analysis in READINGS]
    if not all(read_fits(folder) for folder in folders):
        return None
    work = os.path.join(args.out, "series", "readings")
    ok = run_comparison([os.path.join(folder, "manifest.csv") for folder in folders],
                        [name for name, _ in READINGS], cdpost, args, work)
    target = os.path.join(args.report, "series", "readings")
    if ok:
        copy_matching(work, READINGS_FILES, target)
    return target, ok


def read_compared_fits(path):
    """cdpost's compared_fits.csv -> [(name, {reading: (value, error)}, difference in sigma or None, unit)]."""
    def estimate(row, reading):
        value, error = row[reading], row[reading + "_error"]
        return (float(value), float(error) if error else None) if value else None
    with open(path, newline="") as src:
        return [(row["name"], {name: estimate(row, name) for name, _ in READINGS},
                 float(row["difference_sigma"]) if row["difference_sigma"] else None, row["unit"])
                for row in csv.DictReader(src)]


def paired_readings(records, name):
    """{mu: {"count": [...], "layer": [...], "difference": [layer - count at each angle both ran]}}
    of `name` over the analysed L = 45 d runs of each series' own rain (replicas left out)."""
    values = {}
    for r in records:
        if (r.results and r.get(name) and float(r.vars["L"]) == 45 and r.series in FLOW_SERIES
                and not r.series.endswith("replicas")):
            values[(reading(r.vars), r.vars["mu"], r.vars["theta"])] = r.get(name)[0]
    by_mu = {}
    for (which, mu, theta), value in values.items():
        entry = by_mu.setdefault(mu, {"count": [], "layer": [], "difference": []})
        entry[which].append(value)
        if which == "layer" and ("count", mu, theta) in values:
            entry["difference"].append(value - values[("count", mu, theta)])
    return by_mu


def mean_cell(values):
    return f"{number(sum(values) / len(values), 4)} ({len(values)} runs)" if values else "–"


def difference_cell(differences):
    """Mean of the paired differences ± its standard error (the scatter over the angles)."""
    if not differences:
        return "–"
    mean, _, error = mean_sd_se(differences)
    return f"{with_error(mean, error if math.isfinite(error) else None)} ({len(differences)} angles)"


def section_readings(records, readings, destination):
    """Both readings of the 45 d cell side by side (publish_readings): every series fit with the
    difference, the figures, and per friction the means of READING_MEANS' quantities in each
    reading with their layer − count difference at the same angles."""
    if readings is None:
        return ""
    folder, ok = readings
    relative = os.path.relpath(folder, destination)
    text = "## Two readings of the 45 d cell\n\n"
    if not ok:
        return text + ("The comparison of `series/flow_rules` and `series/layer_flow_rules` (cdpost series "
                       "--compare) failed: its log is `series/readings/cdpost.log` in the campaign folder.\n")
    rows = [[name, result_text(values["count"]), result_text(values["layer"]),
             "–" if difference is None else f"{difference:+.1f}", unit]
            for name, values, difference, unit in read_compared_fits(os.path.join(folder, "compared_fits.csv"))]
    text += ("Every series fit of the count reading (3967 grains) and of the layer reading (3290 grains, a "
             "40–49 d layer; `doc/scene.md`), each made by `series/flow_rules` and `series/layer_flow_rules` "
             f"alone, side by side in [{relative}]({relative}/report.md) (`cdpost series --compare`); the "
             "difference is layer − count in units of the combined error.\n\n"
             + markdown_table(["fit", "count", "layer", "difference (σ)", "unit"], rows) + "\n")
    shown = [f for f in READING_FIGURES if os.path.exists(os.path.join(folder, "figures", f + ".png"))]
    text += "".join(f"![{f}]({relative}/figures/{f}.png) " for f in shown) + "\n"
    mean_rows = []
    for name, heading in READING_MEANS:
        by_mu = paired_readings(records, name)
        for mu in sorted(by_mu, key=float):
            entry = by_mu[mu]
            mean_rows.append([heading, mu, mean_cell(entry["count"]), mean_cell(entry["layer"]),
                              difference_cell(entry["difference"])])
    return text + ("\nMeans over each friction's analysed runs (replicas left out), and the layer − count "
                   "difference at the angles both readings ran, its mean ± standard error over those "
                   "angles:\n\n") + markdown_table(["quantity", "mu", "count", "layer", "layer − count"], mean_rows)


def section_replicas(pairs, scatter):
    if not pairs:
        return ""
    rows = [[name, number(s, 3), n] for name, (s, n) in scatter.items()]
    listed = ", ".join(f"{a.name} / {b.name}" for a, b in pairs)
    return ("## Scatter between depositions\n\nTwo runs at the same point from different rains "
            f"({listed}); the standard deviation of one run, s = √(Σ d² / 2n) over the n pairs of "
            "differences d, is the honest error bar of a single run (the block errors of one run's "
            "window are smaller: they miss the slow fluctuations of one realisation).\n\n"
            + markdown_table(["quantity", "s (one run)", "pairs"], rows))


# The columns of cdref's table.csv shown in the report, and their headings; each value column
# is followed in the file by its error column ("error", empty where there is none).
COMPARISON_COLUMNS = [("label", "run"), ("overlap_target_d", "overlap target (d)"),
                      ("overlap_mean_d", "overlap mean (d)"), ("U_sqrt(g d)", "U (√(gd))"), ("phi", "φ"),
                      ("h_d", "h (d)"), ("f_Hz", "f (Hz)"), ("A_sqrt(g d)", "A (√(gd))"),
                      ("A_mean_sqrt(g d)", "A_mean (√(gd))"), ("contact_excess", "contact excess"),
                      ("cpu_per_physical_s_s/s", "CPU s / phys s")]


def comparison_summary(path):
    """(headings, rows) of the chosen columns of a cdref table.csv, values with their errors."""
    with open(path, newline="") as src:
        reader = csv.reader(src)
        names = next(reader)
        rows = list(reader)
    index = {name: k for k, name in enumerate(names) if name != "error"}

    def cell(row, name):
        k = index.get(name)
        if k is None or k >= len(row) or row[k] == "":
            return "–"
        try:
            value = float(row[k])
        except ValueError:
            return row[k]
        has_error = k + 1 < len(names) and names[k + 1] == "error" and row[k + 1] != ""
        return with_error(value, float(row[k + 1])) if has_error else number(value, 4)
    return [heading for _, heading in COMPARISON_COLUMNS], [[cell(r, n) for n, _ in COMPARISON_COLUMNS] for r in rows]


def publish_comparisons(comparisons, destination):
    """results/soft/<name>/: the small files of each reference/run_comparison.sh output folder given."""
    for source in comparisons:
        name = os.path.basename(os.path.normpath(source))
        folder = os.path.join(source, "comparison")
        copy_matching(folder if os.path.isdir(folder) else source, COMPARISON_FILES,
                      os.path.join(destination, "soft", name))


def section_comparisons(destination, page_folder):
    """Every comparison published in results/soft/, given now or by an earlier report, linked from a
    page in page_folder."""
    text = ""
    for target in sorted(glob.glob(os.path.join(destination, "soft", "*", ""))):
        name = os.path.basename(os.path.normpath(target))
        if not os.path.exists(os.path.join(target, "table.csv")):
            text += f"## Rigid against soft: {name}\n\nno comparison table in results/soft/{name}\n\n"
            continue
        headings, rows = comparison_summary(os.path.join(target, "table.csv"))
        relative = os.path.relpath(target, page_folder)
        commands = (f"its commands in [{relative}/commands.txt]({relative}/commands.txt), "
                    if os.path.exists(os.path.join(target, "commands.txt")) else "")
        full = (f" and the full report in [{relative}/report.md]({relative}/report.md)"
                if os.path.exists(os.path.join(target, "report.md")) else "")
        text += (f"## Rigid against soft: {name}\n\nThe same packing run by each model (reference/run_comparison.sh, "
                 f"{commands}every column in [{relative}/table.csv]({relative}/table.csv){full}).\n\n"
                 + markdown_table(headings, rows))
        spectra = sorted(os.path.relpath(f, target) for f in glob.glob(os.path.join(target, "figures", "spectra*.png")))
        text += "\n" + "".join(f"![{os.path.basename(f)}]({relative}/{f}) " for f in spectra[:2]) + "\n\n"
    return text


def section_snapshots(records, destination):
    """The snapshot of the fastest and of the slowest analysed run."""
    analysed = [r for r in records if r.results and r.get("U")]
    if not analysed:
        return ""
    chosen = {max(analysed, key=lambda r: r.get("U")[0]).name: "fastest",
              min(analysed, key=lambda r: r.get("U")[0]).name: "slowest"}
    text = ("## Snapshots\n\nGrains coloured by their x-velocity, the walls drawn, periodic images shaded above "
            "the wall tops; beside each, the run's u(z) with its Bagnold and creep fits.\n\n")
    for r in analysed:
        if r.name not in chosen:
            continue
        # The snapshot's SVG (a circle per grain and image, megabytes at 45 d) stays in the run folder.
        figures = ("figures/snapshot.png", "figures/profile.png", "figures/profile.svg")
        if r.local:
            copy_matching(r.source, figures, r.published)
        shown = [f for f in figures if f.endswith(".png") and os.path.exists(os.path.join(r.published, f))]
        for figure in shown:
            text += f"![{chosen[r.name]} run, {r.name}](runs/{r.name}/{figure}) "
        text += "\n"
    return text + "\n"


def kept_discussion(path):
    """The hand-written discussion of an existing README.md, markers included."""
    try:
        text = open(path).read()
    except OSError:
        return None
    begin, end = text.find(DISCUSSION_BEGIN), text.find(DISCUSSION_END)
    if begin < 0 or end < begin:
        return None
    return text[begin:end + len(DISCUSSION_END)]


def publish_series(records, cdpost, args, changes):
    """results/series/<analysis>/: the manifest over the published runs (results/runs/<name>, so
    that `cdpost series` can be run again from results/ alone) and cdpost's series results, for
    every analysis with two analysed runs; returns {analysis: its folder in results/}. The fits
    it changes of the earlier publication go to `changes`."""
    published = {}
    for analysis, belongs in ANALYSES.items():
        runs = [(r.published, os.path.join(r.published, "results.csv"), r.vars)
                for r in records if r.results and belongs(r)]
        if len(runs) < 2:
            continue
        target = os.path.join(args.report, "series", analysis)
        work = os.path.join(args.out, "series", analysis, "published-post")
        before = read_fits(target)
        if run_series(analysis, target, runs, cdpost, args, out=work):
            copy_matching(work, SERIES_FILES, target)
            published[analysis] = target
            if changed_numbers(before, read_fits(target)):
                changes[os.path.join("series", analysis, "fits.csv")] = changed_numbers(before, read_fits(target))
    return published


def section_changes(changes, destination, command):
    """Every published number this report changed, dropped or added, in changes.md beside the
    README, and a paragraph pointing at it (none: no section, and no page)."""
    path = os.path.join(destination, "changes.md")
    if not changes:
        if os.path.exists(path):
            os.remove(path)
        return ""
    rows = [[f, name, "–" if old is None else number(old, 6), "–" if new is None else number(new, 6)]
            for f, entries in sorted(changes.items()) for name, old, new in entries]
    with open(path, "w") as out:
        out.write(page_header("Changed by the last report", command) + "\nNumbers of an earlier publication that "
                  "this analysis changed (a new cdpost, a re-analysed run), dropped (–) or added; the earlier "
                  "values are in the git history of results/.\n\n" + markdown_table(["file", "name", "was", "now"],
                                                                                    rows))
    return (f"## Changed by this report\n\n{len(rows)} published numbers in {len(changes)} files changed, dropped or "
            f"added: [changes.md](changes.md).\n")


# The keys of the L series' comparison with the source that the README's table adds (the
# readings have one cell length).
LENGTH_KEYS = ("sign_f_vs_L", "sign_A_mean_vs_L")


def read_source_rows(folder, columns):
    """source_comparison.csv of a series folder -> [(key, quantity, source, {reading: (reading, verdict)},
    tolerance)], `columns` mapping the file's labels to the readings' names; [] without the file."""
    path = os.path.join(folder, "source_comparison.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as src:
        return [(row["key"], row["quantity"], row["source"],
                 {name: (row[label], row["verdict_" + label]) for label, name in columns.items() if row[label]},
                 row["tolerance"]) for row in csv.DictReader(src)]


def solver_caveat(key, reading_name, records):
    """What a comparison row of one reading rests on, if not every run of its friction (all
    frictions for a row of none) recorded at most 0.1 % of its steps unconverged: '' or a caveat."""
    friction = re.search(r"_mu([0-9.]+?)(?:_|$)", key)
    if key in LENGTH_KEYS:  # the cell length's rows rest on the L series' runs
        runs = [r for r in records if counted(r) and ANALYSES["L_series"](r) and reading(r.vars) == reading_name]
    else:
        runs = [r for r in records if counted(r) and reading(r.vars) == reading_name and r.vars.get("L") == "45"
                and (friction is None or same_value(r.vars["mu"], friction.group(1)))]
    shares = [unconverged_share(r.cost) for r in runs]
    flagged = sum(1 for share in shares if share is not None and share > UNCONVERGED_LIMIT)
    inferred = sum(1 for r, share in zip(runs, shares) if share is None and getattr(r, "inferred", None))
    unrecorded = sum(1 for share in shares if share is None) - inferred
    parts = ([f"⚠ {flagged} run(s) above {100 * UNCONVERGED_LIMIT:g} % unconverged"] if flagged else []) + \
        ([f"solver health inferred for {inferred} of {len(runs)} runs"] if inferred else []) + \
        ([f"solver health not recorded for {unrecorded} of {len(runs)} runs"] if unrecorded else [])
    return " (" + "; ".join(parts) + ")" if parts else ""


def section_source(destination, records=()):
    """The comparison with the source (results/source.csv) as `cdpost series --source` made it:
    both readings' rows, and the L series' rows of the cell length; a row resting on runs with
    unconverged steps, or runs that did not record them, says so."""
    series = os.path.join(destination, "series")
    rows = read_source_rows(os.path.join(series, "readings"), {name: name for name, _ in READINGS})
    rows += [row for row in read_source_rows(os.path.join(series, "L_series"), {"ours": "count"})
             if row[0] in LENGTH_KEYS]
    if not rows:
        return ""
    names = [name for name, _ in READINGS]
    table, agree = [], {name: [0, 0] for name in names}
    for key, quantity, source, readings, tolerance in rows:
        verdicts = []
        for name in names:
            if name in readings and readings[name][1] in ("agrees", "outside"):
                agree[name][0] += readings[name][1] == "agrees"
                agree[name][1] += 1
            if name in readings:
                verdicts.append(f"{name} {readings[name][1]}" + solver_caveat(key, name, records))
        table.append([quantity, source] + [readings[n][0] if n in readings else "–" for n in names]
                     + [tolerance, "; ".join(verdicts)])
    tally = ", ".join(f"the {name} reading {a} of {n}" for name, (a, n) in agree.items())
    return ("## Against the source\n\nThe source's numbers ([source.csv](source.csv)) beside both readings, "
            "made by `cdpost series --source` ([series/readings/report.md](series/readings/report.md), section "
            "*Against the source*, with the fit parameters shown apart as degenerate and the source's two flow "
            "rules checked against each other; the cell length from "
            "[series/L_series/report.md](series/L_series/report.md)). Comparisons that agree: " + tally + ".\n\n"
            + markdown_table(["quantity", "source"] + [f"{n} reading" for n in names] + ["tolerance", "verdict"],
                             table) + "\n")


def section_key_figures(destination):
    shown = [("series/readings", f) for f in ("U_vs_theta", "phi_vs_U", "f_vs_scale")] + [("series/L_series",
                                                                                          "L_series")]
    links = "".join(f"![{f}]({folder}/figures/{f}.png) " for folder, f in shown
                    if os.path.exists(os.path.join(destination, folder, "figures", f + ".png")))
    return ("## Key figures\n\nBoth readings on the same axes with the source drawn over them (open symbols: its "
            "Pouliquen rule at each run's own θ and h; asterisks: its φ(U) law; dashed: its range of f), and the "
            "cell length series.\n\n" + links + "\n") if links else ""


def section_where(destination):
    verdict = os.path.join("series", "creep_length", "verdict.md")
    creep = (f"- [{verdict}]({verdict}): the creep length, the grains' or the cell's, and the coherence along the cell "
             "(`studies/creep_verdict.py`, doc/creep.md).\n" if os.path.exists(os.path.join(destination, verdict))
             else "")
    return ("## Where the tables are\n\n"
            "- [runs/README.md](runs/README.md): every run (parameters, window, cost, state), its U, φ, h, I, f, A, "
            "profile fits, and the scatter between replicas; each run's own files in `runs/<name>/`.\n"
            "- [series/README.md](series/README.md): the fits of each series (flow rules, packing, frequency laws, "
            "cell length) and both readings side by side with their per-friction means.\n"
            "- `series/<analysis>/report.md`: every fit, residual, held fit and figure of one series "
            "([flow_rules](series/flow_rules/report.md), [layer_flow_rules](series/layer_flow_rules/report.md), "
            "[L_series](series/L_series/report.md), [readings](series/readings/report.md)).\n"
            + creep +
            "- [soft/README.md](soft/README.md): rigid against soft-sphere runs of the same packing.\n"
            "- [bed/analysis/bed.md](bed/analysis/bed.md): the erodible bed against the solver's tolerance and its "
            "floor at rest (doc/bed.md).\n"
            "- `size_law/`: flows rained with diameters uniform in area, the size law's part of the packing law's "
            "offset (doc/source.md, `studies/size_law_offset.py`).\n"
            "- `accuracy/`: cheaper solver settings against a reference on the 45 d scene (doc/accuracy.md).\n"
            "- `plane_shear/`: µ(I) and φ(I) of the same grains in plane shear (doc/plane_shear_results.md).\n"
            "- `stalls/`: the corpus of hard steps and the settings measured on it (doc/stalls.md).\n\n"
            "Which study makes each folder, and its one report command: "
            "[doc/studies.md](../doc/studies.md).\n")


def page_header(title, command):
    return (f"# {title}\n\nGenerated from the campaign's runs by\n\n    {command}\n\n(every number below comes "
            "from the files beside this page; errors are one standard error unless said otherwise).\n")


def write_page(path, header, parts):
    """A generated page: its header, the hand-written discussion kept from the page as it was, then
    `parts`."""
    discussion = kept_discussion(path) or f"{DISCUSSION_BEGIN}\n(no discussion yet)\n{DISCUSSION_END}"
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w") as out:
        out.write("\n".join(p for p in [header, discussion + "\n"] + parts if p))
    os.replace(path + ".tmp", path)


def write_report(records, copied_series, readings, destination, command, changes):
    """Writes results/README.md (the source comparison, key figures, where each table lives) and the
    pages it links, runs/README.md, series/README.md and soft/README.md; returns the README's path."""
    pairs = replica_pairs(records)
    series = os.path.join(destination, "series")
    flow_rules = copied_series.get("flow_rules", os.path.join(series, "flow_rules"))
    length = copied_series.get("L_series", os.path.join(series, "L_series"))
    write_page(os.path.join(destination, "runs", "README.md"), page_header("The runs", command), [
        section_runs(records),
        section_quantities("Flow", "Means over each run's stationary window (block standard errors).",
                           records, FLOW_COLUMNS),
        section_quantities("Oscillation of the flowing layer", "f: spectral peak of v(t) (error: half width at "
                           "half power); A its amplitude; A_mean the mean amplitude at f ≥ 100 Hz.",
                           records, OSCILLATION_COLUMNS),
        section_quantities("Velocity profiles", "Bagnold fit u = slip + a (h^1.5 − (h − z)^1.5) over the layer; "
                           "creep length λ of u ∝ exp(z/λ) below the wall tops.", records, PROFILE_COLUMNS),
        section_replicas(pairs, replica_scatter(pairs)),
    ])
    write_page(os.path.join(series, "README.md"), page_header("The series fits", command), [
        section_fits("Flow rules and packing", flow_rules, ("pouliquen", "muI", "phi_"),
                     ("U_vs_theta", "pouliquen_beta_free", "phi_vs_U"), series),
        section_fits("Frequency laws and correlations", flow_rules, ("f_vs", "correlation", "depth"),
                     ("f_vs_scale", "f_vs_shear_rate", "A_vs_U", "A_vs_phi", "amplitude_vs_depth"), series),
        section_fits("Cell length", length, ("correlation", "f_vs_L", "A_vs_L", "A_mean_vs_L"), ("L_series",),
                     series),
        section_readings(records, readings, series),
    ])
    write_page(os.path.join(destination, "soft", "README.md"), page_header("Rigid against soft", command),
               [section_comparisons(destination, os.path.join(destination, "soft"))])
    readme = os.path.join(destination, "README.md")
    write_page(readme, page_header("Results: the erodible-bed chute", command), [
        section_source(destination, records),
        section_key_figures(destination),
        section_snapshots(records, destination),
        section_where(destination),
        section_changes(changes, destination, command),
    ])
    return readme


def analyse_finished_runs(jobs, cdpost, args):
    """cdpost on the finished runs it has not analysed yet."""
    for job in jobs:
        if job.kind == "run" and job.done and not os.path.exists(os.path.join(job.folder, "post", "results.csv")):
            ok, message = postprocess_run(job, cdpost, args)
            print(f"cdpost run {job.name}: " + ("done" if ok else "failed: " + message), flush=True)


def write_results(args):
    """--report: cdpost on the finished runs it has not analysed yet, the series analyses made
    again from every analysed run, then the results folder."""
    cdpost = campaign_cdpost(args)
    if cdpost is None:
        print("--report needs cdpost (build/postproc/cdpost, --cdpost)", file=sys.stderr)
        return 2
    jobs = build_jobs(args)
    analyse_finished_runs(jobs, cdpost, args)
    os.makedirs(args.report, exist_ok=True)
    records = [RunRecord(job, args.report) for job in jobs if job.kind == "run"]
    changes = {}
    for r in records:
        refusal = publication_refusal(r, args) if r.local else None
        if refusal:
            print(refusal, flush=True)
            r.source, r.results, r.state = None, None, refusal
    refusal = health_refusal(records, args)
    if refusal:  # before anything of results/ is written
        print(refusal, file=sys.stderr, flush=True)
        return 2
    for r in records:
        if r.results and r.local:
            write_run(r, args.report, changes)
    write_health_marks(records, args.report)
    series = publish_series(records, cdpost, args, changes)
    readings = publish_readings(series, cdpost, args)
    command = " ".join(shlex.quote(a) for a in ["studies/chute_campaign.py"] + args.argv)
    publish_comparisons(args.comparison, args.report)
    readme = write_report(records, series, readings, args.report, command, changes)
    for path, entries in sorted(changes.items()):
        print(f"{path}: {len(entries)} published numbers changed, dropped or added (README, 'Changed by this report')",
              flush=True)
    analysed = sum(r.results is not None for r in records)
    published = sum(r.results is not None and not r.local for r in records)
    print(f"{readme}: {analysed} of {len(records)} runs analysed ({published} read from their published results)",
          flush=True)
    report_stale_numbers(args.report)
    return 0


def report_stale_numbers(destination):
    """When the report rewrote the repository's results/: the sentences of the kept discussions (and
    doc/source.md) whose marked numbers the new tables no longer give, one line each."""
    if os.path.realpath(destination) != os.path.realpath(os.path.join(TOP, "results")):
        return
    stale = page_numbers.check_pages(TOP)
    for page, line, key, problem in stale:
        print(f"{page}:{line}: {key}: {problem}", flush=True)
    if stale:
        print(f"{len(stale)} marked numbers of the pages' prose disagree with the new tables: "
              "studies/page_numbers.py --update rewrites them; then read those sentences again (ctest "
              "chute.page_numbers fails until then)", flush=True)
