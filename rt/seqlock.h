// A single-writer seqlock for a trivially copyable block (the kernel's status
// in shared memory): the writer never waits, readers retry while a write is
// in progress. No pointers: it can live in shared memory.
//
//   writer: seq ← seq+1 (odd)  │ data ← new │ seq ← seq+1 (even)
//   reader: s0 ← seq (even?)   │ copy data  │ s1 ← seq; retry unless s0 == s1
//
// The copy of a block being written may be torn; the sequence check throws
// such a copy away. Bytes are copied through relaxed atomic loads and stores
// so that the race on the data itself is no data race (C++ memory model).
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <thread>
#include <type_traits>

namespace lcnc::rt {

template <typename T>
class Seqlock {
  static_assert(std::is_trivially_copyable_v<T>);
  static constexpr std::size_t kWords = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);

 public:
  // Writer (one thread only): publishes `value`. Never blocks.
  void store(const T& value) noexcept {
    std::uint64_t words[kWords] = {};
    std::memcpy(words, &value, sizeof(T));
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    // release fence: the odd sequence is visible before any data word
    // (pairs with the reader's acquire fence after its data loads).
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i) data_[i].store(words[i], std::memory_order_relaxed);
    // release: the data words are visible before the even sequence (pairs
    // with the reader's acquire load of seq_ at the start of its read).
    seq_.store(s + 2, std::memory_order_release);
  }

  // Reader (any thread or process): a consistent copy; false if `tries`
  // attempts all met a write in progress (the caller shows stale data).
  [[nodiscard]] bool load(T& out, int tries = 1000) const noexcept {
    std::uint64_t words[kWords];
    for (int t = 0; t < tries; ++t) {
      // acquire: pairs with the writer's final release store.
      const std::uint64_t s0 = seq_.load(std::memory_order_acquire);
      if (s0 & 1u) continue;
      for (std::size_t i = 0; i < kWords; ++i) words[i] = data_[i].load(std::memory_order_relaxed);
      // acquire fence: the data loads happen before the second sequence load
      // (pairs with the writer's release fence).
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s0) {
        std::memcpy(&out, words, sizeof(T));
        return true;
      }
    }
    return false;
  }

  // Reader outside the RT path (HMI, CLI): a writer preempted in the middle
  // of its store holds the sequence odd for as long as it is off the CPU, so
  // spinning alone can fail on a loaded machine. This one spins, then yields
  // the CPU (a syscall: never in the RT loop) until `patience` has passed.
  [[nodiscard]] bool load_patiently(T& out, std::chrono::milliseconds patience) const {
    const auto until = std::chrono::steady_clock::now() + patience;
    for (;;) {
      if (load(out, 64)) return true;
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::yield();
    }
  }

  [[nodiscard]] std::uint64_t sequence() const noexcept { return seq_.load(std::memory_order_acquire); }

 private:
  std::atomic<std::uint64_t> seq_{0};
  std::atomic<std::uint64_t> data_[kWords]{};
};

}  // namespace lcnc::rt
