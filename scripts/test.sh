#!/usr/bin/env bash
# Builds everything and runs every test (ctest).
#   --ci   warnings are errors, and a second pass under ASan+UBSan
set -euo pipefail
cd "$(dirname "$0")/.."
ci=0
[ "${1:-}" = "--ci" ] && ci=1
scripts/deps.sh
werror=OFF
[ $ci = 1 ] && werror=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLCNC_WERROR=$werror >/dev/null
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2
if [ $ci = 1 ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DLCNC_WERROR=ON \
        -DLCNC_SANITIZE=ON -DLCNC_BUILD_BENCH=OFF >/dev/null
  cmake --build build-asan -j2
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j2 -LE hdl  # GHDL itself is not sanitized
fi
