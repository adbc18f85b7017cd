// Shared by the simulation tests: the Gen3 chain from the project's robot
// description (loaded once) and a small closed loop.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <memory>

#include "description/robot_model.hpp"
#include "kelo_base.hpp"
#include "sim/config.hpp"
#include "sim/drivers.hpp"
#include "sim/world.hpp"

namespace mospec::sim::testing {

// The chain of robots/kinova-gen3.jsonld (its contexts resolve to mospec's own
// metamodels), or nullptr when a world file maps them to a folder that is absent.
inline const runtime::Chain* gen3() {
  static const std::unique_ptr<runtime::Chain> chain = []() -> std::unique_ptr<runtime::Chain> {
    const WorldConfig c = default_world();
    for (const auto& [prefix, dir] : c.robot.maps) {
      if (!std::filesystem::exists(dir)) return nullptr;
    }
    return std::make_unique<runtime::Chain>(
        description::load_chain(c.robot.model, c.robot.chain_iri, c.robot.maps));
  }();
  return chain.get();
}

// The default world with the paper's base (robots/kelo-base.jsonld): what
// `mospec sim` builds.
inline WorldConfig test_world() {
  WorldConfig c = default_world();
  c.drives = ::mospec::testing::paper_base();
  return c;
}

#define NEED_GEN3()                                                            \
  const runtime::Chain* gen3_chain = ::mospec::sim::testing::gen3();           \
  if (gen3_chain == nullptr) GTEST_SKIP() << "needs the published metamodels"; \
  const runtime::Chain& arm_chain = *gen3_chain

inline std::vector<runtime::Pose> mounts(const WorldConfig& c) {
  std::vector<runtime::Pose> X_PB;
  for (const ArmSetup& a : c.arms) X_PB.push_back(a.X_PB);
  return X_PB;
}

// One chain per arm of `c`, each `arm` (the default robot's two Gen3).
inline std::vector<runtime::Chain> chains(const WorldConfig& c, const runtime::Chain& arm) {
  return std::vector<runtime::Chain>(c.arms.size(), arm);
}

// Runs `ticks` control ticks: read, let `control` fill the command, write, step.
inline void run(World& world, int ticks,
                const std::function<void(const robot::MeasuredState&, robot::Command&)>& control) {
  robot::MeasuredState s = world.make_state();
  robot::Command cmd = world.make_command();
  for (int k = 0; k < ticks; ++k) {
    world.read(s);
    control(s, cmd);
    world.write(cmd);
    world.step();
  }
}

}  // namespace mospec::sim::testing
