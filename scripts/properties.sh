#!/usr/bin/env bash
# Builds (Release) and runs the RapidCheck properties of tests/properties on new random
# seeds; ctest runs them on one fixed draw. A failure prints the seed and a reproduce
# string (RC_PARAMS="reproduce=...") and the script ends non-zero.
#   scripts/properties.sh [--runs N] [--cases C]   N runs (default 20) of C cases per property (default 1000)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs=20
cases=1000
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="${2:?--runs needs a number}"; shift 2 ;;
    --cases) cases="${2:?--cases needs a number}"; shift 2 ;;
    *) echo "properties.sh: unknown argument '$1' (use --runs N, --cases C)" >&2; exit 2 ;;
  esac
done
case "$runs$cases" in *[!0-9]*) echo "properties.sh: --runs and --cases take whole numbers" >&2; exit 2 ;; esac
build="${CUEPLAN_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCUEPLAN_BUILD_TESTS=ON > /dev/null
cmake --build "$build" -j "$(nproc)" --target properties_impact_test properties_shot_test
status=0
for ((i = 1; i <= runs; i++)); do
  for t in properties_impact_test properties_shot_test; do
    if ! RC_PARAMS="max_success=$cases" "$build/tests/properties/$t" > "$build/$t.log" 2>&1; then
      echo "run $i: $t failed:"
      grep -E "Using configuration|Falsifiable|RC_PARAMS=|FAILED  \]" "$build/$t.log" || true
      status=1
    fi
  done
done
[ "$status" -eq 0 ] && echo "properties: $runs runs x $cases cases per property, no failure"
exit "$status"
