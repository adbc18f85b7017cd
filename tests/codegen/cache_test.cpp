// The controller cache's rules that need no compiler: where the cache lives
// (XDG), which directories it accepts, what its key covers, and which paths
// a generated project may be built in. (Building, reuse and the tampered
// library: controller_test.cpp and cache_cli_test.sh.)
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "codegen/build.hpp"
#include "codegen/codegen.hpp"
#include "programs.hpp"

namespace mospec::codegen {
namespace {

namespace fs = std::filesystem;

// A scratch directory of this test, removed at the end.
class Scratch {
 public:
  Scratch() : dir_(fs::temp_directory_path() / ("mospec-cache-test-" + std::to_string(getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::permissions(dir_, fs::perms::owner_all);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

mode_t mode_of(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(lstat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

// The message of the error `f` throws ("" when it throws none), its code in `code`.
template <typename F>
std::string error_of(F&& f, std::string* code = nullptr) {
  try {
    f();
  } catch (const Error& e) {
    if (code != nullptr) *code = e.code();
    return e.what();
  }
  return {};
}

TEST(CacheDir, IsXdgCacheHomeThenHomeAndNeverTheWorkingDirectory) {
  EXPECT_EQ(default_cache_dir("/x/cache", "/home/u"), "/x/cache/mospec");
  EXPECT_EQ(default_cache_dir(nullptr, "/home/u"), "/home/u/.cache/mospec");
  // The XDG specification: a relative or empty path is ignored.
  EXPECT_EQ(default_cache_dir("", "/home/u"), "/home/u/.cache/mospec");
  EXPECT_EQ(default_cache_dir("relative/cache", "/home/u"), "/home/u/.cache/mospec");
  EXPECT_EQ(default_cache_dir(".", "/home/u"), "/home/u/.cache/mospec");
  std::string code;
  const std::string msg = error_of([] { default_cache_dir(nullptr, nullptr); }, &code);
  EXPECT_EQ(code, "usage");
  EXPECT_NE(msg.find("neither XDG_CACHE_HOME nor HOME"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--cache DIR"), std::string::npos) << msg;
  EXPECT_NE(error_of([] { default_cache_dir("rel", "also-relative"); }), "");
}

TEST(CacheDir, MissingDirectoriesAreCreatedPrivate) {
  Scratch s;
  const fs::path root = s.dir() / "a" / "b" / "mospec";
  ensure_private_dir(root.string());
  EXPECT_TRUE(fs::is_directory(root));
  EXPECT_EQ(mode_of(s.dir() / "a"), 0700u);
  EXPECT_EQ(mode_of(root), 0700u);
  ensure_private_dir(root.string());  // an existing private directory is fine
}

TEST(CacheDir, AWritableByOthersDirectoryIsRefusedWithTheFix) {
  Scratch s;
  for (const mode_t mode : {0777u, 0770u, 0702u, 01777u}) {
    const fs::path root = s.dir() / ("root-" + std::to_string(mode));
    fs::create_directory(root);
    ASSERT_EQ(chmod(root.c_str(), mode), 0);
    std::string code;
    const std::string msg = error_of([&] { ensure_private_dir(root.string()); }, &code);
    EXPECT_EQ(code, "unsafe-cache") << mode;
    EXPECT_NE(msg.find("'" + root.string() + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("other users can write into it"), std::string::npos) << msg;
    EXPECT_NE(msg.find("chmod go-w"), std::string::npos) << msg;
  }
}

TEST(CacheDir, ASymlinkOrAFileIsRefused) {
  Scratch s;
  fs::create_directory(s.dir() / "real");
  fs::permissions(s.dir() / "real", fs::perms::owner_all);
  fs::create_directory_symlink(s.dir() / "real", s.dir() / "link");
  EXPECT_NE(error_of([&] {
              ensure_private_dir((s.dir() / "link").string());
            }).find("it is a symbolic link"),
            std::string::npos);
  std::FILE* f = std::fopen((s.dir() / "file").c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  EXPECT_NE(
      error_of([&] { ensure_private_dir((s.dir() / "file").string()); }).find("not a directory"),
      std::string::npos);
}

TEST(CacheDir, ADirectoryOfAnotherUserIsRefused) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to give a directory to another user";
  Scratch s;
  const fs::path root = s.dir() / "theirs";
  fs::create_directory(root);
  fs::permissions(root, fs::perms::owner_all);
  ASSERT_EQ(chown(root.c_str(), 65534, 65534), 0);
  const std::string msg = error_of([&] { ensure_private_dir(root.string()); });
  EXPECT_NE(msg.find("'" + root.string() + "': it is owned by user id 65534, not by you"),
            std::string::npos)
      << msg;
}

// Everything that affects the build changes the key, one field at a time.
TEST(CacheKey, EveryInputOfTheBuildChangesTheKey) {
  SourceFiles files;
  const std::vector<GeneratedFile> rendered = render(testing::small_program(files), &files);
  BuildConfig c;
  c.version = "0.1.0";
  c.runtime_id = "r";
  c.package = "/p";
  c.package_content = "pc";
  c.compiler = "/usr/bin/c++";
  c.compiler_version = "GNU 12";
  c.flags = {"-DCMAKE_BUILD_TYPE=Release", "CXXFLAGS="};
  const std::string key = cache_key(rendered, c);
  EXPECT_EQ(key.size(), 64u);
  EXPECT_EQ(key.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(cache_key(rendered, c), key) << "deterministic";

  std::vector<std::string> keys{key};
  auto changed = rendered;
  changed[2].content.append(" ");  // a generated source
  keys.push_back(cache_key(changed, c));
  changed = rendered;
  changed[1].path = "other.hpp";  // a file name
  keys.push_back(cache_key(changed, c));
  changed = rendered;
  changed.pop_back();  // a file less
  keys.push_back(cache_key(changed, c));
  for (auto mutate : std::vector<std::function<void(BuildConfig&)>>{
           [](BuildConfig& b) { b.version = "0.1.1"; },
           [](BuildConfig& b) { b.runtime_id = "r2"; },
           [](BuildConfig& b) { b.package = "/q"; },
           [](BuildConfig& b) { b.package_content = "pc2"; },
           [](BuildConfig& b) { b.compiler = "/usr/bin/clang++"; },
           [](BuildConfig& b) { b.compiler_version = "GNU 13"; },
           [](BuildConfig& b) { b.flags[1] = "CXXFLAGS=-O0"; },  // a flag
           [](BuildConfig& b) { b.flags.push_back("-DX=1"); },
       }) {
    BuildConfig m = c;
    mutate(m);
    keys.push_back(cache_key(rendered, m));
  }
  // Field boundaries are part of the key: moving a byte from one field to
  // the next changes it.
  BuildConfig shifted = c;
  shifted.version = "0.1.0r";
  shifted.runtime_id = "";
  keys.push_back(cache_key(rendered, shifted));
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end());
}

TEST(CacheKey, TheCurrentConfigurationNamesTheToolchain) {
  const BuildConfig c = current_build_config();
  EXPECT_FALSE(c.version.empty());
  EXPECT_EQ(c.runtime_id.size(), 64u);
  EXPECT_EQ(c.package_content.size(), 64u);
  EXPECT_NE(c.compiler_version.find("\n"), std::string::npos) << "the compiler's --version output";
  EXPECT_FALSE(c.flags.empty());
}

TEST(Sha256, MatchesTheKnownDigests) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(CmakePath, WhatCMakeCannotQuoteIsRefused) {
  for (const std::string& bad :
       std::vector<std::string>{"/tmp/a\"b", "/tmp/a\nb", "/tmp/a\\b", "/tmp/$HOME", "/tmp/a;b",
                                "/tmp/a\rb", std::string("/tmp/a\0b", 8), "/tmp/a\x7f"}) {
    std::string code;
    const std::string msg = error_of([&] { check_cmake_path(bad, "the thing"); }, &code);
    EXPECT_EQ(code, "unsafe-path") << bad;
    EXPECT_EQ(msg.rfind("mospec: error: the thing '", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "the message quotes the path escaped: " << msg;
  }
  for (const std::string& good :
       std::vector<std::string>{"/tmp/odd dir 'x'/p", "/tmp/a#b", "/tmp/é", "relative/dir"}) {
    EXPECT_EQ(error_of([&] { check_cmake_path(good, "the thing"); }), "") << good;
  }
}

// An output directory whose name holds a quote and a line break (which once
// injected commands into the build files): refused, nothing written.
TEST(CmakePath, GenerateRefusesSuchAnOutputDirectory) {
  Scratch s;
  const fs::path out = s.dir() / "x\")\nexecute_process(COMMAND touch pwned)\n#";
  SourceFiles files;
  const ir::Program p = testing::small_program(files);
  std::string code;
  const std::string msg = error_of([&] { generate(p, out.string(), &files); }, &code);
  EXPECT_EQ(code, "unsafe-path");
  EXPECT_NE(msg.find("the output directory"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'\"'"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(out));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(s.dir())) ++entries;
  EXPECT_EQ(entries, 0u);
}

TEST(CmakePath, BuildRefusesSuchAProjectDirectory) {
  Scratch s;
  const fs::path dir = s.dir() / "a\nb";
  fs::create_directories(dir);
  std::FILE* f = std::fopen((dir / "CMakeLists.txt").c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  std::string code;
  const std::string msg = error_of([&] { build_project(dir.string()); }, &code);
  EXPECT_EQ(code, "unsafe-path");
  EXPECT_NE(msg.find("the generated project's directory"), std::string::npos) << msg;
  EXPECT_NE(msg.find("control character 0x0A"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(dir / "build"));
}

}  // namespace
}  // namespace mospec::codegen
