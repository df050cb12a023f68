#!/usr/bin/env python3
"""Where a step of fix contact/dynamics goes: the self time of `perf record -g` samples grouped
into the parts of a step, as doc/benchmarks.md reports them.

    perf record -g -o perf.data lmp_cd -in inputs/in.chute -var stage flow -var start START ...
    bench/step_profile.py perf.data [other.data ...]     # one column per file

Each symbol goes to the first part whose pattern it matches; the rest is "other". The shares
are of all samples of the process (LAMMPS's own work included).
"""
import re
import subprocess
import sys

PARTS = [
    ("Gauss-Seidel sweeps", r"solve_in_cycles|solve_in_full_sweeps|sweep_measuring|sweep_listed|for_kind|"
                            r"update_contact|update_frictional|update_frictionless|ActiveContacts"),
    ("LAMMPS neighbour builds", r"NPair|NBin|NStencil|Neighbor::"),
    ("pair collection and selection", r"collect_|disk_disk_geometry|is_candidate|StepContacts::offer|StepContacts::add|"
                                      r"contact_frame|wall_contact|pair_key|between_atoms|against_wall|add_pair|"
                                      r"minimum_image|PairReach"),
    ("pairs joining (watched pairs checked)", r"promote_closing|closes_after_solve|ClosingPairs"),
    ("contact mechanics", r"prepare_mechanics"),
    ("warm start and its store", r"carried_impulse|remember_impulse|forget_impulses|store_impulses|load_warm_start|"
                                 r"store_warm_start|append_history|warm_start|apply_impulses|for_each_loaded"),
    ("ordering", r"interleaved_order|reorder|shuffle"),
    ("overlaps and outputs", r"measure_overlaps|fill_local_output|reduce_step_outputs|end_of_step_gap|compute_vector"),
    ("bodies in and out", r"gather_bodies|map_bodies|write_back_motion|initial_integrate|final_integrate"),
]


def group(report):
    """Shares (%) of each part of a step from the text of `perf report --sort symbol --stdio`."""
    totals = {name: 0.0 for name, _ in PARTS}
    totals["other"] = 0.0
    for line in report.splitlines():
        match = re.match(r"\s+([\d.]+)%\s+\[[.k]\]\s+(.*)", line)
        if not match:
            continue
        share, symbol = float(match.group(1)), match.group(2)
        part = next((name for name, pattern in PARTS if re.search(pattern, symbol)), "other")
        totals[part] += share
    return totals


def shares(perf_data):
    report = subprocess.run(["perf", "report", "-i", perf_data, "--no-children", "--sort", "symbol", "--stdio",
                             "-g", "none"], check=True, capture_output=True, text=True).stdout
    totals = group(report)
    if sum(totals.values()) == 0.0:
        sys.exit(f"step_profile.py: {perf_data}: no samples in perf's report")
    return totals


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: step_profile.py PERF_DATA [PERF_DATA ...]")
    columns = [shares(path) for path in sys.argv[1:]]
    print("| part of a step | " + " | ".join(sys.argv[1:]) + " |")
    print("|---|" + "---|" * len(columns))
    for name in [n for n, _ in PARTS] + ["other"]:
        print(f"| {name} | " + " | ".join(f"{c[name]:.1f} %" for c in columns) + " |")


if __name__ == "__main__":
    main()
