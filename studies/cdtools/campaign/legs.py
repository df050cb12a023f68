"""A finished job: a deposition's result, a run's legs spliced into its folder, and its cost."""

import gzip
import math
import os
import shutil

from ..cdpost import RUN_RECORD
from ..lammps_files import read_chunk_records, read_dump_records, read_time_file, read_time_records, time_span
from ..logs import error_line, merged_solver_health, parse_summary, read_outputs, read_progress, solver_health
from .jobs import write_json

# Output files of one leg: (name, kind). Kind "time" is a fix ave/time file, "chunk" a fix
# ave/chunk file, "dump" a gzipped dump; all are spliced by time step.
LEG_OUTPUTS = (("flow.time", "time"), ("solver.time", "time"), ("profile.chunk", "chunk"),
               ("packing.chunk", "chunk"), ("layers.chunk", "chunk"), ("columns.chunk", "chunk"),
               ("dump.chute.gz", "dump"))
READERS = {"time": read_time_records, "chunk": read_chunk_records, "dump": read_dump_records}


def splice_legs(leg_dirs, starts, name, kind, destination):
    """Join one output file over the legs: the record of time step T is taken from the last
    leg that started at or before T and holds T (a later leg recomputed what an interrupted
    earlier one wrote past the restart it continues from). False if no leg holds a record."""
    chosen, header = {}, None
    for leg_dir, start in zip(leg_dirs, starts):
        path = os.path.join(leg_dir, name)
        if not os.path.exists(path):
            continue
        leg_header, records = READERS[kind](path)
        if header is None and leg_header:
            header = leg_header
        for step, text in records:
            if step >= start:
                chosen[step] = text
    if not chosen:
        return False
    body = "".join(header or []) + "".join(chosen[s] for s in sorted(chosen))
    tmp = destination + ".tmp"
    with (gzip.open(tmp, "wt") if kind == "dump" else open(tmp, "w")) as out:
        out.write(body)
    os.replace(tmp, destination)
    return True


def carry_record(leg_dirs, folder):
    """The newest leg's chute.params into the run's folder (the legs of a run share its
    variables); nothing if no leg has one (legs run before the deck wrote it)."""
    for leg_dir in reversed(leg_dirs):
        path = os.path.join(leg_dir, RUN_RECORD)
        if os.path.exists(path):
            shutil.copy2(path, os.path.join(folder, RUN_RECORD))
            return


def leg_error(leg_dir):
    """The first ERROR line of a leg's log or screen output, or None."""
    return error_line(read_outputs(leg_dir))


def finish_deposition(job):
    """result.json and DONE of a deposition whose process ended; the problem, or None."""
    progress = read_progress(os.path.join(job.folder, "log.lammps"))
    if not progress.summary or not os.path.exists(os.path.join(job.folder, "deposition.restart")):
        return leg_error(job.folder) or "deposition ended without its restart"
    result = parse_summary(progress.summary)
    result.update(wall_seconds=progress.wall, steps=progress.steps)
    write_json(os.path.join(job.folder, "result.json"), result)
    open(os.path.join(job.folder, "DONE"), "w").close()
    return None


def finish_run(job):
    """The legs' outputs spliced into the run's folder, its restart and chute.params, cost.json,
    result.json and DONE; the problem, or None."""
    legs = job.legs()
    starts = []
    for leg in legs:
        start = read_progress(os.path.join(leg, "log.lammps")).first_step
        starts.append(start if start is not None else math.inf)
    for name, kind in LEG_OUTPUTS:
        splice_legs(legs, starts, name, kind, os.path.join(job.folder, name))
    shutil.copy2(os.path.join(legs[-1], "chute.restart"), os.path.join(job.folder, "chute.restart"))
    carry_record(legs, job.folder)
    write_json(os.path.join(job.folder, "cost.json"), run_cost(job, legs))
    summary = read_progress(os.path.join(legs[-1], "log.lammps")).summary
    write_json(os.path.join(job.folder, "result.json"), parse_summary(summary))
    open(os.path.join(job.folder, "DONE"), "w").close()
    return None


def mean_solver_column(folder, column):
    """Mean of one column of a run's solver.time (per-step values of the fix averaged over each
    solver_interval), or None if the file or the column (older decks) is missing."""
    solver = os.path.join(folder, "solver.time")
    if not os.path.exists(solver):
        return None
    values = [row[column] for row in read_time_file(solver) if column in row]
    return sum(values) / len(values) if values else None


def run_cost(job, legs):
    """Wall and CPU time per physical second over the chute legs, from LAMMPS's own loop
    timers. A leg killed before its end printed no timers, so the physical time is the chute
    time covered by the legs that did."""
    wall, steps, cpu = 0.0, 0, 0.0
    spans = []
    for leg in legs:
        progress = read_progress(os.path.join(leg, "log.lammps"))
        wall += progress.wall
        steps += progress.steps
        cpu += progress.cpu
        span = time_span(os.path.join(leg, "flow.time"))
        if span and progress.steps > 0:
            spans.append(span)
    physical = max(s[1] for s in spans) - min(s[0] for s in spans) if spans else 0.0
    return dict(grains=job.grains(), steps=steps, physical_seconds=physical, wall_seconds=wall,
                wall_per_physical_second=wall / physical if physical > 0 else None,
                cpu_seconds=cpu, cpu_per_physical_second=cpu / physical if physical > 0 else None,
                seconds_per_grain_step=wall / (steps * job.grains()) if steps else None,
                mean_sweeps_per_step=mean_solver_column(job.folder, "f_cd[1]"),
                mean_solves_per_step=mean_solver_column(job.folder, "f_cd[12]"), legs=len(legs),
                solver=merged_solver_health([solver_health(os.path.join(leg, "log.lammps")) for leg in legs]))
