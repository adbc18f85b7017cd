// The World as a robot: timing (command delay), faults, seeds and determinism,
// the CSV log and the world file.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "description/chain_jsonld.hpp"
#include "description/urdf_import.hpp"
#include "sim/log.hpp"
#include "sim_test_util.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::sim {
namespace {

using testing::mounts;
using testing::run;
using testing::test_world;

WorldConfig arm_only() {
  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  c.table.present = false;
  return c;
}

// The measured joint torque is the applied motor torque; with one tick of
// delay the command written at tick k acts from tick k+1 on.
TEST(World, CommandsActOneTickLater) {
  NEED_GEN3();
  for (int delay : {0, 1}) {
    WorldConfig c = arm_only();
    c.command_delay_ticks = delay;
    World w(c, arm_chain);
    robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
    robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
    std::vector<double> seen;
    for (int k = 0; k < 6; ++k) {
      w.read(s);
      seen.push_back(s.arm[robot::kLeftArm].tau[6]);
      cmd.arm_tau[robot::kLeftArm][6] = k >= 2 ? 1.5 : 0.0;
      w.write(cmd);
      w.step();
    }
    // Written at tick 2; applied during tick 2 (delay 0) or 3 (delay 1);
    // read back after that tick.
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(seen[static_cast<size_t>(k)], k >= 3 + delay ? 1.5 : 0.0)
          << "delay " << delay << " tick " << k;
    }
  }
}

TEST(World, TorquesAreLimitedToThePublishedEfforts) {
  NEED_GEN3();
  World w(arm_only(), arm_chain);
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  std::fill(cmd.arm_tau[0].begin(), cmd.arm_tau[0].end(), 100.0);
  w.write(cmd);
  w.step();
  w.step();
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  w.read(s);
  const robot::JointValues expected{39, 39, 39, 39, 9, 9, 9};
  EXPECT_EQ(s.arm[0].tau, expected);
}

// The robot interface clamps what it latches and counts it per actuator: a
// gain of 1e300 asks for 1e300 N·m, the robot applies 39 N·m.
TEST(World, CommandsBeyondTheLimitsAreClampedAndCounted) {
  NEED_GEN3();
  World w(arm_only(), arm_chain);
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  run(w, 5, [](const robot::MeasuredState& s, robot::Command& c) {
    c = robot::make_command(robot::gen3_pair_shape());
    if (s.clock.tick >= 2) c.arm_tau[robot::kLeftArm][4] = -1e300;
  });
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  w.read(s);
  EXPECT_EQ(s.arm[robot::kLeftArm].tau[4], -9.0);
  const robot::ClampRecord& r = w.limiter().records()[7 + 4];
  EXPECT_EQ(r.ticks, 3u);
  EXPECT_EQ(r.first_tick, 2u);
  EXPECT_EQ(r.max_requested, 1e300);
  EXPECT_EQ(r.limit, 9.0);
  int clamped = 0;
  for (const robot::ClampRecord& q : w.limiter().records()) clamped += q.ticks > 0 ? 1 : 0;
  EXPECT_EQ(clamped, 1);
}

// hub_wrench (what the limiter bounds) is kelo.hpp's composition G(q) F_d of
// the drive forces the hub torques make.
TEST(World, HubWrenchIsTheKeloComposition) {
  const runtime::KeloModel kelo(::mospec::testing::paper_base());
  runtime::KeloData data(kelo);
  const std::vector<double> q{0.7, -1.2, 2.0, 0.3};
  const std::vector<double> tau{1.0, -2.0, 0.5, 3.0, -1.5, 2.5, 0.25, -0.75};
  runtime::kelo_set_pivots(kelo, data, Eigen::Vector4d(q[0], q[1], q[2], q[3]));
  runtime::KeloDriveVector F_d(8);
  for (int i = 0; i < 4; ++i) {
    const double f_l = tau[static_cast<size_t>(2 * i)] / kelo.wheel_radius;
    const double f_r = tau[static_cast<size_t>(2 * i + 1)] / kelo.wheel_radius;
    F_d[2 * i] = f_l + f_r;
    F_d[2 * i + 1] = kelo.lateral_ratio * (f_r - f_l);
  }
  const runtime::Vec3 expected = data.G * F_d;
  const robot::PlatformWrench F = hub_wrench(kelo, q, tau);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(F[static_cast<size_t>(k)], expected[k], 1e-9) << k;
}

// A platform force of 4e10 N: every hub saturates, the wrench is held to the
// traction limit μ m g, and all of it is reported.
TEST(World, APlatformForceBeyondTractionIsClampedAndReported) {
  NEED_GEN3();
  WorldConfig c = test_world();
  c.base = BaseFidelity::Planar;
  c.table.present = false;
  World w(c, arm_chain);
  GravityCompensation arms(arm_chain, mounts(c));
  PlatformWrenchDriver drives(c.drives);
  drives.F_p = runtime::Vec3(4e10, 0, 0);
  run(w, 50, [&](const robot::MeasuredState& s, robot::Command& cmd) {
    arms.compute(s, cmd);
    drives.compute(s, cmd);
  });
  const auto records = w.limiter().records();
  const double traction = c.platform.wheel_friction * w.robot_mass() * 9.81;
  EXPECT_NEAR(w.limiter().limits().platform_force, traction, 1e-9 * traction);
  const robot::ClampRecord& force =
      records[static_cast<size_t>(w.limiter().platform_force_index())];
  EXPECT_EQ(force.ticks, 50u);
  EXPECT_EQ(force.first_tick, 0u);
  EXPECT_GT(force.max_requested, 1e10);
  for (int wh = 0; wh < 8; ++wh) {
    EXPECT_GT(records[static_cast<size_t>(14 + wh)].ticks, 0u) << wh;
  }
  // What the base receives stays within the limit.
  const runtime::Vec3 F = w.ground_wrench_P();
  EXPECT_LE(std::hypot(F.x(), F.y()), traction * (1 + 1e-9));
  EXPECT_GT(F.x(), 0.5 * traction);  // and still pushes forward
  // The arms held by gravity compensation: nothing else clamped.
  for (size_t j = 0; j < 14; ++j) EXPECT_EQ(records[j].ticks, 0u) << j;
}

TEST(World, ClockCountsTicks) {
  NEED_GEN3();
  World w(arm_only(), arm_chain);
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  w.read(s);
  EXPECT_EQ(s.clock.tick, 0u);
  EXPECT_EQ(s.clock.dt, 0.0);
  w.step();
  w.step();
  w.read(s);
  EXPECT_EQ(s.clock.tick, 2u);
  EXPECT_DOUBLE_EQ(s.clock.t, 0.002);
  EXPECT_DOUBLE_EQ(s.clock.dt, 0.001);
}

TEST(World, SensorFaultsReachTheControllerNotTheTruth) {
  NEED_GEN3();
  World w(arm_only(), arm_chain);
  w.faults().inject_nan("right_arm.q[1]", 2, 2);
  w.faults().inject_stale("left_arm.tau[0]", 1);
  GravityCompensation g(arm_chain, mounts(w.config()));
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape()), truth = s;
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  double held = 0;
  for (int k = 0; k < 6; ++k) {
    w.read(s);
    w.read_true(truth);
    EXPECT_EQ(std::isnan(s.arm[0].q[1]), k == 2 || k == 3) << k;
    EXPECT_FALSE(std::isnan(truth.arm[0].q[1]));
    if (k == 0) held = s.arm[1].tau[0];
    if (k >= 1) {
      EXPECT_EQ(s.arm[1].tau[0], held) << k;
    }
    g.compute(s, cmd);  // a NaN reading gives a zero command for that arm
    w.write(cmd);
    w.step();
  }
  EXPECT_EQ(w.rejected_entries(), 0u);
}

TEST(World, DroppedCommandsKeepThePreviousOne) {
  NEED_GEN3();
  WorldConfig c = arm_only();
  c.command_delay_ticks = 0;
  World w(c, arm_chain);
  w.faults().drop_commands(2, 2);
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> applied;
  for (int k = 0; k < 6; ++k) {
    cmd.arm_tau[0][6] = 0.1 * k;
    w.write(cmd);
    w.step();
    w.read(s);
    applied.push_back(s.arm[0].tau[6]);
  }
  const std::vector<double> expected{0.0, 0.1, 0.1, 0.1, 0.4, 0.5};
  for (size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(applied[k], expected[k], 1e-12) << k;
}

TEST(World, NonFiniteCommandsAreRejected) {
  NEED_GEN3();
  World w(arm_only(), arm_chain);
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  cmd.arm_tau[0][0] = std::numeric_limits<double>::quiet_NaN();
  cmd.wheel_tau[3] = std::numeric_limits<double>::infinity();
  w.write(cmd);
  w.step();
  w.step();
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  w.read(s);
  EXPECT_EQ(s.arm[0].tau[0], 0.0);
  EXPECT_EQ(w.rejected_entries(), 2u);
}

WorldConfig perturbed(std::uint64_t seed) {
  WorldConfig c = test_world();
  c.seed = seed;
  c.perturbation = {0.05, 0.02, 0.05, 0.5};
  return c;
}

std::string run_logged(const runtime::Chain& chain, const WorldConfig& c, int ticks) {
  World w(c, chain);
  GravityCompensation arms(chain, mounts(c));
  PlatformWrenchDriver drives(c.drives);
  drives.F_p = runtime::Vec3(10, 0, 1);
  arms.f_E_P = {runtime::Vec3(5, 0, 0), runtime::Vec3(5, 0, 0)};
  CsvLog log(w);
  run(w, ticks, [&](const robot::MeasuredState& s, robot::Command& cmd) {
    arms.compute(s, cmd);
    drives.compute(s, cmd);
    log.record(w);
  });
  return log.text();
}

TEST(World, SameSeedSameBytes) {
  NEED_GEN3();
  for (BaseFidelity b : {BaseFidelity::Wheeled, BaseFidelity::Planar}) {
    WorldConfig c = perturbed(42);
    c.base = b;
    const std::string a = run_logged(arm_chain, c, 400);
    const std::string again = run_logged(arm_chain, c, 400);
    EXPECT_EQ(a, again) << to_string(b);
    c.seed = 43;
    EXPECT_NE(a, run_logged(arm_chain, c, 400)) << to_string(b);
  }
}

TEST(World, SeedsPerturbTheInitialConditions) {
  NEED_GEN3();
  robot::MeasuredState nominal = robot::make_state(robot::gen3_pair_shape()), s1 = nominal,
                       s2 = nominal;
  World(test_world(), arm_chain).read(nominal);
  World(perturbed(1), arm_chain).read(s1);
  World(perturbed(2), arm_chain).read(s2);
  EXPECT_NE(s1.arm[0].q, nominal.arm[0].q);
  EXPECT_NE(s1.arm[0].q, s2.arm[0].q);
  EXPECT_NE(s1.pivot_q, s2.pivot_q);
  for (int i = 0; i < 7; ++i) {
    const auto j = static_cast<size_t>(i);
    EXPECT_LE(std::abs(s1.arm[1].q[j] - nominal.arm[1].q[j]), 0.05);
  }
  EXPECT_LE(std::abs(s1.truth.p_WoPo_W[0] - nominal.truth.p_WoPo_W[0]), 0.02);
  EXPECT_LE(std::abs(s1.truth.yaw - nominal.truth.yaw), 0.05);
  // Zero amplitudes: the seed changes nothing.
  WorldConfig c = test_world();
  c.seed = 99;
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  World(c, arm_chain).read(s);
  EXPECT_EQ(s.arm[0].q, nominal.arm[0].q);
}

TEST(CsvLog, HeaderAndRowsHaveTheSameColumns) {
  NEED_GEN3();
  const std::string text = run_logged(arm_chain, test_world(), 3);
  size_t lines = 0, start = 0;
  long columns = -1;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    ASSERT_NE(end, std::string::npos);
    const long n = std::count(text.begin() + static_cast<long>(start),
                              text.begin() + static_cast<long>(end), ',') +
                   1;
    if (columns < 0) columns = n;
    EXPECT_EQ(n, columns) << "line " << lines;
    start = end + 1;
    ++lines;
  }
  EXPECT_EQ(lines, 4u);
  EXPECT_EQ(columns, 1 + 2 * 21 + 4 + 8 + 4 + 2 * 10 + 3);
  EXPECT_EQ(text.substr(0, 13), "t,right_q0,ri");
}

TEST(WorldFile, OverridesTheDefaults) {
  const WorldConfig c = parse_world_config(R"({
    "base": "planar", "seed": 7, "substeps": 1,
    "initial": { "base_x": -1.5, "base_yaw": 0.1, "pivot_q": [0, 0.1, 0.2, 0.3] },
    "arms": { "left": { "q": [1, 2, 3, 4, 5, 6, "180 deg"], "chain": "https://ex.org/left" } },
    "perturbation": { "arm_q": 0.01 },
    "table": { "present": false, "pose": { "x": "50 cm", "y": -0.2, "yaw": "-90 deg" } },
    "mount": { "active": true },
    "robot": { "model": "robots/x.jsonld", "map": { "https://ex.org/": "ctx" } }
  })",
                                           "/data/worlds/w.json");
  EXPECT_EQ(c.base, BaseFidelity::Planar);
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.substeps, 1);
  EXPECT_EQ(*c.initial.base_x, -1.5);
  EXPECT_EQ(c.initial.pivot_q[3], 0.3);
  EXPECT_DOUBLE_EQ(c.arms[robot::kLeftArm].q0[6], 3.141592653589793);
  EXPECT_EQ(arm_chain(c, robot::kLeftArm), "https://ex.org/left");
  // The right arm is the world's robot: bound by its chain, the default's here.
  EXPECT_EQ(arm_chain(c, robot::kRightArm), c.robot.chain_iri);
  EXPECT_DOUBLE_EQ(c.table.x, 0.5);
  EXPECT_EQ(c.table.y, -0.2);
  EXPECT_DOUBLE_EQ(c.table.yaw, -1.5707963267948966);
  EXPECT_EQ(c.arms[robot::kRightArm].q0, test_world().arms[robot::kRightArm].q0);
  EXPECT_EQ(c.perturbation.arm_q, 0.01);
  EXPECT_FALSE(c.table.present);
  EXPECT_TRUE(c.mount.active);
  EXPECT_EQ(c.robot.model, "/data/worlds/robots/x.jsonld");  // relative to the file
  EXPECT_EQ(c.robot.maps.back().second, "/data/worlds/ctx");
}

std::string error_of(const std::string& text) {
  try {
    parse_world_config(text, "w.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(WorldFile, ErrorsAreLocated) {
  EXPECT_EQ(error_of("{\n  \"bse\": \"planar\"\n}"),
            "w.json:2:3: error: world: unknown key 'bse' (expected one of: base, "
            "control_period, substeps, command_delay_ticks, seed, robot, arms, actuation, "
            "end_effector, platform, table, mount, initial, perturbation)");
  EXPECT_EQ(error_of("{ \"base\": \"hover\" }"),
            "w.json:1:11: error: base: expected \"wheeled\", \"planar\" or \"fixed\"");
  EXPECT_EQ(error_of("{ \"arms\": { \"right\": { \"q\": [] } } }"),
            "w.json:1:29: error: arms.right.q: expected an array of 1 to 64 numbers, one per "
            "joint");
  EXPECT_EQ(error_of("{ \"arms\": { \"third\": { \"q\": [0] } } }"),
            "w.json:1:22: error: arms.third: a new arm needs its `robot` (model and chain) and "
            "`q` (mospec's default robot has the arms right and left)");
  {
    // A hostile file cannot grow the robot without bound: the 17th arm is refused.
    std::string many = "{ \"arms\": {";
    for (int i = 0; i < 15; ++i) {
      many += std::string(i ? ", " : " ") + "\"a" + std::to_string(i) +
              "\": { \"robot\": { \"model\": \"x.jsonld\", \"chain\": \"c\" }, \"q\": [0], "
              "\"actuation\": { \"effort_limit\": [1] } }";
    }
    many += " } }";
    EXPECT_NE(error_of(many).find("arms.a14: a robot has at most 16 arms"), std::string::npos)
        << error_of(many);
  }
  EXPECT_EQ(error_of("{ \"arms\": { \"Right\": { \"q\": [0] } } }"),
            "w.json:1:13: error: arms.Right: an arm's name must be 1 to 32 lower-case letters and "
            "digits (it prefixes sensor names and log columns)");
  EXPECT_EQ(error_of("{ \"arms\": { \"left\": { \"present\": false, \"q\": [0] } } }"),
            "w.json:1:21: error: arms.left: an absent arm takes no other keys");
  EXPECT_EQ(error_of("{ \"seed\": -1 }"), "w.json:1:11: error: seed: expected an integer 0..2^53");
  EXPECT_EQ(error_of("{ \"arms\": { \"left\": { \"mount\": { \"direction-cosine-x\": [1, 1, 0] } "
                     "} } }"),
            "w.json:1:32: error: arms.left.mount: the direction cosines are not a rotation");
  EXPECT_NE(error_of("{ \"base\": "), "no error");  // malformed JSON, located by the parser
}

// A world file comes with a downloaded bundle: the robot model and robot.map
// directories it names stay inside its own directory (or mospec's robots).
TEST(WorldFile, RobotFilesStayInsideTheWorldFilesTree) {
  namespace fs = std::filesystem;
  const fs::path tree = fs::temp_directory_path() / ("mospec-world-" + std::to_string(::getpid()));
  fs::remove_all(tree);
  fs::create_directories(tree / "bundle" / "robots");
  fs::create_directories(tree / "outside");
  fs::create_directory_symlink(tree / "outside", tree / "bundle" / "link-out");
  const std::string world = (tree / "bundle" / "w.json").string();
  const auto error = [&](const std::string& robot) -> std::string {
    try {
      parse_world_config("{ \"robot\": " + robot + " }", world);
    } catch (const Error& e) {
      return e.code() + ": " + e.diagnostic().message;
    }
    return "no error";
  };
  EXPECT_EQ(error(R"({ "model": "robots/arm.jsonld", "map": { "https://ex.org/": "ctx" } })"),
            "no error");
  for (const std::string robot : {
           R"({ "model": "../outside/arm.jsonld" })",
           R"({ "model": "/etc/passwd" })",
           R"({ "model": "link-out/arm.jsonld" })",
           R"({ "map": { "https://comp-rob2b.github.io/metamodels/": "/" } })",
           R"({ "map": { "https://ex.org/": "robots/../../outside" } })",
           R"({ "map": { "https://ex.org/": "link-out" } })",
       }) {
    const std::string e = error(robot);
    EXPECT_EQ(e.substr(0, e.find(':')), "invalid-world") << robot << " -> " << e;
    EXPECT_EQ(e.rfind("invalid-world: robot.", 0), 0u) << robot << " -> " << e;
    EXPECT_NE(e.find("lies outside the model tree"), std::string::npos) << e;
  }
  fs::remove_all(tree);
}

TEST(World, RejectsAChainThatDoesNotFitItsArm) {
  const runtime::Chain empty("base");
  try {
    World w(test_world(), empty);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: the chain 'base' -> 'base' of the right arm has 0 joints, but "
                 "arms.right.q has 7 entries; give one per joint");
  }
  // An arm whose world-file entry states another joint count: located there.
  NEED_GEN3();
  const WorldConfig c =
      parse_world_config("{ \"arms\": { \"left\": { \"q\": [0, 1, 0, 1, 0, 1] } } }", "w.json");
  try {
    World w(c, arm_chain);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "w.json:1:21: error: the chain 'base_link' -> 'EndEffector_Link' of the left arm "
                 "has 7 joints, but arms.left.q has 6 entries; give one per joint");
  }
}

// A robot of any arms and joint counts, revolute and prismatic: the default
// right Gen3, no left arm, and a two-joint "lift" (a vertical slide carrying a
// hinge). The world is built from the chains, the robot interface is sized by
// them, gravity compensation holds both, and the slide's limit is a force.
TEST(World, AnyArmsRevoluteAndPrismatic) {
  NEED_GEN3();
  runtime::Chain lift("lift_base");
  runtime::Segment slide;
  slide.link = "carriage";
  slide.joint = "slide";
  slide.type = runtime::JointType::Prismatic;
  slide.X_PJ.p = runtime::Vec3(0, 0, 0.1);
  slide.axis_J = runtime::Vec3::UnitZ();
  slide.inertia.mass = 2.0;
  slide.inertia.I_Scm_S = runtime::Mat3::Identity() * 0.01;
  lift.add_segment(slide);
  runtime::Segment hinge;
  hinge.link = "paddle";
  hinge.joint = "hinge";
  hinge.X_PJ.p = runtime::Vec3(0, 0, 0.05);
  hinge.axis_J = runtime::Vec3::UnitY();
  hinge.inertia.mass = 1.0;
  hinge.inertia.p_SoScm_S = runtime::Vec3(0, 0, 0.1);
  hinge.inertia.I_Scm_S = runtime::Mat3::Identity() * 0.005;
  lift.add_segment(hinge);

  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  c.table.present = false;
  c.arms.erase(c.arms.begin() + robot::kLeftArm);
  ArmSetup a;
  a.name = "lift";
  a.X_PB.p = runtime::Vec3(-0.2, 0, 0);
  a.q0 = {0.1, 0.3};
  a.actuation = ArmActuation{{200, 20}, {-0.05, -3}, {0.25, 3}, 0.05};
  c.arms.push_back(a);
  World w(c, std::vector<runtime::Chain>{arm_chain, lift});
  ASSERT_EQ(w.shape().arms.size(), 2u);
  EXPECT_EQ(w.shape().arms[1].name, "lift");
  EXPECT_EQ(w.shape().arms[1].joints, 2);
  EXPECT_NE(w.mjcf().find(R"(<joint name="lift_slide" type="slide")"), std::string::npos);
  EXPECT_NE(w.mjcf().find(R"(<joint name="lift_hinge" type="hinge")"), std::string::npos);
  robot::MeasuredState s = w.make_state();
  w.read(s);
  ASSERT_EQ(s.arm.size(), 2u);
  EXPECT_EQ(s.arm[0].q.size(), 7u);
  ASSERT_EQ(s.arm[1].q.size(), 2u);
  EXPECT_DOUBLE_EQ(s.arm[1].q[0], 0.1);

  GravityCompensation g(w.arms(), mounts(c));
  run(w, 500, [&](const robot::MeasuredState& m, robot::Command& cmd) { g.compute(m, cmd); });
  w.read(s);
  EXPECT_NEAR(s.arm[1].q[0], 0.1, 1e-3) << "the slide holds against gravity";
  EXPECT_NEAR(s.arm[1].q[1], 0.3, 1e-3) << "the hinge holds";
  EXPECT_NEAR(s.arm[1].tau[0], 9.81 * 3.0, 0.05) << "the slide carries both links [N]";
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(s.arm[0].q[j], c.arms[0].q0[j], 1e-3) << j;

  // The slide's actuator is limited in newtons; its record says so.
  robot::Command cmd = w.make_command();
  cmd.arm_tau[1][0] = 500.0;
  w.write(cmd);
  const robot::ClampRecord& slide_limit = w.limiter().records()[7];
  EXPECT_EQ(slide_limit.quantity, "lift_arm.tau[0]");
  EXPECT_EQ(std::string(slide_limit.unit), "N");
  EXPECT_EQ(slide_limit.ticks, 1u);
  EXPECT_EQ(std::string(w.limiter().records()[8].unit), "N·m");
  // And its sensors have names.
  w.faults().inject_nan("lift_arm.q[1]", 0);
  EXPECT_THROW(w.faults().inject_nan("left_arm.q[0]", 0), Error);
}

// A robot description whose joint limits are the published kc-ext:JointLimit,
// written by hand with the published context URL (which resolves to mospec's
// own context), loads, and its limits become the arm's actuation when the
// world file states none: efforts, and position limits where stated.
TEST(World, ActuationDefaultsToPublishedJointLimits) {
  const std::string urdf = R"(<robot name="duo">
  <link name="base"/>
  <link name="a"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="b"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>
    <origin xyz="0 0 0.2"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";
  description::ChainJsonldOptions options;
  options.base = "https://mospec.example/robots/duo/";
  options.limits = false;  // the limits below are the hand-written ones
  std::string text =
      description::chain_to_jsonld(description::chain_from_urdf(urdf, "base", "b"), options);
  const auto bound = [](const char* kind, const char* unit, double v) {
    return "{ \"@type\": \"Quantity\", \"quantity-kind\": \"" + std::string(kind) +
           "\", \"unit\": \"" + unit + "\", \"value\": " + std::to_string(v) + " }";
  };
  const auto limit = [&](const std::string& id, const char* type, const char* joint,
                         const char* kind, const char* unit, double lo, double hi) {
    return "{ \"@id\": \"" + id + "\", \"@type\": [\"JointLimit\", \"" + type +
           "\"], \"of-joint\": \"" + joint + "\", \"lower\": " + bound(kind, unit, lo) +
           ", \"upper\": " + bound(kind, unit, hi) + " },\n";
  };
  const std::string limits =
      limit("eff-1", "kc-stat:JointForce", "joint-j1", "Torque", "N-M", -40, 40) +
      limit("eff-2", "kc-stat:JointForce", "joint-j2", "Torque", "N-M", -12, 12) +
      limit("pos-2", "kc-stat:JointPosition", "joint-j2", "Angle", "RAD", -0.5, 1.5) +
      limit("vel-2", "kc-stat:JointVelocity", "joint-j2", "AngularVelocity", "RAD-PER-SEC", -2, 2);
  const std::string graph = "\"@graph\": [\n";
  text.insert(text.find(graph) + graph.size(), limits);
  const std::string qudt = "\"https://comp-rob2b.github.io/metamodels/qudt.json\",\n";
  text.insert(text.find(qudt) + qudt.size(),
              "\"https://comp-rob2b.github.io/metamodels/kinematic-chain/state.json\",\n"
              "\"https://secorolab.github.io/metamodels/kinematic-chain/"
              "structural-entities-extension.json\",\n");
  const std::string path =
      ::testing::TempDir() + "/mospec-duo-" + std::to_string(::getpid()) + ".jsonld";
  write_output(path, text);
  const runtime::Chain chain = description::load_chain(path, options.base + "chain");
  ASSERT_EQ(chain.size(), 2);
  EXPECT_EQ(chain.segment(1).limits.velocity, 2.0);

  WorldConfig c = default_world();
  c.arms.resize(1);
  actuation_from_chains(c, std::vector<runtime::Chain>{chain});
  ASSERT_TRUE(c.arms[0].actuation.has_value());
  const ArmActuation& a = *c.arms[0].actuation;
  EXPECT_EQ(a.effort_limit, (std::vector<double>{40, 12}));
  EXPECT_EQ(a.lower, (std::vector<double>{-1e9, -0.5}));  // j1 states no position limit
  EXPECT_EQ(a.upper, (std::vector<double>{1e9, 1.5}));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace mospec::sim
