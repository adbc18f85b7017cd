// Test-only: the paper's mobile base as robots/kelo-base.jsonld describes it,
// read once with the same reader lowering and `mospec sim` use
// (description::load_base), so tests never restate its numbers.
#pragma once

#include <string>

#include "description/base_rdf.hpp"
#include "runtime/kelo.hpp"
#include "vocab/metamodels.hpp"

namespace mospec::testing {

inline const runtime::KeloConfig& paper_base() {
  static const runtime::KeloConfig config =
      description::load_base(std::string(MOSPEC_SOURCE_DIR) + "/robots/kelo-base.jsonld",
                             std::string(mospec::vocab::robots::kelo_base));
  return config;
}

}  // namespace mospec::testing
