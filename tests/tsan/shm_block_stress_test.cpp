// The kernel ↔ HMI block of rt/shm_interface.h, constructed in a shared
// mapping and used from real threads the way the daemon and the HMIs use it:
//   kernel  publishes Status through the seqlock every iteration, bumps the
//           heartbeat, takes commands, answers each with an event (never
//           waits: a full event ring drops the event and counts it)
//   HMI     sends commands with a running seq, reads the events
//   viewers two more threads read Status and check it is never torn
// Under TSan; every item is checked for order and content.
#include "rt/shm_interface.h"

#include <gtest/gtest.h>

#include <sys/mman.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <thread>
#include <vector>

#include "stress_scale.h"

namespace lcnc::shm {
namespace {

using rt::tsan::mix;
using rt::tsan::scaled;

Status make_status(std::uint64_t n) {
  Status s;
  s.periods = n;
  s.line = static_cast<std::uint32_t>(n / 7);
  for (int i = 0; i < 6; ++i) {
    s.pos_steps[i] = static_cast<std::int64_t>(mix(n * 8 + i) >> 20);
    s.pos[i] = static_cast<double>(s.pos_steps[i]) * 1e-3;
  }
  s.machine_time_s = static_cast<double>(n) * 75e-6;
  s.power_pct = static_cast<float>(n % 101);
  return s;
}

bool consistent(const Status& s) {
  const Status e = make_status(s.periods);
  return s.line == e.line && s.pos_steps == e.pos_steps && s.pos == e.pos &&
         s.machine_time_s == e.machine_time_s && s.power_pct == e.power_pct;
}

Command make_command(std::uint32_t seq) {
  Command c;
  c.type = CommandType::Override;
  c.seq = seq;
  c.value = static_cast<double>(mix(seq) % 1500) * 1e-3;
  std::snprintf(c.text, sizeof c.text, "command %u", seq);
  return c;
}

bool matches(const Command& c, std::uint32_t seq) {
  const Command e = make_command(seq);
  return c.type == e.type && c.seq == seq && c.value == e.value && std::strcmp(c.text, e.text) == 0;
}

TEST(ShmBlockStress, KernelHmiAndViewersShareTheBlock) {
  void* mem = mmap(nullptr, sizeof(ShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(mem, MAP_FAILED);
  ShmBlock* block = new (mem) ShmBlock();

  const std::uint64_t iterations = scaled(std::uint64_t{100'000});
  const std::uint32_t commands = static_cast<std::uint32_t>(scaled(std::uint64_t{20'000}));
  std::atomic<bool> kernel_done{false};

  // kernel
  std::uint64_t kernel_bad_commands = 0, events_dropped = 0, events_sent = 0;
  std::uint32_t commands_taken = 0;
  std::thread kernel([&] {
    for (std::uint64_t n = 1; n <= iterations || commands_taken < commands; ++n) {
      block->status.store(make_status(n));
      block->header.heartbeat.fetch_add(1, std::memory_order_relaxed);
      Command c;
      if (block->commands.try_pop(c)) {
        kernel_bad_commands += !matches(c, commands_taken);
        ++commands_taken;
        Event e;
        e.period = n;
        e.command_seq = c.seq;
        e.line = static_cast<std::uint32_t>(mix(c.seq));
        std::snprintf(e.text, sizeof e.text, "ack %u", c.seq);
        if (block->events.try_push(e)) {
          ++events_sent;
        } else {
          ++events_dropped;
        }
      }
    }
    // release pairs with the HMI's acquire load: it drains the events after.
    kernel_done.store(true, std::memory_order_release);
  });

  // HMI
  std::uint64_t events_received = 0, hmi_bad_events = 0;
  std::thread hmi([&] {
    std::uint32_t sent = 0;
    std::uint64_t last_period = 0;
    std::int64_t last_seq = -1;
    auto drain = [&] {
      Event e;
      while (block->events.try_pop(e)) {
        char text[sizeof e.text];
        std::snprintf(text, sizeof text, "ack %u", e.command_seq);
        const bool ok = e.period > last_period && static_cast<std::int64_t>(e.command_seq) > last_seq &&
                        e.line == static_cast<std::uint32_t>(mix(e.command_seq)) &&
                        std::strcmp(e.text, text) == 0;
        hmi_bad_events += !ok;
        last_period = e.period;
        last_seq = e.command_seq;
        ++events_received;
      }
    };
    while (sent < commands) {
      if (block->commands.try_push(make_command(sent))) {
        ++sent;
      } else {
        std::this_thread::yield();
      }
      drain();
    }
    while (!kernel_done.load(std::memory_order_acquire)) {
      drain();
      std::this_thread::yield();
    }
    drain();
  });

  // viewers
  std::vector<std::uint64_t> viewer_reads(2), viewer_torn(2), viewer_backwards(2), viewer_stale_beat(2);
  std::vector<std::thread> viewers;
  for (std::size_t v = 0; v < 2; ++v) {
    viewers.emplace_back([&, v] {
      std::uint64_t last = 0;
      while (!kernel_done.load(std::memory_order_acquire)) {
        Status s;
        if (!block->status.load(s)) continue;
        ++viewer_reads[v];
        viewer_torn[v] += !consistent(s);
        viewer_backwards[v] += s.periods < last;
        last = s.periods;
        // The kernel bumped the heartbeat for every earlier status before
        // storing this one: the seqlock's release/acquire carries that too.
        viewer_stale_beat[v] += block->header.heartbeat.load(std::memory_order_relaxed) + 1 < s.periods;
      }
    });
  }

  kernel.join();
  hmi.join();
  for (auto& t : viewers) t.join();

  EXPECT_EQ(commands_taken, commands);
  EXPECT_EQ(kernel_bad_commands, 0u);
  EXPECT_EQ(events_received, events_sent);
  EXPECT_EQ(events_sent + events_dropped, commands);
  EXPECT_EQ(hmi_bad_events, 0u);
  EXPECT_GE(block->header.heartbeat.load(), iterations);
  for (std::size_t v = 0; v < 2; ++v) {
    EXPECT_GT(viewer_reads[v], 0u);
    EXPECT_EQ(viewer_torn[v], 0u);
    EXPECT_EQ(viewer_backwards[v], 0u);
    EXPECT_EQ(viewer_stale_beat[v], 0u);
  }
  block->~ShmBlock();
  munmap(mem, sizeof(ShmBlock));
}

}  // namespace
}  // namespace lcnc::shm
