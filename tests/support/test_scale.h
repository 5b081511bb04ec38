// How much bigger the randomized and stress tests run: LCNC_TEST_SCALE, a
// whole number ≥ 1 (default 1; anything else reads as 1), multiplies their
// case counts for long runs by hand, e.g.
//     LCNC_TEST_SCALE=100 ctest --preset default -R 'Property|Fuzz|Stress'
// The one knob for every suite (core, rt, TSan): what CI runs is scale 1.
#pragma once

#include <cstdint>
#include <cstdlib>

namespace lcnc::testing {

inline std::uint64_t test_scale() {
  const char* s = std::getenv("LCNC_TEST_SCALE");
  if (s == nullptr) return 1;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(s, &end, 10);
  return end != s && *end == '\0' && v >= 1 ? v : 1;
}

// n cases, scaled.
template <class N>
N scaled(N n) {
  return static_cast<N>(n * static_cast<N>(test_scale()));
}

}  // namespace lcnc::testing
