#!/usr/bin/env bash
# Rigid and soft-sphere runs of one chute (mu, theta), one after the other on one core, then
# the comparison report (cdref compare). Runs that finished before are read, not rerun, so an
# interrupted campaign resumes and a finished one is re-analysed in seconds.
#
#   reference/run_comparison.sh [options] OUT
#
# Every model starts from the same packing: in.rain makes the initial rain, one deposition
# in LAMMPS GRANULAR (Hooke, overlap 1e-4 by default) settles it into OUT/packing.data, and each run then
# settles that packing for --settle under its own contact law before gravity is tilted.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: reference/run_comparison.sh [options] OUT

  --mu M               friction (default 0.5)
  --theta DEG          tilt (default 24)
  --cells N            cell length L in d (default 16)
  --grains N           grains (default 320)
  --bed-walls N        wall height in d (default 10)
  --overlaps "A B .."  soft stiffness series: target overlaps at the floor, in d (default "1e-2 1e-3 1e-4")
  --codes "C .."       soft codes: granular liggghts (default both)
  --hertz "A .."       LAMMPS GRANULAR Hertz runs at these overlaps (default 1e-3; "" for none)
  --rigid-tolerances "T .."  rigid runs (default 1e-3; "" for none)
  --rigid-dt S         rigid time step (default 1e-5)
  --rigid-skin N       rigid neighbour skin in d (default 0.3; a grain may move half of it in a step)
  --rigid-acceleration A  rigid sweeps: none or conjugate (default none; the fix's acceleration)
  --rigid-extra "K V .."  more fix contact/dynamics keywords for the rigid runs, e.g. "full_sweep_every 8"
                       (the chute deck's cycles); they name the runs (rigid-tolT-K_V)
  --rigid-parts N      run each rigid flow as N restarted parts of flow/N (default 1): keeps
                       each lmp_cd process short; the parts' outputs are appended
  --soft-parts N       the same for the soft flows, LAMMPS GRANULAR and LIGGGHTS (default 1):
                       a campaign cut between parts continues at the next one
  --deposit S          deposition time of the shared packing (default 0.2)
  --deposit-overlap A  stiffness of that deposition, as a target overlap (default 1e-4: the
                       rigid runs inherit its overlaps)
  --settle S           settling of the packing by each model before the tilt (default 0.05)
  --flow S             chute time (default 1.0)
  --sample S           longest sampling interval of flow.time (default 1e-4)
  --segment S          spectrum segment (default 0.25)
  --compare "ARGS"     more options for cdref compare, e.g. "--t-start 0.55" (a common window)
  --read-only          do not run anything; compare the runs already in OUT/runs
  --lmp PATH --liggghts PATH --lmp-cd PATH --cdref PATH   executables
                       (defaults: lmp, liggghts, BUILD/lmp_cd, BUILD/reference/cdref with
                        BUILD = $BUILD_DIR or build/ of the repository)
EOF
}

arguments="$*"
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/.." && pwd)
build=${BUILD_DIR:-$top/build}
mu=0.5 theta=24 cells=16 grains=320 bed_walls=10
overlaps="1e-2 1e-3 1e-4" codes="granular liggghts" hertz="1e-3" rigid_tolerances="1e-3" rigid_dt=1e-5 rigid_skin=0.3 rigid_acceleration=none rigid_extra="" rigid_parts=1 soft_parts=1
deposit=0.2 deposit_overlap=1e-4 settle=0.05 flow=1.0 sample=1e-4 segment=0.25 read_only=0 compare_args=""
lmp=lmp liggghts=liggghts lmp_cd=$build/lmp_cd cdref=""
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --mu) mu=$2; shift 2 ;;
    --theta) theta=$2; shift 2 ;;
    --cells) cells=$2; shift 2 ;;
    --grains) grains=$2; shift 2 ;;
    --bed-walls) bed_walls=$2; shift 2 ;;
    --overlaps) overlaps=$2; shift 2 ;;
    --codes) codes=$2; shift 2 ;;
    --hertz) hertz=$2; shift 2 ;;
    --rigid-tolerances) rigid_tolerances=$2; shift 2 ;;
    --rigid-dt) rigid_dt=$2; shift 2 ;;
    --rigid-skin) rigid_skin=$2; shift 2 ;;
    --rigid-acceleration) rigid_acceleration=$2; shift 2 ;;
    --rigid-extra) rigid_extra=$2; shift 2 ;;
    --rigid-parts) rigid_parts=$2; shift 2 ;;
    --soft-parts) soft_parts=$2; shift 2 ;;
    --deposit) deposit=$2; shift 2 ;;
    --deposit-overlap) deposit_overlap=$2; shift 2 ;;
    --settle) settle=$2; shift 2 ;;
    --flow) flow=$2; shift 2 ;;
    --sample) sample=$2; shift 2 ;;
    --segment) segment=$2; shift 2 ;;
    --compare) compare_args=$2; shift 2 ;;
    --read-only) read_only=1; shift ;;
    --lmp) lmp=$2; shift 2 ;;
    --liggghts) liggghts=$2; shift 2 ;;
    --lmp-cd) lmp_cd=$2; shift 2 ;;
    --cdref) cdref=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "run_comparison.sh: unknown option $1" >&2; usage >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "run_comparison.sh: one OUT only" >&2; exit 2; }; out=$1; shift ;;
  esac
done
[ -n "$out" ] || { usage >&2; exit 2; }
if [ -z "$cdref" ]; then
  for candidate in "$build/reference/cdref" "$build/tests/reference/reference-build/cdref"; do
    [ -x "$candidate" ] && { cdref=$candidate; break; }
  done
fi
[ -n "$cdref" ] && [ -x "$cdref" ] || { echo "run_comparison.sh: cdref not found (build it, or give --cdref)" >&2; exit 2; }

mkdir -p "$out/runs"
out=$(cd "$out" && pwd)
commands=$out/commands.txt
TIMEFORMAT='%R %U %S'

# run NAME EXECUTABLE DECK LOG [ARGS...]: runs DECK in OUT/runs/NAME unless it finished before;
# the wall, user and system seconds of the whole process go to timing.txt.
run() {
  local name=$1 exe=$2 deck=$3 log=$4; shift 4
  local dir=$out/runs/$name
  echo "cd runs/$name && $exe -in reference/$(basename "$deck") -log $log $*" >> "$commands"
  if [ -f "$dir/done" ]; then echo "== $name: done before, read"; return 0; fi
  [ "$read_only" -eq 0 ] || { echo "run_comparison.sh: --read-only but $name has not run" >&2; exit 1; }
  rm -rf "$dir"; mkdir -p "$dir"
  echo "== $name ($(date +%H:%M:%S), load $(cut -d' ' -f1-3 /proc/loadavg))"
  local timing
  timing=$( { time (cd "$dir" && stdbuf -o0 "$exe" -in "$deck" -log "$log" "$@" > screen.txt 2>&1) ; } 2>&1 ) || {
    echo "run_comparison.sh: $name failed; see $dir/screen.txt" >&2; tail -5 "$dir/screen.txt" >&2; exit 1; }
  echo "$timing" > "$dir/timing.txt"
  echo "   wall/user/sys s: $timing"
  touch "$dir/done"
}

# append_part DIR PART: appends the outputs of the continued run DIR/PART to those of DIR,
# dropping what PART wrote at or before DIR's last timestep (its setup step repeats it).
append_part() {
  local dir=$1 part=$2 last
  last=$(awk '!/^#/ && NF { step = $1 } END { print step }' "$dir/flow.time")
  for f in flow.time solver.time; do      # solver.time: the rigid runs only
    [ -f "$dir/$part/$f" ] || continue
    awk -v last="$last" '!/^#/ && NF && $1 > last' "$dir/$part/$f" >> "$dir/$f"
  done
  for f in profile.chunk layers.chunk; do
    awk -v last="$last" '/^#/ { next } /^[0-9]/ { keep = ($1 > last) } keep' "$dir/$part/$f" >> "$dir/$f"
  done
  awk -v last="$last" '/^ITEM: TIMESTEP/ { getline step; keep = (step > last); if (keep) print "ITEM: TIMESTEP"; if (keep) print step; next } keep' \
    "$dir/$part/dump.chute" >> "$dir/dump.chute"
}

: > "$commands"
echo "# reference/run_comparison.sh $arguments (mu $mu, theta $theta, L $cells d, $grains grains, walls $bed_walls d)" >> "$commands"

# The shared initial state.
if [ ! -f "$out/packing.data" ]; then
  [ "$read_only" -eq 0 ] || { echo "run_comparison.sh: --read-only but no $out/packing.data" >&2; exit 1; }
  echo "== rain and deposition ($(date +%H:%M:%S))"
  (cd "$out" && "$lmp" -in "$here/in.rain" -log rain.log -screen none -var out rain.data \
     -var cells "$cells" -var grains "$grains" -var bed_walls "$bed_walls") ||
    { echo "run_comparison.sh: in.rain failed; see $out/rain.log" >&2; tail -3 "$out/rain.log" >&2; exit 1; }
  mkdir -p "$out/deposition"
  (cd "$out/deposition" && "$lmp" -in "$here/in.chute_granular" -log log.lammps -screen none \
     -var data ../rain.data -var bed_walls "$bed_walls" -var overlap "$deposit_overlap" -var settle "$deposit" -var flow 0) ||
    { echo "run_comparison.sh: the deposition failed; see $out/deposition/log.lammps" >&2; exit 1; }
  cp "$out/deposition/packing.data" "$out/packing.data"
fi
echo "lmp -in reference/in.rain -var out rain.data -var cells $cells -var grains $grains -var bed_walls $bed_walls" >> "$commands"
echo "cd deposition && lmp -in reference/in.chute_granular -var data ../rain.data -var bed_walls $bed_walls -var overlap $deposit_overlap -var settle $deposit -var flow 0" >> "$commands"

# chunk_files DIR: LIGGGHTS writes fix ave/spatial files; cdpost and append_part read the
# fix ave/chunk form (cdref spatial-to-chunk). Nothing to do for LAMMPS's runs.
chunk_files() {
  local dir=$1 f
  for f in profile layers; do
    if [ ! -f "$dir/$f.chunk" ] && [ -f "$dir/$f.spatial" ]; then
      "$cdref" spatial-to-chunk "$dir/$f.spatial" "$dir/$f.chunk" > /dev/null
    fi
  done
}

# run_parts NAME PARTS EXECUTABLE DECK LOG [ARGS...]: the flow of NAME as PARTS restarted parts
# (ARGS give each part's share of the flow): part 1 from the packing, part p in NAME/partp
# from the previous part's flow.restart, its outputs appended to NAME's once.
run_parts() {
  local name=$1 parts=$2 exe=$3 deck=$4 log=$5 previous; shift 5
  run "$name" "$exe" "$deck" "$log" "${packing[@]}" "$@"
  chunk_files "$out/runs/$name"
  for ((p = 2; p <= parts; p++)); do
    previous=..; [ "$p" -eq 2 ] || previous=../part$((p - 1))
    run "$name/part$p" "$exe" "$deck" "$log" -var part "$p" -var restart_in "$previous/flow.restart" "$@"
    chunk_files "$out/runs/$name/part$p"
    if [ ! -f "$out/runs/$name/part$p/appended" ]; then
      append_part "$out/runs/$name" "part$p"
      touch "$out/runs/$name/part$p/appended"
    fi
    echo "(append the outputs of runs/$name/part$p to runs/$name: run_comparison.sh's append_part)" >> "$commands"
  done
  dirs+=("$out/runs/$name")
}

dirs=()
packing=(-var data ../../packing.data -var settle "$settle")
rigid_flow=$(awk -v f="$flow" -v n="$rigid_parts" 'BEGIN { print f / n }')
soft_flow=$(awk -v f="$flow" -v n="$soft_parts" 'BEGIN { print f / n }')
soft=(-var mu "$mu" -var theta "$theta" -var bed_walls "$bed_walls" -var flow "$soft_flow" -var sample_max "$sample")
rigid_suffix=${rigid_extra:+-$(echo "$rigid_extra" | tr ' ' '_')}
for tolerance in $rigid_tolerances; do
  run_parts "rigid-tol$tolerance$rigid_suffix" "$rigid_parts" "$lmp_cd" "$here/in.chute_rigid" log.lammps \
    -var mu "$mu" -var theta "$theta" -var bed_walls "$bed_walls" -var flow "$rigid_flow" -var sample_max "$sample" \
    -var tolerance "$tolerance" -var dt "$rigid_dt" -var skin "$rigid_skin" -var acceleration "$rigid_acceleration" \
    -var solver_extra "$rigid_extra"
done
for overlap in $overlaps; do
  for code in $codes; do
    case "$code" in
      granular)
        run_parts "granular-hooke-$overlap" "$soft_parts" "$lmp" "$here/in.chute_granular" log.lammps "${soft[@]}" \
          -var model hooke -var overlap "$overlap" ;;
      liggghts)
        run_parts "liggghts-hooke-$overlap" "$soft_parts" "$liggghts" "$here/in.chute_liggghts" log.liggghts "${soft[@]}" \
          -var overlap "$overlap"
        echo "(each part: cdref spatial-to-chunk profile.spatial profile.chunk; cdref spatial-to-chunk layers.spatial layers.chunk)" >> "$commands" ;;
      *) echo "run_comparison.sh: unknown code '$code' (granular, liggghts)" >&2; exit 2 ;;
    esac
  done
done
for overlap in $hertz; do
  run_parts "granular-hertz-$overlap" "$soft_parts" "$lmp" "$here/in.chute_granular" log.lammps "${soft[@]}" \
    -var model hertz -var overlap "$overlap"
done

echo "cdref compare runs/* --out comparison --segment $segment $compare_args --commands commands.txt" >> "$commands"
# shellcheck disable=SC2086  # compare_args is a list of options
"$cdref" compare "${dirs[@]}" --out "$out/comparison" --segment "$segment" $compare_args --commands "$commands"
