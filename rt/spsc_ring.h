// Lock-free single-producer single-consumer ring of fixed capacity (after
// rigtorp/SPSCQueue). No pointers inside, so it can live in shared memory;
// trivially copyable items only.
//
// Indices are free-running 64-bit counters (never wrap in practice: 2^64
// periods of 75 µs is 44 million years); slot = counter & (Capacity − 1).
// Invariants: 0 ≤ tail − head ≤ Capacity (checked by the consumer: see
// try_pop); only the producer writes tail_, only the consumer writes head_. Each side keeps a cached copy of the other
// side's index to avoid touching its cache line on every call.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>

namespace lcnc::rt {

inline constexpr std::size_t kCacheLine = 64;

template <typename T, std::size_t Capacity>
class SpscRing {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");
  static_assert(std::is_trivially_copyable_v<T>, "items are copied as bytes");
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);

 public:
  static constexpr std::size_t kCapacity = Capacity;

  // Producer side. False when full: the caller decides to wait or drop;
  // it never spins here.
  [[nodiscard]] bool try_push(const T& item) noexcept {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);  // own index
    if (tail - head_cache_ == Capacity) {
      // acquire pairs with the consumer's release store of head_: the slot we
      // are about to overwrite has been read completely.
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail - head_cache_ == Capacity) return false;
    }
    slots_[tail & kMask] = item;
    // release pairs with the consumer's acquire load of tail_: the item is
    // visible before the index that publishes it.
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer side. False when empty.
  //
  // A ring in shared memory can be written by any process that maps it, so
  // the indices are not trusted: a distance the producer cannot make
  // (tail − head > Capacity, which includes tail behind head) is a corrupt
  // ring. The consumer then drops what is in it (head ← tail), counts a
  // resync, and says empty — it never hands out more than the ring holds
  // nor spins on it.
  [[nodiscard]] bool try_pop(T& out) noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);  // own index
    if (head == tail_cache_ || tail_cache_ - head > Capacity) {
      // acquire pairs with the producer's release store of tail_.
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head == tail_cache_) return false;
      if (tail_cache_ - head > Capacity) {
        ++resyncs_;
        head_.store(tail_cache_, std::memory_order_release);
        return false;
      }
    }
    out = slots_[head & kMask];
    // release pairs with the producer's acquire load of head_: our read of the
    // slot happens before the producer may reuse it.
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side: the item try_pop would take next, left in the ring (valid
  // until the next try_pop); nullptr when there is none, or the indices are
  // corrupt (try_pop then resyncs).
  [[nodiscard]] const T* front() noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);  // own index
    if (head == tail_cache_ || tail_cache_ - head > Capacity) {
      // acquire pairs with the producer's release store of tail_.
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head == tail_cache_ || tail_cache_ - head > Capacity) return nullptr;
    }
    return &slots_[head & kMask];
  }

  // Items in the ring as seen from any thread (a snapshot; exact only from
  // the producer or consumer when the other side is idle).
  [[nodiscard]] std::size_t size() const noexcept {
    // acquire: pairs with both release stores; a snapshot, may be stale.
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    const std::uint64_t tail = tail_.load(std::memory_order_acquire);
    // A third thread may see head and tail from different moments: never
    // more than the ring holds.
    return tail >= head ? static_cast<std::size_t>(std::min<std::uint64_t>(tail - head, Capacity)) : 0;
  }
  [[nodiscard]] bool empty() const noexcept { return size() == 0; }
  // Consumer side: how many times try_pop found the indices corrupt.
  [[nodiscard]] std::uint64_t resyncs() const noexcept { return resyncs_; }

 private:
  static constexpr std::uint64_t kMask = Capacity - 1;

  // Consumer's line: its index and its cache of the producer's.
  alignas(kCacheLine) std::atomic<std::uint64_t> head_{0};
  std::uint64_t tail_cache_ = 0;
  std::uint64_t resyncs_ = 0;
  // Producer's line.
  alignas(kCacheLine) std::atomic<std::uint64_t> tail_{0};
  std::uint64_t head_cache_ = 0;
  alignas(kCacheLine) T slots_[Capacity];
};

}  // namespace lcnc::rt
