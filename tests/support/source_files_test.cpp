// SourceFiles names every file of a load by a small id, handed out while the
// load's documents are parsed on two threads.
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "support/diagnostics.hpp"

namespace {

using mospec::SourceFiles;

// (Appended, not "a" + std::to_string(...): GCC 12 warns falsely of an
// overlapping memcpy there.)
std::string name(std::string_view prefix, int i) {
  std::string out(prefix);
  out.append(std::to_string(i));
  return out;
}

TEST(SourceFiles, IdsAreDenseStableAndOnePerPath) {
  SourceFiles files;
  EXPECT_EQ(files.size(), 1u);  // id 0: no file
  EXPECT_EQ(files.path(0), "");
  std::vector<const std::string*> seen;
  // Past the first block and several doublings.
  for (int i = 0; i < 1000; ++i) {
    const uint32_t id = files.add(name("file-", i).append(".json"));
    ASSERT_EQ(id, static_cast<uint32_t>(i + 1));
    seen.push_back(&files.path(id));
  }
  EXPECT_EQ(files.add("file-17.json"), 18u);
  EXPECT_EQ(files.size(), 1001u);
  for (int i = 0; i < 1000; ++i) {
    // A path stays where it is while later ones are added.
    EXPECT_EQ(&files.path(static_cast<uint32_t>(i + 1)), seen[static_cast<size_t>(i)]);
    EXPECT_EQ(files.path(static_cast<uint32_t>(i + 1)), name("file-", i).append(".json"));
  }
  EXPECT_EQ(files.path(5000), "");  // unknown: no file
}

TEST(SourceFiles, CopiesKeepTheIdsAndMovesTakeThem) {
  SourceFiles files;
  for (int i = 0; i < 100; ++i) files.add(name("f", i));
  const SourceFiles copy = files;
  ASSERT_EQ(copy.size(), files.size());
  for (uint32_t id = 0; id < copy.size(); ++id) EXPECT_EQ(copy.path(id), files.path(id));
  SourceFiles moved = std::move(files);
  EXPECT_EQ(moved.size(), 101u);
  EXPECT_EQ(moved.path(100), "f99");
  EXPECT_EQ(moved.add("f42"), 43u);
}

// Two threads add the same paths (and their own) while reading back every
// id they were given: each path gets one id, and every id names its path.
TEST(SourceFiles, AddsFromTwoThreadsAgreeOnEveryId) {
  SourceFiles files;
  constexpr int kPaths = 3000;
  std::vector<uint32_t> ids[2];
  auto work = [&](int t) {
    for (int i = 0; i < kPaths; ++i) {
      const std::string shared = name("shared-", i);
      const uint32_t id = files.add(shared);
      ids[t].push_back(id);
      EXPECT_EQ(files.path(id), shared);
      const std::string own = name(name("own-", t).append("-"), i);
      EXPECT_EQ(files.path(files.add(own)), own);
    }
  };
  std::thread other(work, 1);
  work(0);
  other.join();
  EXPECT_EQ(ids[0], ids[1]);
  EXPECT_EQ(files.size(), 1u + 3u * kPaths);
}

}  // namespace
