#!/usr/bin/env bash
# Set-up (idempotent), the default scene and its postprocessing.
# inputs/in.default_scene: rain deposition of 400 disks in a 20 d cell with 10 d walls, then a
# 1.5 s chute flow at 24 degrees (its cost: doc/chute.md). cdpost then writes post/report.md
# and post/figures/ (u_t, profile, spectrum, spectra_depth, snapshot).
# Outputs go to ${OUT_DIR:-runs/default_scene}; extra arguments are passed to lmp_cd
# (e.g. -var theta 26 -var duration 3).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/scripts/setup.sh"
build=${BUILD_DIR:-$top/build}
out=${OUT_DIR:-$top/runs/default_scene}
mkdir -p "$out"
cd "$out"
"$build/lmp_cd" -in "$top/inputs/in.default_scene" -var inputs "$top/inputs" -log log.lammps "$@"

# The deck's last line: CHUTE y_top_m <wall tops (m)> time_s <chute time (s)> ...
t_end=$(grep '^CHUTE ' log.lammps | tail -n 1 | awk '{print $5}')
cdpost=${CDPOST:-$build/postproc/cdpost}
if [ ! -x "$cdpost" ]; then
  echo "default scene finished: outputs in $out (cdpost not built: no figures)"
  exit 0
fi
# cdpost reads the wall tops and the sample rate from the run's chute.params. Segments of 0.25 s
# (4 Hz resolution) suit a run of a few seconds. A short run may not pass the stationarity test;
# its second half is then analysed, and cdpost and the report say it is not stationary.
if ! "$cdpost" run "$out" --dump "$out/dump.chute.gz" --segment 0.25; then
  t_start=$(awk -v t="$t_end" 'BEGIN {print t / 2}')
  echo "no stationary regime detected: analysing t >= $t_start s (run longer with -var duration)"
  "$cdpost" run "$out" --dump "$out/dump.chute.gz" --segment 0.25 --t-start "$t_start"
fi
echo "default scene finished: outputs in $out, report in $out/post/report.md"
