// rt::SpscRing under ThreadSanitizer: a producer and a consumer thread move
// millions of items through small rings (full and empty all the time), every
// item checked for order and content; the same on a ring constructed in a
// byte buffer — an anonymous shared mapping, and one memfd mapped at two
// addresses, the producer using one and the consumer the other, as two
// processes would see a segment of shared memory.
//
// TSan checks the slots (plain memory) against the head_/tail_ acquire/
// release pairs. Across the two aliases of the memfd it sees two unrelated
// objects, so that test checks the pointer-free layout, not the orderings.
// Worker threads record what they saw in plain variables; the gtest
// assertions run on the main thread after join() (gtest itself is not
// instrumented).
#include "rt/spsc_ring.h"

#include <gtest/gtest.h>

#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <thread>

#include "stress_scale.h"

namespace lcnc::rt {
namespace {

using tsan::mix;
using tsan::scaled;

// 48 bytes: six words, each derived from the sequence number.
struct Item {
  std::uint64_t seq = 0;
  std::array<std::uint64_t, 5> words{};
};

Item make_item(std::uint64_t seq) {
  Item it;
  it.seq = seq;
  for (std::size_t i = 0; i < it.words.size(); ++i) it.words[i] = mix(seq * 8 + i);
  return it;
}

bool matches(const Item& it, std::uint64_t seq) {
  if (it.seq != seq) return false;
  for (std::size_t i = 0; i < it.words.size(); ++i)
    if (it.words[i] != mix(seq * 8 + i)) return false;
  return true;
}

struct Outcome {
  std::uint64_t received = 0;
  std::uint64_t out_of_order = 0;     // wrong sequence number
  std::uint64_t corrupt = 0;          // right number, wrong content
  std::uint64_t full = 0, empty = 0;  // how often each side found the ring so
  bool empty_at_end = false;
  int full_pause = 0;  // the consumer's pause is done
};

// Producer pushes n items through `in`, the consumer pops them from `out`
// (the same ring, or an alias of it). Neither side spins on the ring: a
// refused push or pop yields, as the planner and the RT thread do. Each side
// pauses once (the producer at n/4, the consumer at n/2), so that the other
// certainly finds the ring empty, then full, whatever the scheduling.
template <typename Ring>
Outcome run_pair(Ring& in, Ring& out, std::uint64_t n) {
  Outcome o;
  std::uint64_t full = 0;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < n; ++i) {
      if (i == n / 4) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      const Item it = make_item(i);
      while (!in.try_push(it)) {
        ++full;
        std::this_thread::yield();
      }
    }
  });
  std::thread consumer([&] {
    Item it;
    while (o.received < n) {
      if (o.received == n / 2 && o.full_pause == 0) {
        o.full_pause = 1;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      if (!out.try_pop(it)) {
        ++o.empty;
        std::this_thread::yield();
        continue;
      }
      if (it.seq != o.received) {
        ++o.out_of_order;
      } else if (!matches(it, o.received)) {
        ++o.corrupt;
      }
      ++o.received;
    }
    o.empty_at_end = !out.try_pop(it);
  });
  producer.join();
  consumer.join();
  o.full = full;
  return o;
}

void expect_clean(const Outcome& o, std::uint64_t n) {
  EXPECT_EQ(o.received, n);
  EXPECT_EQ(o.out_of_order, 0u);
  EXPECT_EQ(o.corrupt, 0u);
  EXPECT_TRUE(o.empty_at_end);
  // Both edges were exercised (a ring that never fills tests half the code).
  EXPECT_GT(o.full, 0u);
  EXPECT_GT(o.empty, 0u);
}

// A page-aligned MAP_SHARED mapping, as shm_open + mmap gives.
class SharedMapping {
 public:
  explicit SharedMapping(std::size_t size) : size_(size) {
    void* p = mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    addr_ = p == MAP_FAILED ? nullptr : p;
  }
  ~SharedMapping() {
    if (addr_ != nullptr) munmap(addr_, size_);
  }
  SharedMapping(const SharedMapping&) = delete;
  SharedMapping& operator=(const SharedMapping&) = delete;
  [[nodiscard]] void* addr() const { return addr_; }

 private:
  std::size_t size_;
  void* addr_ = nullptr;
};

TEST(SpscRingStress, MillionsOfItemsArriveInOrderAndIntact) {
  using Ring = SpscRing<Item, 64>;
  auto ring = std::make_unique<Ring>();
  const std::uint64_t n = scaled(std::uint64_t{2'000'000});
  expect_clean(run_pair(*ring, *ring, n), n);
}

// Capacity 2, the smallest: every push and pop meets a full or empty ring,
// and slot reuse happens every other item.
TEST(SpscRingStress, SmallestRingStaysInOrder) {
  using Ring = SpscRing<Item, 2>;
  auto ring = std::make_unique<Ring>();
  const std::uint64_t n = scaled(std::uint64_t{500'000});
  expect_clean(run_pair(*ring, *ring, n), n);
}

// The ring constructed in place in a byte buffer: a shared mapping, as the
// kernel ↔ HMI segment (rt/shm_interface.h) holds its rings.
TEST(SpscRingStress, RingInASharedByteBufferStaysInOrder) {
  using Ring = SpscRing<Item, 256>;
  static_assert(alignof(Ring) <= 4096, "a page-aligned buffer aligns the ring");
  SharedMapping map(sizeof(Ring));
  ASSERT_NE(map.addr(), nullptr);
  Ring* ring = new (map.addr()) Ring();
  const std::uint64_t n = scaled(std::uint64_t{2'000'000});
  expect_clean(run_pair(*ring, *ring, n), n);
  ring->~Ring();
}

// One memfd mapped twice: the producer pushes through one address, the
// consumer pops through the other. Works only because the ring holds
// indices, never pointers (the shared-memory requirement).
TEST(SpscRingStress, RingSeenThroughTwoMappingsStaysInOrder) {
  using Ring = SpscRing<Item, 256>;
  const int fd = memfd_create("lcnc_tsan_spsc", MFD_CLOEXEC);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(ftruncate(fd, sizeof(Ring)), 0);
  void* a = mmap(nullptr, sizeof(Ring), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  void* b = mmap(nullptr, sizeof(Ring), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  ASSERT_NE(a, MAP_FAILED);
  ASSERT_NE(b, MAP_FAILED);
  ASSERT_NE(a, b);
  Ring* producer_view = new (a) Ring();
  Ring* consumer_view = std::launder(static_cast<Ring*>(b));
  const std::uint64_t n = scaled(std::uint64_t{1'000'000});
  expect_clean(run_pair(*producer_view, *consumer_view, n), n);
  munmap(a, sizeof(Ring));
  munmap(b, sizeof(Ring));
}

}  // namespace
}  // namespace lcnc::rt
