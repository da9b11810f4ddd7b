#!/bin/sh
# Submits a sharded sweep to Slurm: a job array of N tasks (one shard each), then a merge job
# that runs once every task has ended (afterany: a failed task leaves its shard missing, and
# the merge then says which).
#   deploy/slurm/submit.sh N OUT_DIR [bimloc run arguments...]
# Run it from the repository root on a login node; OUT_DIR must be on a folder every node
# shares. Example:
#   deploy/slurm/submit.sh 8 /shared/sweeps/site_office --plan worlds/site_office.ifc --all-rooms --seeds 10
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 N OUT_DIR [bimloc run arguments...]" >&2
  exit 2
fi
N=$1 OUT=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
array=$(sbatch --parsable --array=1-"$N" --output="$OUT/slurm-%A_%a.out" "$here/shard.sbatch" "$N" "$OUT" "$@")
merge=$(sbatch --parsable --dependency=afterany:"${array%%;*}" --output="$OUT/slurm-merge-%j.out" "$here/merge.sbatch" "$N" "$OUT")
echo "array job $array (N = $N), merge job $merge: $OUT/merged.json when done"
