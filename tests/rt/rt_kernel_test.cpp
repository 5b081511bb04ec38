#include "rt/rt_kernel.h"

#include <gtest/gtest.h>

#include <linux/filter.h>
#include <linux/seccomp.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <ucontext.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <random>
#include <thread>

#include "drivers/sim_machine.h"

// The replacement operators below pair malloc with free on purpose; gcc
// cannot see that when it inlines them.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

// Allocations made by a thread that set t_count_allocations are counted, so a
// test can prove that the RT thread's loop allocated nothing.
namespace {
std::atomic<std::uint64_t> g_allocations{0};
thread_local bool t_count_allocations = false;
void count_allocation() {
  if (t_count_allocations) g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace
void* operator new(std::size_t n) {
  count_allocation();
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  count_allocation();
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace lcnc::rt {
namespace {

MachineConfig machine() {
  MachineConfig m;
  m.period_ns = 75'000;
  m.dda = DdaConfig{8, 300};
  for (int i = 0; i < 3; ++i) {
    m.axes[i].present = true;
    m.axes[i].axis = static_cast<Axis>(i);
    m.axes[i].max = 1000;
    m.axes[i].max_velocity = 500;
    m.axes[i].max_acceleration = 5000;
  }
  return m;
}

struct Rig {
  MachineConfig m = machine();
  std::unique_ptr<PositionBuffer> buffer = std::make_unique<PositionBuffer>();
  std::unique_ptr<TraceRing> trace = std::make_unique<TraceRing>();
  std::array<std::int64_t, kAxisCount> start{};
  drivers::SimMachine sim{start};
  RtKernel kernel{m, *buffer, sim, trace.get(), start};
};

// Fills the buffer with random increments; returns their per-axis sum.
std::array<std::int64_t, kAxisCount> fill(PositionBuffer& buf, std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::array<std::int64_t, kAxisCount> sum{};
  for (std::size_t k = 0; k < n; ++k) {
    PeriodIncrement inc;
    for (int a = 0; a < 3; ++a) {
      inc.steps[a] = static_cast<std::int32_t>(rng() % 101) - 50;
      sum[a] += inc.steps[a];
    }
    inc.segment = static_cast<std::uint32_t>(k);
    inc.end_of_program = k + 1 == n;
    EXPECT_TRUE(buf.try_push(inc));
  }
  return sum;
}

TEST(RtKernel, ExecutesEveryEntryAndSumOfPulsesEqualsCommandedSteps) {
  Rig r;
  const auto sum = fill(*r.buffer, 4000, 1);
  r.kernel.start(RtOptions{false, 0, {}, {}});
  r.kernel.join();
  EXPECT_EQ(r.kernel.motion_periods(), 4000u);
  EXPECT_EQ(r.kernel.underruns(), 0u);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(r.sim.position_steps(a), sum[a]);
    EXPECT_EQ(r.kernel.position_steps(a), sum[a]);
  }
  EXPECT_EQ(r.sim.bad_frames(), 0u);
  EXPECT_EQ(r.kernel.latency().total(), r.kernel.periods());
  // every period left a trace record, in order
  TraceRecord rec;
  std::uint64_t expect = 0;
  while (r.trace->try_pop(rec)) EXPECT_EQ(rec.period, expect++);
  EXPECT_EQ(expect, r.kernel.periods());
}

TEST(RtKernel, EmptyBufferWhileRunningIsAnUnderrunThatHoldsPosition) {
  Rig r;
  PeriodIncrement inc;
  inc.steps[0] = 10;
  ASSERT_TRUE(r.buffer->try_push(inc));
  r.kernel.start(RtOptions{false, 0, {}, {}});
  // let the buffer run dry for a while, then finish the job
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  PeriodIncrement last;
  last.steps[0] = 5;
  last.end_of_program = true;
  while (!r.buffer->try_push(last)) {
  }
  r.kernel.join();
  EXPECT_GT(r.kernel.underruns(), 10u);
  EXPECT_EQ(r.sim.position_steps(0), 15);  // held, no jump, nothing lost
  TraceRecord rec;
  std::int64_t prev = 0;
  while (r.trace->try_pop(rec)) {
    if (rec.underrun) {
      EXPECT_EQ(rec.pos_steps[0], prev);  // position held
    }
    prev = rec.pos_steps[0];
  }
}

TEST(RtKernel, StopEndsTheLoopWithinAFewPeriods) {
  Rig r;
  r.kernel.start(RtOptions{false, 0, {}, {}});  // empty buffer: holds forever
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  r.kernel.stop();
  r.kernel.join();
  EXPECT_TRUE(r.kernel.finished());
  EXPECT_EQ(r.sim.position_steps(0), 0);
}

// The RT loop allocates nothing: the RT thread's own allocations counted over
// the whole loop, from the enter hook to the exit hook.
TEST(RtKernel, LoopNeverAllocates) {
  Rig r;
  fill(*r.buffer, 3000, 2);
  std::atomic<std::uint64_t> at_enter{0}, at_exit{0};
  RtOptions opt{false, 0,
                [&] {
                  at_enter = g_allocations.load();
                  t_count_allocations = true;
                },
                [&] {
                  t_count_allocations = false;
                  at_exit = g_allocations.load();
                }};
  r.kernel.start(opt);
  r.kernel.join();
  EXPECT_EQ(r.kernel.motion_periods(), 3000u);
  EXPECT_EQ(at_exit.load() - at_enter.load(), 0u);
}

// The counter works: an allocation on a counting thread is seen.
TEST(RtKernel, AllocationCounterSeesAllocations) {
  const std::uint64_t before = g_allocations.load();
  std::thread([] {
    t_count_allocations = true;
    auto p = std::make_unique<int>(7);
    t_count_allocations = false;
    EXPECT_EQ(*p, 7);
  }).join();
  EXPECT_EQ(g_allocations.load() - before, 1u);
}

// The RT loop makes no syscall but its clock sleep: a seccomp filter on the RT
// thread traps every other syscall from the first period to the last, and the
// SIGSYS handler records it. (Not under the sanitizers, whose runtimes make
// syscalls of their own.)
#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
std::atomic<int> g_bad_syscalls{0};
std::atomic<long> g_first_bad_syscall{-1};

void on_sigsys(int, siginfo_t* info, void* ctx) {
  g_bad_syscalls.fetch_add(1);
  long expected = -1;
  g_first_bad_syscall.compare_exchange_strong(expected, info->si_syscall);
  // the trapped syscall did not run; make it return -ENOSYS
  static_cast<ucontext_t*>(ctx)->uc_mcontext.gregs[REG_RAX] = -ENOSYS;
}

void install_syscall_filter() {
  // Allowed: the clock sleep and clock read; the return from the SIGSYS
  // handler itself; then what the thread's own exit
  // needs (after the loop): exit, madvise (stack release), rt_sigprocmask, munmap.
  sock_filter code[] = {
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, nr)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_clock_nanosleep, 7, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_clock_gettime, 6, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_rt_sigreturn, 5, 0),  // leaving the SIGSYS handler
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_exit, 4, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_madvise, 3, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_rt_sigprocmask, 2, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_munmap, 1, 0),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_TRAP),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
  };
  sock_fprog prog{static_cast<unsigned short>(sizeof code / sizeof code[0]), code};
  prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0);
  prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog);
}

TEST(RtKernel, LoopMakesNoSyscallButTheClockSleep) {
  struct sigaction sa {};
  sa.sa_sigaction = on_sigsys;
  sa.sa_flags = SA_SIGINFO;
  ASSERT_EQ(sigaction(SIGSYS, &sa, nullptr), 0);
  Rig r;
  fill(*r.buffer, 3000, 3);
  std::atomic<bool> filtered{false};
  std::atomic<int> bad_at_exit{-1};
  RtOptions opt{false, 0,
                [&] {
                  install_syscall_filter();
                  filtered = true;
                },
                [&] { bad_at_exit = g_bad_syscalls.load(); }};
  r.kernel.start(opt);
  r.kernel.join();
  ASSERT_TRUE(filtered.load());
  EXPECT_EQ(r.kernel.motion_periods(), 3000u);
  EXPECT_EQ(bad_at_exit.load(), 0) << "first forbidden syscall: " << g_first_bad_syscall.load();
  signal(SIGSYS, SIG_DFL);
}
#endif

}  // namespace
}  // namespace lcnc::rt
