// MJCF generation: the simulated world as MuJoCo XML text, made from the arm's
// kinematic chain (the project's robot description), the KELO geometry and
// the world configuration. Nothing here is a hand-maintained robot file.
//
// Names in the generated model (used by World to look things up):
//   bodies    platform, drive<i>, drive<i>_left, drive<i>_right, table,
//             <arm>_base, <arm>_<link> (one per chain segment)
//   joints    base (wheeled: free), base_x / base_y / base_yaw (planar),
//             drive<i>_pivot, drive<i>_left, drive<i>_right, <arm>_<joint>
//   actuators <arm>_<joint> (torque motors, 14), drive<i>_left / _right
//             (wheeled only, 8), in that order
//   geoms     floor, table, <arm>_ee (contact sphere), wheel spheres
//   equality  <arm>_mount (connect, SC2)
// with <arm> = "right" / "left" and drives numbered as in kelo.hpp.
//
// Contact filtering (contype/conaffinity bits): bit 0 floor–wheels, bit 1
// table–end-effectors; every other geom is visual only.
#pragma once

#include <array>
#include <string>

#include "runtime/chain.hpp"
#include "sim/config.hpp"

namespace mospec::sim {

// Quantities derived from the configuration and the chain before the model is
// generated (all for the nominal, unperturbed initial conditions).
struct WorldLayout {
  std::array<runtime::Vec3, robot::kArms> p_PoE_P{
      runtime::Vec3::Zero(), runtime::Vec3::Zero()};  // end-effector centres, in P [m]
  double table_height = 0.0;  // the table's top (front edge) above the floor [m]
  double base_x = 0.0;        // the platform origin's initial x [m]
};

// Throws mospec::Error("invalid-world") when the chain does not have
// robot::kArmJoints revolute joints or a lower limit is not below its upper.
WorldLayout layout_world(const WorldConfig& config, const runtime::Chain& arm);

std::string world_mjcf(const WorldConfig& config, const runtime::Chain& arm,
                       const WorldLayout& layout);

}  // namespace mospec::sim
