#!/usr/bin/env bash
# The code's layout (issue 26): the command line (apps/cueplan) stays a thin face over
# the api - at most 25 % of the project's C++ lines - and no face includes another
# face's files (the server, batch streaming and Python none of apps/cueplan's). Prints the line counts it checks.
# Usage: layout_test.sh ROOT
set -euo pipefail
root="${1:?usage: layout_test.sh ROOT}"
cd "$root"
total=0
apps=0
for dir in physics problems planner draw api server batch apps python; do
  n=$(find "$dir" \( -name '*.cpp' -o -name '*.hpp' \) -print0 | xargs -0 cat | wc -l)
  printf '%-9s %6d lines\n' "$dir" "$n"
  total=$((total + n))
  [ "$dir" = apps ] && apps=$n
done
printf '%-9s %6d lines; apps/ %d.%d %%\n' total "$total" $((100 * apps / total)) \
  $((1000 * apps / total % 10))
status=0
if [ $((4 * apps)) -gt "$total" ]; then
  echo "FAIL: apps/ holds more than 25 % of the code lines"
  status=1
fi
# The server's, batch streaming's and Python's files include only their own headers and
# the libraries' (cueplan/...): never a file of apps/ (the command line), nor of another
# face.
for dir in server batch python/src; do
  for f in "$dir"/*.cpp "$dir"/*.hpp; do
    for h in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f"); do
      case "$h" in
        cueplan/*) ;;
        *) [ -e "$dir/$h" ] || { echo "FAIL: $f includes $h, not a file of $dir/"; status=1; } ;;
      esac
      case "$h" in
        *apps/*|*../*) echo "FAIL: $f includes $h, outside its face"; status=1 ;;
      esac
      if [ -e "apps/cueplan/$(basename "$h")" ] && [ ! -e "$dir/$h" ]; then
        echo "FAIL: $f includes $h, a file of apps/cueplan"
        status=1
      fi
    done
  done
done
# Batch streaming and the server build without the command line's library.
for f in batch/CMakeLists.txt server/CMakeLists.txt python/CMakeLists.txt; do
  if grep -n 'cueplan_cli' "$f"; then
    echo "FAIL: $f links cueplan_cli, the command line's library"
    status=1
  fi
done
# The api includes no face: nothing outside cueplan/...
if grep -rn '#include "[^c][^u]' api/ >/dev/null; then
  grep -rn '#include "[^c][^u]' api/
  echo "FAIL: api/ includes a face's file"
  status=1
fi
exit $status
