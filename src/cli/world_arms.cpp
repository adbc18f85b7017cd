#include "cli/world_arms.hpp"

#include "description/robot_model.hpp"

namespace mospec::cli {

std::vector<runtime::Chain> arm_chains(const sim::WorldConfig& config, const ir::Program* program) {
  std::vector<runtime::Chain> chains;
  for (size_t k = 0; k < config.arms.size(); ++k) {
    const ir::ArmSolver* driven = nullptr;
    if (program) {
      for (const ir::ArmSolver& a : program->arms) {
        if (a.port == static_cast<int>(k)) driven = &a;
      }
    }
    if (driven) {
      chains.push_back(driven->robot_chain);
    } else {
      const sim::RobotModelSource source = sim::arm_source(config, k);
      chains.push_back(description::load_chain(source.model, source.chain_iri, source.maps));
    }
  }
  return chains;
}

}  // namespace mospec::cli
