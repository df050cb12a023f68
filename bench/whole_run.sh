#!/usr/bin/env bash
# Whole-run timing of lmp_cd on bench/in.bench_column, pinned to one core. hyperfine times the
# whole command (start-up included); LAMMPS's own "Loop time" of each run splits it into the
# collapse phase and the bed phase, and the deck prints the mean sweeps and contact updates
# per step of each phase. Medians over the runs are printed as a Markdown table.
#
#   bench/whole_run.sh                          # 3 runs of the default 592-disk deck
#   RUNS=5 VARS="-var rows 54 -var collapse_steps 500 -var bed_steps 200" bench/whole_run.sh
#
# Environment: LMP executable (default build/lmp_cd), RUNS (3), CPU core to pin (1),
# VARS extra deck variables, OUT directory kept for the logs and hyperfine's JSON (default: new
# temporary directory).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${LMP:-$here/../build/lmp_cd}
runs=${RUNS:-3}
cpu=${CPU:-1}
vars=${VARS:-}
out=${OUT:-$(mktemp -d /tmp/whole_run.XXXXXX)}
mkdir -p "$out"

[ -x "$lmp" ] || { echo "whole_run.sh: no executable $lmp: build lmp_cd first" >&2; exit 1; }
command -v hyperfine >/dev/null || { echo "whole_run.sh: hyperfine not found (Debian: hyperfine)" >&2; exit 1; }
rm -f "$out"/log.*

# $$ is the PID of the shell hyperfine starts for each run: one log per run.
hyperfine --runs "$runs" --style basic --export-json "$out/hyperfine.json" --command-name lmp_cd \
  "taskset -c $cpu $lmp -in $here/in.bench_column $vars -screen none -log $out/log.\$\$"

python3 - "$out" <<'PY'
import glob, json, re, statistics, sys

out = sys.argv[1]
phases = ("collapse", "bed")
rows = {p: [] for p in phases}
atoms = dt = None
for path in sorted(glob.glob(f"{out}/log.*")):
    text = open(path).read()
    dt = float(re.search(r"^timestep (\S+)$", text, re.M).group(1))
    loops = re.findall(r"Loop time of (\S+) on 1 procs for (\d+) steps with (\d+) atoms\s+([\d.]+)% CPU use", text)
    means = {m[0]: m[1:] for m in re.findall(r"^means (\w+): sweeps (\S+) contacts (\S+) updates (\S+)$", text, re.M)}
    for phase, (wall, steps, natoms, cpu_use) in zip(phases, loops):
        wall, steps, cpu_use = float(wall), int(steps), float(cpu_use) / 100.0
        sweeps, contacts, updates = map(float, means[phase])
        atoms = int(natoms)
        rows[phase].append({
            "steps": steps,
            "wall_ms_per_step": 1e3 * wall / steps,
            "cpu_ms_per_step": 1e3 * wall * cpu_use / steps,
            "wall_s_per_physical_s": wall / (steps * dt),
            "cpu_s_per_physical_s": wall * cpu_use / (steps * dt),
            "sweeps": sweeps, "contacts": contacts,
            "updates_per_s": updates * steps / (wall * cpu_use),
        })

median = lambda phase, key: statistics.median(r[key] for r in rows[phase])
run = json.load(open(f"{out}/hyperfine.json"))["results"][0]
print(f"\n{len(run['times'])} runs, {atoms} disks, dt = {dt:g} s, logs in {out}")
print(f"whole command: median {run['median']:.2f} s wall, mean user {run['user']:.2f} s + system {run['system']:.2f} s\n")
print("| phase | steps | wall ms/step | CPU ms/step | wall s per physical s | CPU s per physical s "
      "| sweeps/step | contacts | contact updates/s (CPU) |")
print("|---|---|---|---|---|---|---|---|---|")
for p in phases:
    if not rows[p]:
        continue
    print(f"| {p} | {rows[p][0]['steps']} | {median(p, 'wall_ms_per_step'):.2f} | {median(p, 'cpu_ms_per_step'):.2f} "
          f"| {median(p, 'wall_s_per_physical_s'):.0f} | {median(p, 'cpu_s_per_physical_s'):.0f} "
          f"| {median(p, 'sweeps'):.0f} | {median(p, 'contacts'):.0f} | {median(p, 'updates_per_s') / 1e6:.1f}e6 |")
PY
