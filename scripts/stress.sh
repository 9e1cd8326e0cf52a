#!/usr/bin/env bash
# Builds (Release) and runs the full stress runs of tests/stress, printing their figures
# (tests/README.md records them).
#   scripts/stress.sh [--seed S]   the runs with another random seed (default 1)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seed=1
if [ "${1:-}" = "--seed" ] && [ -n "${2:-}" ]; then
  seed="$2"
elif [ -n "${1:-}" ]; then
  echo "stress.sh: unknown argument '$1' (the only one is --seed S)" >&2
  exit 2
fi
build="${CUEPLAN_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCUEPLAN_BUILD_TESTS=ON \
  -DCUEPLAN_BUILD_STRESS=ON > /dev/null
cmake --build "$build" -j "$(nproc)" --target stress_impacts stress_shots
status=0
"$build/tests/stress/stress_impacts" --impacts 1000000 --paper-sample 1000 --paper-steps 100000 \
  --seed "$seed" --json "$build/stress_impacts.json" || status=1
"$build/tests/stress/stress_impacts" --method extrapolation --impacts 1000000 --paper-sample 1000 \
  --paper-steps 100000 --seed "$seed" --json "$build/stress_impacts_extrapolation.json" || status=1
"$build/tests/stress/stress_shots" --shots 50000 --seed "$seed" \
  --json "$build/stress_shots.json" || status=1
echo "figures also in $build/stress_impacts.json, $build/stress_impacts_extrapolation.json and $build/stress_shots.json"
exit "$status"
