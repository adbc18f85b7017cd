// The robot interface: what one control tick reads from and writes to the
// robot — any number of serial arms (each with its own joint count) on a
// KELO base with any number of castor drives (the paper's has four).
//
// The same structs are filled by the MuJoCo simulation (src/sim) and would be
// filled by a real EtherCAT (KELO drives) / arm low-level adapter: arrays sized
// once at setup from the robot's RobotShape (make_state, make_command), never
// resized per tick, plain doubles in SI units (rad or m, rad/s or m/s, N·m or
// N, s). Sign conventions are those of the runtime (src/runtime/kelo.hpp
// for the drives, the chain model's joint axes for the arms); an adapter flips
// signs of mirrored motors or encoders, not the controller.
//
// Layouts:
//   arm[k]                           the robot's arm k, in RobotShape order
//                                    (mospec's default robot: 0 the right
//                                    Gen3, 1 the left); entry i is joint i of
//                                    its chain, 0-based (Gen3 "Actuator1" is 0);
//   pivot_q[i]                       drive i, numbered as the base's robot
//                                    description does (the paper's base,
//                                    robots/kelo-base.jsonld: 0 front-left,
//                                    1 rear-left, 2 rear-right, 3 front-right);
//   wheel_qd / wheel_tau             [drive 0 left, drive 0 right, drive 1
//                                    left, …] (kelo.hpp's order).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mospec::robot {

// The arms of mospec's default robot (sim::default_world), in its order.
inline constexpr int kRightArm = 0;
inline constexpr int kLeftArm = 1;

// One value per joint of one arm, sized at setup.
using JointValues = std::vector<double>;

// The clock of one sample: the tick counter and the time stamp the sample was
// taken at, and the measured period since the previous sample (a real loop
// measures it from a monotonic clock; 0 for the first sample).
struct ClockSample {
  std::uint64_t tick = 0;
  double t = 0.0;   // [s]
  double dt = 0.0;  // [s]
};

// What the structs are sized by: the robot's arms, each named (it prefixes
// sensor names and log columns) and with its joint count.
struct ArmShape {
  std::string name;
  int joints = 0;
};
struct RobotShape {
  std::vector<ArmShape> arms;
  int drives = 4;  // the base's castor drives (two wheels each); 0: no base
};

// One arm's joint measurements (revolute joints in rad, rad/s, N·m; prismatic
// in m, m/s, N).
struct ArmMeasurement {
  JointValues q;    // joint positions
  JointValues qd;   // joint velocities
  JointValues tau;  // joint torques or forces (torque sensors)
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
  std::vector<ArmMeasurement> arm;  // one per arm of the RobotShape
  JointValues pivot_q;   // per drive: pivot angle, x_P to x_Di about +z [rad]
  JointValues wheel_qd;  // per wheel (2 per drive): rate, positive rolling forward [rad/s]
  GroundTruth truth;                // logging only
};

// Everything one tick writes. `tick` is the clock tick the command was
// computed for (adapters may use it to detect stale commands).
struct Command {
  std::uint64_t tick = 0;
  std::vector<JointValues> arm_tau;  // per arm: joint torques [N·m] (prismatic: forces [N])
  JointValues wheel_tau;              // hub torques, positive driving forward [N·m]
};

// A sample and a command sized for `shape`, all values 0. Made once at setup;
// the per-tick code only writes into them (copying one sized alike into
// another allocates nothing either).
MeasuredState make_state(const RobotShape& shape);
Command make_command(const RobotShape& shape);

// Zeroes every value of `command` in place (its sizes kept), tick included.
void zero(Command& command) noexcept;

// mospec's default robot (sim::default_world): the right and the left Gen3, 7
// joints each.
RobotShape gen3_pair_shape();

// A robot a control loop runs against. read() returns the newest sample into
// a state made for the robot's shape; write() hands over the command for the
// next period (made likewise). Both are called from the
// control thread once per tick and must not allocate or throw.
class RobotInterface {
 public:
  virtual ~RobotInterface() = default;
  virtual void read(MeasuredState& state) noexcept = 0;
  virtual void write(const Command& command) noexcept = 0;
};

}  // namespace mospec::robot
