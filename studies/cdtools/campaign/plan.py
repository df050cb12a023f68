"""What the campaign runs: the series of the scene, the jobs they make (runs and the depositions
they start from), and the parameters each job records and must keep."""

import fnmatch
import math
import os
import re
import subprocess

from ..run import DECK, TOP
from ..text import parameter
from .jobs import Job, read_json, write_json

# The series of the scene (doc/chute.md). Angles in degrees, L in mean diameters d.
REPLICA_SEED = 20261123
SERIES = {
    "mu0.05": [dict(mu=0.05, theta=t, L=45) for t in range(16, 23)],
    "mu0.5": [dict(mu=0.5, theta=t, L=45) for t in range(22, 29)],
    "mu2": [dict(mu=2, theta=t, L=45) for t in range(24, 31)],
    "L": [dict(mu=0.5, theta=22, L=n) for n in (12, 22, 32, 52, 72, 102, 152)],
    # Another deposition (rain seed) at one point per friction: the scatter between two
    # realisations of a run, which the error bars of one run's windows understate.
    "replicas": [dict(mu=mu, theta=theta, L=45, seed=REPLICA_SEED)
                 for mu, theta in ((0.05, 20), (0.5, 24), (2, 28))],
}
# The other reading of the source's 45 d cell (doc/scene.md): the count whose flowing layer is
# 40-49 d thick (deck variable reading=layer), the same friction series and replicas.
LAYER_SERIES = {"layer_" + name: [dict(point, reading="layer") for point in SERIES[name]]
                for name in ("mu0.05", "mu0.5", "mu2", "replicas")}
SERIES.update(LAYER_SERIES)
# The evidence for the solver health of runs that did not record it (issue 63; doc/campaign.md,
# *Solver health*): one fresh 10 s run per friction and reading at the deck's defaults, named
# health_<run>. Their runs take no --var (DEFAULTS_ONLY) and join no analysis.
SERIES["health_evidence"] = [dict(mu=mu, theta=theta, L=45, reading=r) for mu, theta in ((0.05, 20), (0.5, 24), (2, 28))
                             for r in ("count", "layer")]
NAME_PREFIX = {"health_evidence": "health_"}

# The creep length: the grains' or the cell's (issue 63, item 3; doc/creep.md, *Grains or cell*).
# Count reading throughout. The deck's grains 0 scales the count with L alone, so a bed between
# other walls than the source's 30 d is given its grains: the 45 d cell's count scaled with L,
# plus the bed added (or taken away) at the trapped bed's packing, BED_PACKING (the layer
# reading's and the re-runs' phi over -29 < z < -1 d: 0.811-0.833), so that the same flowing layer
# stands over it.
SOURCE_WALLS, BED_PACKING, COUNT_PER_45D = 30, 0.82, 3967
CREEP_SEEDS = (20261124, 20261125)


def grains_for_walls(length, wall_height, dispersity=0.4):
    """Grains of the count reading's cell of `length` d between walls of `wall_height` d."""
    grain_area = math.pi / 4 * (1 + dispersity ** 2 / 12)   # in d^2 (the deck's, size law diameter)
    return round(COUNT_PER_45D * length / 45 + BED_PACKING * length * (wall_height - SOURCE_WALLS) / grain_area)


SERIES.update({
    # mu 0.5, 22 deg, L 45 between 15 and 60 d walls, two rains each.
    "creep_walls": [dict(mu=0.5, theta=22, L=45, wall_height=w, grains=grains_for_walls(45, w), seed=seed)
                    for w in (15, 60) for seed in (20261122, REPLICA_SEED)],
    # two more rains at L 22, 45, 72 (the L series' runs and the replica seed are the first).
    "creep_seeds": [dict(mu=0.5, theta=22, L=n, seed=seed) for n in (22, 45, 72) for seed in CREEP_SEEDS],
    # mu 2, 28 deg at L 22 and 102 (L 45: the count reading's mu 2 series re-run, mu2_theta28_L45).
    "creep_mu2": [dict(mu=2, theta=28, L=n) for n in (22, 102)],
    # the bed deepened to 60 d at L 102 and 152, where the creep reaches the 30 d bed's bottom.
    "creep_deep": [dict(mu=0.5, theta=22, L=n, wall_height=60, grains=grains_for_walls(n, 60)) for n in (102, 152)],
})
CREEP_SERIES = ("creep_walls", "creep_seeds", "creep_mu2", "creep_deep")

# The signs settled (issue 63, item 5; doc/campaign.md, *The signs' rains*): two more rains, seeds not
# used by any other series, in the layer reading at three angles per friction 2 deg apart inside
# each friction's published range (its ends left out: the slowest run nears the stop, mu 2's 30 deg
# lies beyond plane shear's I), so that f on mu, A on mu and their scatter between rains rest on
# three rains at each. They join the layer reading's flow-rules analysis.
SIGN_SEEDS = (20261126, 20261127)
SIGN_ANGLES = {0.05: (17, 19, 21), 0.5: (23, 25, 27), 2: (25, 27, 29)}
SERIES["layer_signs"] = [dict(mu=mu, theta=theta, L=45, seed=seed, reading="layer")
                         for mu, angles in SIGN_ANGLES.items() for theta in angles for seed in SIGN_SEEDS]
DEFAULTS_ONLY = {"health_evidence"}
# The series whose runs measure the flow of the 45 d cell at the published settings: the readings'
# means and the replica pairs are made of these alone.
FLOW_SERIES = ("mu0.05", "mu0.5", "mu2", "replicas") + tuple(LAYER_SERIES)
# The cdpost series analyses: the flow rules need every mu together; the L series also takes
# the 45 d run at the same (mu, theta) from the mu = 0.5 series.
ANALYSES = {
    "flow_rules": lambda job: job.series in ("mu0.05", "mu0.5", "mu2"),
    "L_series": lambda job: (job.series in ("L", "mu0.5") and float(job.vars["mu"]) == 0.5
                             and float(job.vars["theta"]) == 22 and reading(job.vars) == "count"),
    "layer_flow_rules": lambda job: job.series in ("layer_mu0.05", "layer_mu0.5", "layer_mu2", "layer_signs"),
    # The creep length against L and the walls: the creep series, the L series, and the 45 d runs
    # they extend (mu 0.5 at 22 deg, mu 2 at 28 deg; count reading, first rain).
    "creep_length": lambda job: (job.series in CREEP_SERIES + ("L",)
                                 or (job.series, float(job.vars["theta"])) in (("mu0.5", 22), ("mu2", 28))),
}

# Deck variables that shape the deposition: one packing serves every run with the same
# values (by default one per L, deposited with mu_deposition = 0.5, for all three mu).
DEPOSITION_VARS = ("L", "reading", "grains", "wall_height", "mu_deposition", "e", "e_wall", "seed", "d",
                   "dispersity", "density", "g", "dt_deposition", "tolerance_deposition",
                   "rain_fill", "settle_ke", "settle_max", "max_iterations_deposition")
# Wall laws default to the grains' (mu, e) of each run unless --var sets them.
WALL_DEFAULTS = {"mu_wall": "mu", "e_wall": "e"}


def deck_defaults():
    """The deck's index variables and their defaults (the deck is the one source)."""
    defaults = {}
    with open(DECK) as src:
        for line in src:
            match = re.match(r"variable\s+(\w+)\s+index\s+(\S+)", line)
            # An empty default ("") is the deck's own: passed on, it would reach LAMMPS as a word.
            if match and "${" not in match.group(2) and match.group(2) != '""':
                defaults[match.group(1)] = match.group(2)
    defaults.pop("stage", None)
    defaults.pop("start", None)
    return defaults


def run_variables(args, defaults, point, series=None):
    """The deck variables of one series point: the deck's defaults, the point's values, then
    --var (which wins; not for a series of DEFAULTS_ONLY), the wall laws following the grains'
    unless set."""
    given = {} if series in DEFAULTS_ONLY else args.var
    variables = dict(defaults, duration=parameter(args.duration))
    variables.update({key: parameter(value) for key, value in point.items()})
    variables.update(given)
    for wall, grain in WALL_DEFAULTS.items():
        if not given.get(wall):
            variables[wall] = variables[grain]
    return variables


def reading(variables):
    """The reading of the source's cell a job's variables select ('count' before the switch)."""
    return variables.get("reading", "count")


def reading_suffix(variables):
    return "" if reading(variables) == "count" else "_" + reading(variables)


def wall_suffix(point):
    """'_wall<h>' for a series point whose walls are not the source's 30 d, else '' (walls set by
    --var name no run: the whole campaign stands between them)."""
    walls = (point or {}).get("wall_height", SOURCE_WALLS)
    return "" if same_value(walls, SOURCE_WALLS) else f"_wall{walls}"


def run_name(variables, defaults, series=None, point=None):
    name = NAME_PREFIX.get(series, "") + f"mu{variables['mu']}_theta{variables['theta']}_L{variables['L']}"
    name += f"_seed{variables['seed']}" if variables["seed"] != defaults["seed"] else ""
    return name + wall_suffix(point) + reading_suffix(variables)


def build_jobs(args):
    """The depositions, then the runs, of the series and runs selected (--series, --only)."""
    defaults = deck_defaults()
    depositions, runs = {}, {}
    for series in args.series or list(SERIES):
        for point in SERIES[series]:
            variables = run_variables(args, defaults, point, series)
            name = run_name(variables, defaults, series, point)
            if args.only and not any(fnmatch.fnmatch(name, p) for p in args.only):
                continue
            for pattern, values in getattr(args, "run_var", []):
                if fnmatch.fnmatch(name, pattern):
                    variables.update(values)
            deposition = deposition_of(args, variables, depositions, point)
            if name not in runs:
                runs[name] = new_run(args, name, series, variables, deposition)
    return list(depositions.values()) + list(runs.values())


def deposition_of(args, variables, depositions, point=None):
    """The deposition a run starts from, added to `depositions` if new."""
    dep_vars = {k: variables[k] for k in DEPOSITION_VARS if k in variables}
    name = (f"mu{dep_vars['mu_deposition']}_L{dep_vars['L']}_seed{dep_vars['seed']}" + wall_suffix(point)
            + reading_suffix(dep_vars))
    if name not in depositions:
        depositions[name] = Job("deposition", name, os.path.join(args.out, "depositions", name), dep_vars)
    return depositions[name]


def new_run(args, name, series, variables, deposition):
    folder = os.path.join(args.out, "runs", name)
    recorded = read_json(os.path.join(folder, "params.json"))
    if recorded is not None:
        old = recorded.get("vars", {})
        if float(old.get("duration", 0)) > float(variables["duration"]):
            variables["duration"] = old["duration"]    # an extended run stays extended
        # A deck variable added after the run started is not the run's: it goes on with its own
        # copy of the deck, which has that variable's old behaviour (unless --var sets it).
        given = set(args.var).union(*(values for _, values in getattr(args, "run_var", [])))
        for key in set(variables) - set(old) - given:
            del variables[key]
    return Job("run", name, folder, variables, deposition, series)


def same_value(a, b):
    """Two deck values are the same setting: equal as numbers (1e-4 and 1.0e-4), else as text."""
    try:
        return float(a) == float(b)
    except (TypeError, ValueError):
        return str(a) == str(b)


def changed_vars(old, new, keys):
    """'name old -> new' for each of `keys` whose value differs but duration (runs are
    extended), comma-separated; '' if none."""
    changed = sorted(k for k in keys if k != "duration" and not same_value(old.get(k), new.get(k)))
    return ", ".join(f"{k} {old.get(k)} -> {new.get(k)}" for k in changed)


def check_recorded_params(job):
    """A run continues only with the parameters it was started with (duration may grow)."""
    path = os.path.join(job.folder, "params.json")
    recorded = read_json(path)
    if recorded is None:
        return None
    old = recorded.get("vars", {})
    changed = changed_vars(old, job.vars, set(old) | set(job.vars))
    return "parameters differ from those recorded in " + path + ": " + changed if changed else None


def recorded_duration(job):
    """The chute time a run's params.json records (its own if none is recorded)."""
    recorded = read_json(os.path.join(job.folder, "params.json"), {})
    return float(recorded.get("vars", {}).get("duration", job.vars["duration"]))


def git_commit():
    try:
        return subprocess.run(["git", "-C", TOP, "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def record_params(job, args):
    path = os.path.join(job.folder, "params.json")
    os.makedirs(job.folder, exist_ok=True)
    data = read_json(path, {})
    data.update(name=job.name, kind=job.kind, vars=job.vars, deck=job.deck, deck_source=DECK, lmp=args.lmp,
                launcher=args.launcher, commit=data.get("commit", git_commit()),
                units="SI: m, s, kg; L, wall_height in d; theta in degrees",
                y_top=float(job.vars["wall_height"]) * float(job.vars["d"]),
                grains=job.grains())
    if job.kind == "run":
        data["deposition"] = job.deposition.folder
        data["series"] = job.series
    write_json(path, data)
