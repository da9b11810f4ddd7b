#!/bin/sh
# One shard of a sweep, the command every array task runs (Slurm, Kubernetes, and
# tests/test_shards.cpp locally):
#   deploy/run_shard.sh K N OUT_DIR [bimloc run arguments...]
# runs `bimloc run ARGS --shard K/N --json` and writes OUT_DIR/shard-K-of-N.json atomically
# (a temporary name in OUT_DIR, then a rename: a shared folder never shows half a shard).
# A scenario that fails its expectations is a result, not a failed task: bimloc run exits 1
# then, with its JSON written, and this script exits 0. Any other failure (exit 2: bad
# arguments, a missing plan; docs/exit_codes.md) fails the task with bimloc's message and
# leaves no file.
# BIMLOC: the binary (default: bimloc on the PATH).
set -u
if [ $# -lt 3 ]; then
  echo "usage: $0 K N OUT_DIR [bimloc run arguments...]" >&2
  exit 2
fi
K=$1 N=$2 OUT=$3
shift 3
BIMLOC=${BIMLOC:-bimloc}
mkdir -p "$OUT" || exit 1
part="$OUT/.shard-$K-of-$N.json.$$"
"$BIMLOC" run "$@" --shard "$K/$N" --json >"$part"
status=$?
if [ "$status" -le 1 ] && [ -s "$part" ]; then
  mv -f "$part" "$OUT/shard-$K-of-$N.json" && exit 0
fi
rm -f "$part"
[ "$status" -ne 0 ] || status=1
exit "$status"
