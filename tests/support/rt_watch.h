// Watching a thread for the RT rules: the allocations and
// the locks a thread takes while it has set t_count_allocations are counted,
// so a test can prove that the RT loop (or an RT-path call) takes none.
//
// Defines the replaceable operator new/delete and interposes the pthread
// lock entry points: include it in exactly one source file of a test
// executable.
#pragma once

#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

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
// Locks taken by a watched thread are counted the same way: these wrappers
// interpose the pthread lock entry points (std::mutex, condition variables,
// stdio's locks and spdlog all go through them) and forward to libc's.
namespace {
std::atomic<std::uint64_t> g_locks{0};
template <typename Fn>
Fn next_symbol(const char* name) {
  return reinterpret_cast<Fn>(dlsym(RTLD_NEXT, name));
}
}  // namespace
extern "C" int pthread_mutex_lock(pthread_mutex_t* m) {
  static const auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_lock");
  if (t_count_allocations) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real(m);
}
extern "C" int pthread_mutex_trylock(pthread_mutex_t* m) {
  static const auto real = next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_trylock");
  if (t_count_allocations) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real(m);
}
extern "C" int pthread_rwlock_rdlock(pthread_rwlock_t* l) {
  static const auto real = next_symbol<int (*)(pthread_rwlock_t*)>("pthread_rwlock_rdlock");
  if (t_count_allocations) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real(l);
}
extern "C" int pthread_rwlock_wrlock(pthread_rwlock_t* l) {
  static const auto real = next_symbol<int (*)(pthread_rwlock_t*)>("pthread_rwlock_wrlock");
  if (t_count_allocations) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real(l);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
