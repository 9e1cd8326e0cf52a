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
