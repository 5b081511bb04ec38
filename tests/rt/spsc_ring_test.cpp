#include "rt/spsc_ring.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <thread>

namespace lcnc::rt {
namespace {

TEST(SpscRing, FifoOrderAndCapacity) {
  auto ring = std::make_unique<SpscRing<int, 8>>();
  for (int i = 0; i < 8; ++i) EXPECT_TRUE(ring->try_push(i));
  EXPECT_FALSE(ring->try_push(99));  // full: refuses, never spins
  EXPECT_EQ(ring->size(), 8u);
  int v = -1;
  for (int i = 0; i < 8; ++i) {
    ASSERT_TRUE(ring->try_pop(v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(ring->try_pop(v));
  EXPECT_TRUE(ring->empty());
}

TEST(SpscRing, IndicesSitOnSeparateCacheLines) {
  using Ring = SpscRing<std::uint64_t, 16>;
  static_assert(alignof(Ring) >= kCacheLine);
  static_assert(sizeof(Ring) >= 3 * kCacheLine);
  SUCCEED();
}

// Two threads, fixed seed, N items with a checksum: every item arrives once,
// in order. LCNC_FUZZ_SCALE multiplies N for long runs.
TEST(SpscRing, TwoThreadFuzzPreservesEveryItemInOrder) {
  struct Item {
    std::uint64_t seq;
    std::uint64_t mix;
  };
  auto ring = std::make_unique<SpscRing<Item, 64>>();
  std::uint64_t scale = 1;
  if (const char* s = std::getenv("LCNC_FUZZ_SCALE")) scale = std::strtoull(s, nullptr, 10);
  const std::uint64_t n = 2'000'000 * scale;
  auto mix = [](std::uint64_t x) { return x * 0x9E3779B97F4A7C15ull ^ (x >> 7); };
  std::uint64_t sent_sum = 0;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < n; ++i) {
      const Item it{i, mix(i)};
      while (!ring->try_push(it)) std::this_thread::yield();
      sent_sum += it.mix;
    }
  });
  std::uint64_t got_sum = 0, expect = 0;
  bool in_order = true;
  Item it{};
  while (expect < n) {
    if (!ring->try_pop(it)) {
      std::this_thread::yield();
      continue;
    }
    in_order = in_order && it.seq == expect && it.mix == mix(expect);
    got_sum += it.mix;
    ++expect;
  }
  producer.join();
  EXPECT_TRUE(in_order);
  EXPECT_EQ(got_sum, sent_sum);
  EXPECT_TRUE(ring->empty());
}

}  // namespace
}  // namespace lcnc::rt
