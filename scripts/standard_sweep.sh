#!/usr/bin/env bash
# The standard sets a localizer change is checked on before it lands (issue 28): every room of
# every shared plan on the exact and the construction site (seed 1, 40 s), and the 15 generated
# floors "f98" (worldgen seeds 98000-98011 and apartment blocks 98100-98102; every room, seed 1,
# 60 s, exact). Writes OUT/<set>.json; compare two binaries with
#   scripts/sweep_runs.py A/OUT/shared_exact.json --against B/OUT/shared_exact.json
#
#   scripts/standard_sweep.sh BIMLOC OUT [SET...]    # sets: shared_exact shared_construction f98
#
# Environment: SHARED (../shared beside the checkout), JOBS (2), NICE (0), EXTRA (more sweep
# options, e.g. "--config my.yaml"). A set already written is skipped.
set -euo pipefail
if [ $# -lt 2 ]; then sed -n 2,11p "$0" | sed 's/^# \{0,1\}//'; exit 2; fi
bin=$(readlink -f "$1"); out=$2; shift 2
sets=("$@"); [ ${#sets[@]} -eq 0 ] && sets=(shared_exact shared_construction f98)
here=$(cd "$(dirname "$0")/.." && pwd)
shared=${SHARED:-$here/../shared}; jobs=${JOBS:-2}; nice_level=${NICE:-0}; extra=${EXTRA:-}
mkdir -p "$out"
if [[ " ${sets[*]} " == *" f98 "* ]] && [ ! -d "$out/f98_floors" ]; then
  rm -rf "$out/f98_floors.part"
  "$bin" worldgen --random 98000 --random-count 12 --out "$out/f98_floors.part" > /dev/null
  "$bin" worldgen --random 98100 --random-count 3 --style apartment_block --out "$out/f98_floors.part" > /dev/null
  mv "$out/f98_floors.part" "$out/f98_floors"
fi
for set in "${sets[@]}"; do
  [ -s "$out/$set.json" ] && continue
  case $set in
    shared_exact) args=("$shared"/ifc/*.ifc --duration 40) ;;
    shared_construction) args=("$shared"/ifc/*.ifc --duration 40 --site construction) ;;
    f98) args=("$out"/f98_floors/*.ifc --duration 60) ;;
    *) echo "unknown set $set" >&2; exit 2 ;;
  esac
  # shellcheck disable=SC2086
  nice -n "$nice_level" "$bin" sweep "${args[@]}" --seeds 1 --jobs "$jobs" --json $extra \
    > "$out/$set.json.part" 2> "$out/$set.err" || true
  [ -s "$out/$set.json.part" ] && mv "$out/$set.json.part" "$out/$set.json" || { echo "$set: no JSON" >&2; exit 1; }
  echo "$set: $(python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["summary"]; print(s["runs"], "runs,", s["localized"], "localized,", s["false_convergences"], "false")' "$out/$set.json")"
done
