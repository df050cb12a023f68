"""The erodible-bed chute campaign behind studies/chute_campaign.py (doc/chute.md).

A campaign is a set of runs, each a chute at one (mu, theta, L) started from a settled packing
deposited at the same (mu, L, seed). Every deposition and every run has its own folder under
the campaign's folder:

    depositions/<name>/   deposition.restart, .data, .dump, log, params.json, result.json
    runs/<name>/          params.json; legs/NN/ (one lmp_cd process each); when finished the
                          spliced flow.time, profile.chunk, packing.chunk, layers.chunk,
                          solver.time, dump.chute.gz, chute.restart, cost.json, DONE, post/
    series/<series>/manifest.csv and the cdpost series analysis (series-post/)

A run is made of legs: each leg is one lmp_cd process started from the deposition or from the
newest restart of the previous legs, running up to the same chute time (run ... upto). An
interrupted campaign started again with the same options skips finished runs and continues
unfinished ones from their newest restart. The legs' output files are spliced by time step when
the run finishes (later legs win).

Modules: plan (the series, the jobs and their recorded parameters), jobs (one job's folder,
legs and process), legs (splicing and cost of a finished run), schedule (running the jobs),
report (the results folder of --report).
"""
