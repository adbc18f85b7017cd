// Setup time only: the arm's kinematic chain from the project's JSON-LD robot
// description (robots/kinova-gen3.jsonld by default), loaded offline through
// the project's JSON-LD loader and read back with runtime::chain_from_rdf.
#pragma once

#include "runtime/chain.hpp"
#include "sim/config.hpp"

namespace mospec::sim {

// Throws mospec::Error naming the file (loading) or the entity (reading).
runtime::Chain load_arm_chain(const RobotModelSource& source);

}  // namespace mospec::sim
