// read_file refuses anything but a regular file of bounded size, without
// blocking; write_output never writes through a planted symbolic link.
#include "support/io.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/diagnostics.hpp"

namespace fs = std::filesystem;
using mospec::Error;
using mospec::read_file;
using mospec::write_output;

namespace {

class IoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mospec-io-test-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  fs::path dir_;
};

// The message read_file gives for `p`, or "" when it reads.
std::string read_error(const std::string& p, size_t limit = mospec::kMaxInputFileBytes) {
  try {
    read_file(p, limit);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "io");
    return e.what();
  }
  return "";
}

TEST_F(IoTest, ReadsRegularFiles) {
  write_output(path("a.txt"), "hello\n");
  EXPECT_EQ(read_file(path("a.txt")), "hello\n");
  write_output(path("empty.txt"), "");
  EXPECT_EQ(read_file(path("empty.txt")), "");
}

// Around the read buffer's size (a read that ends short at the file's size
// ends the file; a full one asks again).
TEST_F(IoTest, ReadsWholeFilesOfEverySizeAroundTheBuffer) {
  for (size_t size : {size_t{1}, size_t{4095}, size_t{65535}, size_t{65536}, size_t{65537},
                      size_t{3 * 65536 + 17}}) {
    std::string text(size, 'x');
    for (size_t i = 0; i < size; ++i) text[i] = static_cast<char>('a' + (i * 7) % 26);
    std::ofstream(path("f.txt"), std::ios::binary) << text;
    EXPECT_EQ(read_file(path("f.txt")), text) << size;
  }
}

TEST_F(IoTest, RefusesAFifoWithoutBlocking) {
  // No writer ever opens it: a blocking open would hang this test forever.
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  EXPECT_EQ(read_error(path("fifo")),
            "mospec: error: cannot read '" + path("fifo") + "': not a regular file (a FIFO)");
}

TEST_F(IoTest, RefusesDevices) {
  for (const char* dev : {"/dev/urandom", "/dev/zero", "/dev/null"}) {
    if (!fs::exists(dev)) continue;
    EXPECT_EQ(read_error(dev), std::string("mospec: error: cannot read '") + dev +
                                   "': not a regular file (a character device)");
  }
}

TEST_F(IoTest, RefusesDirectoriesAndMissingFiles) {
  EXPECT_EQ(read_error(dir_.string()),
            "mospec: error: cannot read '" + dir_.string() + "': Is a directory");
  EXPECT_EQ(read_error(path("missing")),
            "mospec: error: cannot read '" + path("missing") + "': No such file or directory");
}

TEST_F(IoTest, RefusesOversizedFilesByTheirSize) {
  // A sparse file: 1 GiB long, no blocks written; refused before any read.
  {
    int fd = ::open(path("big").c_str(), O_CREAT | O_WRONLY, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::ftruncate(fd, off_t{1} << 30), 0);
    ::close(fd);
  }
  EXPECT_EQ(read_error(path("big")), "mospec: error: cannot read '" + path("big") +
                                         "': file is too large (1073741824 bytes; the limit is " +
                                         std::to_string(mospec::kMaxInputFileBytes) + " bytes)");
  // The limit is inclusive.
  write_output(path("ten"), "0123456789");
  EXPECT_EQ(read_file(path("ten"), 10), "0123456789");
  EXPECT_EQ(read_error(path("ten"), 9),
            "mospec: error: cannot read '" + path("ten") +
                "': file is too large (10 bytes; the limit is 9 bytes)");
}

TEST_F(IoTest, WriteReplacesTheTargetAndLeavesNoTemporary) {
  write_output(path("out.txt"), "one");
  write_output(path("out.txt"), "two");
  EXPECT_EQ(slurp(path("out.txt")), "two");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 1u);
}

TEST_F(IoTest, WrittenFilesHaveTheUsualPermissions) {
  const mode_t old = ::umask(022);
  write_output(path("out.txt"), "x");
  ::umask(old);
  EXPECT_EQ(fs::status(path("out.txt")).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::others_read);
}

TEST_F(IoTest, NeverFollowsALinkPlantedAtATemporaryName) {
  // The victim: a file the links point to, which must stay unchanged.
  write_output(path("victim"), "precious\n");
  // The old predictable name, and the likeliest mkstemp-style names.
  const std::string out = path("out.txt");
  fs::create_symlink(path("victim"), out + ".tmp." + std::to_string(::getpid()));
  fs::create_symlink(path("victim"), path(".out.txt.tmp.XXXXXX"));
  fs::create_symlink(path("victim"), out + ".tmp");
  for (int i = 0; i < 20; ++i) write_output(out, "output " + std::to_string(i) + "\n");
  EXPECT_EQ(slurp(path("victim")), "precious\n");
  EXPECT_EQ(slurp(out), "output 19\n");
  EXPECT_FALSE(fs::is_symlink(out));
}

TEST_F(IoTest, ALinkAtTheTargetIsReplacedNotWrittenThrough) {
  write_output(path("victim"), "precious\n");
  fs::create_symlink(path("victim"), path("out.txt"));
  write_output(path("out.txt"), "new\n");
  EXPECT_EQ(slurp(path("victim")), "precious\n");
  EXPECT_FALSE(fs::is_symlink(path("out.txt")));
  EXPECT_EQ(slurp(path("out.txt")), "new\n");
}

TEST_F(IoTest, FailedWritesLeaveNothingBehind) {
  EXPECT_THROW(write_output(path("no-such-dir/out.txt"), "x"), Error);
  EXPECT_THROW(write_output(dir_.string(), "x"), Error);  // a directory
  if (fs::exists("/dev/full")) {
    try {
      write_output("/dev/full", "x");
      ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("cannot write '/dev/full'"), std::string::npos);
    }
  }
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 0u);
}

}  // namespace
