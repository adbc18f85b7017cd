// The robot interface: what one control tick reads from and writes to the
// robot — two Kinova Gen3 arms on a KELO base with four castor drives.
//
// The same structs are filled by the MuJoCo simulation (src/sim) and would be
// filled by a real EtherCAT (KELO drives) / Kortex low-level (arms) adapter:
// fixed-size arrays, no allocation, plain doubles in SI units (rad, rad/s,
// N·m, m, s). Sign conventions are those of the runtime (src/runtime/kelo.hpp
// for the drives, the chain model's joint axes for the arms); an adapter flips
// signs of mirrored motors or encoders, not the controller.
//
// Layouts:
//   arm[kRightArm], arm[kLeftArm]    joint i of the chain, 0-based (Gen3
//                                    "Actuator1" is index 0);
//   pivot_q[i]                       drive i, numbered as in kelo.hpp:
//                                    0 front-left, 1 rear-left, 2 rear-right,
//                                    3 front-right;
//   wheel_qd / wheel_tau             [drive 0 left, drive 0 right, drive 1
//                                    left, …] (kelo.hpp's order).
#pragma once

#include <array>
#include <cstdint>

namespace mospec::robot {

inline constexpr int kArms = 2;
inline constexpr int kArmJoints = 7;
inline constexpr int kDrives = 4;
inline constexpr int kWheels = 2 * kDrives;

inline constexpr int kRightArm = 0;
inline constexpr int kLeftArm = 1;

using ArmVector = std::array<double, kArmJoints>;
using DriveVector = std::array<double, kDrives>;
using WheelVector = std::array<double, kWheels>;

// The clock of one sample: the tick counter and the time stamp the sample was
// taken at, and the measured period since the previous sample (a real loop
// measures it from a monotonic clock; 0 for the first sample).
struct ClockSample {
  std::uint64_t tick = 0;
  double t = 0.0;   // [s]
  double dt = 0.0;  // [s]
};

// One arm's joint measurements.
struct ArmMeasurement {
  ArmVector q{};    // joint positions [rad]
  ArmVector qd{};   // joint velocities [rad/s]
  ArmVector tau{};  // joint torques (torque sensors) [N·m]
};

// Ground truth that no real robot measures: the simulator fills it for logs
// and tests. A controller must not read it.
struct GroundTruth {
  std::array<double, 3> p_WoPo_W{};           // platform origin in the world [m]
  std::array<double, 4> quat_WP{1, 0, 0, 0};  // platform orientation (w, x, y, z)
  double yaw = 0.0;                           // heading of x_P about z_W [rad]
};

// Everything one tick reads.
struct MeasuredState {
  ClockSample clock;
  std::array<ArmMeasurement, kArms> arm{};
  DriveVector pivot_q{};   // drive pivot angles, x_P to x_Di about +z [rad]
  WheelVector wheel_qd{};  // wheel rates, positive rolling forward [rad/s]
  GroundTruth truth;       // logging only
};

// Everything one tick writes. `tick` is the clock tick the command was
// computed for (adapters may use it to detect stale commands).
struct Command {
  std::uint64_t tick = 0;
  std::array<ArmVector, kArms> arm_tau{};  // joint torques [N·m]
  WheelVector wheel_tau{};                 // hub torques, positive driving forward [N·m]
};

// A robot a control loop runs against. read() returns the newest sample;
// write() hands over the command for the next period. Both are called from the
// control thread once per tick and must not allocate or throw.
class RobotInterface {
 public:
  virtual ~RobotInterface() = default;
  virtual void read(MeasuredState& state) noexcept = 0;
  virtual void write(const Command& command) noexcept = 0;
};

}  // namespace mospec::robot
