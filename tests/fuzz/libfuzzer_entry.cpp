// libFuzzer's entry for one target, chosen at build time (LCNC_FUZZ_TARGET).
#include <cstdlib>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const lcnc::fuzz::Target* t = lcnc::fuzz::find_target(LCNC_FUZZ_TARGET);
  if (t == nullptr) std::abort();
  return t->run(data, size);
}
