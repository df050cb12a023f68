#!/usr/bin/env bash
# Set-up (idempotent) and the default scene: a small rigid-disk deposition and chute.
# Outputs go to ${OUT_DIR:-runs/default_scene}; extra arguments are passed to lmp_cd
# (e.g. -var theta 26).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/scripts/setup.sh"
out=${OUT_DIR:-$top/runs/default_scene}
mkdir -p "$out"
cd "$out"
"${BUILD_DIR:-$top/build}/lmp_cd" -in "$top/inputs/in.default_scene" -log log.lammps "$@"
echo "default scene finished: outputs in $out"
