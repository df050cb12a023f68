"""The package of the project's Python tools (standard library only).

    lammps_files   fix ave/time and ave/chunk files, dumps (gzip cut by a kill included)
    logs           LAMMPS logs: the decks' 'TAG key value' lines, ERROR lines, thermo rows, timers
    run            paths, lmp_cd command lines and -var arguments, mpirun, running processes
    cdpost         finding cdpost, reading its results.csv
    stats          means and standard errors, pooled scatter, differences in errors, slopes
    text           numbers, values with errors, durations, Markdown tables
    campaign/      the chute campaign of scripts/chute_campaign.py

How the tools import it, without editing sys.path: Python puts a script's folder first on the
module path, so scripts/*.py find this folder beside them; bench/cdtools is a link to it for
bench/*.py; the tests in tests/chute get PYTHONPATH=scripts:bench from ctest (by hand:
PYTHONPATH=scripts:bench tests/chute/test_cdtools.py).
"""
