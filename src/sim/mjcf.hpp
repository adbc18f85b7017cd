// MJCF generation: the simulated world as MuJoCo XML text, made from each
// arm's kinematic chain (what the task models and robot descriptions say), the
// KELO geometry and the world configuration. Nothing here is a hand-maintained
// robot file.
//
// Names in the generated model (used by World to look things up):
//   bodies    platform, drive<i>, drive<i>_left, drive<i>_right, table,
//             <arm>_base, <arm>_<link> (one per chain segment)
//   joints    base (wheeled: free), base_x / base_y / base_yaw (planar),
//             drive<i>_pivot, drive<i>_left, drive<i>_right, <arm>_<joint>
//             (hinge for a revolute joint, slide for a prismatic one)
//   actuators <arm>_<joint> (torque or force motors, one per arm joint),
//             drive<i>_left / _right (wheeled only, 8), in that order
//   geoms     floor, table, <arm>_ee (contact sphere), wheel spheres
//   equality  <arm>_mount (connect, SC2)
// with <arm> each arm's name (WorldConfig::arms) and drives numbered as in kelo.hpp.
//
// Contact filtering (contype/conaffinity bits): bit 0 floor–wheels, bit 1
// table–end-effectors; every other geom is visual only.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "runtime/chain.hpp"
#include "sim/config.hpp"

namespace mospec::sim {

// Quantities derived from the configuration and the chain before the model is
// generated (all for the nominal, unperturbed initial conditions).
struct WorldLayout {
  std::vector<runtime::Vec3> p_PoE_P;  // per arm: end-effector centre, in P [m]
  double table_height = 0.0;           // the table's top (front edge) above the floor [m]
  double base_x = 0.0;                 // the platform origin's initial x [m]
};

// `arms`: one chain per config.arms entry. Throws mospec::Error("invalid-world")
// naming the arm when the counts differ, when an arm's initial configuration
// or actuation does not have one entry per joint of its chain, or a lower
// limit is not below its upper.
WorldLayout layout_world(const WorldConfig& config, std::span<const runtime::Chain> arms);

std::string world_mjcf(const WorldConfig& config, std::span<const runtime::Chain> arms,
                       const WorldLayout& layout);

}  // namespace mospec::sim
