#include "support/io.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/diagnostics.hpp"

namespace mospec {
namespace fs = std::filesystem;

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw Error("io", "cannot read '" + path + "': is a directory");
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    throw Error("io", "cannot read '" + path + "': " + std::strerror(errno));
  }
  std::string out;
  char buffer[1 << 16];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) out.append(buffer, n);
  bool failed = std::ferror(f) != 0;
  int saved = errno;
  std::fclose(f);
  if (failed) throw Error("io", "cannot read '" + path + "': " + std::strerror(saved));
  return out;
}

namespace {

void write_stream(std::FILE* f, std::string_view content, const std::string& name) {
  if (std::fwrite(content.data(), 1, content.size(), f) != content.size() || std::fflush(f) != 0) {
    throw Error("io", "cannot write '" + name + "': " + std::strerror(errno));
  }
}

}  // namespace

void write_output(const std::string& path, std::string_view content) {
  if (path == "-") {
    write_stream(stdout, content, "<stdout>");
    return;
  }
  std::error_code ec;
  auto status = fs::status(path, ec);
  if (!ec && fs::exists(status) && !fs::is_regular_file(status)) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) throw Error("io", "cannot write '" + path + "': " + std::strerror(errno));
    try {
      write_stream(f, content, path);
    } catch (...) {
      std::fclose(f);
      throw;
    }
    if (std::fclose(f) != 0) {
      throw Error("io", "cannot write '" + path + "': " + std::strerror(errno));
    }
    return;
  }
  std::string tmp = path + ".tmp." + std::to_string(::getpid());
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw Error("io", "cannot write '" + path + "': " + std::strerror(errno));
  bool ok =
      std::fwrite(content.data(), 1, content.size(), f) == content.size() && std::fflush(f) == 0;
  int saved = errno;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    throw Error("io", "cannot write '" + path + "': " + std::strerror(saved));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    saved = errno;
    std::remove(tmp.c_str());
    throw Error("io", "cannot write '" + path + "': " + std::strerror(saved));
  }
}

}  // namespace mospec
