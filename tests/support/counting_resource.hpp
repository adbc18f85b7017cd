// A memory resource that counts what reaches it and passes every request on
// to the heap: for tests that check where a container's blocks come from and
// that every block is given back.
#pragma once

#include <cstddef>
#include <memory_resource>

namespace mospec::test {

class CountingResource final : public std::pmr::memory_resource {
 public:
  std::size_t allocations = 0, deallocations = 0, live_bytes = 0;

 private:
  void* do_allocate(std::size_t bytes, std::size_t alignment) override {
    ++allocations;
    live_bytes += bytes;
    return std::pmr::new_delete_resource()->allocate(bytes, alignment);
  }
  void do_deallocate(void* p, std::size_t bytes, std::size_t alignment) override {
    ++deallocations;
    live_bytes -= bytes;
    std::pmr::new_delete_resource()->deallocate(p, bytes, alignment);
  }
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override {
    return this == &other;
  }
};

}  // namespace mospec::test
