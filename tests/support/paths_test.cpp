// CanonicalPaths answers exactly what canonical_path answers (it only
// remembers the components it has checked), through links, `..`, `.`,
// doubled slashes, relative paths and paths that do not exist.
#include "support/paths.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/canonical_paths.hpp"

namespace fs = std::filesystem;

namespace {

class CanonicalPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mospec-paths-test-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "tree" / "models" / "sub");
    fs::create_directories(dir_ / "outside");
    std::ofstream(dir_ / "tree" / "models" / "a.json") << "{}";
    std::ofstream(dir_ / "tree" / "models" / "sub" / "b.json") << "{}";
    std::ofstream(dir_ / "outside" / "secret.json") << "{}";
    fs::create_directory_symlink(dir_ / "outside", dir_ / "tree" / "models" / "escape");
    fs::create_symlink(dir_ / "outside" / "secret.json", dir_ / "tree" / "models" / "link.json");
    fs::create_directory_symlink("sub", dir_ / "tree" / "models" / "relative-link");
    fs::create_symlink(dir_ / "nowhere", dir_ / "tree" / "models" / "dangling.json");
    fs::create_directory_symlink("/", dir_ / "tree" / "root-link");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string p(const std::string& rel) const { return (dir_ / rel).string(); }
  fs::path dir_;
};

TEST_F(CanonicalPathsTest, AnswersWhatCanonicalPathAnswers) {
  const std::vector<std::string> paths = {
      p("tree/models/a.json"),
      p("tree/models/sub/b.json"),
      p("tree/models/sub/../a.json"),
      p("tree/models/./sub//b.json"),
      p("tree/models/"),
      p("tree/models/escape/secret.json"),
      p("tree/models/link.json"),
      p("tree/models/relative-link/b.json"),
      p("tree/models/relative-link/../a.json"),
      p("tree/models/dangling.json"),
      p("tree/models/missing.json"),
      p("tree/models/missing/../a.json"),
      p("tree/models/a.json/.."),
      p("tree/root-link/tmp"),
      p("tree/models/escape/../../tree/models/a.json"),
      "/",
      "/..",
      "//",
  };
  // Twice over one instance, so the second round is answered from memory.
  mospec::CanonicalPaths canonical;
  for (int round = 0; round < 2; ++round) {
    for (const std::string& path : paths) {
      EXPECT_EQ(canonical.canonical(path), mospec::canonical_path(path).string())
          << path << " (round " << round << ")";
    }
  }
}

TEST_F(CanonicalPathsTest, RelativePathsResolveAgainstTheWorkingDirectory) {
  const fs::path was = fs::current_path();
  fs::current_path(dir_ / "tree");
  mospec::CanonicalPaths canonical;
  for (const std::string path : {"models/a.json", "./models/sub/../a.json", "models/escape/x",
                                 "../outside/secret.json", ".", "models/link.json"}) {
    EXPECT_EQ(canonical.canonical(path), mospec::canonical_path(path).string()) << path;
  }
  fs::current_path(was);
}

TEST_F(CanonicalPathsTest, ALinkIsNeverTakenForItsOwnSpelling) {
  // What the sandbox relies on: a link inside the tree names its target.
  mospec::CanonicalPaths canonical;
  EXPECT_EQ(canonical.canonical(p("tree/models/escape/secret.json")),
            fs::canonical(p("outside/secret.json")).string());
  EXPECT_EQ(canonical.canonical(p("tree/models/link.json")),
            fs::canonical(p("outside/secret.json")).string());
}

}  // namespace
