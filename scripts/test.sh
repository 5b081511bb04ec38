#!/usr/bin/env bash
# Builds everything and runs every test (ctest).
#   --quick  the unit tests alone (core, rt, drivers, hmi): no end-to-end,
#            HAL, HDL or package test, no sanitizer pass; for the edit-test
#            loop from a built tree
#   --ci     warnings are errors, the house style and checks (scripts/lint.sh:
#            clang-format, clang-tidy), a second pass under ASan+UBSan and a
#            third, the lock-free parts' stress tests (tests/tsan), under TSan
# The tests of the real-time path itself (label `realtime`: wall-clock
# latency, the loop's allocation, lock and syscall proofs, and the jobs on
# LinuxCNC's HAL, whose servo thread keeps the wall clock) run after the
# others, one at a time. Every other test runs the simulated machine on the
# simulated clock or waits on events, so load on the computer cannot change
# its verdict. The presets are in CMakePresets.json (cmake --preset, ctest
# --preset); ccache is used when installed (scripts/configure.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=all
case "${1:-}" in
  --ci) mode=ci ;;
  --quick) mode=quick ;;
  "") ;;
  *) echo "usage: scripts/test.sh [--quick | --ci]" >&2; exit 2 ;;
esac
scripts/deps.sh
# CI builds each target as a few unity files (CMAKE_UNITY_BUILD: a third of
# the compile time from nothing); the edit-test loop one object per source.
werror=OFF unity=OFF
[ $mode = ci ] && werror=ON unity=ON
scripts/configure.sh default -DLCNC_WERROR=$werror -DCMAKE_UNITY_BUILD=$unity
if [ $mode = quick ]; then
  cmake --build build -j2 --target core_tests rt_tests drivers_tests hmi_tests
  ctest --preset quick
  exit 0
fi
cmake --build build -j2
[ $mode = ci ] && scripts/lint.sh
ctest --preset default
ctest --preset realtime
if [ $mode = ci ]; then
  scripts/configure.sh asan
  cmake --build build-asan -j2
  # the random-program property at a fiftieth of its size (ASan: ~0.3 s a
  # program; the plain pass runs it whole); GHDL itself is not sanitized,
  # and the real-time path's own tests are the plain pass's
  ctest --preset asan
  # TSan: only the tsan_tests target (header-only, seconds to build).
  scripts/configure.sh tsan
  cmake --build --preset tsan
  # gcc 12's TSan runtime cannot place its shadow memory when the kernel
  # randomizes mmap with more than 28 bits (vm.mmap_rnd_bits, raised on newer
  # kernels): "FATAL: ThreadSanitizer: unexpected memory mapping". Run with
  # ASLR off (setarch -R, inherited by ctest's children) wherever permitted.
  no_aslr=()
  setarch "$(uname -m)" -R true 2>/dev/null && no_aslr=(setarch "$(uname -m)" -R)
  "${no_aslr[@]}" ctest --preset tsan
fi
