#!/usr/bin/env bash
# The Slurm recipe of examples/cluster, run without Slurm: solve_array.sbatch as three
# array tasks (the variables Slurm sets, set by hand), then merge.sbatch; the merged
# file must be the unsharded `solve --batch` output line for line, apart from time_s.
# The exact impact method and a small budget keep it quick (no impact table to build).
set -euo pipefail
: "${CUEPLAN_BINARY:?}" "${CUEPLAN_EXAMPLES:?}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cluster="$CUEPLAN_EXAMPLES/cluster"
for script in "$cluster"/*.sbatch "$cluster"/submit.sh; do bash -n "$script"; done

for i in 0 1 2 3 4 5 6; do
  printf '{"id": %d, "cue_ball": [%s, %s], "target": [%s, 1.1], "limits": {"cushions": %d}}\n' \
    "$i" "0.$((4 + i))" "0.$((5 + i % 3))" "2.$((1 + i))" $((i % 2))
  [ "$i" = 3 ] && echo ""  # a blank line: skipped, not a problem
done > "$work/problems.jsonl"
# (solve_array.sbatch adds --max-time 3600; the unsharded run gets it too.)
options=(--method exact --max-evaluations 250 --samples 8 --alternatives 0 --seed 3)
rc=0
"$CUEPLAN_BINARY" solve --batch "$work/problems.jsonl" --threads 2 --max-time 3600 "${options[@]}" \
  > "$work/whole.jsonl" 2> "$work/whole.err" || rc=$?
[ "$rc" -le 1 ] || { echo "unsharded run failed ($rc):"; cat "$work/whole.err"; exit 1; }

for k in 2 0 1; do  # any order, as an array's tasks start; task 1 as if rerun alone
  if [ "$k" = 1 ]; then range=(SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=1 SHARDS=3)
  else range=(SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=2); fi
  env SLURM_ARRAY_TASK_ID=$k "${range[@]}" SLURM_CPUS_PER_TASK=1 \
    PROBLEMS="$work/problems.jsonl" OUT_DIR="$work/out" CUEPLAN_CACHE_DIR="$work/cache" \
    CUEPLAN="$CUEPLAN_BINARY" bash "$cluster/solve_array.sbatch" "${options[@]}" 2> "$work/task$k.err" ||
    { echo "task $k failed:"; cat "$work/task$k.err"; exit 1; }
  [ -f "$work/out/part.$k.jsonl" ] || { echo "task $k wrote no part"; exit 1; }
done
[ "$(wc -l < "$work/out/part.0.jsonl")" = 3 ] || { echo "shard 0 should hold problems 0, 3, 6"; exit 1; }

# A missing part stops the merge with its name.
mv "$work/out/part.1.jsonl" "$work/part1.jsonl"
if OUT_DIR="$work/out" SHARDS=3 CUEPLAN="$CUEPLAN_BINARY" bash "$cluster/merge.sbatch" 2> "$work/merge.err"; then
  echo "merge went on without part 1"; exit 1
fi
grep -q "part.1.jsonl is missing" "$work/merge.err" || { cat "$work/merge.err"; exit 1; }
mv "$work/part1.jsonl" "$work/out/part.1.jsonl"

OUT_DIR="$work/out" SHARDS=3 CUEPLAN="$CUEPLAN_BINARY" bash "$cluster/merge.sbatch"
strip() { sed -E 's/"time_s": ?[-0-9.eE+]+,? ?//g' "$1"; }
if ! diff <(strip "$work/whole.jsonl") <(strip "$work/out/results.jsonl") > "$work/diff"; then
  echo "merged shards differ from the unsharded run:"; head -20 "$work/diff"; exit 1
fi
[ "$(wc -l < "$work/out/results.jsonl")" = 7 ] || { echo "expected 7 lines"; exit 1; }
echo "cluster recipe: 3 array tasks merged to the unsharded output (7 problems)"
