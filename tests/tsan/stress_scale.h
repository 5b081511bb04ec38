// Sizes of the TSan stress tests: a default that keeps the CI pass short
// under TSan's 5–15× slowdown, multiplied by LCNC_TEST_SCALE for long runs
// (support/test_scale.h).
#pragma once

#include <cstdint>
#include <cstdlib>

#include "../support/test_scale.h"

namespace lcnc::rt::tsan {

using lcnc::testing::scaled;

// A value every field of a test item derives from, so a wrong or torn item
// is detectable (splitmix64's finalizer).
inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace lcnc::rt::tsan
