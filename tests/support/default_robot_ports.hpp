// The arms of mospec's default robot as the CLI binds them from the default
// world (sim::default_world(): the Gen3 chain drives arm 0, the right arm; its
// left twin arm 1), for tests that lower models without the CLI. Lowering
// itself knows no robot: ir::LowerOptions::ports is empty unless the caller
// states the robot's arms.
#pragma once

#include <map>
#include <string>

#include "vocab/metamodels.hpp"

namespace mospec::testing {

inline std::map<std::string, int> default_robot_ports() {
  return {{std::string(vocab::robots::kinova_gen3_chain), 0},
          {std::string(vocab::robots::kinova_gen3_left_chain), 1}};
}

}  // namespace mospec::testing
