// mospec::Arena: allocations are aligned as asked, never overlap, come from
// a borrowed first buffer before the heap, and grow past it.
#include "support/arena.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory_resource>
#include <string>
#include <vector>

#include "counting_resource.hpp"

namespace {

using mospec::test::CountingResource;

TEST(Arena, AlignsEveryAllocationAndNeverOverlaps) {
  CountingResource heap;
  {
    mospec::Arena arena(64, &heap);
    std::vector<std::pair<std::uintptr_t, size_t>> blocks;
    for (size_t i = 0; i < 2000; ++i) {
      const size_t bytes = (i * 37) % 300;
      const size_t alignment = size_t{1} << (i % 7);  // 1 .. 64
      void* p = arena.allocate(bytes, alignment);
      ASSERT_NE(p, nullptr);
      const auto at = reinterpret_cast<std::uintptr_t>(p);
      EXPECT_EQ(at % alignment, 0u) << i;
      std::memset(p, 0xab, bytes);  // writable (and checked by ASan)
      blocks.emplace_back(at, bytes);
    }
    std::sort(blocks.begin(), blocks.end());
    for (size_t i = 1; i < blocks.size(); ++i) {
      EXPECT_LE(blocks[i - 1].first + blocks[i - 1].second, blocks[i].first);
    }
    EXPECT_GT(heap.allocations, 1u);
    EXPECT_EQ(arena.allocated_bytes(), heap.live_bytes);
  }
  EXPECT_EQ(heap.deallocations, heap.allocations);
  EXPECT_EQ(heap.live_bytes, 0u);
}

TEST(Arena, UsesABorrowedBufferFirstAndNeverFreesIt) {
  CountingResource heap;
  alignas(std::max_align_t) std::byte buffer[1024];
  const auto begin = reinterpret_cast<std::uintptr_t>(buffer);
  {
    mospec::Arena arena(buffer, sizeof buffer, &heap);
    std::pmr::vector<int> small(&arena);
    small.reserve(100);
    const auto at = reinterpret_cast<std::uintptr_t>(small.data());
    EXPECT_GE(at, begin);
    EXPECT_LE(at + 400, begin + sizeof buffer);
    EXPECT_EQ(heap.allocations, 0u);
    EXPECT_EQ(arena.allocated_bytes(), 0u);
    // Past the buffer: the heap, for a block at least as large as the request.
    std::pmr::string large(5000, 'x', &arena);
    EXPECT_EQ(heap.allocations, 1u);
    EXPECT_GE(arena.allocated_bytes(), 5000u);
  }
  EXPECT_EQ(heap.deallocations, 1u);
}

TEST(Arena, ReleaseFreesEverythingAndTheArenaStaysUsable) {
  CountingResource heap;
  mospec::Arena arena(128, &heap);
  for (int i = 0; i < 50; ++i) EXPECT_NE(arena.allocate(100, 8), nullptr);
  EXPECT_GT(heap.allocations, 0u);
  arena.release();
  EXPECT_EQ(heap.live_bytes, 0u);
  void* p = arena.allocate(16, 16);
  EXPECT_NE(p, nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % 16, 0u);
}

TEST(Arena, ZeroBytesStillGetsAPointer) {
  mospec::Arena arena;
  EXPECT_NE(arena.allocate(0, 1), nullptr);
}

TEST(Arena, AnImpossibleRequestThrows) {
  mospec::Arena arena;
  EXPECT_THROW((void)arena.allocate(SIZE_MAX - 8, 8), std::bad_alloc);
}

}  // namespace
