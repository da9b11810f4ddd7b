#!/bin/sh
# The final step of a sharded sweep: merges OUT_DIR/shard-*-of-N.json into OUT_DIR/merged.json
# (exactly the unsharded `bimloc run --json`) and OUT_DIR/merged.txt (its table).
#   deploy/merge_shards.sh N OUT_DIR
# bimloc report merge names a missing, doubled or foreign shard and fails. As run_shard.sh,
# failed scenarios are results (exit status 0 once merged.json is written).
set -u
if [ $# -ne 2 ]; then
  echo "usage: $0 N OUT_DIR" >&2
  exit 2
fi
N=$1 OUT=$2
BIMLOC=${BIMLOC:-bimloc}
set --  # the shards' files, as arguments (a missing one is named by bimloc report merge)
k=1
while [ "$k" -le "$N" ]; do
  set -- "$@" "$OUT/shard-$k-of-$N.json"
  k=$((k + 1))
done
"$BIMLOC" report merge "$@" --json >"$OUT/.merged.json.$$"
status=$?
if [ "$status" -le 1 ] && [ -s "$OUT/.merged.json.$$" ]; then
  mv -f "$OUT/.merged.json.$$" "$OUT/merged.json"
  "$BIMLOC" report merge "$@" >"$OUT/merged.txt"
  cat "$OUT/merged.txt"
  exit 0
fi
rm -f "$OUT/.merged.json.$$"
exit "$status"
