#!/usr/bin/env python3
"""Checks of bench/step_profile.py's grouping, run by ctest (no perf, no simulation): each
symbol of a perf report lands in its part of a step, the shares add up, and lines that are not
samples (headers, call chains) are ignored. Standard library only."""

import os
import sys

# bench/step_profile.py, found from this file
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir, "bench"))

import step_profile  # noqa: E402

REPORT = """# Samples: 1K of event 'cpu-clock'
#
    49.09%  [.] cd::(anonymous namespace)::solve_in_cycles
    17.55%  [.] cd::(anonymous namespace)::for_kind<cd::(anonymous namespace)::sweep_measuring(...)>
     7.93%  [.] LAMMPS_NS::NPairHalfSizeBinNewtoff::build
            |--43.63%--0
     3.64%  [.] LAMMPS_NS::FixContactDynamics::collect_grain_pairs
     2.19%  [.] LAMMPS_NS::FixContactDynamics::LammpsHost::carried_impulse
     1.76%  [.] cd::interleaved_order
     1.46%  [.] cd::prepare_mechanics
     0.64%  [.] cd::promote_closing_pairs
     0.44%  [.] cd::measure_overlaps
     0.29%  [.] LAMMPS_NS::FixContactDynamics::write_back_motion
     0.20%  [k] irqentry_exit_to_user_mode
"""


def main():
    shares = step_profile.group(REPORT)
    expected = {"Gauss-Seidel sweeps": 66.64, "LAMMPS neighbour builds": 7.93, "pair collection and selection": 3.64,
                "warm start and its store": 2.19, "ordering": 1.76, "contact mechanics": 1.46,
                "pairs joining (watched pairs checked)": 0.64,
                "overlaps and outputs": 0.44, "bodies in and out": 0.29, "other": 0.20}
    for part, share in expected.items():
        if abs(shares[part] - share) > 1e-9:
            sys.exit(f"FAIL: {part}: {shares[part]} instead of {share}")
    if abs(sum(shares.values()) - sum(expected.values())) > 1e-9:
        sys.exit("FAIL: the parts do not add up to the samples read")
    if step_profile.group("# no samples\n")["other"] != 0.0:
        sys.exit("FAIL: a header line was read as a sample")
    print("step_profile grouping: ok")


if __name__ == "__main__":
    main()
