// The control tick through the simulator allocates nothing: read, the
// controllers, write and step (MuJoCo included) run 2000 ticks with every heap
// entry point of this executable counting. Own executable, because it replaces
// operator new/delete and glibc's malloc family; skipped under AddressSanitizer.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "sim_test_util.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define MOSPEC_SIM_NO_COUNTING 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MOSPEC_SIM_NO_COUNTING 1
#endif
#endif

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
[[maybe_unused]] void count() {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
}
}  // namespace

#ifndef MOSPEC_SIM_NO_COUNTING
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
void free(void* p) {
  __libc_free(p);
}
}
void* operator new(std::size_t n) {
  count();
  if (void* p = __libc_malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  return operator new(n);
}
void operator delete(void* p) noexcept {
  __libc_free(p);
}
void operator delete[](void* p) noexcept {
  __libc_free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  __libc_free(p);
}
#endif

namespace mospec::sim {
namespace {

TEST(Allocation, TheControlTickAllocatesNothing) {
#ifdef MOSPEC_SIM_NO_COUNTING
  GTEST_SKIP() << "AddressSanitizer owns the allocator";
#endif
  NEED_GEN3();
  for (BaseFidelity b : {BaseFidelity::Wheeled, BaseFidelity::Planar}) {
    WorldConfig c = default_world();
    c.base = b;
    c.mount.active = b == BaseFidelity::Planar;
    World w(c, arm_chain);
    w.faults().inject_nan("right_arm.q[2]", 100, 10);
    w.faults().inject_stale("pivot_q[1]", 200, 10);
    w.faults().drop_commands(300, 5);
    GravityCompensation arms(arm_chain, testing::mounts(c));
    arms.f_E_P = {runtime::Vec3(10, 0, 0), runtime::Vec3(10, 0, 0)};
    PlatformWrenchController drives(c.drives);
    drives.F_p = runtime::Vec3(20, 0, 0.5);
    robot::MeasuredState s;
    robot::Command cmd;
    counting = true;
    for (int k = 0; k < 2000; ++k) {
      w.read(s);
      arms.compute(s, cmd);
      drives.compute(s, cmd);
      w.write(cmd);
      w.step();
      (void)w.contact(k % 2);
      (void)w.ground_wrench_P();
    }
    counting = false;
    EXPECT_EQ(allocations.load(), 0) << to_string(b);
    allocations = 0;
  }
  // The counter itself works (both C++ and C heaps).
  counting = true;
  delete new int(1);
  std::free(std::malloc(8));
  counting = false;
  EXPECT_EQ(allocations.load(), 2);
}

}  // namespace
}  // namespace mospec::sim
