#!/usr/bin/env bash
# The cost of two settings of the chute deck from one restart, side by side: setting A on core 0
# and B on core 1, then swapped, each run continuing START to DURATION (chute time, s). Prints
# each run's user time and the ratio B / A of the sums: both sides ran under the same load.
#
#   bench/side_by_side.sh START DURATION "A's -var pairs" "B's -var pairs" [common -var pairs]
#   bench/side_by_side.sh runs/mu0.5_theta24/chute.restart 8.5 "-var join after" "-var join during" \
#       "-var mu 0.5 -var theta 24"
#
# Environment: LMP (default build/lmp_cd), DECK (inputs/in.chute), OUT (a new temporary folder);
# LMP_A and LMP_B (default LMP) run A and B with two builds: a new build against an old one;
# START_B and DURATION_B (default START and DURATION): B continues another restart up to another
# chute time (two scenes side by side, each for the same span past its own start).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${LMP:-$here/../build/lmp_cd}
lmp_a=${LMP_A:-$lmp} lmp_b=${LMP_B:-$lmp}
deck=${DECK:-$here/../inputs/in.chute}
[ $# -ge 4 ] || { echo "usage: side_by_side.sh START DURATION A_VARS B_VARS [COMMON_VARS]" >&2; exit 1; }
start=$(realpath "$1") duration=$2 vars_a=$3 vars_b=$4 common=${5:-}
start_b=$(realpath "${START_B:-$1}") duration_b=${DURATION_B:-$2}
for file in "$start" "$start_b"; do
  [ -f "$file" ] || { echo "side_by_side.sh: no restart file $file" >&2; exit 1; }
done
for exe in "$lmp_a" "$lmp_b"; do
  [ -x "$exe" ] || { echo "side_by_side.sh: no executable $exe: build lmp_cd first" >&2; exit 1; }
done
lmp_a=$(realpath "$lmp_a") lmp_b=$(realpath "$lmp_b")  # the runs start in their own folders
out=${OUT:-$(mktemp -d /tmp/side_by_side.XXXXXX)}
mkdir -p "$out"

# run NAME CORE EXECUTABLE START END VARS: one run in $out/NAME, its user time in $out/NAME/user.txt
run() {
  mkdir -p "$out/$1"
  # shellcheck disable=SC2086  # the -var pairs are split on purpose
  (cd "$out/$1" && taskset -c "$2" /usr/bin/time -f %U -o user.txt "$3" -in "$deck" -var stage flow \
    -var start "$4" -var duration "$5" $common $6 -screen none -log log.lammps)
}
run a1 0 "$lmp_a" "$start" "$duration" "$vars_a" & run b1 1 "$lmp_b" "$start_b" "$duration_b" "$vars_b" & wait
run a2 1 "$lmp_a" "$start" "$duration" "$vars_a" & run b2 0 "$lmp_b" "$start_b" "$duration_b" "$vars_b" & wait

python3 - "$out" <<'PY'
import sys
out = sys.argv[1]
user = {name: float(open(f"{out}/{name}/user.txt").read().split()[-1]) for name in ("a1", "a2", "b1", "b2")}
print(f"A: {user['a1']:.2f} s (core 0), {user['a2']:.2f} s (core 1)")
print(f"B: {user['b1']:.2f} s (core 1), {user['b2']:.2f} s (core 0)")
print(f"B / A: {(user['b1'] + user['b2']) / (user['a1'] + user['a2']):.3f}   (runs in {out})")
for name in ("a1", "a2", "b1", "b2"):
    lines = [line for line in open(f"{out}/{name}/log.lammps") if " solver: " in line]
    print(f"{name}: " + (lines[-1].split(" solver: ")[1].strip() if lines else "no solver line"))
PY
