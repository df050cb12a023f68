"""Running lmp_cd and the programs around it: the repository's paths, lmp_cd command lines with
their -var arguments, MPI launchers, and processes run to completion (checked, or timed by their
CPU use) or started to run on their own."""

import os
import shutil
import signal
import subprocess
import threading
import time

TOP = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DECK = os.path.join(TOP, "inputs", "in.chute")
BUILT_LMP_CD = os.path.join(TOP, "build", "lmp_cd")
BUILT_CDPOST = os.path.join(TOP, "build", "postproc", "cdpost")


def deck_copy(folder):
    """folder/in.chute, copied from inputs/in.chute at its first use: LAMMPS reads a deck as it
    goes, so an edit of inputs/in.chute must never reach a study's run under way."""
    deck = os.path.join(folder, "in.chute")
    if not os.path.exists(deck):
        os.makedirs(folder, exist_ok=True)
        shutil.copy2(DECK, deck + ".tmp")
        os.replace(deck + ".tmp", deck)
    return deck


def var_arguments(variables):
    """{name: value} -> ['-var', name, value, ...] in the dict's order."""
    return [item for name, value in variables.items() for item in ("-var", name, str(value))]


def name_value_pairs(text):
    """'L=10 grains=200' -> {'L': '10', 'grains': '200'}; ValueError naming a pair without '='
    or a name given twice (LAMMPS would keep the first -var of a name without a word)."""
    pairs = {}
    for pair in text.split():
        if "=" not in pair:
            raise ValueError(f"'{pair}' is not name=value")
        name, value = pair.split("=", 1)
        if name in pairs:
            raise ValueError(f"'{name}' is given twice")
        pairs[name] = value
    return pairs


def lmp_command(lmp, deck, variables, log="log.lammps", screen=None, launcher=()):
    """launcher + lmp_cd reading `deck` with -var arguments; its log and screen output named."""
    command = list(launcher) + [lmp, "-in", deck, "-log", log]
    if screen is not None:
        command += ["-screen", screen]
    return command + var_arguments(variables)


def mpi_launcher(mpirun, ranks, oversubscribe=True):
    """mpirun -np ranks (oversubscribing if the cores are fewer), allowed to run as root."""
    launcher = [mpirun, "-np", str(ranks)] + (["--oversubscribe"] if oversubscribe else [])
    if os.geteuid() == 0:
        launcher.append("--allow-run-as-root")    # Open MPI refuses root otherwise
    return launcher


def run_checked(command, folder):
    """Runs command in folder (made if missing) and returns the wall seconds it took; a failure
    raises RuntimeError with the command and the last ERROR line of folder/log.lammps (else of
    the standard error)."""
    os.makedirs(folder, exist_ok=True)
    started = time.time()
    done = subprocess.run(command, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        log = os.path.join(folder, "log.lammps")
        errors = [line.strip() for line in open(log)] if os.path.exists(log) else []
        errors = [line for line in errors if line.startswith("ERROR")] or done.stderr.strip().splitlines()[-1:]
        raise RuntimeError(f"{' '.join(command)} failed in {folder}: {errors[-1:] or 'no message'}")
    return time.time() - started


def run_timed(command, folder, output, timeout):
    """Runs command in folder, its standard output and error into the file `output`; killed
    after `timeout` wall seconds. Returns (exit status, or 'timeout'; CPU seconds it used)."""
    with open(output, "w") as out:
        process = subprocess.Popen(command, cwd=folder, stdout=out, stderr=subprocess.STDOUT)
        timer = threading.Timer(timeout, process.kill)
        timer.start()
        _, status, usage = os.wait4(process.pid, 0)
        timer.cancel()
        process.returncode = os.waitstatus_to_exitcode(status)
    exit_status = "timeout" if process.returncode == -signal.SIGKILL else process.returncode
    return exit_status, usage.ru_utime + usage.ru_stime


def _die_with_parent():
    """In the child: SIGTERM when the parent dies (Linux prctl PR_SET_PDEATHSIG)."""
    try:
        import ctypes
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)
    except (OSError, AttributeError):
        pass


def start_detached(command, folder):
    """Starts command in folder in a session of its own (its output discarded), to be stopped
    with its process group; it receives SIGTERM if this process dies, so that a killed caller
    leaves no simulation writing into folders it will resume."""
    return subprocess.Popen(command, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True, preexec_fn=_die_with_parent)


def check_snapshot_study(parser, args):
    """The option checks of the studies that solve one step from snapshots (bench/
    solve_error_by_depth.py, rank_solutions): tolerances > 0 and snapshot files that exist;
    parser.error otherwise."""
    if min(args.tolerances + [args.reference_tolerance]) <= 0:
        parser.error("tolerances must be > 0")
    missing = [s for s in args.snapshots if not os.path.isfile(s)]
    if missing:
        parser.error(f"--snapshots: no file {missing[0]}")
