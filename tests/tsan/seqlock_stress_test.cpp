// rt::Seqlock under ThreadSanitizer: one writer publishes a multi-field block
// as fast as it can while several readers copy it; every field derives from
// one counter, so a torn copy (fields from two writes) is detected, and each
// reader checks that what it sees never goes backwards.
//
// What TSan can and cannot say here: the data words are relaxed atomics, so
// the data itself never races in the C++ sense; the guarantee that matters —
// no torn copy is ever returned — rests on the release/acquire fence pair,
// which gcc's TSan does not model. So the outcome is checked directly, with
// the writer and readers on real threads, and TSan watches everything around
// it (the caller's copies, the block in shared memory in shm_block_stress_test).
#include "rt/seqlock.h"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <memory>
#include <thread>
#include <vector>

#include "stress_scale.h"

namespace lcnc::rt {
namespace {

using tsan::mix;
using tsan::scaled;

// Shaped like the kernel's status (rt/shm_interface.h): 17 words, the last
// one partly padding.
struct Block {
  std::uint64_t n = 0;
  std::array<std::int64_t, 6> pos_steps{};
  std::array<double, 6> pos{};
  double machine_time_s = 0.0;
  std::uint32_t line = 0;
  float power_pct = 0.0f;
  char tag[13] = {};
};
static_assert(sizeof(Block) == 17 * sizeof(std::uint64_t));

Block make(std::uint64_t n) {
  Block b;
  b.n = n;
  for (int i = 0; i < 6; ++i) {
    b.pos_steps[i] = static_cast<std::int64_t>(mix(n * 16 + i));
    b.pos[i] = static_cast<double>(b.pos_steps[i] % 1'000'000) * 1e-3;
  }
  b.machine_time_s = static_cast<double>(n) * 75e-6;
  b.line = static_cast<std::uint32_t>(mix(n));
  b.power_pct = static_cast<float>(n % 101);
  for (int i = 0; i < 12; ++i) b.tag[i] = static_cast<char>('a' + (n + i) % 26);
  return b;
}

bool consistent(const Block& b) {
  const Block e = make(b.n);
  return b.pos_steps == e.pos_steps && b.pos == e.pos && b.machine_time_s == e.machine_time_s &&
         b.line == e.line && b.power_pct == e.power_pct && std::memcmp(b.tag, e.tag, 13) == 0;
}

struct ReaderOutcome {
  std::uint64_t reads = 0;      // consistent copies returned
  std::uint64_t gave_up = 0;    // load() met writes on every try (allowed: stale data)
  std::uint64_t torn = 0;       // a copy mixing two writes: must never happen
  std::uint64_t backwards = 0;  // an older block after a newer one: must never happen
};

// One writer, `readers` readers; `tries` per load (1: nearly every load
// during a write gives up, the retry loop is the caller's).
void run(Seqlock<Block>& lock, int readers, int tries, std::uint64_t writes) {
  lock.store(make(0));
  std::atomic<bool> done{false};
  std::vector<ReaderOutcome> outcomes(static_cast<std::size_t>(readers));
  std::vector<std::thread> threads;
  for (int r = 0; r < readers; ++r) {
    threads.emplace_back([&, r] {
      ReaderOutcome& o = outcomes[static_cast<std::size_t>(r)];
      std::uint64_t last = 0;
      // acquire pairs with the writer's release store of done: the final
      // load below then sees the last write.
      for (bool finishing = false; !finishing;) {
        finishing = done.load(std::memory_order_acquire);
        Block b;
        if (!lock.load(b, tries)) {
          ++o.gave_up;
          continue;
        }
        ++o.reads;
        o.torn += !consistent(b);
        o.backwards += b.n < last;
        last = b.n;
      }
    });
  }
  std::thread writer([&] {
    for (std::uint64_t n = 1; n <= writes; ++n) lock.store(make(n));
    done.store(true, std::memory_order_release);
  });
  writer.join();
  for (auto& t : threads) t.join();

  for (const ReaderOutcome& o : outcomes) {
    EXPECT_GT(o.reads, 0u);
    EXPECT_EQ(o.torn, 0u);
    EXPECT_EQ(o.backwards, 0u);
  }
  Block last;
  ASSERT_TRUE(lock.load(last));
  EXPECT_EQ(last.n, writes);
  EXPECT_EQ(lock.sequence(), 2 * (writes + 1));
}

TEST(SeqlockStress, ThreeReadersNeverSeeATornBlock) {
  auto lock = std::make_unique<Seqlock<Block>>();
  run(*lock, 3, 1000, scaled(std::uint64_t{1'000'000}));
}

// tries = 1: a load that meets a write returns false at once, so the
// readers' copies overlap writes as often as possible.
TEST(SeqlockStress, SingleTryReadersNeverSeeATornBlock) {
  auto lock = std::make_unique<Seqlock<Block>>();
  run(*lock, 2, 1, scaled(std::uint64_t{500'000}));
}

}  // namespace
}  // namespace lcnc::rt
