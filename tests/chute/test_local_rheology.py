#!/usr/bin/env python3
"""Checks of studies/local_rheology.py on synthetic tables, run by ctest (no simulation, no
figure), and of its committed re-run table against the re-run folders.

    tests/chute/test_local_rheology.py

Plane shear's mu(I) = mu_s + (mu_2 - mu_s)/(1 + I0/I) is recovered from exact points and phi(I) =
phi_c - b I from a line; a run on the fits has theta - arctan mu_ps(I) = 0 and phi - phi_ps = 0, one
a degree steeper +1; a re-run replaces its published run (and says so), a run of another reading
or name does not; the summary's ranges, means and counts by hand; the committed re-run table
(results/series/local_rheology/reruns/runs.csv) holds every finished re-run of results/rerun/, so a
re-run committed without `studies/local_rheology.py --cdpost ...` fails here. Standard library only.
"""

import math

from study_test import check, load_study


def fits_recovered(tool):
    inertial = [0.01, 0.03, 0.08, 0.15, 0.3, 0.5]
    exact = {"mu_s": 0.28, "mu_2": 0.95, "I0": 0.4}
    fit = tool.fit_mu_of_i(inertial, [tool.mu_at(exact, i) for i in inertial])
    check(all(abs(fit[k] - exact[k]) < 1e-6 for k in exact) and fit["rms"] < 1e-8, f"mu(I) fit {fit}")
    line = tool.fit_phi_of_i([0.0, 0.1, 0.2], [0.80, 0.77, 0.74])
    check(abs(line["phi_c"] - 0.80) < 1e-12 and abs(line["b"] - 0.3) < 1e-12 and line["rms"] < 1e-12,
          f"phi(I) fit {line}")
    try:
        tool.fit_mu_of_i([0.1, 0.2, 0.3], [0.3, 0.4, 0.5])
        check(False, "a mu(I) fit from 3 points is refused")
    except ValueError:
        pass
    return exact, line


def comparison(tool, mu_fit, phi_fit):
    fits = {0.5: {"mu": mu_fit, "phi": phi_fit, "I_range": (0.01, 0.2)}}
    on = math.degrees(math.atan(tool.mu_at(mu_fit, 0.1)))
    readings = [("count", {"a": (0.5, on, 0.1, 0.001, 0.77), "b": (0.5, on + 1.0, 0.1, None, 0.78),
                           "c": (2.0, 25.0, 0.1, None, 0.75)}),
                ("layer", {"a": (0.5, on, 0.3, None, 0.71)})]
    reruns = {"count": {"b": {"I_local": "0.1", "I_local_error": "", "phi_local": "0.775"}}}
    chute = tool.points(readings, reruns)
    used = {(p[0], p[1]): p[2] for p in chute}
    check(used == {("count", "a"): "published", ("count", "b"): "rerun", ("count", "c"): "published",
                   ("layer", "a"): "published"}, f"which run is read: {used}")
    rows = tool.compared(chute, fits)
    check([(r["reading"], r["run"]) for r in rows] == [("count", "a"), ("count", "b"), ("layer", "a")],
          "a friction plane shear lacks is left out")
    a, b, layer = rows
    check(abs(a["dtheta"]) < 1e-9 and abs(a["dphi"]) < 1e-12 and a["inside"], f"a run on the fits: {a}")
    # b: a degree steeper, the re-run's phi 0.775 against 0.80 - 0.3 x 0.1 = 0.77.
    check(abs(b["dtheta"] - 1.0) < 1e-9 and abs(b["dphi"] - 0.005) < 1e-12, f"the re-run: {b}")
    check(not layer["inside"] and abs(layer["dphi"] - (0.71 - 0.71)) < 1e-12, f"beyond plane shear's I: {layer}")
    groups = tool.summary(rows)
    count = groups[("count", 0.5)]
    check((count["runs"], count["reruns"], count["outside"]) == (2, 1, 0), f"counts {count}")
    low, high, mean, se = count["dtheta"]
    check(abs(low) < 1e-9 and abs(high - 1) < 1e-9 and abs(mean - 0.5) < 1e-9 and abs(se - 0.5) < 1e-9,
          f"dtheta summary {count['dtheta']}")
    check(groups[("layer", "all")]["outside"] == 1, "the run beyond plane shear's I counted")


def committed_reruns(tool):
    missing = tool.unanalysed_reruns()
    check(not missing, f"re-runs not in results/series/local_rheology/reruns/runs.csv: {missing}; run "
                       "studies/local_rheology.py --out results/series/local_rheology --cdpost build/postproc/cdpost")
    fits, rows = tool.load()
    reruns = [r["run"] for r in rows if r["used"] == "rerun"]
    in_series = {r["run"] for r in rows}  # a replica's re-run replaces no series run
    folders = [n for folder in tool.RERUNS.values() for n in tool.rerun_folders(folder) if n in in_series]
    check(sorted(reruns) == sorted(folders), f"re-runs read {reruns}, folders {folders}")
    return len(reruns)


def main():
    tool = load_study("local_rheology")
    mu_fit, phi_fit = fits_recovered(tool)
    comparison(tool, mu_fit, phi_fit)
    count = committed_reruns(tool)
    print(f"local_rheology: every check passed ({count} re-runs read in place of published runs)")


if __name__ == "__main__":
    main()
