// The simulated robot's arms: which chain the simulator builds for each arm of
// the world (sim::WorldConfig::arms).
#pragma once

#include <vector>

#include "ir/ir.hpp"
#include "sim/config.hpp"

namespace mospec::cli {

// One chain per arm of `config`, in its order: the task models' chain for an
// arm a solver of `program` drives (so the simulated arm is the one the
// controller was made for, by construction), else the arm's robot description
// (sim::arm_source). `program` may be null (`mospec sim`).
std::vector<runtime::Chain> arm_chains(const sim::WorldConfig& config, const ir::Program* program);

}  // namespace mospec::cli
