#!/usr/bin/env bash
# Installs, builds (Release) and runs cueplan's main job on bundled examples: a position
# shot, a rebound and a pot with position.
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
echo
echo "\$ cueplan solve problems/pots/cut_middle_pocket.yaml --svg build/pot.svg"
echo "(pot the red in the middle pocket and leave the cue ball on the target)"
"$cueplan" solve "$root/problems/pots/cut_middle_pocket.yaml" --svg "${CUEPLAN_BUILD_DIR:-$root/build}/pot.svg"
