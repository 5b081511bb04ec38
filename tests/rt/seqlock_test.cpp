#include "rt/seqlock.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <thread>
#include <type_traits>

#include "support/test_scale.h"

namespace lcnc::rt {
namespace {

// Every field of a published block derives from one counter, so a torn copy
// (half old, half new) is detectable.
struct Block {
  std::uint64_t n;
  std::uint64_t twice;
  double third;
  std::uint32_t low;
  char tag[20];
};

Block make(std::uint64_t n) {
  Block b{};
  b.n = n;
  b.twice = 2 * n;
  b.third = static_cast<double>(n) / 3.0;
  b.low = static_cast<std::uint32_t>(n);
  for (int i = 0; i < 19; ++i) b.tag[i] = static_cast<char>('a' + (n + i) % 26);
  return b;
}

bool consistent(const Block& b) {
  Block e = make(b.n);
  return b.twice == e.twice && b.third == e.third && b.low == e.low && std::equal(b.tag, b.tag + 19, e.tag);
}

TEST(Seqlock, ReadsWhatWasWritten) {
  Seqlock<Block> s;
  s.store(make(42));
  Block b{};
  ASSERT_TRUE(s.load(b));
  EXPECT_EQ(b.n, 42u);
  EXPECT_TRUE(consistent(b));
  EXPECT_EQ(s.sequence(), 2u);
}

// A writer stores as fast as it can while a reader copies: no copy is ever
// torn, and the values seen never go backwards. LCNC_TEST_SCALE scales it.
TEST(Seqlock, ConcurrentReadsAreNeverTorn) {
  auto s = std::make_unique<Seqlock<Block>>();
  s->store(make(0));
  const std::uint64_t writes = testing::scaled<std::uint64_t>(2'000'000);
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::uint64_t n = 1; n <= writes; ++n) s->store(make(n));
    done = true;
  });
  std::uint64_t reads = 0, torn = 0, backwards = 0, last = 0;
  while (!done.load()) {
    Block b{};
    if (!s->load(b)) continue;
    ++reads;
    torn += !consistent(b);
    backwards += b.n < last;
    last = b.n;
  }
  writer.join();
  EXPECT_GT(reads, 1000u);
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(backwards, 0u);
}

// A writer preempted between its two sequence stores (simulated: the
// sequence word, the lock's first member, held odd for 30 ms) defeats a
// spinning read; the patient read of the HMI and CLI waits it out, and gives
// up when its patience is shorter than the stall.
TEST(Seqlock, APatientReadWaitsOutAWriterPreemptedMidWrite) {
  static_assert(std::is_standard_layout_v<Seqlock<Block>>);
  Seqlock<Block> s;
  s.store(make(7));
  auto& seq = *reinterpret_cast<std::atomic<std::uint64_t>*>(&s);
  ASSERT_EQ(seq.load(), 2u);
  seq.store(3);  // the write begun
  std::thread writer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    seq.store(4, std::memory_order_release);  // and finished (the data were not changed)
  });
  Block b{};
  EXPECT_FALSE(s.load(b));
  EXPECT_FALSE(s.load_patiently(b, std::chrono::milliseconds(2)));
  EXPECT_TRUE(s.load_patiently(b, std::chrono::milliseconds(5000)));
  writer.join();
  EXPECT_EQ(b.n, 7u);
  EXPECT_TRUE(consistent(b));
}

}  // namespace
}  // namespace lcnc::rt
