#!/usr/bin/env bash
# Configures a tree from a preset of CMakePresets.json (default: default),
# with ccache as the compiler launcher when it is installed: the paths of
# the checkout and the build folder left out of the hash, so a second clone
# of the same sources compiles only what differs. scripts/demo.sh and
# scripts/test.sh configure through it, so the README's two commands share
# one build/ and the second builds only what the first did not.
#   scripts/configure.sh [PRESET] [-DVAR=VALUE ...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset=default
case "${1:-}" in -*|"") ;; *) preset=$1; shift ;; esac
launcher=()
if command -v ccache >/dev/null; then
  launcher=("-DCMAKE_CXX_COMPILER_LAUNCHER=env;CCACHE_BASEDIR=$PWD;CCACHE_NOHASHDIR=true;ccache")
fi
cmake --preset "$preset" "${launcher[@]}" "$@" >/dev/null
