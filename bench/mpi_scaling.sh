#!/usr/bin/env bash
# Strong scaling (np 1 vs 2 on L = 152 d) and weak scaling (L = 76 d on 1 rank vs 152 d on 2;
# sizes set by STRONG_CELLS and WEAK_CELLS)
# of fix contact/dynamics, from the same settled, flowing bed; prints a Markdown table.
# Wall times: LAMMPS's "Loop time" of the timed stage, median of REPEATS runs; sweeps: the
# fix's running total of Gauss-Seidel iterations (f_cd[8]) over the timed steps.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
lmp=${LMP_CD:-$top/build/lmp_cd}
work=${WORK_DIR:-$top/runs/mpi_scaling}
steps=${STEPS:-500}
repeats=${REPEATS:-3}
strong_cells=${STRONG_CELLS:-152}
weak_cells=${WEAK_CELLS:-76}    # half the strong cell: the same work per rank on 1 rank
mkdir -p "$work"
cd "$work"
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)

prepare() {    # cells
  # The bed is settled at tolerance 1e-3 (faster); the timed steps use the deck default 1e-4.
  [ -f "scaling_$1.restart" ] || "${mpi[@]}" -np 1 "$lmp" -in "$top/bench/in.mpi_scaling" -var tolerance 1e-3 \
      -var cells "$1" -var stage prepare -log "prepare_$1.log" -screen none
}

# Prints "loop_seconds sweeps" of one timed run.
timed() {    # cells np
  local log="time_$1_np$2.log"
  "${mpi[@]}" -np "$2" "$lmp" -in "$top/bench/in.mpi_scaling" -var cells "$1" -var stage time \
      -var steps "$steps" -log "$log" -screen none
  local loop sweeps_first sweeps_last
  loop=$(awk '/^Loop time/ {print $4}' "$log" | tail -n1)
  sweeps_first=$(awk '/^ *Step/ {getline; print $7; exit}' "$log")
  sweeps_last=$(awk '/^Loop time/ {print prev} {prev=$7}' "$log" | tail -n1)
  echo "$loop $(echo "$sweeps_last - $sweeps_first" | bc)"
}

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

row() {    # label cells np
  local times=() sweeps=""
  for _ in $(seq "$repeats"); do
    read -r t s < <(timed "$2" "$3")
    times+=("$t")
    sweeps=$s
  done
  local med
  med=$(printf '%s\n' "${times[@]}" | median)
  echo "$1|$2|$3|$med|$sweeps"
}

prepare "$strong_cells"
prepare "$weak_cells"
{
  row strong "$strong_cells" 1
  row strong "$strong_cells" 2
  row weak "$weak_cells" 1
} > rows.txt
echo "| case | L (d) | ranks | wall time of $steps steps (s, median of $repeats) | GS sweeps over the steps |"
echo "|---|---|---|---|---|"
while IFS='|' read -r c l n t s; do echo "| $c | $l | $n | $t | $s |"; done < rows.txt
awk -F'|' '$1=="strong" && $3==1 {t1=$4} $1=="strong" && $3==2 {t2=$4} END {printf "\nstrong speed-up on 2 ranks: %.2f\n", t1/t2}' rows.txt
awk -F'|' '$1=="weak" {t1=$4} $1=="strong" && $3==2 {t2=$4} END {printf "weak-scaling efficiency (half cell on 1 rank / full cell on 2): %.2f\n", t1/t2}' rows.txt
