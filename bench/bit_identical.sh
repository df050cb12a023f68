#!/usr/bin/env bash
# bench/bit_identical.sh OUT LMP_OLD LMP_NEW [extra -var pairs]: the tiny chute cell (layer reading,
# L 12 d) flowing 0.05 s at 26 degrees, mu 0.5 and 2, with two builds from one deposition; cmp of
# flow.time and solver.time says whether a change kept the trajectories bit for bit.
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: $0 OUT LMP_OLD LMP_NEW [-var NAME VALUE ...]" >&2; exit 2; }
out=$1 old=$(realpath "$2") new=$(realpath "$3"); shift 3
deck=$(cd "$(dirname "$0")/.." && pwd)/inputs/in.chute
common=(-var reading layer -var L 12 -var wall_height 10)
mkdir -p "$out" && cd "$out"
if [ ! -f dep/deposition.restart ]; then
  mkdir -p dep && (cd dep && "$old" -in "$deck" -var stage deposition "${common[@]}" -screen none -log log.lammps)
fi
status=0
for mu in 0.5 2; do
  for side in old new; do
    exe=$old; [ $side = new ] && exe=$new
    rm -rf $side.mu$mu && mkdir -p $side.mu$mu
    (cd $side.mu$mu && "$exe" -in "$deck" -var stage flow -var start ../dep/deposition.restart -var duration 0.05 \
      -var mu $mu -var theta 26 "${common[@]}" "$@" -screen none -log log.lammps)
  done
  for f in flow.time solver.time; do
    if cmp -s old.mu$mu/$f new.mu$mu/$f; then echo "mu $mu $f identical"; else echo "mu $mu $f DIFFERS"; status=1; fi
  done
done
exit $status
