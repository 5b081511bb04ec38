#!/usr/bin/env bash
# The house rules a compiler does not check: every C++ source formatted as
# .clang-format says, and the sources of the libraries and executables
# clean under .clang-tidy's checks. Needs a configured build/ (its
# compile_commands.json); scripts/test.sh --ci runs it after the build.
#   --fix   reformat the files instead of reporting them
# clang-tidy's verdict on a clean source is kept (scripts/tidy_cached.py),
# so a run checks again only what changed, as ccache does for the compiler.
set -euo pipefail
cd "$(dirname "$0")/.."
fix=0
[ "${1:-}" = --fix ] && fix=1
# the include checker's broken tree is a fixture whose line numbers its test expects
mapfile -t all < <(git ls-files '*.cpp' '*.h' ':!tests/layout/broken_tree')
if [ $fix = 1 ]; then
  clang-format -i "${all[@]}"
  exit 0
fi
echo "lint: clang-format over ${#all[@]} files" >&2
if ! clang-format --dry-run --Werror "${all[@]}" 2>/tmp/lint-format.$$; then
  grep -E "^[^ ].*: (error|warning):" /tmp/lint-format.$$ | cut -d: -f1 | sort -u | sed 's/^/  not formatted: /' >&2
  rm -f /tmp/lint-format.$$
  echo "lint: run scripts/lint.sh --fix (clang-format -i) and commit the result" >&2
  exit 1
fi
rm -f /tmp/lint-format.$$
[ -f build/compile_commands.json ] || { echo "lint: configure build/ first (cmake --preset default)" >&2; exit 2; }
mapfile -t sources < <(git ls-files 'core/*.cpp' 'rt/*.cpp' 'drivers/*.cpp' 'app/*.cpp' 'hmi/*.cpp')
exec python3 scripts/tidy_cached.py build "${sources[@]}"
