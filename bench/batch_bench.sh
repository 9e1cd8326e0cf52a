#!/usr/bin/env bash
# Batches beyond one process: memory of the streaming batches against a binary from
# before they streamed, `solve --batch` throughput on 1 and 2 threads, and the Dask
# atlas on 1 and 2 LocalCluster workers - runs alternating, each configuration
# several times, so a shared machine's load falls on both alike.
#   bench/batch_bench.sh [OLD_CUEPLAN]    (OLD_CUEPLAN: a binary to compare memory with)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
new="$root/build/apps/cueplan/cueplan"
old="${1:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
py=/usr/bin/python3
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"

# Inputs: 100k rebounds, 200k shots (random, seeded), 40 problems.
$py - "$work" <<'PY'
import json, random, sys
w = sys.argv[1]
r = random.Random(19)
with open(f"{w}/rebounds.csv", "w") as f:
    f.write("speed,angle_deg,topspin_k,sidespin_k\n")
    for _ in range(100000):
        f.write(f"{r.uniform(0.1, 2):.6g},{r.uniform(5, 175):.6g},{r.uniform(-1, 1):.4g},{r.uniform(-1, 1):.4g}\n")
with open(f"{w}/shots.csv", "w") as f:
    f.write("speed,aim_deg,topspin_k,sidespin_k\n")
    for _ in range(200000):
        f.write(f"{r.uniform(0.2, 3):.6g},{r.uniform(-180, 180):.6g},{r.uniform(-1, 1):.4g},{r.uniform(-1, 1):.4g}\n")
with open(f"{w}/problems.jsonl", "w") as f:
    for i in range(40):
        f.write(json.dumps({"id": i, "cue_ball": [round(r.uniform(0.3, 3.2), 3), round(r.uniform(0.3, 1.5), 3)],
                            "target": [round(r.uniform(0.3, 3.2), 3), round(r.uniform(0.3, 1.5), 3)],
                            "limits": {"cushions": r.choice([0, 1, 2])}}) + "\n")
PY

peak() {  # peak resident memory (MB) and seconds of a command
  /usr/bin/time -f "%M %e" -o "$work/time" "$@" > /dev/null 2> /dev/null || true
  read -r kb s < "$work/time"
  echo "$((kb / 1024)) MB, $s s"
}
echo "== memory (peak resident; output to /dev/null) =="
for b in $old $new; do
  echo "$b"
  echo "  rebound --batch, 100k rows, exact, 2 threads:    $(peak "$b" rebound --batch "$work/rebounds.csv" --threads 2)"
  echo "  simulate --batch, 200k shots, exact, 2 threads:  $(peak "$b" simulate "$root/problems/one_rail_position.yaml" --batch "$work/shots.csv" --threads 2)"
done

echo "== solve --batch: 40 problems, default options (table, 2000 evaluations, 200 samples) =="
"$new" solve --batch "$work/problems.jsonl" --threads 1 > /dev/null 2>&1 || true  # the table, loaded once
# Cores used = CPU seconds / wall seconds: on a machine shared with other sessions'
# work, how much of a second core the run was given.
for round in 1 2 3; do
  for t in 1 2; do
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$new" solve --batch "$work/problems.jsonl" \
      --threads $t > "$work/out$t.jsonl" 2> /dev/null || true
    read -r e u s < "$work/time"
    echo "  round $round, --threads $t: $(echo "40 / $e" | bc -l | cut -c1-5) problems/s, $e s wall, $(echo "($u + $s) / $e" | bc -l | cut -c1-4) cores used"
  done
done

echo "== Dask atlas: 16 x 8 cells x 1 target (128 solves, table, 600 evaluations, 50 samples) =="
for round in 1 2 3; do
  for w in 1 2; do
    PYTHONPATH="$root/build/python" $py "$root/examples/dask_atlas.py" --workers $w --grid 16 8 2>/dev/null |
      grep '^atlas:' | sed "s/^/  round $round: /"
  done
done
