"""The numbers of the results pages' prose against the committed data they come from.

A number in a sentence of results/README.md, results/runs/README.md, results/series/README.md or
doc/source.md that comes from a run carries a marker just after it, an HTML comment that Markdown
does not show:

    the slope is −0.022 ± 0.016<!-- check: f_mu_slope:layer_flow_rules -->, within two errors

KEY is a family and its arguments, separated by ':'. The family computes a tuple of values from
the committed files (each run's results.json through its series' manifest.csv, the series'
runs.csv, fits.csv and source_comparison.csv, the plane-shear tables, the re-runs' table of
results/series/local_rheology/), with the estimator the tables use; the marker checks the last
len(tuple) numbers before it in its paragraph, in order. A printed number agrees when it is its
value rounded to the decimals printed (half a unit of its last digit, and a sign that matches).
A number's sign is '−' (U+2212), '-' or '+' written just before its digits after a space or an
opening bracket, '^' or '×'; '–' (U+2013) between two numbers is a range; in '4e-05' the last
digit is the fifth decimal.

    check_pages(root)       [(page, line, key, problem)] over PAGES; empty when every number agrees
    check_text(text, data)  the same for one text
    update_pages(root)      rewrite each disagreeing number from its value (same decimals, sign
                            style), [(page, line, key, old, new)]: the sentences around them are
                            then read again by hand (a verdict may have turned)
    FAMILIES                the families, each with the docstring of what it computes

Standard library only; tests/chute/test_page_numbers.py runs it on the committed pages.
"""

import csv
import json
import math
import os
import re
import statistics
import sys

from . import stats

PAGES = ("results/README.md", "results/runs/README.md", "results/series/README.md", "doc/source.md",
         "results/rerun/count_mu2/README.md")
MARKER = re.compile(r"(?<!`)<!--\s*check:\s*(\S+?)\s*-->(?!`)")  # in `code`: shown, not a marker
NUMBER = re.compile(r"(?<![\w.])([−+-]?)(\d+(?:\.\d+)?)(?:e([−+-]?\d+))?(?![\w])")
SIGN_BEFORE = re.compile(r"(^|[\s(\[^×/=,;:–])$")


def read_rows(path):
    """The rows of a CSV whose '#' lines are its provenance."""
    with open(path, newline="") as src:
        return list(csv.DictReader(line for line in src if not line.startswith("#")))


def _float(text):
    return float(text) if text not in (None, "") else None


class Data:
    """The committed files under the repository root, read once."""

    def __init__(self, root):
        self.root = root
        self._cache = {}

    def _memo(self, key, make):
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    def path(self, *parts):
        return os.path.join(self.root, *parts)

    def series_runs(self, series):
        """[(name, manifest row, {quantity: (value, error)})] of a series in its manifest's order
        ('a+b': the runs of both; 'a[L<=102]': those whose manifest column L is at most 102)."""
        if "+" in series:
            return [run for part in series.split("+") for run in self.series_runs(part)]
        condition = re.fullmatch(r"(\w+)\[(\w+)(<=|>=|!=|=|<|>)([\d.]+)\]", series)
        if condition:
            base, column, operator, bound = condition.groups()
            compare = {"<=": float.__le__, ">=": float.__ge__, "!=": float.__ne__, "=": float.__eq__,
                       "<": float.__lt__, ">": float.__gt__}[operator]
            return [run for run in self.series_runs(base) if compare(float(run[1][column]), float(bound))]

        def make():
            folder = self.path("results", "series", series)
            runs = []
            for row in read_rows(os.path.join(folder, "manifest.csv")):
                run = os.path.normpath(os.path.join(folder, row["run"]))
                runs.append((os.path.basename(run), row, self.run(os.path.basename(run))))
            return runs
        return self._memo(("series", series), make)

    def run(self, name):
        """{quantity: (value, error)} of results/runs/NAME/results.json."""
        def make():
            with open(self.path("results", "runs", name, "results.json")) as src:
                results = json.load(src)["results"]
            values = {r["name"]: (r["value"], r["error"]) for r in results if r["value"] is not None}
            if "U" in values and "bagnold_slip" in values:  # the sheared layer's own speed
                values["U_minus_slip"] = (values["U"][0] - values["bagnold_slip"][0], None)
            return values
        return self._memo(("run", name), make)

    def runs_csv(self, series):
        """{run name: row} of results/series/SERIES/runs.csv (derived columns: I_local, ...)."""
        def make():
            rows = read_rows(self.path("results", "series", series, "runs.csv"))
            return {os.path.basename(r["run"]): r for r in rows}
        return self._memo(("runs_csv", series), make)

    def fits(self, series):
        """{name: (value, error)} of results/series/SERIES/fits.csv."""
        def make():
            rows = read_rows(self.path("results", "series", series, "fits.csv"))
            return {r["name"]: (float(r["value"]), _float(r["error"])) for r in rows}
        return self._memo(("fits", series), make)

    def comparison(self):
        """The rows of results/series/readings/source_comparison.csv."""
        return self._memo("comparison", lambda: read_rows(self.path("results", "series", "readings",
                                                                    "source_comparison.csv")))

    def quantity(self, series, name, quantity):
        """(value, error) of a run's quantity: results.json, else its series' runs.csv."""
        results = self.run(name)
        if quantity in results:
            return results[quantity]
        row = {}
        for part in re.sub(r"\[[^]]*\]", "", series).split("+"):
            row = self.runs_csv(part).get(name) or row
        if row.get(quantity):
            return float(row[quantity]), _float(row.get(quantity + "_error"))
        return None


# The estimators, as cdpost's (postproc/src/fit/linear_fit.cpp, source/source_comparison.cpp).

def least_squares(xs, ys):
    """(intercept, slope) of the unweighted line."""
    return stats.least_squares_line(xs, ys)


def weighted_slope(xs, ys, sigmas):
    """(slope, error, chi2/dof) of y on x weighted by 1/sigma^2, the error scaled by sqrt(chi2/dof)
    where that exceeds 1 (fit_weighted_slope)."""
    w = [1 / s ** 2 for s in sigmas]
    s, sx, sy = sum(w), sum(wi * x for wi, x in zip(w, xs)), sum(wi * y for wi, y in zip(w, ys))
    sxx = sum(wi * x * x for wi, x in zip(w, xs))
    sxy = sum(wi * x * y for wi, x, y in zip(w, xs, ys))
    det = s * sxx - sx * sx
    slope, intercept = (s * sxy - sx * sy) / det, (sxx * sy - sx * sxy) / det
    chi2 = sum(((y - intercept - slope * x) / sg) ** 2 for x, y, sg in zip(xs, ys, sigmas)) / (len(xs) - 2)
    return slope, math.sqrt(s / det) * max(1.0, math.sqrt(chi2)), chi2


def _f_points(data, series, against):
    """(x, ln f, sigma of ln f) of the series' runs with f, its error and `against`."""
    points = []
    for name, row, results in data.series_runs(series):
        f, x = results.get("f"), against(row, results)
        if f and f[1] and x is not None:
            points.append((x, f[0], f[1] / f[0]))
    return points


def f_mu(data, series):
    """Slope of ln f about the power law of f on f_scale (every run) against ln mu, weighted by the
    peak's half width over f: (slope, error, chi2/dof)."""
    points = []
    for name, row, results in data.series_runs(series):
        f, x = results.get("f"), results.get("f_scale")
        if f and f[1] and x:
            points.append((float(row["mu"]), f[0], x[0], f[1] / f[0]))
    a, b = least_squares([math.log(p[2]) for p in points], [math.log(p[1]) for p in points])
    return weighted_slope([math.log(p[0]) for p in points],
                          [math.log(p[1]) - a - b * math.log(p[2]) for p in points], [p[3] for p in points])


def A_mu(data, series):
    """Slope of ln A against ln mu, each run's error 1/(2 sqrt(spectrum_segments)): (slope, error,
    chi2/dof)."""
    xs, ys, sigmas = [], [], []
    for name, row, results in data.series_runs(series):
        a, k = results.get("A"), results.get("spectrum_segments")
        if a and k and a[0] > 0 and k[0] > 0:
            xs.append(math.log(float(row["mu"])))
            ys.append(math.log(a[0]))
            sigmas.append(0.5 / math.sqrt(k[0]))
    return weighted_slope(xs, ys, sigmas)


def f_L(data, series="L_series"):
    """Exponent of f against L weighted as f on mu is (ln f on ln L, error of ln f the half width
    over f): (exponent, error, chi2/dof)."""
    points = _f_points(data, series, lambda row, results: math.log(float(row["L"])))
    return weighted_slope([p[0] for p in points], [math.log(p[1]) for p in points], [p[2] for p in points])


# The families of KEY. Each takes the Data and its ':' arguments and returns a tuple of numbers.

def family_fit(data, series, name, part="both"):
    """A series fit of fits.csv: value and error (part 'value': the value alone)."""
    value, error = data.fits(series)[name]
    return (value,) if part == "value" or error is None else (value, error)


def family_run(data, name, quantity, part="value"):
    """A run's quantity (results.json, else runs.csv of a series holding it); part 'both': ± error."""
    value, error = data.run(name)[quantity]
    return (value, error) if part == "both" else (value,)


def family_run_as(data, name, quantity, unit):
    """A run's quantity in another unit: 's' a time in sqrt(d/g) in seconds (the run's d and g,
    params.json), '%' a fraction in per cent."""
    value = data.run(name)[quantity][0]
    if unit == "%":
        return (100 * value,)
    if unit != "s":
        raise ValueError(f"run_as: unit '{unit}' is neither 's' nor '%'")
    with open(data.path("results", "runs", name, "params.json")) as src:
        settings = json.load(src)["vars"]
    return (value * math.sqrt(float(settings["d"]) / float(settings["g"])),)


def _series_values(data, series, quantity, mu=None):
    values = []
    runs = data.series_runs(series)
    if "L" in runs[0][1]:
        runs = sorted(runs, key=lambda run: float(run[1]["L"]))
    for name, row, _ in runs:
        if mu is not None and float(row["mu"]) != float(mu):
            continue
        q = data.quantity(series, name, quantity)
        if q is not None:
            values.append(q[0])
    return values


def family_range(data, series, quantity, mu=None):
    """Smallest and largest of a quantity over a series' runs (of one friction if mu is given)."""
    values = _series_values(data, series, quantity, mu)
    return min(values), max(values)


def family_median(data, series, quantity):
    """Median of a quantity over a series' runs."""
    return (statistics.median(_series_values(data, series, quantity)),)


def family_f_mu(data, series, part="slope"):
    """f on mu as the table's sign row makes it (f_mu): 'slope' slope and error, 'chi2' chi2/dof."""
    slope, error, chi2 = f_mu(data, series)
    return (chi2,) if part == "chi2" else (slope, error)


def family_A_mu(data, series, part="slope"):
    """A on mu as the table's sign row makes it (A_mu): 'slope' slope and error, 'chi2' chi2/dof."""
    slope, error, chi2 = A_mu(data, series)
    return (chi2,) if part == "chi2" else (slope, error)


def family_f_L(data, part="slope"):
    """f on L weighted as f on mu (f_L): 'slope' exponent and error, 'sigmas' exponent/error."""
    slope, error, chi2 = f_L(data)
    if part == "sigmas":
        return (abs(slope) / error,)
    return (chi2,) if part == "chi2" else (slope, error)


def family_scaled_range(data, series, quantity, power):
    """Smallest and largest of quantity × (L/d)^power over the L series' runs (of one run: its value)."""
    values = []
    for name, row, results in data.series_runs(series):
        values.append(results[quantity][0] * float(row["L"]) ** float(power))
    return (values[0],) if len(values) == 1 else (min(values), max(values))


def family_list(data, series, quantity, mu=None):
    """A quantity of every run of a series, runs without it left out: in the manifest's order, the
    L series by L."""
    return tuple(_series_values(data, series, quantity, mu))


def family_counts(data, reading, kind="quantities"):
    """Of results/series/readings/source_comparison.csv, column verdict_READING: 'quantities' the
    agreeing and the compared rows (agrees, outside), 'signs' the agreeing and all sign rows."""
    verdicts = [r["verdict_" + reading] for r in data.comparison()]
    if kind == "signs":
        return verdicts.count("sign agrees"), verdicts.count("sign agrees") + verdicts.count("sign differs")
    return verdicts.count("agrees"), verdicts.count("agrees") + verdicts.count("outside")


def _packing(data):
    def make():
        studies = data.path("studies")
        if studies not in sys.path:
            sys.path.insert(0, studies)
        import packing_against_plane_shear as packing
        readings = [("count", packing.chute_points(data.path("results", "series", "flow_rules", "runs.csv"))),
                    ("layer", packing.chute_points(data.path("results", "series", "layer_flow_rules", "runs.csv")))]
        plane = {mu: packing.plane_shear_points(data.path("results", "plane_shear", f"plane_shear_mu{mu:g}_1e-4.csv"))
                 for mu in (0.05, 0.5, 2.0)}
        return {(r[0], r[1]): r[2:] for r in packing.summary(packing.offsets(readings, plane))}
    return data._memo("packing", make)


def family_packing(data, reading, mu, part="mean"):
    """The chute's phi at mid-layer minus plane shear's phi(I) (studies/packing_against_plane_shear.py):
    'mean' mean and standard error, 'mean_only' the mean, 'range' smallest and largest, 'runs' the
    runs."""
    runs, low, high, mean, se = _packing(data)[(reading, float(mu))]
    return {"mean": (mean, se), "mean_only": (mean,), "range": (low, high), "runs": (runs,)}[part]


def _local(data):
    def make():
        studies = data.path("studies")
        if studies not in sys.path:
            sys.path.insert(0, studies)
        import local_rheology
        fits, rows = local_rheology.load(data.path("results", "series", "local_rheology", local_rheology.RERUN_TABLE))
        return fits, rows, local_rheology.summary(rows)
    return data._memo("local", make)


def family_local(data, reading, mu, quantity, part="range"):
    """The chute's mid-layer point against plane shear's fits (studies/local_rheology.py). READING
    count or layer, MU a friction or 'all', QUANTITY dtheta (theta - arctan mu_ps(I), deg) or dphi
    (phi - phi_ps(I)) with PART 'range' (smallest, largest), 'mean' (mean, standard error) or
    'mean_only'; QUANTITY runs, reruns or outside: how many. READING 'fit': plane shear's fit at MU,
    QUANTITY rms_deg or rms_phi. READING 'rerun': the re-run named MU, QUANTITY counts: its phi_local
    from the grain counts minus from the measured phi(z)."""
    fits, rows, groups = _local(data)
    if reading == "fit":
        fit = fits[float(mu)]
        return (fit["rms_deg"],) if quantity == "rms_deg" else (fit["phi"]["rms"],)
    if reading == "rerun":
        import local_rheology
        row = local_rheology.rerun_rows(data.path("results", "series", "local_rheology",
                                                  local_rheology.RERUN_TABLE))[mu]
        return (float(row["phi_local_from_counts"]) - float(row["phi_local"]),)
    group = groups[(reading, mu if mu == "all" else float(mu))]
    if quantity in ("runs", "reruns", "outside"):
        return (group[quantity],)
    low, high, mean, se = group[quantity]
    return {"range": (low, high), "mean": (mean, se), "mean_only": (mean,)}[part]


def _two_packings(data):
    def make():
        studies = data.path("studies")
        if studies not in sys.path:
            sys.path.insert(0, studies)
        import two_packings
        rows, _ = two_packings.load(data.path("results", "series", "packing"))
        return rows, two_packings.groups(rows)
    return data._memo("two_packings", make)


def family_two_packings(data, reading, solver="", mu="", quantity="dphi_bulk", part="mean"):
    """The two readings' packings (studies/two_packings.py). READING count or layer, SOLVER published
    or today, QUANTITY dphi_local, dphi_bulk (phi at mid-layer or in the bulk minus plane shear's
    phi(I)) or local_minus_bulk, PART 'mean' (mean, standard error) or 'mean_only'; READING 'counts':
    phi_local from the grain counts minus from the area over the runs with both (mean, standard error);
    'paired', SOLVER count or layer: today's count runs' dphi_bulk minus the published runs' of that
    reading at the same friction and angle (mean, standard error; MU 'runs': how many); 'tolerance': plane shear's
    phi at 1e-3 minus at 1e-4 at fixed I (mean, standard error); 'mix': the mid-layer's mean grain
    area over the cell's, smallest and largest over the runs with snapshots; SOLVER 'error': the
    largest gap between the counts' phi over the area's as the size mix predicts it and as measured."""
    rows, groups = _two_packings(data)
    import two_packings
    if reading == "counts":
        mean, _, se, _ = two_packings.counts_against_area(rows)
        return mean, se
    if reading == "paired":
        mean, se, runs = two_packings.paired_mean(rows, solver)
        return (runs,) if mu == "runs" else (mean, se)
    if reading == "tolerance":
        mean, _, se = stats.mean_sd_se(shift for *_, shift in two_packings.plane_shear_tolerance_shifts())
        return mean, se
    if reading == "mix":
        _, mix = two_packings.load(data.path("results", "series", "packing"))
        if solver == "error":
            return (max(abs(two_packings.predicted_ratio(r) - two_packings.measured_ratio(rows, name))
                        for name, r in mix.items()),)
        ratios = [float(r["mid_over_cell"]) for r in mix.values()]
        return min(ratios), max(ratios)
    mean, se = groups[(reading, solver, float(mu))][quantity]
    return {"mean": (mean, se), "mean_only": (mean,)}[part]


def _replica_pairs(data, quantity, reading):
    """[(replica, published)] values (value, error) of a quantity over the replica pairs (runs of a
    replicas series, named *_seed*, and the run of their name without the seed)."""
    pairs = []
    for name in sorted(os.listdir(data.path("results", "runs"))):
        if "_seed" not in name or (reading != "both" and name.endswith("_layer") != (reading == "layer")):
            continue
        with open(data.path("results", "runs", name, "params.json")) as src:
            if not json.load(src).get("series", "").endswith("replicas"):
                continue  # another rain of another study (the creep series' seeds)
        a, b = data.run(name).get(quantity), data.run(re.sub(r"_seed\d+", "", name)).get(quantity)
        if a and b:
            pairs.append((a, b))
    return pairs


def family_replica(data, quantity, reading="both", part="scatter"):
    """Scatter of one run from the replica pairs: sqrt(sum d^2 / 2n), as the runs page's table;
    reading 'count' or 'layer': that reading's pairs alone. Part 'blocks': smallest and largest
    scatter over the block error of each run of the pairs; 'percent': of 100 scatter / value."""
    pairs = _replica_pairs(data, quantity, reading)
    scatter = math.sqrt(sum((a[0] - b[0]) ** 2 for a, b in pairs) / (2 * len(pairs)))
    if part == "scatter":
        return (scatter,)
    runs = [run for pair in pairs for run in pair]
    ratios = {"blocks": [scatter / run[1] for run in runs if run[1]],
              "percent": [100 * scatter / abs(run[0]) for run in runs]}[part]
    if not ratios:
        raise ValueError(f"replica:{quantity}: no block errors in its runs")
    return min(ratios), max(ratios)


def family_fits_range(data, series, names):
    """Smallest and largest of the fits named (',' between names) of the series ('a+b': both)."""
    values = [data.fits(part)[name][0] for part in series.split("+") for name in names.split(",")]
    return min(values), max(values)


def source_value(data, key):
    """The source's value of a row of results/source.csv (its source_low)."""
    rows = read_rows(data.path("results", "source.csv"))
    return float(next(r for r in rows if r["name"] == key)["source_low"])


def family_below_source(data, series, name, source_key):
    """The source's value minus a series fit's: how far the fit lies under the source."""
    return (source_value(data, source_key) - data.fits(series)[name][0],)


def family_readings(data, series, reading, rule, mu):
    """Smallest and largest theta - theta_source(I) of inertial_readings.csv: reading I, I_bagnold or
    I_local, rule pouliquen or muI, one friction."""
    column = {"pouliquen": "theta_minus_pouliquen_deg", "muI": "theta_minus_muI_deg"}[rule]
    values = [float(r[column]) for part in series.split("+")
              for r in read_rows(data.path("results", "series", part, "inertial_readings.csv"))
              if r["reading"] == reading and (mu == "all" or float(r["mu"]) == float(mu)) and r[column]]
    return min(values), max(values)


def family_ratio_range(data, series, numerator, denominator):
    """Smallest and largest numerator/denominator of the series' runs (runs.csv columns)."""
    values = [float(r[numerator]) / float(r[denominator]) for part in series.split("+")
              for r in data.runs_csv(part).values() if r.get(numerator) and r.get(denominator)]
    return min(values), max(values)


def family_fits(data, series, names):
    """The values of the fits named (',' between names), in that order."""
    return tuple(data.fits(series)[name][0] for name in names.split(","))


def family_table_range(data, prefix, label):
    """Smallest and largest number after 'LABEL:' (up to ';') in the count and layer cells of the
    rows of results/series/readings/source_comparison.csv whose key is PREFIX_mu<mu>."""
    values = []
    for row in data.comparison():
        if re.fullmatch(re.escape(prefix) + r"_mu[\d.]+", row["key"]):
            for cell in (row["count"], row["layer"]):
                part = cell.split(label + ":", 1)[1].split(";")[0]
                values += [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", part)]
    return min(values), max(values)


def family_f_L_without(data, largest):
    """The weighted exponent of f on L (f_L) over the runs with L < LARGEST: exponent and error."""
    points = [p for p in _f_points(data, "L_series", lambda row, results: math.log(float(row["L"])))
              if p[0] < math.log(float(largest))]
    slope, error, _ = weighted_slope([p[0] for p in points], [math.log(p[1]) for p in points], [p[2] for p in points])
    return slope, error


def family_size_law(data, mu):
    """The size law's shift of phi about the layer reading's phi(U) law at one friction, area minus
    diameter (studies/size_law_offset.py): mean and standard error, and the runs."""
    studies = data.path("studies")
    if studies not in sys.path:
        sys.path.insert(0, studies)
    import size_law_offset
    fits = size_law_offset.read_results(data.path("results", "series", "layer_flow_rules", "fits.csv"))
    rows = size_law_offset.shift_rows(data.path("results", "size_law"), data.path("results", "runs"), fits)
    shifts = [r["shift"] for r in rows if float(r["mu"]) == float(mu)]
    mean, _, se = statistics.mean(shifts), None, statistics.stdev(shifts) / math.sqrt(len(shifts))
    return mean, se, len(shifts)


def family_cmp(data, name, column="both"):
    """A fit of results/series/readings/compared_fits.csv: column 'count' or 'layer' its value and
    error, 'diff' layer - count in combined errors."""
    rows = {r["name"]: r for r in read_rows(data.path("results", "series", "readings", "compared_fits.csv"))}
    row = rows[name]
    if column == "diff":
        return (float(row["difference_sigma"]),)
    return (float(row[column]),) + ((float(row[column + "_error"]),) if row[column + "_error"] else ())


def _pairs(data, quantity, mu):
    """[(count value, layer value)] of a quantity at each angle both readings ran at one friction
    ('all': every friction)."""
    count = {(row["mu"], row["theta"]): name for name, row, _ in data.series_runs("flow_rules")}
    pairs = []
    for name, row, _ in data.series_runs("layer_flow_rules"):
        if (mu == "all" or float(row["mu"]) == float(mu)) and (row["mu"], row["theta"]) in count:
            a = data.quantity("flow_rules", count[(row["mu"], row["theta"])], quantity)
            b = data.quantity("layer_flow_rules", name, quantity)
            if a is not None and b is not None:
                pairs.append((a[0], b[0]))
    return pairs


def family_change(data, quantity, mu, how="fall"):
    """Over the angles both readings ran: 'fall' smallest and largest 100 (1 - layer/count) (%),
    'rise' 100 (layer/count - 1), 'diff' layer - count, 'ratio' count/layer, 'fall15'
    100 (1 - (layer/count)^1.5) (the fall of U that h^1.5 predicts from h), 'mean' mean and standard
    error of layer - count, 'median' median of layer - count."""
    pairs = _pairs(data, quantity, mu)
    if how == "mean":
        values = [b - a for a, b in pairs]
        return statistics.mean(values), statistics.stdev(values) / math.sqrt(len(values))
    if how == "median":
        return (statistics.median(b - a for a, b in pairs),)
    values = {"fall": [100 * (1 - b / a) for a, b in pairs], "rise": [100 * (b / a - 1) for a, b in pairs],
              "diff": [b - a for a, b in pairs], "ratio": [a / b for a, b in pairs],
              "fall15": [100 * (1 - (b / a) ** 1.5) for a, b in pairs]}[how]
    return min(values), max(values)


def family_ends(data, series, quantity, mu):
    """A quantity at the lowest and at the highest angle of one friction's runs of a series."""
    runs = sorted((float(row["theta"]), name) for name, row, _ in data.series_runs(series)
                  if float(row["mu"]) == float(mu))
    return tuple(data.quantity(series, runs[i][1], quantity)[0] for i in (0, -1))


def family_fit_scaled(data, series, name, factor):
    """A series fit's value and error times FACTOR (k × 10⁻³ printed as k: factor 1000)."""
    return tuple(x * float(factor) for x in family_fit(data, series, name))


def family_cmp_range(data, names, how="sigma"):
    """Over the compared fits named (',' between names): 'sigma' smallest and largest layer - count
    in combined errors, 'delta' in value, 'abs' the largest |layer - count| in combined errors,
    'ratio' layer/count of the one fit named."""
    rows = {r["name"]: r for r in read_rows(data.path("results", "series", "readings", "compared_fits.csv"))}
    chosen = [rows[name] for name in names.split(",")]
    if how == "ratio":
        return (float(chosen[0]["layer"]) / float(chosen[0]["count"]),)
    if how == "abs":
        return (max(abs(float(r["difference_sigma"])) for r in chosen),)
    values = [float(r["difference_sigma"]) if how == "sigma" else float(r["layer"]) - float(r["count"])
              for r in chosen]
    return min(values), max(values)


def family_fit_diff(data, series, names, references):
    """Each fit named minus its reference (',' between names, in pairs): a definition's shift."""
    fits = data.fits(series)
    return tuple(fits[a][0] - fits[b][0] for a, b in zip(names.split(","), references.split(",")))


FAMILIES = {"fit": family_fit, "run": family_run, "run_as": family_run_as, "range": family_range,
            "median": family_median,
            "f_mu": family_f_mu, "A_mu": family_A_mu, "f_L": family_f_L, "scaled_range": family_scaled_range,
            "list": family_list, "counts": family_counts, "packing": family_packing, "replica": family_replica,
            "fits_range": family_fits_range, "below_source": family_below_source, "readings": family_readings,
            "ratio_range": family_ratio_range, "fits": family_fits, "table_range": family_table_range,
            "f_L_without": family_f_L_without, "size_law": family_size_law,
            "cmp": family_cmp, "change": family_change, "ends": family_ends,
            "fit_scaled": family_fit_scaled, "cmp_range": family_cmp_range,
            "fit_diff": family_fit_diff, "local": family_local,
            "two_packings": family_two_packings}


def values_of(key, data):
    family, *arguments = key.split(":")
    if family not in FAMILIES:
        raise KeyError(f"no family '{family}'")
    return FAMILIES[family](data, *arguments)


def printed_spans(text):
    """[(start, end, value, decimals)] of the numbers in text, signs read as the module's docstring
    says (a sign not read as one is left outside the span)."""
    numbers = []
    for match in NUMBER.finditer(text):
        sign, digits, exponent = match.group(1), match.group(2), int((match.group(3) or "0").replace("−", "-"))
        start = match.start()
        if sign and not SIGN_BEFORE.search(text[:match.start()]):
            sign, start = "", match.start(2)
        value = float(digits) * 10.0 ** exponent * (-1 if sign in ("−", "-") else 1)
        decimals = (len(digits.split(".")[1]) if "." in digits else 0) - exponent
        numbers.append((start, match.end(), value, decimals))
    return numbers


def printed_numbers(text):
    """[(value, decimals)] of the numbers in text."""
    return [(value, decimals) for _, _, value, decimals in printed_spans(text)]


def agrees(printed, decimals, value):
    return abs(printed - value) <= 0.5 * 10 ** -decimals * (1 + 1e-9) + 1e-12


def _marked(text, data):
    """Per marker: (line, key, problem or None, [(start, end, printed, decimals, value)] of the
    numbers it checks, their spans in text)."""
    found = []
    paragraph_start = 0
    for match in MARKER.finditer(text):
        blank = text.rfind("\n\n", 0, match.start())
        start = max(blank + 2 if blank >= 0 else 0, paragraph_start)
        before, origin = _without_markers(text, start, match.start())
        line = text.count("\n", 0, match.start()) + 1
        key = match.group(1)
        try:
            values = values_of(key, data)
        except Exception as error:  # an unknown family, a missing file or quantity
            found.append((line, key, f"cannot compute: {error!r}", []))
            continue
        spans = printed_spans(before)[-len(values):]
        if len(spans) < len(values):
            found.append((line, key, f"{len(values)} numbers expected before the marker", []))
            continue
        numbers = [(origin(a), origin(a) + (b - a), p, dec, v) for (a, b, p, dec), v in zip(spans, values)]
        wrong = [(p, v) for _, _, p, dec, v in numbers if not agrees(p, dec, v)]
        problem = ", ".join(f"{p:g} printed, {v:.6g} computed" for p, v in wrong) if wrong else None
        found.append((line, key, problem, numbers))
    return found


def _without_markers(text, start, end):
    """text[start:end] with each marker read as one space, and the map from a position in it back
    to one in text (a number never spans a marker)."""
    pieces, offsets = [], []  # offsets: (position in the result, position in text) of each piece
    position, length = start, 0
    for match in MARKER.finditer(text, start, end):
        offsets.append((length, position))
        pieces += [text[position:match.start()], " "]
        length += match.start() - position + 1
        position = match.end()
    offsets.append((length, position))
    pieces.append(text[position:end])

    def origin(index):
        here, there = max(o for o in offsets if o[0] <= index)
        return there + index - here
    return "".join(pieces), origin


def check_text(text, data, page="text"):
    """[(page, line, key, problem)] of the markers of text."""
    return [(page, line, key, problem) for line, key, problem, _ in _marked(text, data) if problem]


def written(value, printed_text, decimals):
    """value as printed_text writes its number: the same decimals (or a mantissa's, in Python's
    exponent form), a sign where it has one or the value is negative ('−' unless it wrote '-')."""
    sign, digits, exponent = NUMBER.fullmatch(printed_text).groups()
    if exponent is None:
        body = f"{abs(value):.{max(decimals, 0)}f}"
    else:
        body = f"{abs(value):.{len(digits.split('.')[1]) if '.' in digits else 0}e}"
        if "−" in exponent:
            body = body.replace("-", "−")
    if value < 0 and float(body.replace("−", "-")) != 0:
        return ("-" if sign == "-" else "−") + body
    return ("+" if sign else "") + body


def update_text(text, data):
    """(text with every disagreeing number before a marker rewritten from its value, [(line, key,
    old, new)]); a number two markers disagree on is left and reported as a conflict."""
    replacements = {}
    for line, key, problem, numbers in _marked(text, data):
        for start, end, printed, decimals, value in numbers:
            if agrees(printed, decimals, value):
                continue
            new = written(value, text[start:end], decimals)
            previous = replacements.setdefault((start, end), (line, key, text[start:end], new))
            if previous[3] != new:
                replacements[(start, end)] = (line, key, text[start:end], "conflict: " + previous[3] + " / " + new)
    changes = []
    for (start, end), (line, key, old, new) in sorted(replacements.items(), reverse=True):
        changes.append((line, key, old, new))
        if not new.startswith("conflict"):
            text = text[:start] + new + text[end:]
    return text, sorted(changes)


def markers(text):
    return MARKER.findall(text)


def check_pages(root, pages=PAGES):
    data = Data(root)
    problems = []
    for page in pages:
        with open(os.path.join(root, page)) as src:
            problems += check_text(src.read(), data, page)
    return problems


def update_pages(root, pages=PAGES):
    """Rewrite the disagreeing numbers of the pages from the data; [(page, line, key, old, new)]."""
    data = Data(root)
    changes = []
    for page in pages:
        path = os.path.join(root, page)
        with open(path) as src:
            text, page_changes = update_text(src.read(), data)
        if any(not new.startswith("conflict") for *_, new in page_changes):
            with open(path, "w") as dst:
                dst.write(text)
        changes += [(page,) + change for change in page_changes]
    return changes
