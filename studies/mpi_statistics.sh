#!/usr/bin/env bash
# Statistical equivalence of fix contact/dynamics on 1, 2 and 4 ranks: the same chute flow
# (inputs/in.chute on the default-scene cell unless overridden) from one deposition, run on
# each rank count, analysed by cdpost over the same window; prints a Markdown table of
# U, phi, h, f, A with their errors (cdpost: batch means; f: half width of the peak; A has
# none), and for every rank count the largest difference from one rank in units of the
# combined error, sqrt(err_1^2 + err_N^2).
#
# Environment: RANKS ("1 2 4"), DURATION (chute time, s; 3), T_START (start of the analysed
# window, s; 1), SEGMENT (spectral segment, s; 0.5), CELL_VARS (-var pairs for in.chute;
# the default scene's cell), WORK (runs/mpi_statistics), LMP_CD, CDPOST.
# More ranks than cores are run oversubscribed, which is impractical: every sweep synchronises
# the ranks (a measured case: doc/benchmarks.md).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
lmp=${LMP_CD:-$top/build/lmp_cd}
cdpost=${CDPOST:-$top/build/postproc/cdpost}
work=${WORK:-$top/runs/mpi_statistics}
ranks=${RANKS:-"1 2 4"}
duration=${DURATION:-3}
t_start=${T_START:-1}
segment=${SEGMENT:-0.5}
read -r -a cell <<< "${CELL_VARS:--var L 20 -var grains 400 -var wall_height 10 -var mu 0.5 -var theta 24}"
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)

mkdir -p "$work/deposition"
if [ ! -f "$work/deposition/deposition.restart" ]; then
  (cd "$work/deposition" && "$lmp" -in "$top/inputs/in.chute" -var stage deposition "${cell[@]}" \
     -log log.lammps -screen none)
fi

for np in $ranks; do
  run="$work/np$np"
  if [ ! -f "$run/post/results.csv" ]; then
    mkdir -p "$run"
    (cd "$run" && /usr/bin/time -f "%e s wall, %U s user" -o time.txt \
       "${mpi[@]}" -np "$np" "$lmp" -in "$top/inputs/in.chute" -var stage flow "${cell[@]}" \
       -var start "$work/deposition/deposition.restart" -var duration "$duration" \
       -log log.lammps -screen none)
    y_top=$(awk '/^CHUTE / {print $3}' "$run/log.lammps" | tail -n 1)
    "$cdpost" run "$run" --z0 "$y_top" --segment "$segment" --t-start "$t_start" > "$run/cdpost.txt"
  fi
done

python3 - "$work" $ranks <<'PY'
import csv, math, os, re, sys
work, ranks = sys.argv[1], sys.argv[2:]
names = ["U", "phi", "h", "f", "A"]

def results(np):
    with open(os.path.join(work, f"np{np}", "post", "results.csv")) as src:
        return {r["name"]: (float(r["value"]), float(r["error"]) if r["error"] else 0.0)
                for r in csv.DictReader(src)}

def grid(np):
    with open(os.path.join(work, f"np{np}", "log.lammps")) as src:
        found = re.search(r"(\d+) by (\d+) by (\d+) MPI processor grid", src.read())
    return "x".join(found.groups()[:2]) if found else "1x1"

table = {np: results(np) for np in ranks}
print("| ranks (grid) | " + " | ".join(names) + " | largest difference from 1 rank |")
print("|---" * (len(names) + 2) + "|")
for np in ranks:
    cells, worst = [], 0.0
    for n in names:
        value, error = table[np][n]
        cells.append(f"{value:.4g} ± {error:.2g}" if error > 0 else f"{value:.4g}")
        v1, e1 = table[ranks[0]][n]
        combined = math.hypot(e1, error)
        if np != ranks[0] and combined > 0:
            worst = max(worst, abs(value - v1) / combined)
    print(f"| {np} ({grid(np)}) | " + " | ".join(cells) + f" | {worst:.2f} combined errors |")
PY
