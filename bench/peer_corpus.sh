#!/usr/bin/env bash
# The solver against Siconos numerics' on the same problems (doc/peers.md): the corpus as FCLIB
# local problems, every solver on it, the performance profiles.
#
#   bench/peer_corpus.sh OUT
#
# 1. a small erodible-bed cell (10 d, 300 grains, 10 d walls) rained once;
# 2. ordinary steps: 0.2 s of flow at mu 0.05 (20 deg), 0.5 (24 deg), 2 (28 deg), then the next
#    4 ms saved (save_problems 0), every 8th step kept; a resting pile (mu 0.5, theta 0);
# 3. hard steps: from the mu 2 flow, 0.05 s at each (mu, e) of the stall corpus (1, 0.5; 2, 0;
#    2, 0.5; 2, 0.9; 5, 0.5), rescue off, every step over 300 sweeps saved, up to 4 kept a set;
#    the unconverged first; with them the saved hard steps of tests/data (chute at mu 2, 28-30 deg; plane shear at mu 2;
#    the 12 d cell at mu 0.5);
# 4. each kept step as FCLIB (bench/peers/cdp_to_fclib) in OUT/corpus/<class>/, beside its .cdp;
# 5. bench/peers/peer_bench: every solver and variant at 1e-3 on three problems (OUT/screen.csv,
#    kept if there), then those that solved one on the first PEER_PER_CLASS problems of every class
#    (OUT/solves.csv), time limit PEER_TIME_LIMIT CPU s (0.5), a short solve's time the median of
#    PEER_REPEAT runs (5; peer_bench --repeat);
# 6. bench/peer_profiles.py: OUT/profiles.png and OUT/profiles.md (ours, the fix's default; of
#    Siconos's variants the best of each solver), OUT/profiles_newton.* (ours_newton, the Newton
#    polish on, in ours' place), OUT/profiles_over_relaxed.* (ours_over_relaxed, over_relaxation
#    1.8, in ours' place), OUT/profiles_variants.* (every variant), OUT/profiles_at_scale.*
#    (the answers read at the problem's scale, peer_profiles.py --within 10).
# Environment: LMP (build/lmp_cd), PEER_TOOLS (build/bench/peers), PEER_SOLVERS (the screened
# solvers, peer_bench's --solvers; default: every one, Siconos's variants included, peer_bench --list).
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
lmp=${LMP:-$here/../build/lmp_cd}
tools=${PEER_TOOLS:-$here/../build/bench/peers}
deck=$here/../inputs/in.chute
[ $# -ge 1 ] || { echo "usage: peer_corpus.sh OUT" >&2; exit 1; }
out=$(mkdir -p "$1" && cd "$1" && pwd)
cell=(-var L 10 -var grains 300 -var wall_height 10)

chute() {  # chute FOLDER -var ...: one flow stage in FOLDER (skipped if it finished)
  local folder=$1; shift
  mkdir -p "$folder"
  [ -f "$folder/chute.restart" ] || (cd "$folder" && "$lmp" -in "$deck" -var stage flow "${cell[@]}" "$@" \
    -screen none -log log.lammps)
}

keep() {  # keep CLASS EVERY COUNT FILES...: every EVERY-th of FILES, at most COUNT, into the corpus
  local class=$1 every=$2 count=$3; shift 3
  mkdir -p "$out/corpus/$class"
  local k=0 kept=0 f
  for f in "$@"; do
    if [ $((k % every)) -eq 0 ] && [ "$kept" -lt "$count" ]; then cp "$f" "$out/corpus/$class/"; kept=$((kept + 1)); fi
    k=$((k + 1))
  done
}

stalled_first() {  # the saved steps of FOLDER whose solve did not converge, then the others
  local f
  for f in "$1"/hard.*.cdp; do [ -f "$f" ] && grep -aq "converged 0" <(head -c 300 "$f") && echo "$f"; done
  for f in "$1"/hard.*.cdp; do [ -f "$f" ] && grep -aq "converged 1" <(head -c 300 "$f") && echo "$f"; done
}

if [ ! -f "$out/deposition/deposition.restart" ]; then
  mkdir -p "$out/deposition"
  (cd "$out/deposition" && "$lmp" -in "$deck" -var stage deposition "${cell[@]}" -screen none -log log.lammps)
fi
start=$out/deposition/deposition.restart
for set in "0.05 20" "0.5 24" "2 28"; do
  read -r mu theta <<< "$set"
  chute "$out/flow/mu$mu" -var start "$start" -var mu "$mu" -var theta "$theta" -var duration 0.2
  chute "$out/steps/mu$mu" -var start "$out/flow/mu$mu/chute.restart" -var mu "$mu" -var theta "$theta" \
    -var duration 0.204 -var solver_extra "save_problems 0 step"
  keep "chute_mu$mu" 8 3 "$out/steps/mu$mu"/step.*.cdp
done
chute "$out/steps/pile" -var start "$start" -var mu 0.5 -var theta 0 -var duration 0.004 \
  -var solver_extra "save_problems 0 step"
keep pile_mu0.5 8 3 "$out/steps/pile"/step.*.cdp
for set in "1 0.5" "2 0" "2 0.5" "2 0.9" "5 0.5"; do
  read -r mu e <<< "$set"
  chute "$out/hard/mu${mu}_e$e" -var start "$out/flow/mu2/chute.restart" -var mu "$mu" -var e "$e" -var theta 28 \
    -var duration 0.25 -var max_iterations 20000 -var stall_window 0 -var solver_extra "save_problems 300 hard"
  mapfile -t hard < <(stalled_first "$out/hard/mu${mu}_e$e")
  [ ${#hard[@]} -eq 0 ] || keep "stall_mu${mu}_e$e" 1 3 "${hard[@]}"
done
keep saved_hard 1 10 "$here/../tests/data"/*.cdp

for folder in "$out/corpus"/*/; do
  rm -f "$folder"*.hdf5
  "$tools/cdp_to_fclib" --out "$folder" "$folder"*.cdp > /dev/null
done
# Screening: every solver at 1e-3 on one problem of three classes; those that solve none are
# left out of the full run (doc/peers.md says why each was).
limit=${PEER_TIME_LIMIT:-0.5}
first() { for f in "$@"; do echo "$f"; return; done; }
screen=("$(first "$out/corpus/chute_mu0.5"/*.hdf5)" "$(first "$out/corpus/stall_mu2_e0.5"/*.hdf5)"
        "$(first "$out/corpus/saved_hard"/growing*.hdf5)")
[ -f "$out/screen.csv" ] || "$tools/peer_bench" --out "$out/screen.csv" --time-limit "$limit" --targets 1e-3 \
  --solvers "${PEER_SOLVERS:-$("$tools/peer_bench" --list)}" "${screen[@]}" 2> "$out/screen.log"
solvers=$(awk -F, 'NR > 1 && $7 == "solved" && !seen[$4]++ { printf "%s%s", sep, $4; sep = "," }' "$out/screen.csv")
for ours in ours_newton ours_over_relaxed; do  # ours' variants, also after a screening made before them
  case ",$solvers," in *,$ours,*) ;; *) solvers="$solvers,$ours" ;; esac
done
problems=()
for folder in "$out/corpus"/*/; do
  mapfile -t some < <(ls "$folder"*.hdf5 | head -"${PEER_PER_CLASS:-100}")
  problems+=("${some[@]}")
done
"$tools/peer_bench" --out "$out/solves.csv" --time-limit "$limit" --repeat "${PEER_REPEAT:-5}" --solvers "$solvers" \
  "${problems[@]}" 2> "$out/peer_bench.log"
python3 "$here/peer_profiles.py" --out "$out/profiles" --screen "$out/screen.csv" --time-limit "$limit" \
  --leave-out ours_newton,ours_over_relaxed --best-variant "$out/solves.csv"
python3 "$here/peer_profiles.py" --out "$out/profiles_newton" --time-limit "$limit" --ours ours_newton \
  --leave-out ours,ours_over_relaxed --best-variant "$out/solves.csv"
python3 "$here/peer_profiles.py" --out "$out/profiles_over_relaxed" --time-limit "$limit" --ours ours_over_relaxed \
  --leave-out ours,ours_newton --best-variant "$out/solves.csv"
python3 "$here/peer_profiles.py" --out "$out/profiles_variants" --time-limit "$limit" \
  --leave-out ours_newton,ours_over_relaxed "$out/solves.csv"
python3 "$here/peer_profiles.py" --out "$out/profiles_at_scale" --time-limit "$limit" \
  --leave-out ours_newton,ours_over_relaxed --within 10 "$out/solves.csv"
