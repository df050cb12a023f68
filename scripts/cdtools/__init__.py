"""The package of the project's Python tools (standard library only).

    lammps_files      fix ave/time and ave/chunk files, dumps (gzip cut by a kill included)
    logs              LAMMPS logs: the decks' 'TAG key value' lines, ERROR lines, thermo rows, timers
    run               paths, lmp_cd command lines and -var arguments, mpirun, running processes
    cdpost            finding cdpost, reading its results.csv
    stats             means and standard errors, pooled scatter, differences in errors, slopes
    text              numbers, values with errors, durations, Markdown tables
    campaign/         the chute campaign of scripts/chute_campaign.py
    stability_matrix  the stability matrix of scripts/stability_matrix.py
    rank_replicas     replica runs on several rank counts (bench/rank_replicas.py)
    rank_solutions    one step solved on several rank counts (bench/rank_solutions.py)
    step_profile      a step's perf samples grouped by its parts (bench/step_profile.py)

How a tool imports it, one way everywhere (scripts/, bench/, tests/), from any folder, with no
PYTHONPATH and nothing installed: the script puts the folder that holds this package (scripts/)
first on sys.path, found from its own file, before it imports the package:

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "scripts"))

(here from bench/; a script in scripts/ inserts its own folder, one in tests/chute/ goes up two).
realpath resolves symbolic links, so a script run through one (the docs tests link bench/ and
scripts/ into scratch folders) still finds the package.
"""
