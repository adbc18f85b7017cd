// A counting global allocator for allocation tests. Every heap entry point of
// the executable (operator new/delete in all their forms and the C allocator
// malloc/calloc/realloc/aligned_alloc/posix_memalign/free) is replaced by one
// that forwards to glibc and counts while counting is on.
//
// Include this header in exactly ONE translation unit of a test executable (it
// defines the replacements), AFTER every other header (the C library's and
// Eigen's declarations of these functions must come first), and give that
// executable nothing else to test: replacing the allocator is process-wide. Under AddressSanitizer,
// which owns malloc, nothing is replaced and MOSPEC_NO_ALLOC_COUNTING is defined; tests should skip
// then.
#pragma once

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define MOSPEC_NO_ALLOC_COUNTING 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MOSPEC_NO_ALLOC_COUNTING 1
#endif
#endif

namespace mospec::alloc_counter {
inline std::atomic<bool> counting{false};
inline std::atomic<long> allocations{0};
inline void note() {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
}
// The number of allocations made while f runs.
template <typename F>
long during(F&& f) {
  allocations = 0;
  counting = true;
  f();
  counting = false;
  return allocations.load();
}
}  // namespace mospec::alloc_counter

#ifndef MOSPEC_NO_ALLOC_COUNTING
extern "C" {
// glibc's own entry points, so the replacements can forward to them.
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t n) {
  mospec::alloc_counter::note();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  mospec::alloc_counter::note();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  mospec::alloc_counter::note();
  return __libc_realloc(p, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n) {
  mospec::alloc_counter::note();
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t n) {
  mospec::alloc_counter::note();
  *out = __libc_memalign(alignment, n);
  return *out != nullptr ? 0 : ENOMEM;
}
void free(void* p) {
  __libc_free(p);
}
}

void* operator new(std::size_t n) {
  mospec::alloc_counter::note();
  if (void* p = __libc_malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  return operator new(n);
}
void* operator new(std::size_t n, std::align_val_t a) {
  mospec::alloc_counter::note();
  if (void* p = __libc_memalign(static_cast<std::size_t>(a), n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return operator new(n, a);
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
void operator delete(void* p, std::align_val_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  __libc_free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  __libc_free(p);
}
#endif
