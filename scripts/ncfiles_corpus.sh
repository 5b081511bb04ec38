#!/usr/bin/env bash
# How many of LinuxCNC's sample programs `lasercnc check` accepts, and the
# first error of each one it refuses, on a machine wide enough for them
# (tests/data/machines/ncfiles_wide.toml).
#
#   scripts/ncfiles_corpus.sh [BUILD_DIR] [NCFILES_DIR]
#
# Prints a Markdown table (file, result) and the count. The sample programs
# come with Debian's linuxcnc-uspace (scripts/deps.sh installs it).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
ncfiles="${2:-/usr/share/linuxcnc/ncfiles}"
lasercnc="$build/app/lasercnc"
machine="$here/tests/data/machines/ncfiles_wide.toml"
[[ -x "$lasercnc" ]] || { echo "no $lasercnc: build first" >&2; exit 2; }
[[ -d "$ncfiles" ]] || { echo "no $ncfiles: install linuxcnc-uspace" >&2; exit 2; }

total=0
accepted=0
echo "| program | lasercnc check |"
echo "|---|---|"
while IFS= read -r f; do
  total=$((total + 1))
  rel="${f#"$ncfiles"/}"
  if out="$(timeout 60 "$lasercnc" check "$f" --machine "$machine" 2>&1)"; then
    accepted=$((accepted + 1))
    echo "| $rel | accepted |"
  else
    # the first line of the error, without the file's path, '|' escaped
    msg="$(printf '%s\n' "$out" | head -1 | sed -e "s|$ncfiles/||" -e 's/|/\\|/g' | cut -c1-200)"
    echo "| $rel | $msg |"
  fi
done < <(find "$ncfiles" -name '*.ngc' | LC_ALL=C sort)
echo
echo "accepted $accepted of $total"
