#!/usr/bin/env bash
# Installs, builds (Release) and runs cueplan's main job on a bundled example.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
cueplan="${CUEPLAN_BUILD_DIR:-$root/build}/apps/cueplan/cueplan"

echo
echo "\$ cueplan solve problems/one_rail_position.yaml --svg build/plan.svg"
echo "(the first run builds the impact table the search uses, about 30 s, and caches it)"
"$cueplan" solve "$root/problems/one_rail_position.yaml" --svg "${CUEPLAN_BUILD_DIR:-$root/build}/plan.svg"
echo
echo "\$ cueplan rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0"
"$cueplan" rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0
