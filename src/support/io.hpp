// File input/output with located, named errors and no half-written outputs.
//
// Every input mospec reads (models, contexts, shapes, world files, URDF, logs)
// goes through read_file, so none of them can be a device, a pipe or a file too
// large to hold; every output goes through write_output, so no reader ever sees
// half a file and no planted symbolic link is followed.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace mospec {

// The largest input file read_file accepts: 64 MiB, far above any model, shape
// or world file (the largest in the repository is under 1 MiB) and low enough
// that a hostile input cannot exhaust memory.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;

// Reads a whole regular file of at most `limit` bytes. The file is opened
// without blocking (a FIFO does not hang the open), checked with fstat on the
// open descriptor, and refused with mospec::Error (code "io", naming the path
// and the reason) when it is not a regular file (directory, FIFO, socket,
// device such as /dev/urandom), when it is larger than `limit` (the message
// gives both sizes), or when it grows past `limit` while being read.
std::string read_file(const std::string& path, std::size_t limit = kMaxInputFileBytes);

// The reason read_file would give for `path`, or empty when it reads: callers
// that report errors in their own words (the JSON-LD loader) use this form.
// `out` holds the content on success.
std::string read_file_reason(const std::string& path, std::string& out,
                             std::size_t limit = kMaxInputFileBytes);

// Writes `content` to `path` so that readers never see a partial file: a
// regular (or not yet existing) target is written to a fresh temporary file in
// the same directory, created with O_CREAT|O_EXCL|O_NOFOLLOW under an
// unpredictable name (mkstemp), given the permissions a new file would get
// (0666 & ~umask), then renamed over the target; the temporary is removed on
// every error. A symbolic link at the target itself is replaced, never followed.
// "-" means standard output; other special files (devices, pipes) are written
// directly and every write and the final flush are checked. Throws mospec::Error
// (code "io").
void write_output(const std::string& path, std::string_view content);

}  // namespace mospec
