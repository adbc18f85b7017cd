// The simulated robot and its world, in Drake's shape: declare, then step.
//
// The constructor declares everything once — it generates the MJCF text from
// the arms' chains and the configuration (sim/mjcf.hpp), compiles it in memory
// (no files), looks up every joint, actuator, geom and constraint by name and
// sets the initial state (with the seeded perturbations). After that the
// World owns the whole state; a controller sees only the robot interface:
// read() a MeasuredState, write() a Command, and the loop calls step().
//
// Timing: one step() is one control tick of config.control_period, made of
// config.substeps physics steps. With command_delay_ticks = 1 (the default)
// the command written during tick k acts during tick k+1, as in a real loop
// whose command reaches the drives one cycle after the sample it was computed
// from. A dropped command (fault) leaves the previous one in force. The
// command written before the first step also acts during the first tick (the
// robot holds still until the loop starts; it does not fall for one tick).
//
// Determinism: no wall clock, no threads, one seeded generator; two Worlds
// made from the same configuration and driven by the same commands produce
// bit-identical states.
//
// Ground truth (contact forces, end-effector positions, the ground's wrench on
// the base) is for logs and tests; a controller must not use it.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "robot/faults.hpp"
#include "robot/interface.hpp"
#include "robot/limits.hpp"
#include "runtime/chain.hpp"
#include "runtime/kelo.hpp"
#include "sim/config.hpp"
#include "sim/mjcf.hpp"

struct mjModel_;
struct mjData_;

namespace mospec::sim {

// One arm's interaction with the table (ground truth).
struct ArmContact {
  int contacts = 0;                                 // end-effector–table contact points
  double normal_force = 0.0;                        // sum of their normal forces [N]
  runtime::Vec3 f_E_W = runtime::Vec3::Zero();      // table's force on the end-effector, in W [N]
  runtime::Vec3 f_mount_W = runtime::Vec3::Zero();  // SC2 mount's force on the end-effector [N]
};

// The platform wrench [f_x, f_y, m_z] (seen by P) that hub torques produce at
// the pivot angles `pivot_q`: F_p = G(q) F_d with kelo.hpp's massless drive
// model (f = τ/r, f_x = f_l + f_r, f_y = d/(2s) (f_r - f_l)). Per tick:
// noexcept and allocation-free.
robot::PlatformWrench hub_wrench(const runtime::KeloModel& model, std::span<const double> pivot_q,
                                 std::span<const double> wheel_tau) noexcept;

class World final : public robot::RobotInterface {
 public:
  // `arms`: each arm's chain, one per config.arms entry (in that order).
  // Throws mospec::Error("invalid-world") when a chain does not fit its arm's
  // configuration, and ("mujoco") with MuJoCo's message when the model does
  // not compile.
  World(const WorldConfig& config, std::vector<runtime::Chain> arms);
  // Every arm of the world is `arm` (mospec's default robot: two Gen3).
  World(const WorldConfig& config, const runtime::Chain& arm)
      : World(config, std::vector<runtime::Chain>(config.arms.size(), arm)) {}
  ~World() override;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // --- The robot's shape: its arms and their chains. ---
  const robot::RobotShape& shape() const noexcept { return shape_; }
  const std::vector<runtime::Chain>& arms() const noexcept { return chains_; }
  // A sample and a command sized for this robot (setup; they allocate).
  robot::MeasuredState make_state() const { return robot::make_state(shape_); }
  robot::Command make_command() const { return robot::make_command(shape_); }

  // --- The robot interface (per tick, noexcept, no allocation). ---
  // The sample at the current tick, with the sensor faults applied, into a
  // state made by make_state().
  void read(robot::MeasuredState& state) noexcept override;
  // Latches the command for the coming period (unless a fault drops it).
  // Non-finite entries are replaced by 0 and counted (rejected_entries());
  // then every joint and hub torque is clamped to its limit and the platform
  // wrench to the traction limit (limiter(), robot/limits.hpp), counted per
  // actuator.
  void write(const robot::Command& command) noexcept override;
  // Advances one control tick.
  void step() noexcept;

  // The true sample (no faults): what logs record.
  void read_true(robot::MeasuredState& state) const noexcept;

  // --- Setup and test hooks. ---
  robot::FaultInjector& faults() noexcept { return faults_; }
  // Activates or releases SC2's mounts; activation anchors each end-effector
  // to the table where it is now. No-op without a table.
  void set_mount_active(bool active) noexcept;
  bool mount_active() const noexcept { return mount_active_; }

  std::uint64_t tick() const noexcept { return tick_; }
  double time() const noexcept;
  const WorldConfig& config() const noexcept { return config_; }
  const WorldLayout& layout() const noexcept { return layout_; }
  const std::string& mjcf() const noexcept { return mjcf_; }
  std::uint64_t rejected_entries() const noexcept { return rejected_; }
  // The actuation limits and what they clamped so far. The arms' limits are
  // config.actuation.effort_limit, the hubs' config.platform.wheel_torque_limit;
  // the platform wrench is bounded by traction (platform_limits()).
  const robot::CommandLimiter& limiter() const noexcept { return limiter_; }
  // How often MuJoCo had to intervene: bad positions, velocities or
  // accelerations (it resets the state) or a full contact or constraint
  // buffer. Zero in a healthy run.
  int instabilities() const noexcept;

  // --- Ground truth. ---
  ArmContact contact(int arm) const noexcept;
  // The end-effector centre in W [m].
  runtime::Vec3 p_WoE_W(int arm) const noexcept;
  // The horizontal wrench [f_x, f_y, m_z] (kelo.hpp's layout) that the
  // ground exerts on the robot through the wheels, seen by P, moment about Po:
  // wheeled, from the wheel–floor contact forces; planar, the drive wrench
  // G F_d applied in the last physics step; fixed, zero.
  runtime::Vec3 ground_wrench_P() const noexcept;
  // The platform pose X_WP.
  runtime::Pose X_WP() const noexcept;
  // Total mass of the simulated robot [kg].
  double robot_mass() const noexcept;
  // hub_wrench() at the current pivot angles.
  robot::PlatformWrench platform_wrench(std::span<const double> wheel_tau) const noexcept;

  // MuJoCo's model and data, read-only, for tests and benchmarks.
  const mjModel_* mj_model() const noexcept { return m_; }
  const mjData_* mj_data() const noexcept { return d_; }

 private:
  void declare();
  void set_initial_state();
  void apply_command(const robot::Command& command) noexcept;
  void planar_forces() noexcept;
  void planar_drives_after_step() noexcept;
  void anchor_mounts() noexcept;
  robot::CommandLimits command_limits() const;

  WorldConfig config_;
  std::vector<runtime::Chain> chains_;
  robot::RobotShape shape_;
  WorldLayout layout_;
  std::string mjcf_;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;

  // Addresses looked up once (MuJoCo ids).
  std::vector<std::vector<int>> arm_qpos_, arm_dof_, arm_act_;  // per arm, per joint
  std::vector<int> pivot_qpos_, pivot_dof_;  // per drive
  std::vector<int> wheel_dof_, wheel_act_;    // per wheel
  std::vector<int> ee_geom_, ee_site_, mount_eq_;  // per arm
  int base_qpos_ = -1, base_dof_ = -1, platform_body_ = -1, table_geom_ = -1, table_body_ = -1,
      floor_geom_ = -1;

  // The planar base's drives (kinematic castors) and the wrench they apply.
  runtime::KeloModel kelo_;
  runtime::KeloData kelo_data_;
  std::vector<double> initial_pivot_q_;  // per drive (config.initial.pivot_q or zeros)
  std::vector<double> planar_pivot_q_, planar_wheel_qd_;
  mutable std::vector<double> pivot_buffer_;  // platform_wrench's pivot angles (setup-sized)
  runtime::KeloPivotVector pivot_work_;       // a per-tick workspace (setup-sized)
  runtime::KeloDriveVector drive_work_;
  runtime::Vec3 planar_F_p_ = runtime::Vec3::Zero();

  robot::FaultInjector faults_;
  robot::CommandLimiter limiter_;
  robot::Command current_{};   // the last accepted command
  robot::Command previous_{};  // the one accepted before the last step
  std::uint64_t tick_ = 0;
  std::uint64_t rejected_ = 0;
  bool mount_active_ = false;
};

}  // namespace mospec::sim
