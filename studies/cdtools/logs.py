"""LAMMPS logs and screen output: the decks' summary lines ('TAG key value ...'), ERROR lines,
thermo rows, and the run loops' timers."""

import dataclasses
import os
import re


def parse_summary(line):
    """'DEPOSITION grains 3967 time_s 0.35 ...' -> {key: number, or the text if not one}."""
    fields = line.split()[1:]
    result = {}
    for key, value in zip(fields[0::2], fields[1::2]):
        try:
            result[key] = float(value)
        except ValueError:
            result[key] = value
    return result


def tagged_line(text, tag):
    """The first line of text starting with 'TAG ', parsed (parse_summary), or None."""
    line = next((line for line in text.splitlines() if line.startswith(tag + " ")), None)
    return None if line is None else parse_summary(line)


def log_summary(folder, tag):
    """The last line of folder/log.lammps starting with 'TAG ', parsed; RuntimeError naming the
    log if there is none (the run did not reach it)."""
    path = os.path.join(folder, "log.lammps")
    line = None
    with open(path) as src:
        for candidate in src:
            if candidate.startswith(tag + " "):
                line = candidate
    if line is None:
        raise RuntimeError(f"{path}: no line starting with {tag}")
    return parse_summary(line)


def error_line(text):
    """The first ERROR line of a log or screen text, stripped, or None."""
    return next((line.strip() for line in text.splitlines() if line.startswith("ERROR")), None)


def read_outputs(folder, names=("log.lammps", "screen.txt")):
    """The text of a run folder's log and screen output (those that exist), one after the other."""
    text = []
    for name in names:
        try:
            with open(os.path.join(folder, name), errors="replace") as src:
                text.append(src.read())
        except OSError:
            pass
    return "".join(text)


def thermo_rows(text, first_column="Step"):
    """Rows of every thermo block of a log or screen text, as dicts by column name."""
    rows, names = [], None
    for line in text.splitlines():
        fields = line.split()
        if fields and fields[0] == first_column:
            names = fields
            continue
        if names is None:
            continue
        if len(fields) != len(names):
            names = None
            continue
        try:
            rows.append(dict(zip(names, map(float, fields))))
        except ValueError:
            names = None
    return rows


def has_non_finite(text):
    """True if a nan or inf stands in the text as a number."""
    return re.search(r"(?<![A-Za-z_])-?(nan|inf)(?![A-Za-z_])", text, re.IGNORECASE) is not None


@dataclasses.dataclass
class LogProgress:
    """How far a run's log got, and LAMMPS's own timers of its run loops."""
    first_step: int = None    # step of the first thermo row (where the run started)
    last_step: int = None     # step of the last thermo row
    wall: float = 0.0         # wall seconds of the finished loops ('Loop time of')
    steps: int = 0            # steps of those loops
    cpu: float = 0.0          # CPU seconds of those loops (wall time x '% CPU use')
    summary: str = None       # the last summary line of one of the tags asked for


LOOP_TIME = re.compile(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps")
CPU_USE = re.compile(r"([0-9.]+)% CPU use(?: with (\d+) MPI tasks)?")


def read_progress(path, tags=("CHUTE", "DEPOSITION")):
    """LogProgress of a log file (all zeros and None if it cannot be read)."""
    progress = LogProgress()
    in_thermo, loop_wall = False, None
    try:
        with open(path) as src:
            for line in src:
                if line.startswith("Step "):
                    in_thermo = True
                    continue
                if line.startswith("Loop time of"):
                    in_thermo = False
                    loop = LOOP_TIME.match(line)
                    if loop:
                        loop_wall = float(loop.group(1))
                        progress.wall += loop_wall
                        progress.steps += int(loop.group(2))
                    continue
                cpu = CPU_USE.match(line)
                if cpu and loop_wall is not None:
                    # LAMMPS's CPU use is the mean over the MPI tasks (each with its threads).
                    tasks = int(cpu.group(2) or 1)
                    progress.cpu += loop_wall * tasks * float(cpu.group(1)) / 100.0
                    loop_wall = None
                    continue
                if line.startswith(tuple(tag + " " for tag in tags)):
                    progress.summary = line.strip()
                fields = line.split()
                if in_thermo and fields and fields[0].isdigit():
                    progress.last_step = int(fields[0])
                    if progress.first_step is None:
                        progress.first_step = progress.last_step
    except OSError:
        pass
    return progress


# The fix's end-of-run line (cd::describe of its run statistics).
SOLVER_LINE = re.compile(
    r"Fix contact/dynamics \S+ solver: (?P<steps>\d+) steps, (?P<unconverged>\d+) unconverged \([^)]*\), "
    r"largest final norm (?P<largest_final_norm>[^,]+), sweeps per step median (?P<sweeps_median>\d+), "
    r"99th percentile (?P<sweeps_p99>\d+), max (?P<sweeps_max>\d+), (?P<rescued>\d+) rescued from a stall"
    r"(?: \((?P<restarted>\d+) started again from zero(?:, (?P<block_solved>\d+) by exact block solves)?\))?")


def solver_health(path):
    """The last end-of-run solver line of a log as numbers, or None if it has none (a leg killed
    before its end, or a log of a build before the line existed)."""
    found = None
    try:
        with open(path) as src:
            for line in src:
                match = SOLVER_LINE.search(line)
                if match:
                    found = match
    except OSError:
        return None
    if found is None:
        return None
    health = {key: float(value) if key == "largest_final_norm" else int(value or 0)
              for key, value in found.groupdict().items()}
    return with_fraction(health)


def with_fraction(health):
    health["unconverged_fraction"] = health["unconverged"] / health["steps"] if health["steps"] else 0.0
    return health


def merged_solver_health(healths):
    """One run's solver health from its legs' (None where a leg recorded none). Counts add and the
    largest values are the largest; the sweep quantiles of several legs are their step-weighted
    median and largest 99th percentile, marked by 'legs' > 1. None if no leg recorded any."""
    recorded = [h for h in healths if h]
    if not recorded:
        return None
    if len(recorded) == 1:
        return dict(recorded[0], legs=1, legs_unrecorded=len(healths) - 1)
    merged = {key: sum(h.get(key, 0) for h in recorded)
              for key in ("steps", "unconverged", "rescued", "restarted", "block_solved")}
    merged["largest_final_norm"] = max(h["largest_final_norm"] for h in recorded)
    merged["sweeps_max"] = max(h["sweeps_max"] for h in recorded)
    merged["sweeps_p99"] = max(h["sweeps_p99"] for h in recorded)
    by_median = sorted(recorded, key=lambda h: h["sweeps_median"])
    half, seen = merged["steps"] / 2.0, 0
    for h in by_median:
        seen += h["steps"]
        if seen >= half:
            merged["sweeps_median"] = h["sweeps_median"]
            break
    merged.update(legs=len(recorded), legs_unrecorded=len(healths) - len(recorded))
    return with_fraction(merged)
