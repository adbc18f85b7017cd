// A lock for critical sections of a few hundred nanoseconds that two threads
// enter often (the shared context cache of a load): spinning a little is far
// cheaper there than std::mutex putting the waiter to sleep and waking it with
// two system calls. After a short spin it yields, so a holder that was
// preempted still gets the core back.
#pragma once

#include <atomic>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace mospec {

class SpinLock {
 public:
  void lock() noexcept {
    for (int spins = 0; locked_.exchange(true, std::memory_order_acquire); ++spins) {
      // Wait on a plain load, so the waiter does not take the line away from
      // the holder with writes.
      while (locked_.load(std::memory_order_relaxed)) {
        if (spins++ < kSpinsBeforeYield) {
          pause();
        } else {
          std::this_thread::yield();
        }
      }
    }
  }
  bool try_lock() noexcept {
    return !locked_.load(std::memory_order_relaxed) &&
           !locked_.exchange(true, std::memory_order_acquire);
  }
  void unlock() noexcept { locked_.store(false, std::memory_order_release); }

 private:
  static constexpr int kSpinsBeforeYield = 4096;
  static void pause() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
  }
  std::atomic<bool> locked_{false};
};

}  // namespace mospec
