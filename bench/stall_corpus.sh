#!/usr/bin/env bash
# The corpus of hard steps and the solver settings measured on it (doc/stalls.md).
#
#   bench/stall_corpus.sh OUT [DEPOSITION]
#
# 1. a deposition of the 45 d cell, layer reading (or DEPOSITION, a deposition.restart);
# 2. 1.5 s of flow at mu 2, 28 deg with the deck's defaults, the stall rescue off (the state the
#    corpus starts from);
# 3. from there, 0.03 s at each (mu, e) of the corpus, cap 1e5, rescue off: every step needing
#    more than 3000 sweeps saved (fix contact/dynamics save_problems) in OUT/corpus/<mu>_<e>/;
# 4. bench/solver_corpus on two or three unconverged steps of each set (one converged at mu 1,
#    where none stalled), five settings: the deck's and the series' sweeps without and with the
#    rescue, and relaxation 0.7 throughout; OUT/study/<set>/{solves,history}.csv;
# 5. bench/corpus_figure.py: OUT/corpus.png and OUT/corpus.md.
# Cost: about 1.5 CPU h (step 3 at mu 5 and step 4 dominate). Environment: LMP (build/lmp_cd),
# CORPUS_TOOL (build/bench/solver_corpus).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${LMP:-$here/../build/lmp_cd}
tool=${CORPUS_TOOL:-$here/../build/bench/solver_corpus}
deck=$here/../inputs/in.chute
[ $# -ge 1 ] || { echo "usage: stall_corpus.sh OUT [DEPOSITION]" >&2; exit 1; }
out=$(mkdir -p "$1" && cd "$1" && pwd)
cell=(-var reading layer -var L 45)

chute() {  # chute FOLDER -var ...: one flow stage in FOLDER (skipped if it finished)
  local folder=$1; shift
  mkdir -p "$folder"
  [ -f "$folder/chute.restart" ] || (cd "$folder" && "$lmp" -in "$deck" -var stage flow "${cell[@]}" "$@" \
    -screen none -log log.lammps)
}

deposition=${2:-$out/deposition/deposition.restart}
if [ ! -f "$deposition" ]; then
  mkdir -p "$out/deposition"
  (cd "$out/deposition" && "$lmp" -in "$deck" -var stage deposition "${cell[@]}" -screen none -log log.lammps)
fi
chute "$out/flow" -var start "$deposition" -var mu 2 -var theta 28 -var duration 1.5 -var solver_extra "stall_window 0"
for set in "1 0.5" "2 0" "2 0.5" "2 0.9" "5 0.5"; do
  read -r mu e <<< "$set"
  chute "$out/corpus/mu${mu}_e$e" -var start "$out/flow/chute.restart" -var mu "$mu" -var e "$e" -var theta 28 \
    -var duration 1.53 -var max_iterations 100000 -var solver_extra "stall_window 0 save_problems 3000 hard"
done

# Up to `count` problems of a set whose solve ended as `converged` (0 or 1) in the run.
pick() { for f in "$out/corpus/$1"/hard.*.cdp; do grep -aq "converged $2" <(head -c 300 "$f") && echo "$f"; done | head -"$3"; }
tolerance="tolerance=1e-3 max_iterations=100000"
sets=()
for set in "mu1_e0.5 1 1" "mu2_e0 0 2" "mu2_e0.5 0 3" "mu2_e0.9 0 2" "mu5_e0.5 0 3"; do
  read -r name converged count <<< "$set"
  mapfile -t problems < <(pick "$name" "$converged" "$count")
  [ ${#problems[@]} -gt 0 ] || continue
  mkdir -p "$out/study/$name"
  "$tool" --out "$out/study/$name" --d 5e-4 --z0 0.015 --reference-cap 50000 \
    --setting deck_no_rescue "$tolerance acceleration=conjugate full_sweep_every=8 stall_window=0" \
    --setting series_no_rescue "$tolerance acceleration=conjugate stall_window=0" \
    --setting deck "$tolerance acceleration=conjugate full_sweep_every=8" \
    --setting series "$tolerance acceleration=conjugate" \
    --setting relaxed_0.7 "$tolerance relaxation=0.7 stall_window=0" \
    "${problems[@]}"
  sets+=("$out/study/$name")
done
python3 "$here/corpus_figure.py" --out "$out/corpus" "${sets[@]}"
