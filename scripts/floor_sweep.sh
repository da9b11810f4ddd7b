#!/usr/bin/env bash
# Sweep generated floors for the "never falsely" and "localized" counts of issue 28's acceptance:
# draw COUNT floors from SEED with `bimloc worldgen --random`, then `bimloc sweep` every room of
# each floor (seed 1, 60 s) into OUT/runs/<floor>.json, one floor per job. Summarize with
# scripts/sweep_runs.py OUT/runs (and against another binary's OUT with --against).
#
#   scripts/floor_sweep.sh BIMLOC OUT SEED COUNT [STYLE]
#
# BIMLOC: the bimloc binary. STYLE: a worldgen --style (default: the office, residential,
# school, hall cycle). Environment: JOBS (2) floors at a time, NICE (0) niceness, DURATION (60),
# SEEDS (1) seeds per room, SITE (exact) site preset, FLOORS a directory of floors to sweep
# instead of drawing them (SEED, COUNT, STYLE then ignored). A floor already swept is skipped,
# so an interrupted sweep resumes.
set -euo pipefail
if [ $# -lt 4 ]; then sed -n 2,12p "$0" | sed 's/^# \{0,1\}//'; exit 2; fi
bin=$(readlink -f "$1"); out=$2; seed=$3; count=$4; style=${5:-}
jobs=${JOBS:-2}; nice_level=${NICE:-0}; duration=${DURATION:-60}; seeds=${SEEDS:-1}; site=${SITE:-exact}
mkdir -p "$out/runs"
floors=${FLOORS:-$out/floors}
if [ -z "${FLOORS:-}" ] && [ ! -d "$floors" ]; then
  args=(worldgen --random "$seed" --random-count "$count" --out "$floors.part")
  [ -n "$style" ] && args+=(--style "$style")
  rm -rf "$floors.part"; "$bin" "${args[@]}" > "$out/worldgen.txt"; mv "$floors.part" "$floors"
fi
export bin out duration seeds site nice_level
sweep_one() {
  local f=$1 name; name=$(basename "$f" .ifc)
  [ -s "$out/runs/$name.json" ] && return 0
  # Exit status 1 (a start not localized, or localized falsely) still writes the JSON.
  nice -n "$nice_level" "$bin" sweep "$f" --seeds "$seeds" --duration "$duration" --site "$site" --json \
    > "$out/runs/$name.json.part" 2> "$out/runs/$name.err" || true
  if [ -s "$out/runs/$name.json.part" ]; then mv "$out/runs/$name.json.part" "$out/runs/$name.json"; echo "$name"
  else echo "$name: no JSON (see $out/runs/$name.err)" >&2; fi
}
export -f sweep_one
ls "$floors"/*.ifc | xargs -P "$jobs" -I{} bash -c 'sweep_one "$@"' _ {}
