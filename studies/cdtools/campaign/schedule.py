"""Running the campaign's jobs: several at once, runs after their deposition, progress and time
left, a finished run postprocessed (and extended while cdpost finds it not stationary), a clean
stop on SIGINT or SIGTERM."""

import os
import shlex
import shutil
import signal
import subprocess
import sys
import time

from ..cdpost import find_cdpost
from ..lammps_files import time_span
from ..logs import read_outputs, read_progress
from ..text import duration, parameter
from .jobs import read_json
from .legs import finish_deposition, finish_run, leg_error
from .plan import check_recorded_params, record_params, recorded_duration
from .post import analysed, postprocess_run, postprocess_series, window_seconds


def list_jobs(jobs):
    """--list: every job, its grains and state (runs: the chute time reached)."""
    for job in jobs:
        state = "done" if job.done else ("started" if job.kind == "run" and job.legs() else "pending")
        extra = ""
        if job.kind == "run":
            reached = job.work_done()
            extra = f"  {reached:.3f}/{job.vars['duration']} s"
            if job.done and reached < float(job.vars["duration"]) - 1e-9:
                state = "to extend"
        print(f"{job.kind:10s} {job.name:34s} {job.grains():6d} grains  {state}{extra}")


def parameter_problem(jobs):
    """The first run whose parameters differ from those it recorded, as a message; or None."""
    for job in jobs:
        problem = check_recorded_params(job)
        if problem and job.kind == "run":
            return f"{job.name}: {problem}"
    return None


def reopen_extended_runs(jobs, args):
    """Runs whose duration was raised since they finished are continued, and so are analysed
    runs whose stationary window is shorter than --min-window-seconds (while --max-duration allows)."""
    for job in jobs:
        if job.kind == "run" and job.done and float(job.vars["duration"]) > recorded_duration(job) + 1e-12:
            os.remove(os.path.join(job.folder, "DONE"))
        elif not args.dry_run and job.kind == "run" and analysed(job) and short_window(job, args) \
                and can_extend(job, args):
            print(f"{job.name}: stationary window {window_seconds(job):.2f} s, extended to {extend(job, args)} s",
                  flush=True)


def short_window(job, args):
    window = window_seconds(job)
    return window is not None and window < args.min_window_seconds


def can_extend(job, args):
    return args.max_duration > float(job.vars["duration"]) + 1e-9


def jobs_to_run(jobs):
    """The unfinished jobs, less those whose lmp_cd another runner left running."""
    pending = []
    for job in jobs:
        if job.done:
            continue
        live = job.live_leg()
        if live:
            print(f"{job.name}: {live[0]} is still being run by pid {live[1]}; skipped "
                  "(stop that process or wait for it, then run again)", flush=True)
            continue
        pending.append(job)
    return pending


def print_plan(jobs, pending, args):
    print(f"{len(jobs)} jobs ({sum(j.kind == 'run' for j in jobs)} runs, "
          f"{sum(j.kind == 'deposition' for j in jobs)} depositions), {len(jobs) - len(pending)} done; "
          f"{args.jobs} at once, launcher: {' '.join(args.launcher) or '(none)'}", flush=True)


def print_commands(pending, args):
    """--dry-run: the command line of each pending job."""
    for job in pending:
        print(" ".join(shlex.quote(c) for c in job.command(args, "<restart>")))


def after_run(job, args, cdpost, pending):
    """Report a finished run, postprocess it, and extend it when it is not stationary or its
    stationary window is shorter than --min-window-seconds."""
    line = f"done run {job.name}"
    cost = read_json(os.path.join(job.folder, "cost.json"), {})
    if cost.get("cpu_per_physical_second"):
        line += (f": {cost['cpu_per_physical_second']:.0f} CPU s ({cost['wall_per_physical_second']:.0f}"
                 " wall s) per physical second")
    if cdpost:
        ok, message = postprocess_run(job, cdpost, args)
        line += "; cdpost " + ("done" if ok else "failed: " + message)
        if not ok and "stationary" in message and can_extend(job, args):
            line += "; extended to " + extend(job, args) + " s"
            pending.insert(0, job)
        elif ok and short_window(job, args) and can_extend(job, args):
            line += f"; stationary window {window_seconds(job):.2f} s, extended to " + extend(job, args) + " s"
            pending.insert(0, job)
    print(line, flush=True)


def extend(job, args):
    """Raises a finished run's duration by --extend (at most --max-duration) and reopens it;
    returns the new duration."""
    new = parameter(min(float(job.vars["duration"]) + args.extend, args.max_duration))
    job.vars["duration"] = new
    os.remove(os.path.join(job.folder, "DONE"))
    record_params(job, args)
    job.restart_candidates = []
    return new


def measured_rate(jobs):
    """Wall seconds per grain and chute second over every chute leg so far, or None."""
    seconds, grain_seconds = 0.0, 0.0
    for job in jobs:
        if job.kind != "run":
            continue
        for leg in job.legs():
            span = time_span(os.path.join(leg, "flow.time"))
            if span:
                seconds += read_progress(os.path.join(leg, "log.lammps")).wall
                grain_seconds += (span[1] - span[0]) * job.grains()
    return seconds / grain_seconds if grain_seconds > 0 else None


def estimate_left(jobs, running, seconds_per_grain_chute_second, jobs_at_once):
    """Wall seconds left: running legs from their own rate, queued work from the cost model
    (runs: the measured rate, when there is one)."""
    left_running, queued = [], 0.0
    for job in jobs:
        if job.done or job.failed:
            continue
        per_work = job.prior_seconds_per_work()
        if job.kind == "run" and seconds_per_grain_chute_second:
            per_work = job.grains() * seconds_per_grain_chute_second
        if job in running:
            rate = job.poll_rate()
            reached = job.current_work()
            remaining = max(job.expected_work() - (reached if reached is not None else job.work_done()), 0)
            left_running.append(remaining / rate if rate else remaining * per_work)
        else:
            queued += max(job.expected_work() - job.work_done(), 0) * per_work
    busy = max(left_running) if left_running else 0.0
    return max(busy, (sum(left_running) + queued) / max(jobs_at_once, 1))


class Scheduler:
    """Runs the pending jobs --jobs at a time until all ended or a signal asks to stop."""

    def __init__(self, jobs, pending, args, cdpost):
        self.jobs, self.pending, self.args, self.cdpost = jobs, pending, args, cdpost
        self.running = []
        self.failures = 0
        self.stop_signal = None
        self.last_report = 0.0

    def run(self):
        """Exit status: 0 if every job finished, 1 if any failed, 130 if interrupted."""
        signal.signal(signal.SIGINT, self._on_signal)
        signal.signal(signal.SIGTERM, self._on_signal)
        while (self.pending or self.running) and self.stop_signal is None:
            self._start_what_can_start()
            self._collect_what_ended()
            self._report_progress()
            self._sleep_unless_stopped(self.args.poll)
        if self.stop_signal is not None:
            self._stop_running()
            print("interrupted: run the same command again to continue", flush=True)
            return 130
        if self.cdpost and not self.args.only:
            postprocess_series(self.jobs, self.cdpost, self.args)
        print(f"finished: {sum(j.done for j in self.jobs)}/{len(self.jobs)} done, {self.failures} failed", flush=True)
        return 1 if self.failures else 0

    def _on_signal(self, signum, _frame):
        self.stop_signal = signum

    def _sleep_unless_stopped(self, seconds):
        """Waits between polls, but stops the running legs within a tenth of a second of a
        signal: a leg left running would go on past the restart the next invocation resumes."""
        end = time.time() + seconds
        while self.stop_signal is None and time.time() < end:
            time.sleep(min(0.1, max(0.0, end - time.time())))

    def _fail(self, job, problem):
        job.failed = problem
        self.failures += 1
        print(f"FAILED {job.kind} {job.name}: {problem}", flush=True)

    def _start_what_can_start(self):
        for job in list(self.pending):
            if len(self.running) >= self.args.jobs:
                break
            if job.kind == "run" and not job.deposition.done:
                self._check_deposition(job)
            elif job.kind == "run" and job.last_leg_complete():
                # The runner stopped between the end of the last leg and the splicing.
                self.pending.remove(job)
                finish_run(job)
                after_run(job, self.args, self.cdpost, self.pending)
            else:
                self._start(job)

    def _check_deposition(self, job):
        """A run waits for its deposition; it fails if the deposition failed or will not run."""
        deposition = job.deposition
        if deposition.failed or (deposition not in self.pending and deposition not in self.running):
            self.pending.remove(job)
            self._fail(job, "its deposition " + ("failed" if deposition.failed else "is not available"))

    def _start(self, job):
        record_params(job, self.args)
        start = job.launch(self.args)
        self.pending.remove(job)
        self.running.append(job)
        origin = f" from {os.path.relpath(start, self.args.out)}" if start else ""
        print(f"start {job.kind} {job.name} ({job.grains()} grains){origin}", flush=True)

    def _collect_what_ended(self):
        for job in list(self.running):
            code = job.process.poll()
            if code is not None:
                self.running.remove(job)
                self._ended(job, code)

    def _ended(self, job, code):
        if code != 0:
            problem = leg_error(job.leg_dir) or f"lmp_cd exit status {code}"
            if self._retry_older_restart(job, problem):
                return
        elif job.kind == "deposition":
            problem = finish_deposition(job)
        else:
            problem = finish_run(job)
        if problem:
            self._fail(job, problem)
        elif job.kind == "run":
            after_run(job, self.args, self.cdpost, self.pending)
        else:
            result = read_json(os.path.join(job.folder, "result.json"), {})
            print(f"done deposition {job.name}: phi_bed {result.get('phi_bed')}, bed top "
                  f"{result.get('expected_height_d')} d, settled at {result.get('time_s')} s", flush=True)

    def _retry_older_restart(self, job, problem):
        """A leg that failed reading its restart before running (the newest restart was cut by
        a kill) is tried again from the restart before it. True if it will be."""
        never_ran = "Setting up Verlet run" not in read_outputs(job.leg_dir)
        if job.kind != "run" or not never_ran or "restart" not in problem.lower() or not job.restart_candidates:
            return False
        print(f"{job.name}: {problem}; trying an older restart", flush=True)
        shutil.rmtree(job.leg_dir)
        self.pending.insert(0, job)
        return True

    def _report_progress(self):
        now = time.time()
        if now - self.last_report < self.args.progress_interval or not (self.running or self.pending):
            return
        self.last_report = now
        left = estimate_left(self.jobs, self.running, measured_rate(self.jobs), self.args.jobs)
        finished = sum(j.done for j in self.jobs)
        parts = [f"{job.name} {100.0 * (job.current_work() or 0) / job.total_work():.0f}%" for job in self.running]
        print(f"[{finished}/{len(self.jobs)} done, {len(self.running)} running, {len(self.pending)} queued] "
              + ", ".join(parts) + f"; time left ~{duration(left)}", flush=True)

    def _stop_running(self):
        for job in self.running:
            try:
                os.killpg(job.process.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
        for job in self.running:
            try:
                job.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(job.process.pid, signal.SIGKILL)


def campaign_cdpost(args):
    """The cdpost of --cdpost (None for 'none', saying so when it is not found)."""
    if args.cdpost == "none":
        return None
    cdpost = find_cdpost(args.cdpost)
    if cdpost is None:
        print("cdpost not found (build/postproc/cdpost, --cdpost): runs are not postprocessed", flush=True)
    return cdpost


def run_campaign(jobs, args):
    """Runs the campaign's unfinished jobs (--dry-run: lists their commands); returns the exit
    status."""
    problem = parameter_problem(jobs)
    if problem:
        print(problem, file=sys.stderr)
        return 2
    cdpost = campaign_cdpost(args)
    reopen_extended_runs(jobs, args)
    pending = jobs_to_run(jobs)
    print_plan(jobs, pending, args)
    if args.dry_run:
        print_commands(pending, args)
        return 0
    return Scheduler(jobs, pending, args, cdpost).run()
