#!/usr/bin/env bash
# Instruction counts (valgrind --tool=callgrind) of two cueplan binaries on the same
# fixed work, for A/B comparisons that the shared machine's load cannot disturb:
#   bench/callgrind_ab.sh OLD_CUEPLAN NEW_CUEPLAN
# Work: `simulate --batch` of 2000 seeded random strokes on a shipped problem (3 obstacle
# balls) and on a generated table with 15 obstacle balls, and `solve --method exact` on
# both (1 thread), with the SSE2 kernels (CUEPLAN_SIMD=sse2: valgrind 3.19 does not
# decode every AVX instruction; the results are the same bits). Checks that both
# binaries print the same results (time_s aside; keys and columns only one of them
# prints are left out).
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 OLD_CUEPLAN NEW_CUEPLAN" >&2; exit 2; }
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 - "$work" <<'PY'
import random, sys
work = sys.argv[1]
rng = random.Random(3)
with open(f"{work}/shots.csv", "w") as f:
    f.write("speed,aim_deg,topspin_k,sidespin_k\n")
    for _ in range(2000):
        f.write(f"{rng.uniform(0.3, 3):.6f},{rng.uniform(-180, 180):.6f},"
                f"{rng.uniform(-0.8, 0.8):.6f},{rng.uniform(-0.8, 0.8):.6f}\n")
rng = random.Random(5)
balls = []
while len(balls) < 15:
    x, y = rng.uniform(0.3, 3.2), rng.uniform(0.3, 1.5)
    if all((x - a) ** 2 + (y - b) ** 2 > 0.01 for a, b in balls) and \
       (x - 0.6) ** 2 + (y - 0.9) ** 2 > 0.01 and (x - 3.0) ** 2 + (y - 1.2) ** 2 > 0.01:
        balls.append((x, y))
with open(f"{work}/field15.yaml", "w") as f:
    f.write("name: fifteen balls\ncue_ball: [0.6, 0.9]\ntarget: [3.0, 1.2]\n"
            "limits: {cushions: [0, 3]}\nobstacles: [" +
            ", ".join(f"[{x:.4f}, {y:.4f}]" for x, y in balls) + "]\n")
PY
count() {  # binary, output file, args...
  local bin=$1 out=$2
  shift 2
  CUEPLAN_SIMD=sse2 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$@" > "$out" 2> "$out.log"
  grep -o 'refs: *[0-9,]*' "$out.log" | tr -d ', ' | cut -d: -f2
}
printf '%-44s %15s %15s %8s\n' work old new new/old
for case in "simulate blocked_direct_route|simulate $root/problems/blocked_direct_route.yaml --batch $work/shots.csv --threads 1" \
            "simulate 15 obstacle balls|simulate $work/field15.yaml --batch $work/shots.csv --threads 1" \
            "solve one_rail_position (exact)|solve $root/problems/one_rail_position.yaml --method exact --threads 1 --json" \
            "solve 15 obstacle balls (exact)|solve $work/field15.yaml --method exact --threads 1 --json"; do
  label=${case%%|*}
  read -r -a args <<< "${case#*|}"
  a=$(count "$1" "$work/a.out" "${args[@]}")
  b=$(count "$2" "$work/b.out" "${args[@]}")
  same=same
  if ! python3 - "$work/a.out" "$work/b.out" <<'PY'
import csv, io, json, sys
# What both binaries print: JSON keys present in both (a newer binary may add keys), CSV
# columns of both headers (a newer one may append columns); time_s aside.
def common(a, b):
    if isinstance(a, dict) and isinstance(b, dict):
        keys = [k for k in a if k in b and k != "time_s"]
        return [common(a[k], b[k]) for k in keys], [common(b[k], a[k]) for k in keys]
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        pairs = [common(x, y) for x, y in zip(a, b)]
        return [p[0] for p in pairs], [p[1] for p in pairs]
    return a, b
def load(p):
    text = open(p).read()
    try:
        return json.loads(text)
    except ValueError:
        rows = list(csv.reader(io.StringIO(text)))
        return [dict(zip(rows[0], r)) for r in rows[1:]] if rows else text
a, b = load(sys.argv[1]), load(sys.argv[2])
x, y = common(a, b)
sys.exit(0 if x == y else 1)
PY
  then same="OUTPUTS DIFFER"; fi
  printf '%-44s %15s %15s %8.4f  %s\n' "$label" "$a" "$b" "$(python3 -c "print($b/$a)")" "$same"
done
