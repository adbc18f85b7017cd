// The built libraries' paths, which build_test.sh passes in the environment.
#pragma once

#include <cstdlib>
#include <string>

namespace mospec::codegen::testing {

inline std::string library_from_env(const char* variable) {
  const char* v = std::getenv(variable);
  return v != nullptr ? std::string(v) : std::string();
}

}  // namespace mospec::codegen::testing
