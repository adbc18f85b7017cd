// The simulated world's configuration: which base model, the robot's
// parameters that no model file gives (platform mass, actuator limits), the
// table, and the initial conditions with a seed for randomised perturbations.
//
// Frames (SI units): W is the world and the table frame at once: origin on the
// floor below the middle of the table's front (top) edge, x into the table, y
// left, z up; the table's front face is the plane x = 0. P is the platform
// frame of src/runtime/kelo.hpp (origin at the platform centre on its top deck,
// x forward, z up), at height platform.deck_height above the floor. B_r / B_l
// are the arms' base frames (the chain's root link, "shoulder" in the
// authors' models).
//
// Everything here is plain data; parse_world_config() reads the JSON form
// documented in docs/simulation.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "robot/interface.hpp"
#include "runtime/chain.hpp"
#include "runtime/kelo.hpp"
#include "runtime/spatial.hpp"
#include "support/diagnostics.hpp"

namespace mospec::sim {

// How the mobile base is simulated.
enum class BaseFidelity : unsigned char {
  // A free-floating platform on four castor drives: passive pivot joints, the
  // castor offset and two driven sphere wheels each, in contact with the floor.
  Wheeled,
  // A planar body (slide x, slide y, hinge z) pushed by the drive forces
  // through G(q_pivot); the drives are massless and roll without slip, their
  // pivots follow kinematically (kelo.hpp's drive model). Fast; for tests.
  Planar,
  // The platform welded to the world (arm-only tests).
  Fixed,
};
std::string_view to_string(BaseFidelity);
std::optional<BaseFidelity> parse_base_fidelity(std::string_view);

// The platform's own parameters. Its mass and inertia are not published for
// the paper's robot: the values are plausible guesses, stated here and
// nowhere else.
struct PlatformParameters {
  double mass = 80.0;                            // chassis without drives and arms [kg]
  std::array<double, 3> size{0.60, 0.50, 0.25};  // chassis box below the deck [m]
  double deck_height = 0.35;                     // P's origin above the floor [m]
  double drive_mass = 1.5;                       // one drive's pivot housing [kg]
  double wheel_mass = 0.6;                       // one hub wheel [kg]
  double pivot_damping = 0.005;                  // [N·m·s/rad]
  double wheel_damping = 0.0;                    // hub friction not modelled [N·m·s/rad]
  double wheel_torque_limit = 10.0;              // hub motor limit (assumed) [N·m]
  double wheel_friction = 1.0;                   // wheel-floor Coulomb coefficient
};

// An arm's actuation, one entry per joint of its chain (revolute joints in
// N·m and rad, prismatic in N and m). The default is the Gen3's: Kinova's
// published limits, as in Kinova's GEN3_URDF_V12.urdf <limit> tags (effort
// 39 N·m for actuators 1-4 and 9 N·m for 5-7; position limits on actuators 2,
// 4, 6 only). The Gen3's description is read with the comp-rob2b vocabulary
// alone, so it states no limits (kc-ext:JointLimit): they live here (the world
// file's `actuation`, or an arm's own).
struct ArmActuation {
  std::vector<double> effort_limit{39, 39, 39, 39, 9, 9, 9};               // [N·m]
  std::vector<double> lower{-1e9, -2.41, -1e9, -2.66, -1e9, -2.23, -1e9};  // [rad]; ±1e9: none
  std::vector<double> upper{1e9, 2.41, 1e9, 2.66, 1e9, 2.23, 1e9};
  double damping = 0.05;  // small viscous joint damping [N·m·s/rad]
};

// Where an arm's kinematic chain comes from: a JSON-LD robot description,
// loaded offline with IRI-prefix -> directory maps.
struct RobotModelSource {
  std::string model;                                      // path of the JSON-LD file
  std::string chain_iri;                                  // the KinematicChain node to read
  std::vector<std::pair<std::string, std::string>> maps;  // IRI prefix -> directory
};

// One arm of the robot: its name, which chain the task models call it, its
// mount, initial configuration and actuation.
struct ArmSetup {
  std::string name;  // "right" / "left": prefixes the arm's MJCF names, sensors, log columns
  // The kinematic chain task models name for this arm: an arm solver of that
  // chain drives this arm (ir::LowerOptions::ports). Empty: the world's
  // `robot.chain` (arm_chain()), so a world file that renames the robot's
  // chain renames the arm it binds with it.
  std::string chain_iri;
  // Where the simulator reads the chain from when no arm solver of the
  // program gives it (an idle arm, `mospec sim`); an empty model: the world's
  // `robot`.
  RobotModelSource robot;
  runtime::Pose X_PB;                     // the arm's base B in the platform frame P
  std::vector<double> q0;                 // initial joint positions, one per joint [rad or m]
  std::optional<ArmActuation> actuation;  // unset: the world's `actuation`
  // Where X_PB came from, for messages: empty for the default, else the world
  // file's key or the task model's mount pose that set it.
  std::string mount_source;
  Place where;  // the world file's entry for this arm (unknown for the default)
};

struct TableParameters {
  bool present = true;
  double depth = 0.8;  // along x [m]
  double width = 1.6;  // along y [m]
  // The top (and so the front edge) is at the mean end-effector centre height
  // of the nominal initial configuration, plus this offset [m].
  double edge_height_offset = 0.0;
  double friction = 0.1;  // low, so contacts slide along the edge
  // The table's pose on the floor: its frame (origin below the middle of the
  // front top edge, x into the table) at (x, y) in W, turned by yaw about z.
  // Zero: the table frame is W.
  double x = 0.0, y = 0.0;  // [m]
  double yaw = 0.0;         // [rad]
};

struct EndEffectorParameters {
  double radius = 0.02;  // contact sphere at the chain's tip frame [m]
  double friction = 0.1;
};

// SC2's "custom mount": a point (connect) constraint from each end-effector
// centre to the table, anchored at the initial pose.
struct MountParameters {
  bool active = false;
  double time_constant = 0.01;  // MuJoCo solref time constant [s]
};

// Where the base starts, relative to the table (frame W).
struct InitialConditions {
  // Platform origin x in W; unset: the end-effectors of the nominal
  // configuration stand `contact_gap` in front of the table's face at yaw 0
  // (measured along W's x from the table's x).
  std::optional<double> base_x;
  double contact_gap = 0.0;     // [m]
  double base_y = 0.0;          // [m]
  double base_yaw = 0.0;        // [rad]
  std::vector<double> pivot_q;  // one per drive [rad]; empty: every pivot at 0
};

// Uniform random perturbations of the initial conditions, each in ±amplitude,
// drawn from WorldConfig::seed (0 amplitudes: none).
struct Perturbation {
  double arm_q = 0.0;     // every arm joint [rad]
  double base_xy = 0.0;   // platform x and y [m]
  double base_yaw = 0.0;  // [rad]
  double pivot_q = 0.0;   // every pivot [rad]
};

// Where the mobile base comes from when no controller program gives it: a
// CastorDriveBase (mospec/mobile-base) in a JSON-LD robot description.
struct BaseModelSource {
  std::string model;          // path of the JSON-LD file
  std::string configuration;  // the CastorDriveBase node to read
};

struct WorldConfig {
  BaseFidelity base = BaseFidelity::Wheeled;
  double control_period = 0.001;  // one control tick [s]
  int substeps = 2;               // physics steps per tick
  int command_delay_ticks = 1;    // 0 or 1: a command acts from the next tick on
  std::uint64_t seed = 0;

  RobotModelSource robot;         // the default source of every arm's chain
  std::vector<ArmSetup> arms;     // the robot's arms, in port order
  ArmActuation actuation;         // of every arm that states none of its own
  bool actuation_stated = false;  // the world file states `actuation`
  EndEffectorParameters end_effector;
  PlatformParameters platform;
  // The mobile base's drives: geometry and the weights of Eq. 2-3. Not a
  // default: the caller reads them from the robot description (`base_model`,
  // description::load_base) or takes the controller program's base
  // (ir::kelo_config), so the simulated base and the controller's are the
  // same numbers by construction.
  runtime::KeloConfig drives;
  BaseModelSource base_model;
  TableParameters table;
  MountParameters mount;
  InitialConditions initial;
  Perturbation perturbation;
};

// The default world: the paper's robot (arm mounts from the authors' models)
// in front of the table, arms in the "whisker" pose touching its edge.
WorldConfig default_world();

// The actuation of arm `arm`: its own, else the world's.
const ArmActuation& arm_actuation(const WorldConfig& config, std::size_t arm);
// The chain IRI the task models name arm `arm` by: its own, else the world's
// `robot.chain`.
const std::string& arm_chain(const WorldConfig& config, std::size_t arm);
// Where the chain of arm `arm` is read from: its own source, else the world's
// `robot` (an arm bound by another chain IRI, as the default robot's left
// arm, is the same description under the name its task models give it).
RobotModelSource arm_source(const WorldConfig& config, std::size_t arm);
// The default of an arm's actuation is its robot description's: an arm
// whose world file states no `actuation` (neither the arm's nor the world's)
// takes the limits of its chain (`chains`, one per arm) when the description
// states an effort limit for every joint (a kc-ext:JointLimit that is a
// kc-stat:JointForce, written by `mospec import-urdf` from the URDF's
// <limit>): those efforts, and the
// position limits where stated (elsewhere none). Otherwise the Gen3's.
void actuation_from_chains(WorldConfig& config, std::span<const runtime::Chain> chains);
// The robot interface's shape: the arms' names and joint counts (`joints`,
// one per arm, from their chains) and the base's drives (config.drives).
robot::RobotShape robot_shape(const WorldConfig& config, const std::vector<int>& joints);

// Reads a world file (JSON, schema in docs/simulation.md) over the defaults.
// Unknown keys and wrong types are errors located at file:line:col
// (mospec::Error "invalid-world"). Relative robot paths resolve against the
// file's directory.
// `check_files` false: the files the world names (robot descriptions, map
// directories) are resolved but not checked to lie inside the model tree, for
// a caller that reads only the robot's arms (their names and chains) and
// loads none of them.
WorldConfig parse_world_config(std::string_view text, const std::string& file_name,
                               bool check_files = true);
WorldConfig load_world_config(const std::string& path, bool check_files = true);

}  // namespace mospec::sim
