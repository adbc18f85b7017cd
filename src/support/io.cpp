#include "support/io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "support/diagnostics.hpp"

namespace mospec {
namespace fs = std::filesystem;

namespace {

// Closes a file descriptor on every path out of a scope.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  // Closes now, reporting the result (a deferred write error shows up here).
  int close() {
    int r = ::close(fd_);
    fd_ = -1;
    return r;
  }

 private:
  int fd_;
};

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return std::strerror(EISDIR);
  if (S_ISFIFO(mode)) return "not a regular file (a FIFO)";
  if (S_ISSOCK(mode)) return "not a regular file (a socket)";
  if (S_ISCHR(mode)) return "not a regular file (a character device)";
  if (S_ISBLK(mode)) return "not a regular file (a block device)";
  return "not a regular file";
}

std::string too_large(std::size_t size, std::size_t limit) {
  return "file is too large (" + std::to_string(size) + " bytes; the limit is " +
         std::to_string(limit) + " bytes)";
}

bool write_all(int fd, std::string_view content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

std::string read_file_reason(const std::string& path, std::string& out, std::size_t limit) {
  out.clear();
  if (path.find('\0') != std::string::npos) return "the path contains a NUL byte";
  // O_NONBLOCK: opening a FIFO with no writer would otherwise block forever.
  Fd fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) return std::strerror(errno);
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) return std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return kind_of(st.st_mode);
  if (st.st_size < 0 || static_cast<std::size_t>(st.st_size) > limit) {
    return too_large(static_cast<std::size_t>(st.st_size), limit);
  }
  out.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    // One byte past the limit tells a file that grew while read from one that fits.
    std::size_t want = std::min(sizeof buffer, limit + 1 - out.size());
    ssize_t n = ::read(fd.get(), buffer, want);
    if (n < 0) {
      if (errno == EINTR) continue;
      int saved = errno;
      out.clear();
      return std::strerror(saved);
    }
    if (n == 0) break;
    out.append(buffer, static_cast<std::size_t>(n));
    if (out.size() > limit) {
      out.clear();
      return "file grew past the limit of " + std::to_string(limit) + " bytes while being read";
    }
    // A regular file read short at the size fstat gave has ended: the read
    // that would return 0 is one system call per file saved. A file that
    // changes size while read is read to its end.
    if (static_cast<std::size_t>(n) < want && out.size() == static_cast<std::size_t>(st.st_size)) {
      break;
    }
  }
  return {};
}

std::string read_file(const std::string& path, std::size_t limit) {
  std::string out;
  if (std::string reason = read_file_reason(path, out, limit); !reason.empty()) {
    throw Error("io", "cannot read '" + path + "': " + reason);
  }
  return out;
}

namespace {

void write_stream(std::FILE* f, std::string_view content, const std::string& name) {
  if (std::fwrite(content.data(), 1, content.size(), f) != content.size() || std::fflush(f) != 0) {
    throw Error("io", "cannot write '" + name + "': " + std::strerror(errno));
  }
}

mode_t current_umask() {
  // umask can only be read by setting it; restore it at once (mospec is
  // single-threaded where it writes outputs).
  mode_t mask = ::umask(022);
  ::umask(mask);
  return mask;
}

}  // namespace

void write_output(const std::string& path, std::string_view content) {
  if (path == "-") {
    write_stream(stdout, content, "<stdout>");
    return;
  }
  if (path.empty() || path.find('\0') != std::string::npos) {
    throw Error("io", "cannot write '" + path + "': not a valid file name");
  }
  auto fail = [&](int err) -> Error {
    return Error("io", "cannot write '" + path + "': " + std::strerror(err));
  };
  // A target that is (or links to) a device or a pipe the user named
  // (/dev/stdout, /dev/null, a FIFO) is written directly; anything else goes
  // through a temporary file, and a symbolic link at the target is replaced by
  // the rename, never written through.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw fail(EISDIR);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) throw fail(errno);
    try {
      write_stream(f, content, path);
    } catch (...) {
      std::fclose(f);
      throw;
    }
    if (std::fclose(f) != 0) throw fail(errno);
    return;
  }
  // mkstemp opens with O_CREAT|O_EXCL and a random name: it never opens an
  // existing file, so neither a planted link nor a planted file is written to.
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp.XXXXXX");
  std::string tmpl = (dir / name).string();
  Fd fd(::mkostemp(tmpl.data(), O_CLOEXEC | O_NOFOLLOW));
  if (fd.get() < 0) throw fail(errno);
  bool ok = ::fchmod(fd.get(), 0666 & ~current_umask()) == 0 && write_all(fd.get(), content);
  int saved = ok ? 0 : errno;
  if (fd.close() != 0 && ok) {  // a deferred write error (NFS, quota) shows up here
    ok = false;
    saved = errno;
  }
  if (!ok) {
    ::unlink(tmpl.c_str());
    throw fail(saved);
  }
  if (std::rename(tmpl.c_str(), path.c_str()) != 0) {
    saved = errno;
    ::unlink(tmpl.c_str());
    throw fail(saved);
  }
}

}  // namespace mospec
