// A CSV log of a simulation run: one header line, then one row per recorded
// tick with the true state (no sensor faults), the base's ground-truth pose
// and the contact forces. Numbers are written in their shortest round-trip
// form, so identical runs give byte-identical logs. The text is kept in memory
// and written once (atomically) by the caller.
//
// Columns: t; for each arm (by its name, e.g. right, left): <arm>_q0..,
// <arm>_qd0.., <arm>_tau0.. (one per joint); pivot_q0.. (per drive); wheel_qd0.. (per wheel); base_x, base_y, base_z,
// base_yaw; for each arm: <arm>_ee_x/y/z (end-effector centre in W), <arm>_fn (sum of
// end-effector–table normal forces), <arm>_fx/fy/fz (the table's force on the
// end-effector, in W), <arm>_mount_fx/fy/fz (SC2 mount force on the
// end-effector, in W); ground_fx, ground_fy, ground_mz (the ground's wrench on
// the base, seen by P, see World::ground_wrench_P). Units: SI.
#pragma once

#include <cstddef>
#include <string>

#include "sim/world.hpp"

namespace mospec::sim {

class CsvLog {
 public:
  // The columns of `world`'s arms.
  explicit CsvLog(const World& world);
  void record(const World& world);
  const std::string& text() const { return text_; }
  std::size_t rows() const { return rows_; }

 private:
  void add(double x);
  std::string text_;
  std::size_t rows_ = 0;
  robot::MeasuredState state_;
};

}  // namespace mospec::sim
