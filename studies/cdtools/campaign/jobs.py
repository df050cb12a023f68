"""One job of the campaign, a deposition or a chute run: its folder, its legs, its process."""

import glob
import json
import os
import shlex
import shutil
import time

from ..lammps_files import time_span
from ..logs import parse_summary, read_progress
from ..run import DECK, lmp_command, start_detached

# Prior cost model for the time-left estimate before any run has been measured: wall seconds
# per grain and per second of chute time at the deck's defaults (doc/accuracy.md gives the
# measured cost of the 45 d scene), and per grain and deposition step; replaced by the
# measured rate of finished and running legs as soon as there is one. Chute progress is
# counted in chute time, not steps: the step follows the flow (adapt_dt), so steps do not
# map to time.
PRIOR_SECONDS_PER_GRAIN_CHUTE_SECOND = 0.02
PRIOR_SECONDS_PER_GRAIN_DEPOSITION_STEP = 1.0e-6
# Grains of the 45 d cell: a run of another length without a grain count scales them with L.
GRAINS_PER_45_D = {"count": 3967, "layer": 3290}   # in.chute's counts per 45 d of each reading


def write_json(path, data):
    """Writes data as JSON through a temporary file: a reader never sees half a file."""
    tmp = path + ".tmp"
    with open(tmp, "w") as out:
        json.dump(data, out, indent=2, sort_keys=True)
        out.write("\n")
    os.replace(tmp, path)


def read_json(path, default=None):
    try:
        with open(path) as src:
            return json.load(src)
    except (OSError, ValueError):
        return default


class Job:
    """One deposition or one chute run: a folder, its parameters, its legs."""

    def __init__(self, kind, name, folder, variables, deposition=None, series=None):
        self.kind = kind                  # "deposition" | "run"
        self.name = name
        self.folder = folder
        self.vars = variables             # deck variables (strings)
        self.deposition = deposition      # the Job this run starts from
        self.series = series              # the series a run was listed for
        self.process = None
        self.leg_dir = None
        self.leg_started = None
        self.failed = None
        self.restart_candidates = []
        self.rate_samples = []            # (wall time, work reached)

    # -- state on disk --
    @property
    def done(self):
        return os.path.exists(os.path.join(self.folder, "DONE"))

    def grains(self):
        n = int(float(self.vars.get("grains", "0")))
        per_45d = GRAINS_PER_45_D[self.vars.get("reading", "count")]
        return n if n > 0 else int(round(per_45d * float(self.vars["L"]) / 45))

    def total_work(self):
        """Deposition steps (at most settle_max), or the chute time of a run (s)."""
        if self.kind == "deposition":
            return int(round(float(self.vars["settle_max"]) / float(self.vars["dt_deposition"])))
        return float(self.vars["duration"])

    def expected_work(self):
        """total_work, except that most depositions settle within 0.6 s, not settle_max."""
        if self.kind == "deposition":
            return min(self.total_work(), int(0.6 / float(self.vars["dt_deposition"])))
        return self.total_work()

    def prior_seconds_per_work(self):
        if self.kind == "deposition":
            return self.grains() * PRIOR_SECONDS_PER_GRAIN_DEPOSITION_STEP
        return self.grains() * PRIOR_SECONDS_PER_GRAIN_CHUTE_SECOND

    def legs(self):
        return sorted(glob.glob(os.path.join(self.folder, "legs", "[0-9][0-9]")))

    def work_done(self):
        """Chute time already behind the newest usable restart (0 for a deposition): a
        finished leg's end, or an unfinished leg's last sample less one restart interval (its
        restarts come at least that often)."""
        if self.kind == "deposition":
            return 0
        best = 0.0
        for leg in self.legs():
            span = time_span(os.path.join(leg, "flow.time"))
            if span is None:
                continue
            if os.path.exists(os.path.join(leg, "chute.restart")):
                best = max(best, span[1])
            else:
                best = max(best, span[0], span[1] - float(self.vars["restart_interval"]))
        return best

    def restart_files(self):
        """Restart files to continue from, newest first."""
        files = []
        for leg in reversed(self.legs()):
            final = os.path.join(leg, "chute.restart")
            periodic = [os.path.join(leg, n) for n in ("restart.a", "restart.b")]
            periodic = [p for p in periodic if os.path.exists(p) and os.path.getsize(p) > 0]
            periodic.sort(key=os.path.getmtime, reverse=True)
            if os.path.exists(final):
                files.append(final)
            files.extend(periodic)
        return files

    def last_leg_complete(self):
        """True if the newest leg ran to the run's duration (finished but not spliced)."""
        legs = self.legs()
        if not legs or not os.path.exists(os.path.join(legs[-1], "chute.restart")):
            return False
        summary = read_progress(os.path.join(legs[-1], "log.lammps")).summary
        if not summary:
            return False
        reached = parse_summary(summary).get("time_s", 0.0)
        return reached >= float(self.vars["duration"]) - 0.5 * float(self.vars["dt"])

    def live_leg(self):
        """A leg whose lmp_cd still runs (started by a runner that did not stop it), or None."""
        folders = self.legs() if self.kind == "run" else [self.folder]
        for leg in folders:
            try:
                with open(os.path.join(leg, "pid")) as src:
                    pid = int(src.read())
                if os.path.realpath(os.readlink(f"/proc/{pid}/cwd")) == os.path.realpath(leg):
                    return leg, pid
            except (OSError, ValueError):
                continue
        return None

    # -- launching --
    @property
    def deck(self):
        """The job's own copy of in.chute, taken at its first launch: every leg of a run uses
        the same deck, and editing inputs/in.chute never changes a run under way."""
        return os.path.join(self.folder, "in.chute")

    def command(self, args, start_file):
        variables = dict(self.vars, stage="deposition" if self.kind == "deposition" else "flow")
        if self.kind == "run":
            variables["start"] = start_file
        variables = {key: variables[key] for key in sorted(variables)}
        return lmp_command(args.lmp, self.deck, variables, screen="screen.txt", launcher=args.launcher)

    def launch(self, args):
        """Starts the next leg (a deposition starts again from the rain); returns the restart
        file it starts from (None for a deposition)."""
        os.makedirs(self.folder, exist_ok=True)
        if not os.path.exists(self.deck):
            shutil.copy2(DECK, self.deck + ".tmp")
            os.replace(self.deck + ".tmp", self.deck)
        leg, start_file = self._deposition_leg() if self.kind == "deposition" else self._next_run_leg()
        cmd = self.command(args, start_file)
        with open(os.path.join(leg, "command.sh"), "w") as out:
            out.write("#!/bin/sh\ncd " + shlex.quote(leg) + " && " + " ".join(shlex.quote(c) for c in cmd) + "\n")
        self.process = start_detached(cmd, leg)
        with open(os.path.join(leg, "pid"), "w") as out:
            out.write(f"{self.process.pid}\n")
        self.leg_dir = leg
        self.leg_started = time.time()
        self.rate_samples = []
        return start_file

    def _deposition_leg(self):
        """A deposition is short: an interrupted one starts again from the rain, in its folder."""
        for stale in ("log.lammps", "screen.txt", "deposition.restart"):
            if os.path.exists(os.path.join(self.folder, stale)):
                os.remove(os.path.join(self.folder, stale))
        return self.folder, None

    def _next_run_leg(self):
        """The next legs/NN folder and the newest restart not yet tried (the deposition last)."""
        if not self.restart_candidates:
            self.restart_candidates = self.restart_files() + [
                os.path.join(self.deposition.folder, "deposition.restart")]
        start_file = self.restart_candidates.pop(0)
        leg = os.path.join(self.folder, "legs", f"{len(self.legs()):02d}")
        os.makedirs(leg)
        return leg, start_file

    # -- progress of the running leg --
    def current_work(self):
        """Deposition step or chute time reached by the running leg, None before its first
        output."""
        if self.leg_dir is None:
            return None
        if self.kind == "deposition":
            return read_progress(os.path.join(self.leg_dir, "log.lammps")).last_step
        span = time_span(os.path.join(self.leg_dir, "flow.time"))
        return span[1] if span else None

    def poll_rate(self):
        """Work (deposition steps, chute seconds) per wall second of the running leg, None until
        it progressed twice."""
        last = self.current_work()
        if last is None:
            return None
        now = time.time()
        if not self.rate_samples or self.rate_samples[-1][1] != last:
            self.rate_samples.append((now, last))
        self.rate_samples = self.rate_samples[-20:]
        if len(self.rate_samples) < 2:
            return None
        (t0, s0), (t1, s1) = self.rate_samples[0], self.rate_samples[-1]
        return (s1 - s0) / (t1 - t0) if t1 > t0 else None
