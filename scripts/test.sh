#!/usr/bin/env bash
# Installs, builds (Release, with tests) and runs cueplan's whole test suite.
#   scripts/test.sh             the suite, Release build in build/
#   scripts/test.sh --sanitize  the suite under AddressSanitizer and UndefinedBehaviorSanitizer,
#                               in build-sanitize/
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
if [ "${1:-}" = "--sanitize" ]; then
  export CUEPLAN_BUILD_DIR="${CUEPLAN_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
  # -O1 -g1: what the sanitizers need for their reports (line tables), at half the
  # compile time of -O2 -g (planner.cpp: 39 s CPU against 75 s).
  "$root/scripts/build.sh" -DCUEPLAN_BUILD_TESTS=ON -DCUEPLAN_BUILD_BENCHMARKS=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCUEPLAN_SANITIZE=address,undefined
elif [ -n "${1:-}" ]; then
  echo "test.sh: unknown argument '$1' (the only one is --sanitize)" >&2
  exit 2
else
  "$root/scripts/build.sh" -DCUEPLAN_BUILD_TESTS=ON
fi
cd "${CUEPLAN_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "$(nproc)" --timeout 900
