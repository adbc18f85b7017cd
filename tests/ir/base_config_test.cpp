// The mobile base comes from the model: lowering reads the CastorDriveBase a
// platform solver's `configuration` names (mospec/mobile-base) into the
// program, the lowered base distributes a platform wrench exactly, and a
// simulated base built from the program drives where it is pushed. The bases
// are tests/ir/data/diamond-base (four drives, not the paper's layout) and
// tri-base (three drives); the paper's is robots/kelo-base.jsonld, which SC1
// names.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "app/app.hpp"
#include "default_robot_ports.hpp"
#include "description/robot_model.hpp"
#include "ir/lower.hpp"
#include "kelo_base.hpp"
#include "runtime/kelo.hpp"
#include "sim/drivers.hpp"
#include "sim/world.hpp"
#include "vocab/metamodels.hpp"

namespace mospec::ir {
namespace {

const std::string kSource = MOSPEC_SOURCE_DIR;

Program lower_app(const std::string& app) {
  app::LoadOptions options;
  options.root = kSource;
  app::LoadedModel model = app::load({kSource + "/" + app}, options);
  LowerOptions lower_options;
  lower_options.ports = testing::default_robot_ports();
  return lower(model, lower_options);
}

const Program& diamond() {
  static const Program p = lower_app("tests/ir/data/diamond-base/app.json");
  return p;
}

// Three drives, 120 degrees apart: a drive count other than the paper's.
const Program& tri() {
  static const Program p = lower_app("tests/ir/data/tri-base/app.json");
  return p;
}

TEST(BaseConfiguration, LoweringReadsAThreeDriveBase) {
  const Program& p = tri();
  ASSERT_TRUE(p.base.has_value());
  const runtime::KeloConfig& c = p.base->config;
  ASSERT_EQ(c.geometry.p_PoAi_P.size(), 3u);
  EXPECT_EQ(c.geometry.p_PoAi_P[1], runtime::Vec2(-0.15, 0.26));
  EXPECT_EQ(c.drive_weight.size(), 3u);
  EXPECT_EQ(runtime::KeloModel(c).drives, 3);
}

// Every number of base.jsonld, as lowering put it into the program.
TEST(BaseConfiguration, LoweringReadsTheNamedBase) {
  const Program& p = diamond();
  ASSERT_TRUE(p.base.has_value());
  EXPECT_EQ(p.base->configuration, "https://mospec.example/tests/diamond-base/base");
  const runtime::KeloConfig& c = p.base->config;
  const runtime::Vec2 pivots[] = {{0.35, 0.0}, {0.0, 0.25}, {-0.35, 0.0}, {0.0, -0.25}};
  const double weight[] = {1, 2, 1, 2}, force[] = {1, 0.5, 1, 0.5}, moment[] = {1, 1, 0.5, 1};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c.geometry.p_PoAi_P[i], pivots[i]) << i;
    EXPECT_EQ(c.drive_weight[i], weight[i]) << i;
    EXPECT_EQ(c.align_force_weight[i], force[i]) << i;
    EXPECT_EQ(c.align_moment_weight[i], moment[i]) << i;
  }
  EXPECT_EQ(c.geometry.wheel_radius, 0.05);
  EXPECT_EQ(c.geometry.wheel_distance, 0.09);
  EXPECT_EQ(c.geometry.castor_offset, 0.02);
}

// SC1 names robots/kelo-base.jsonld: the same doubles as the reader gives
// for that file on its own (what `mospec sim` and the tests build).
TEST(BaseConfiguration, Sc1NamesThePaperBase) {
  const Program p = lower_app("models/sc1.json");
  ASSERT_TRUE(p.base.has_value());
  EXPECT_EQ(p.base->configuration, std::string(vocab::robots::kelo_base));
  const runtime::KeloConfig& a = p.base->config;
  const runtime::KeloConfig& b = ::mospec::testing::paper_base();
  EXPECT_EQ(a.geometry.p_PoAi_P, b.geometry.p_PoAi_P);
  EXPECT_EQ(a.geometry.wheel_radius, b.geometry.wheel_radius);
  EXPECT_EQ(a.geometry.wheel_distance, b.geometry.wheel_distance);
  EXPECT_EQ(a.geometry.castor_offset, b.geometry.castor_offset);
  EXPECT_EQ(a.drive_weight, b.drive_weight);
  EXPECT_EQ(a.align_force_weight, b.align_force_weight);
  EXPECT_EQ(a.align_moment_weight, b.align_moment_weight);
}

// Eq. 2-3 on the lowered base: G(q) F_d = F_p for random pivot angles and
// wrenches (the weights and the alignment reference change F_d, never its
// resultant).
TEST(BaseConfiguration, TheLoweredBaseDistributesAWrenchExactly) {
  for (const Program* p : {&diamond(), &tri()}) {
    const runtime::KeloModel model(kelo_config(*p->base));
    runtime::KeloData data(model);
    std::mt19937 rng(16);
    std::uniform_real_distribution<double> angle(-3.14, 3.14), force(-200.0, 200.0);
    for (int k = 0; k < 200; ++k) {
      runtime::KeloPivotVector q(model.drives);
      for (int i = 0; i < model.drives; ++i) q[i] = angle(rng);
      const runtime::Vec3 F_p(force(rng), force(rng), 0.3 * force(rng));
      runtime::kelo_force_step(model, data, q, F_p);
      ASSERT_FALSE(data.input_fault);
      ASSERT_EQ(data.F_d.size(), 2 * model.drives);
      const runtime::Vec3 resultant = data.G * data.F_d;
      for (int i = 0; i < 3; ++i) {
        ASSERT_NEAR(resultant[i], F_p[i], 1e-9 * (1 + F_p.norm())) << model.drives << " " << k;
      }
    }
  }
  const runtime::KeloModel model(kelo_config(*diamond().base));
  runtime::KeloData data(model);
  // The drive weights act: the heavier-weighted side drives (W^-1 = 2) carry
  // more of a pure lateral force than the unit-weighted ones.
  runtime::kelo_set_pivots(model, data, runtime::Vec4::Zero());
  runtime::kelo_distribute(model, data, runtime::Vec3(0, 100, 0),
                           runtime::KeloDriveVector::Zero(2 * model.drives));
  EXPECT_NEAR(data.F_d[3], 2 * data.F_d[1], 1e-9);
}

// A simulated base built from the program (not from a copy of its numbers):
// pushed forward and left, it moves forward and left.
TEST(BaseConfiguration, TheSimulatedBaseDrivesWherePushed) {
  sim::WorldConfig c = sim::default_world();
  for (const auto& [prefix, dir] : c.robot.maps) {
    if (!std::filesystem::exists(dir)) GTEST_SKIP() << "needs the published metamodels";
  }
  const runtime::Chain arm =
      description::load_chain(c.robot.model, c.robot.chain_iri, c.robot.maps);
  c.table.present = false;
  for (const Program* p : {&diamond(), &tri()})
    for (sim::BaseFidelity fidelity : {sim::BaseFidelity::Planar, sim::BaseFidelity::Wheeled}) {
      c.drives = kelo_config(*p->base);
      c.base = fidelity;
      sim::World world(c, arm);
      ASSERT_EQ(world.shape().drives, static_cast<int>(c.drives.geometry.p_PoAi_P.size()));
      sim::GravityCompensation arms(arm,
                                    std::vector<runtime::Pose>{c.arms[0].X_PB, c.arms[1].X_PB});
      sim::PlatformWrenchDriver drives(c.drives);
      drives.F_p = runtime::Vec3(60, 30, 0);  // forward and left, in P
      robot::MeasuredState s = world.make_state(), start = s;
      robot::Command command = world.make_command();
      world.read(start);
      for (int k = 0; k < 1500; ++k) {
        world.read(s);
        arms.compute(s, command);
        drives.compute(s, command);
        world.write(command);
        world.step();
      }
      world.read(s);
      const double dx = s.truth.p_WoPo_W[0] - start.truth.p_WoPo_W[0];
      const double dy = s.truth.p_WoPo_W[1] - start.truth.p_WoPo_W[1];
      const std::string base = std::string(sim::to_string(fidelity)) + ", " +
                               std::to_string(world.shape().drives) + " drives";
      EXPECT_GT(std::hypot(dx, dy), 0.05) << base << ": the base moves";
      // Along the commanded direction (1, 0.5) (yaw 0 at the start): within 15°.
      EXPECT_GT((dx * 1.0 + dy * 0.5) / (std::hypot(dx, dy) * std::hypot(1.0, 0.5)),
                std::cos(15.0 * 3.14159265358979 / 180.0))
          << base << ": moved (" << dx << ", " << dy << ")";
      EXPECT_LT(std::abs(s.truth.yaw - start.truth.yaw), 0.1) << base;
    }
}

}  // namespace
}  // namespace mospec::ir
