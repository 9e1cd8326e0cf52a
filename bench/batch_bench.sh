#!/usr/bin/env bash
# Batches beyond one process: `rebound --batch` on 1 and 2 threads (and where its time
# goes), memory of the streaming batches against a binary from before they streamed,
# `solve --batch` throughput on 1 and 2 threads and its tail, and the Dask atlas on 1
# and 2 LocalCluster workers - runs alternating, each configuration several times, so
# a shared machine's load falls on all alike.
#   bench/batch_bench.sh [OLD_CUEPLAN]    (OLD_CUEPLAN: a binary to compare with)
#   BENCH_ONLY=rebound bench/batch_bench.sh   (one section: rebound, memory, solve, dask)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
new="$root/build/apps/cueplan/cueplan"
old="${1:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
py=/usr/bin/python3
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
only="${BENCH_ONLY:-}"
want() { [ -z "$only" ] || [ "$only" = "$1" ]; }

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

wall() {  # seconds of a command, its output to a file
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" > "$work/rebound.out" 2> /dev/null || true
  read -r e u s < "$work/time"
  echo "$e"
}
if want rebound; then
  echo "== rebound --batch: 100k rows, exact; 1 and 2 threads alternating, output to a file =="
  declare -A sum
  for round in 1 2 3 4 5; do
    line="  round $round:"
    for b in $old $new; do
      for t in 1 2; do
        s=$(wall "$b" rebound --batch "$work/rebounds.csv" --threads $t)
        key="$b $t"
        sum[$key]=$(echo "${sum[$key]:-0} + $s" | bc -l)
        line="$line $([ "$b" = "$new" ] && echo new || echo old) t$t ${s}s"
      done
    done
    echo "$line"
  done
  for b in $old $new; do
    one=${sum["$b 1"]}
    two=${sum["$b 2"]}
    echo "  $b: 1 thread $(echo "$one / 5" | bc -l | cut -c1-5) s, 2 threads $(echo "$two / 5" | bc -l | cut -c1-5) s (means): speedup $(echo "$one / $two" | bc -l | cut -c1-4)x"
  done
  echo "  where the time goes (CUEPLAN_BATCH_TIMES), 1 thread then 2:"
  for t in 1 2; do
    CUEPLAN_BATCH_TIMES=1 "$new" rebound --batch "$work/rebounds.csv" --threads $t 2>&1 > "$work/rebound.out" |
      grep 'times:' | sed 's/^/    /'
  done
fi

peak() {  # peak resident memory (MB) and seconds of a command
  /usr/bin/time -f "%M %e" -o "$work/time" "$@" > /dev/null 2> /dev/null || true
  read -r kb s < "$work/time"
  echo "$((kb / 1024)) MB, $s s"
}
if want memory; then
echo "== memory (peak resident; output to /dev/null) =="
for b in $old $new; do
  echo "$b"
  echo "  rebound --batch, 100k rows, exact, 2 threads:    $(peak "$b" rebound --batch "$work/rebounds.csv" --threads 2)"
  echo "  simulate --batch, 200k shots, exact, 2 threads:  $(peak "$b" simulate "$root/problems/one_rail_position.yaml" --batch "$work/shots.csv" --threads 2)"
done
fi

if want solve; then
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

  # The tail: the last run's per-problem times (time_s) scheduled greedily in input
  # order on 2 threads with no limit on problems held, against the measured wall time.
  $py "$root/bench/batch_tail.py" "$work/out2.jsonl" 2 "$e"
fi

if want dask; then
echo "== Dask atlas: 16 x 8 cells x 1 target (128 solves, table, 600 evaluations, 50 samples) =="
for round in 1 2 3; do
  for w in 1 2; do
    PYTHONPATH="$root/build/python" $py "$root/examples/dask_atlas.py" --workers $w --grid 16 8 2>/dev/null |
      grep '^atlas:' | sed "s/^/  round $round: /"
  done
done
fi
