// Setup time only: a kinematic chain from a JSON-LD robot description (the
// project's robots/kinova-gen3.jsonld by default), loaded offline through the
// app loader and read back with chain_from_rdf.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "runtime/chain.hpp"

namespace mospec::description {

// Loads `model_file` (IRI prefixes resolved through `maps`, prefix ->
// directory, before mospec's own metamodels) and reads the KinematicChain
// `chain_iri`. Throws mospec::Error naming the file (loading) or the entity
// (reading).
runtime::Chain load_chain(const std::string& model_file, const std::string& chain_iri,
                          const std::vector<std::pair<std::string, std::string>>& maps = {});

}  // namespace mospec::description
