#!/usr/bin/env bash
# The code's layout (issue 26): the command line (apps/cueplan) stays a thin face over
# the api - at most 25 % of the project's C++ lines - and no face includes another
# face's files (the server none of apps/cueplan's). Prints the line counts it checks.
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
# The server's files include only its own headers and the libraries' (cueplan/...).
for f in server/*.cpp server/*.hpp; do
  for h in $(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f"); do
    case "$h" in
      cueplan/*) ;;
      *) [ -e "server/$h" ] || { echo "FAIL: $f includes $h, not a server file"; status=1; } ;;
    esac
  done
done
# The api includes no face: nothing outside cueplan/...
if grep -rn '#include "[^c][^u]' api/ >/dev/null; then
  grep -rn '#include "[^c][^u]' api/
  echo "FAIL: api/ includes a face's file"
  status=1
fi
exit $status
