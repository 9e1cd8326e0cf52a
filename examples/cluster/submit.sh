#!/bin/bash
# Submits the three steps with Slurm dependencies: the impact table built once into the
# shared cache, then an array of SHARDS tasks (one shard each), then the merge.
#   PROBLEMS=atlas.jsonl OUT_DIR=$PWD/out CUEPLAN_CACHE_DIR=/shared/cueplan-cache \
#     SHARDS=16 examples/cluster/submit.sh [cueplan solve options...]
# PROBLEMS, OUT_DIR and CUEPLAN_CACHE_DIR must be paths every node sees.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
: "${PROBLEMS:?}" "${OUT_DIR:?}" "${CUEPLAN_CACHE_DIR:?}" "${SHARDS:?}"
export PROBLEMS OUT_DIR CUEPLAN_CACHE_DIR SHARDS
[ -n "${CUEPLAN:-}" ] && export CUEPLAN
mkdir -p "$OUT_DIR"
table=$(sbatch --parsable --export=ALL "$here/prebuild_table.sbatch")
array=$(sbatch --parsable --export=ALL --dependency=afterok:"$table" \
  --array=0-$((SHARDS - 1)) "$here/solve_array.sbatch" "$@")
merge=$(sbatch --parsable --export=ALL --dependency=afterok:"$array" "$here/merge.sbatch")
echo "submitted: table $table, array $array (0-$((SHARDS - 1))), merge $merge"
echo "results: $OUT_DIR/results.jsonl once job $merge finishes"
