#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang with ASan + UBSan + leak detection) in
# build-fuzz/ and runs each on a copy of its seed corpus in build-fuzz/corpus/.
#   scripts/fuzz.sh               1000000 executions per target (fuzz/README.md)
#   scripts/fuzz.sh --runs N      N executions per target
#   scripts/fuzz.sh --time S      at most S seconds per target (default 3600, a safety net)
#   scripts/fuzz.sh --only NAME   one target: problem_loader_fuzzer or cli_fuzzer
# Prints the executions and result of each target; exits non-zero when a target finds a
# crash, a hang (an input running over 10 s), a leak or a broken promise. The input is
# then saved in build-fuzz/findings/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs=1000000
max_time=3600
targets="problem_loader_fuzzer cli_fuzzer"
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="${2:?--runs needs a number}"; shift 2 ;;
    --time) max_time="${2:?--time needs seconds}"; shift 2 ;;
    --only) targets="${2:?--only needs a target}"; shift 2 ;;
    *) echo "fuzz.sh: unknown argument '$1' (use --runs N, --time S)" >&2; exit 2 ;;
  esac
done
case "$runs$max_time" in
  *[!0-9]*) echo "fuzz.sh: --runs and --time take whole numbers" >&2; exit 2 ;;
esac

build="${CUEPLAN_FUZZ_BUILD_DIR:-$root/build-fuzz}"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCUEPLAN_BUILD_FUZZERS=ON -DCUEPLAN_BUILD_TESTS=OFF -DCUEPLAN_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target $targets

# target, seed files, dictionary
run_target() {
  local name="$1" seeds="$2" dict="$3"
  local corpus="$build/corpus/$name" findings="$build/findings/$name"
  mkdir -p "$corpus" "$findings"
  local seed
  for seed in $seeds; do [ -f "$seed" ] && cp "$seed" "$corpus/"; done
  local log="$build/$name.log"
  local status=0 started
  started="$(date +%s)"
  (cd "$findings" && ASAN_OPTIONS=detect_leaks=1 "$build/fuzz/$name" -runs="$runs" \
     -artifact_prefix="$findings/" \
     -max_total_time="$max_time" -timeout=10 -dict="$dict" -print_final_stats=1 \
     "$corpus") >"$log" 2>&1 || status=$?
  local execs seconds result="no crash, hang or leak"
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
  seconds=$(($(date +%s) - started))
  [ "$status" -ne 0 ] && result="FAILED (exit $status; see $log and $findings)"
  printf '%-22s %9s executions in %5s s, corpus %4s files: %s\n' "$name" "${execs:-?}" \
    "$seconds" "$(ls "$corpus" | wc -l)" "$result"
  return "$status"
}

failed=0
for target in $targets; do
  case "$target" in
    problem_loader_fuzzer)
      run_target "$target" "$root/problems/*.yaml $root/problems/routes/*.yaml" \
        "$root/fuzz/problem.dict" || failed=1 ;;
    cli_fuzzer) run_target "$target" "$root/fuzz/cli_seeds/*" "$root/fuzz/cli.dict" || failed=1 ;;
    *) echo "fuzz.sh: unknown target '$target'" >&2; exit 2 ;;
  esac
done
exit "$failed"
