#!/usr/bin/env bash
# Installs, builds (Release) and runs cueplan's main job on a bundled example.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
cueplan="${CUEPLAN_BUILD_DIR:-$root/build}/apps/cueplan/cueplan"

echo
echo "\$ cueplan rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0"
"$cueplan" rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0
echo
echo "\$ cueplan rebound --batch problems/rebound_examples.csv --threads 2"
"$cueplan" rebound --batch "$root/problems/rebound_examples.csv" --threads 2
echo
echo "\$ cueplan simulate problems/one_rail_position.yaml --speed 1.002 --aim -60.36 --topspin-k 0.8 --svg build/one_rail.svg"
"$cueplan" simulate "$root/problems/one_rail_position.yaml" --speed 1.002 --aim -60.36 \
  --topspin-k 0.8 --svg "${CUEPLAN_BUILD_DIR:-$root/build}/one_rail.svg"
