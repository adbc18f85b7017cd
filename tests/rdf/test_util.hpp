// Helpers shared by the rdf tests.
#pragma once

#include <string>
#include <string_view>

namespace mospec::rdf::testing {

// prefix + decimal number. Built by appending because GCC 12 reports a false
// -Wrestrict on `"literal" + std::to_string(n)` in optimised builds.
inline std::string numbered(std::string_view prefix, long n) {
  std::string out(prefix);
  out += std::to_string(n);
  return out;
}

}  // namespace mospec::rdf::testing
