// File input/output with located, named errors and no half-written outputs.
#pragma once

#include <string>
#include <string_view>

namespace mospec {

// Reads a whole file; throws mospec::Error (code "io") naming the path and the
// system's reason.
std::string read_file(const std::string& path);

// Writes `content` to `path` so that readers never see a partial file: a regular
// file is written to a temporary sibling and renamed over the target; "-" means
// standard output; other special files (devices, pipes) are written directly and
// every write and the final flush are checked. Throws mospec::Error (code "io").
void write_output(const std::string& path, std::string_view content);

}  // namespace mospec
