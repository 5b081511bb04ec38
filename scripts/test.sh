#!/usr/bin/env bash
# Builds everything and runs every test (ctest).
#   --ci   warnings are errors, a second pass under ASan+UBSan and a third,
#          the lock-free parts' stress tests (tests/tsan), under TSan
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
  # the random-program property at a fiftieth of its size (ASan: ~0.3 s a program); the plain pass runs it whole
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 LCNC_PROPERTY_PROGRAMS=200 \
    ctest --test-dir build-asan --output-on-failure -j2 -LE hdl  # GHDL itself is not sanitized
  # TSan: only the tsan_tests target (header-only, seconds to build).
  cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLCNC_WERROR=ON \
        -DLCNC_TSAN=ON -DLCNC_BUILD_BENCH=OFF -DLCNC_BUILD_HMI=OFF >/dev/null
  cmake --build build-tsan -j2 --target tsan_tests
  # gcc 12's TSan runtime cannot place its shadow memory when the kernel
  # randomizes mmap with more than 28 bits (vm.mmap_rnd_bits, raised on newer
  # kernels): "FATAL: ThreadSanitizer: unexpected memory mapping". Run with
  # ASLR off (setarch -R, inherited by ctest's children) wherever permitted.
  no_aslr=()
  setarch "$(uname -m)" -R true 2>/dev/null && no_aslr=(setarch "$(uname -m)" -R)
  TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
    "${no_aslr[@]}" ctest --test-dir build-tsan --output-on-failure -j2 -L tsan --no-tests=error
fi
