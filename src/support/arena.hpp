// A monotonic arena: what std::pmr::monotonic_buffer_resource does, with the
// bump inline in do_allocate. The loader's parsed and expanded trees, toRdf's
// node map and lowering's tables make tens of thousands of small allocations
// per load; libstdc++'s monotonic resource spends about 45 instructions on
// each (an out-of-line call and its general alignment and growth paths), this
// one about a dozen when the current block has room.
//
// The first block may be a caller's buffer (borrowed, never freed), so that
// an arena made and dropped per document can reuse one buffer instead of
// asking the heap for a fresh block each time.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory_resource>
#include <new>

namespace mospec {

class Arena final : public std::pmr::memory_resource {
 public:
  // The first block is allocated on first use, `first_block` bytes; each
  // later one is twice the one before (or as large as the request).
  explicit Arena(std::size_t first_block = 4096,
                 std::pmr::memory_resource* upstream = std::pmr::new_delete_resource())
      : next_size_(std::max<std::size_t>(first_block, 64)), upstream_(upstream) {}
  // Allocates from `buffer` (size bytes, borrowed) first.
  Arena(void* buffer, std::size_t size,
        std::pmr::memory_resource* upstream = std::pmr::new_delete_resource())
      : cur_(reinterpret_cast<std::uintptr_t>(buffer)),
        end_(reinterpret_cast<std::uintptr_t>(buffer) + size),
        next_size_(std::max<std::size_t>(size, 64)),
        upstream_(upstream) {}
  ~Arena() override { release(); }
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;

  // Frees every block this arena allocated (not a borrowed first buffer,
  // which is no longer used either).
  void release() noexcept {
    while (blocks_ != nullptr) {
      Block* next = blocks_->next;
      upstream_->deallocate(blocks_, blocks_->size, alignof(std::max_align_t));
      blocks_ = next;
    }
    cur_ = end_ = 0;
  }

  // Bytes of the blocks allocated from upstream so far.
  std::size_t allocated_bytes() const noexcept {
    std::size_t n = 0;
    for (const Block* b = blocks_; b != nullptr; b = b->next) n += b->size;
    return n;
  }

 private:
  struct Block {
    Block* next;
    std::size_t size;
  };

  void* do_allocate(std::size_t bytes, std::size_t alignment) override {
    const std::uintptr_t p = (cur_ + alignment - 1) & ~(std::uintptr_t{alignment} - 1);
    if (p != 0 && p >= cur_ && p <= end_ && bytes <= end_ - p) {
      cur_ = p + bytes;
      return reinterpret_cast<void*>(p);
    }
    return grow(bytes, alignment);
  }
  void do_deallocate(void*, std::size_t, std::size_t) override {}
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override {
    return this == &other;
  }

  void* grow(std::size_t bytes, std::size_t alignment) {
    const std::size_t header = (sizeof(Block) + alignment - 1) & ~(alignment - 1);
    if (bytes > SIZE_MAX / 4 - header - alignment) throw std::bad_alloc();
    std::size_t size = std::max(next_size_, header + bytes);
    next_size_ = size <= SIZE_MAX / 4 ? size * 2 : size;
    // Blocks are aligned for max_align_t; a stricter request gets the slack.
    if (alignment > alignof(std::max_align_t)) size += alignment;
    void* raw = upstream_->allocate(size, alignof(std::max_align_t));
    auto* block = new (raw) Block{blocks_, size};
    blocks_ = block;
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(raw) + sizeof(Block);
    const std::uintptr_t p = (start + alignment - 1) & ~(std::uintptr_t{alignment} - 1);
    cur_ = p + bytes;
    end_ = reinterpret_cast<std::uintptr_t>(raw) + size;
    return reinterpret_cast<void*>(p);
  }

  std::uintptr_t cur_ = 0, end_ = 0;
  std::size_t next_size_;
  Block* blocks_ = nullptr;
  std::pmr::memory_resource* upstream_;
};

}  // namespace mospec
