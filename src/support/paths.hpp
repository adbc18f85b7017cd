// Paths of the model tree: canonical forms, containment, and how a path is
// quoted in a message. One home for the sandbox's geometry, shared by the
// document loader, the app's iri-map check and the world file's robot files.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace mospec {

// `path` made absolute with every symbolic link and `..` resolved (as far as it
// exists; the rest lexically).
std::filesystem::path canonical_path(const std::string& path);

// Whether `path` is `root` or below it, compared component by component (so
// /tree2 is not inside /tree). Both should be canonical.
bool is_within(const std::filesystem::path& path, const std::filesystem::path& root);

// `s` for a message: every byte outside printable ASCII is written as \xHH, so a
// path or IRI from an untrusted file cannot carry control bytes to a terminal.
std::string escaped_bytes(std::string_view s);

}  // namespace mospec
