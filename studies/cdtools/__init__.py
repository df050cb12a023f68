"""The package of the project's Python tools (standard library only).

    lammps_files      fix ave/time and ave/chunk files, dumps (gzip cut by a kill included)
    logs              LAMMPS logs: the decks' 'TAG key value' lines, ERROR lines, thermo rows, timers
    run               paths, lmp_cd command lines and -var arguments, mpirun, running processes
    cdpost            finding cdpost, reading its results.csv
    stats             means and standard errors, pooled scatter, differences in errors, slopes
    text              numbers, values with errors, durations, Markdown tables
    page_numbers      the results pages' marked numbers recomputed from the committed data
    campaign/         the chute campaign of studies/chute_campaign.py

The study drivers beside this package (studies/*.py) are its users, one entry point each; the
benchmarks of bench/ that read LAMMPS files use it too.

How a tool imports it, one way everywhere (studies/, bench/, tests/), from any folder, with no
PYTHONPATH and nothing installed: the script puts the folder that holds this package (studies/)
first on sys.path, found from its own file, before it imports the package:

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "studies"))

(here from bench/; a study in studies/ inserts its own folder, which also makes the other studies
importable, one in tests/chute/ goes up two). realpath resolves symbolic links, so a script run
through one (the docs tests link bench/ and studies/ into scratch folders) still finds the package.
"""
