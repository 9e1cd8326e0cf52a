#!/usr/bin/env bash
# Installs, builds (Release, with tests) and runs cueplan's whole test suite.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh" -DCUEPLAN_BUILD_TESTS=ON
cd "${CUEPLAN_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "$(nproc)" --timeout 900
