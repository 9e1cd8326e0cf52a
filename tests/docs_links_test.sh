#!/usr/bin/env bash
# Checks that every relative link in README.md, CHANGELOG.md and docs/**/*.md resolves
# to a file or folder of the tree, and that a #fragment on a Markdown file (or a bare
# #fragment, on the file itself) names one of its headings as GitHub spells the anchor
# (lower case, punctuation dropped, spaces as hyphens). Links to other sites are
# skipped; links inside code fences and inline code are not links. Prints each broken
# link as FILE:LINE: TARGET and exits 1 if there is any.
#
#   tests/docs_links_test.sh [ROOT]     check the tree at ROOT (default: this repository)
#   tests/docs_links_test.sh --self-test
#                                       check that the checker fails on a broken link and
#                                       passes once it is mended (in a temporary tree)
set -euo pipefail

self="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$(basename "${BASH_SOURCE[0]}")"

# Prints the GitHub anchor of every heading of one Markdown file, one a line.
anchors_of() {
  awk '
    /^[ \t]*(```|~~~)/ { fenced = !fenced; next }
    fenced { next }
    /^#+[ \t]/ {
      h = $0
      sub(/^#+[ \t]+/, "", h)
      sub(/[ \t]+#*[ \t]*$/, "", h)
      h = tolower(h)
      gsub(/[^a-z0-9_ -]/, "", h)
      gsub(/ /, "-", h)
      print h
    }' "$1"
}

# Prints "LINE<TAB>TARGET" for every Markdown link or image of one file, outside code.
links_of() {
  awk '
    /^[ \t]*(```|~~~)/ { fenced = !fenced; next }
    fenced { next }
    {
      line = $0
      gsub(/`[^`]*`/, "", line)          # inline code is not a link
      while (match(line, /\]\([^)[:space:]]+/)) {
        target = substr(line, RSTART + 2, RLENGTH - 2)
        print NR "\t" target
        line = substr(line, RSTART + RLENGTH)
      }
      # reference definitions: [name]: target
      if (match(line, /^[ \t]*\[[^]]+\]:[ \t]+[^ \t]+/)) {
        def = substr(line, RSTART, RLENGTH)
        sub(/^[ \t]*\[[^]]+\]:[ \t]+/, "", def)
        print NR "\t" def
      }
    }' "$1"
}

check_tree() {
  local root="$1" broken=0 checked=0 file line target path fragment
  local -a files=()
  [ -f "$root/README.md" ] && files+=("$root/README.md")
  [ -f "$root/CHANGELOG.md" ] && files+=("$root/CHANGELOG.md")
  if [ -d "$root/docs" ]; then
    while IFS= read -r -d '' file; do files+=("$file"); done \
      < <(find "$root/docs" -name '*.md' -type f -print0 | sort -z)
  fi
  if [ "${#files[@]}" -eq 0 ]; then
    echo "docs_links_test: no README.md or docs/*.md under $root" >&2
    return 1
  fi
  for file in "${files[@]}"; do
    while IFS=$'\t' read -r line target; do
      case "$target" in
        http://* | https://* | mailto:*) continue ;;
      esac
      target="${target#<}"
      target="${target%>}"
      fragment=""
      case "$target" in *'#'*) fragment="${target#*#}" ;; esac
      path="${target%%#*}"
      checked=$((checked + 1))
      if [ -n "$path" ]; then
        path="$(dirname "$file")/$path"
      else
        path="$file"
      fi
      if [ ! -e "$path" ]; then
        echo "${file#"$root"/}:$line: broken link: $target" >&2
        broken=$((broken + 1))
      elif [ -n "$fragment" ] && [ -f "$path" ] && [[ "$path" == *.md ]] &&
        ! anchors_of "$path" | grep -qxF -- "$fragment"; then
        echo "${file#"$root"/}:$line: broken link: $target (no such heading)" >&2
        broken=$((broken + 1))
      fi
    done < <(links_of "$file")
  done
  if [ "$broken" -gt 0 ]; then
    echo "docs_links_test: $broken of $checked relative links are broken" >&2
    return 1
  fi
  echo "docs_links_test: ${#files[@]} files, $checked relative links, all resolve"
}

self_test() {
  local tmp rc out
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' RETURN
  mkdir -p "$tmp/docs/commands"
  printf '# t\n[a](docs/commands/solve.md) and ![p](docs/missing.png)\n`[not](a/link.md)`\n' \
    > "$tmp/README.md"
  printf '[up](../../README.md#t) [web](https://example.org/x) [in](#flags-and-keys)\n' \
    > "$tmp/docs/commands/solve.md"
  printf '```\n[code](nowhere.md)\n```\n## Flags, and `keys`\n[bad](#no-such-heading)\n' \
    >> "$tmp/docs/commands/solve.md"
  set +e
  out="$(bash "$self" "$tmp" 2>&1)"
  rc=$?
  set -e
  if [ "$rc" -eq 0 ] || ! grep -q 'README.md:2: broken link: docs/missing.png' <<< "$out"; then
    echo "self-test: a broken link was not reported (exit $rc): $out" >&2
    return 1
  fi
  if ! grep -q 'solve.md:6: broken link: #no-such-heading (no such heading)' <<< "$out"; then
    echo "self-test: a link to a missing heading was not reported: $out" >&2
    return 1
  fi
  if [ "$(grep -c 'broken link' <<< "$out")" -ne 2 ]; then
    echo "self-test: expected exactly two broken links: $out" >&2
    return 1
  fi
  : > "$tmp/docs/missing.png"
  sed -i 's/#no-such-heading/#flags-and-keys/' "$tmp/docs/commands/solve.md"
  if ! out="$(bash "$self" "$tmp" 2>&1)"; then
    echo "self-test: the mended tree still fails: $out" >&2
    return 1
  fi
  echo "self-test: the broken links were reported, the mended tree passes"
}

if [ "${1:-}" = "--self-test" ]; then
  self_test
else
  check_tree "$(cd "${1:-$(dirname "$self")/..}" && pwd)"
fi
