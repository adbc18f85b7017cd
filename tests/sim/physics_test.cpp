// Physics sanity of the generated world, each check with a stated tolerance.
#include <mujoco/mujoco.h>

#include <cmath>
#include <vector>

#include "sim_test_util.hpp"

namespace mospec::sim {
namespace {

using testing::mounts;
using testing::run;
using testing::test_world;

TEST(World, CompilesForEveryBase) {
  NEED_GEN3();
  for (BaseFidelity b : {BaseFidelity::Wheeled, BaseFidelity::Planar, BaseFidelity::Fixed}) {
    WorldConfig c = test_world();
    c.base = b;
    World w(c, arm_chain);
    const mjModel* m = w.mj_model();
    const int base_dofs = b == BaseFidelity::Wheeled  ? 6 + 4 + 8
                          : b == BaseFidelity::Planar ? 3
                                                      : 0;
    EXPECT_EQ(m->nv, 14 + base_dofs) << to_string(b);
    EXPECT_EQ(m->nu, b == BaseFidelity::Wheeled ? 22 : 14) << to_string(b);
    // Both fidelities carry the same mass: platform, drives, two arms.
    double arm_mass = 0;
    for (int i = 0; i < arm_chain.size(); ++i) arm_mass += arm_chain.segment(i).inertia.mass;
    EXPECT_NEAR(w.robot_mass(), 80 + 4 * (1.5 + 2 * 0.6) + 2 * arm_mass, 1e-9) << to_string(b);
  }
}

TEST(World, TableEdgeIsAtEndEffectorHeightAndTouching) {
  NEED_GEN3();
  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  World w(c, arm_chain);
  for (int k = 0; k < 2; ++k) {
    const runtime::Vec3 p = w.p_WoE_W(k);
    EXPECT_NEAR(p.z(), w.layout().table_height, 1e-3);  // the edge's height
    EXPECT_LT(p.x() + c.end_effector.radius, 1e-9);     // in front of the face
    EXPECT_GT(p.x() + c.end_effector.radius, -1e-3);    // touching it
  }
}

// Gravity compensation from the runtime's RNE holds the arms still.
TEST(Physics, GravityCompensationHoldsThePose) {
  NEED_GEN3();
  for (BaseFidelity b : {BaseFidelity::Fixed, BaseFidelity::Planar, BaseFidelity::Wheeled}) {
    WorldConfig c = test_world();
    c.base = b;
    c.table.present = false;
    World w(c, arm_chain);
    GravityCompensation g(arm_chain, mounts(c));
    robot::MeasuredState s0 = robot::make_state(robot::gen3_pair_shape());
    w.read(s0);
    run(w, 2000, [&](const robot::MeasuredState& s, robot::Command& cmd) { g.compute(s, cmd); });
    robot::MeasuredState s1 = robot::make_state(robot::gen3_pair_shape());
    w.read(s1);
    double drift = 0;
    for (int k = 0; k < 2; ++k) {
      for (int i = 0; i < 7; ++i) {
        const auto ak = static_cast<size_t>(k), ji = static_cast<size_t>(i);
        drift = std::max(drift, std::abs(s1.arm[ak].q[ji] - s0.arm[ak].q[ji]));
      }
    }
    // 2 s: under 2 mrad. On wheels, the arms' weight pitches the platform
    // forward by about 0.2 mrad on its compliant wheel contacts, which the
    // level-platform compensation does not see: under 20 mrad.
    EXPECT_LT(drift, b == BaseFidelity::Wheeled ? 2e-2 : 2e-3) << to_string(b);
  }
}

TEST(Physics, WithoutCompensationTheArmsFall) {
  NEED_GEN3();
  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  c.table.present = false;
  World w(c, arm_chain);
  robot::MeasuredState s0 = robot::make_state(robot::gen3_pair_shape()), s1 = s0;
  w.read(s0);
  run(w, 500, [](const robot::MeasuredState&, robot::Command& cmd) {
    cmd = robot::make_command(robot::gen3_pair_shape());
  });
  w.read(s1);
  EXPECT_GT(std::abs(s1.arm[0].q[1] - s0.arm[0].q[1]), 0.05);
}

// The robot's momentum, from a copy of the simulation data: total linear
// momentum and angular momentum about the world point O, in W.
struct Momentum {
  runtime::Vec3 p = runtime::Vec3::Zero();
  runtime::Vec3 L_O = runtime::Vec3::Zero();
};
Momentum momentum(const World& w, const runtime::Vec3& p_WoO_W) {
  const mjModel* m = w.mj_model();
  mjData* d = mj_makeData(m);
  mj_copyData(d, m, w.mj_data());
  mj_forward(m, d);
  mj_subtreeVel(m, d);
  const int b = mj_name2id(m, mjOBJ_BODY, "platform");
  const double mass = m->body_subtreemass[b];
  const runtime::Vec3 v(d->subtree_linvel[3 * b], d->subtree_linvel[3 * b + 1],
                        d->subtree_linvel[3 * b + 2]);
  const runtime::Vec3 c(d->subtree_com[3 * b], d->subtree_com[3 * b + 1],
                        d->subtree_com[3 * b + 2]);
  const runtime::Vec3 L(d->subtree_angmom[3 * b], d->subtree_angmom[3 * b + 1],
                        d->subtree_angmom[3 * b + 2]);
  Momentum out;
  out.p = mass * v;
  out.L_O = L + (c - p_WoO_W).cross(mass * v);
  mj_deleteData(d);
  return out;
}

// A commanded platform wrench, distributed to the drives by the runtime's KELO
// solver from the measured pivot angles, is the wrench the base receives once
// the drives have aligned: measured on wheels from the wheel-floor contact
// forces, and on both bases from the rate of change of the robot's momentum.
class PlatformWrench : public ::testing::TestWithParam<BaseFidelity> {};

TEST_P(PlatformWrench, ReachesTheBase) {
  NEED_GEN3();
  const BaseFidelity base = GetParam();
  std::vector<runtime::Vec3> wrenches = {runtime::Vec3(40, 0, 0), runtime::Vec3(0, -30, 0),
                                         runtime::Vec3(30, 20, 0), runtime::Vec3(0, 0, 4)};
  // A force together with a moment turns the force's direction in W: the
  // passive castors never settle and take lateral forces of their own, so
  // only the planar model (no castor dynamics) is held to it.
  if (base == BaseFidelity::Planar) wrenches.emplace_back(25, 15, 3);
  for (const runtime::Vec3& F_p : wrenches) {
    WorldConfig c = test_world();
    c.base = base;
    c.table.present = false;
    c.initial.base_x = 0.0;
    c.initial.pivot_q = {0.7, -1.2, 2.0, 0.3};  // misaligned at the start
    World w(c, arm_chain);
    GravityCompensation arms(arm_chain, mounts(c));
    PlatformWrenchDriver drives(c.drives);
    drives.F_p = F_p;
    auto control = [&](const robot::MeasuredState& s, robot::Command& cmd) {
      arms.compute(s, cmd);
      drives.compute(s, cmd);
    };
    run(w, 1500, control);  // the drives align
    // Average over 0.3 s: the contact wrench (wheels) and the momentum rate.
    const runtime::Pose X0 = w.X_WP();
    const Momentum m0 = momentum(w, X0.p);
    runtime::Vec3 contact = runtime::Vec3::Zero();
    const int n = 300;
    for (int k = 0; k < n; ++k) {
      run(w, 1, control);
      contact += w.ground_wrench_P() / n;
    }
    const runtime::Pose X1 = w.X_WP();
    const Momentum m1 = momentum(w, X0.p);
    const double T = n * c.control_period;
    const runtime::Vec3 f_W = (m1.p - m0.p) / T;
    // The moment about the fixed point O = Po(t0) is m_z + (Po - O) × f:
    // take out the second part with Po's mean position.
    const runtime::Vec3 p_OPo_W = (X1.p - X0.p) / 2;
    const double mz = (m1.L_O.z() - m0.L_O.z()) / T - p_OPo_W.cross(f_W).z();
    // The force seen by P half-way through the window.
    const double dyaw = std::atan2(X1.R(1, 0), X1.R(0, 0)) - std::atan2(X0.R(1, 0), X0.R(0, 0));
    const Eigen::Vector2d f_P = Eigen::Rotation2Dd(-dyaw / 2) * (X0.R.transpose() * f_W).head<2>();
    // Wrench tolerance: 5% of the wrench's size, its moment scaled by the
    // base's size L (pivot radius, about 0.29 m).
    const double L = 0.3;
    const double size = std::hypot(F_p.x(), F_p.y(), F_p.z() / L);
    const double tol_f = 0.05 * size, tol_m = 0.05 * size * L;
    const std::string what = std::string(to_string(base)) + " F_p = [" + std::to_string(F_p.x()) +
                             ", " + std::to_string(F_p.y()) + ", " + std::to_string(F_p.z()) + "]";
    EXPECT_NEAR(f_P.x(), F_p.x(), tol_f) << what << " (momentum)";
    EXPECT_NEAR(f_P.y(), F_p.y(), tol_f) << what << " (momentum)";
    EXPECT_NEAR(mz, F_p.z(), tol_m) << what << " (momentum)";
    if (base == BaseFidelity::Wheeled) {
      EXPECT_NEAR(contact.x(), F_p.x(), tol_f) << what << " (contacts)";
      EXPECT_NEAR(contact.y(), F_p.y(), tol_f) << what << " (contacts)";
      EXPECT_NEAR(contact.z(), F_p.z(), tol_m) << what << " (contacts)";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bases, PlatformWrench,
                         ::testing::Values(BaseFidelity::Wheeled, BaseFidelity::Planar),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// The end-effector pushed with 20 N against the table's edge sees 20 N (±5%).
TEST(Physics, PushOnTableGivesTheContactForce) {
  NEED_GEN3();
  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  World w(c, arm_chain);
  GravityCompensation g(arm_chain, mounts(c));
  g.f_E_P[robot::kRightArm] = runtime::Vec3(20, 0, 0);
  g.f_E_P[robot::kLeftArm] = runtime::Vec3(20, 0, 0);
  run(w, 1500, [&](const robot::MeasuredState& s, robot::Command& cmd) { g.compute(s, cmd); });
  for (int k = 0; k < 2; ++k) {
    const ArmContact contact = w.contact(k);
    EXPECT_GE(contact.contacts, 1);
    EXPECT_NEAR(contact.normal_force, 20.0, 1.0) << "arm " << k;
    // The table pushes back along -x.
    EXPECT_NEAR(contact.f_E_W.x(), -20.0, 1.0) << "arm " << k;
  }
}

// SC2's mount: the end-effectors stay anchored to the table under ±20 N, and
// the mount carries the force.
TEST(Physics, MountHoldsUnderTwentyNewtons) {
  NEED_GEN3();
  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  c.initial.contact_gap = 0.01;  // clear of the face: only the mount acts
  c.mount.active = true;
  for (const runtime::Vec3& f :
       {runtime::Vec3(20, 0, 0), runtime::Vec3(-20, 0, 0), runtime::Vec3(0, 20, 0),
        runtime::Vec3(0, -20, 0), runtime::Vec3(0, 0, 20), runtime::Vec3(0, 0, -20)}) {
    World w(c, arm_chain);
    const runtime::Vec3 p0[2] = {w.p_WoE_W(0), w.p_WoE_W(1)};
    GravityCompensation g(arm_chain, mounts(c));
    g.f_E_P = {f, f};
    run(w, 1500, [&](const robot::MeasuredState& s, robot::Command& cmd) { g.compute(s, cmd); });
    for (int k = 0; k < 2; ++k) {
      EXPECT_LT((w.p_WoE_W(k) - p0[k]).norm(), 2e-3) << "arm " << k << " f " << f.transpose();
      const ArmContact a = w.contact(k);
      EXPECT_EQ(a.contacts, 0);
      // The mount's force on the end-effector balances the arm's push.
      EXPECT_NEAR((a.f_mount_W + f).norm(), 0.0, 1.0) << "arm " << k << " f " << f.transpose();
    }
  }
}

// SC2: with the end-effectors mounted to the table and a passive base, the
// arms pushing towards the table move the robot backwards.
TEST(Physics, PushingOnTheMountMovesAPassiveBaseBack) {
  NEED_GEN3();
  for (BaseFidelity b : {BaseFidelity::Planar, BaseFidelity::Wheeled}) {
    WorldConfig c = test_world();
    c.base = b;
    c.initial.contact_gap = 0.01;
    c.mount.active = true;
    World w(c, arm_chain);
    const runtime::Vec3 p0 = w.p_WoE_W(0), base0 = w.X_WP().p;
    GravityCompensation g(arm_chain, mounts(c));
    g.f_E_P = {runtime::Vec3(20, 0, 0), runtime::Vec3(20, 0, 0)};
    run(w, 500, [&](const robot::MeasuredState& s, robot::Command& cmd) { g.compute(s, cmd); });
    EXPECT_LT(w.X_WP().p.x(), base0.x() - 0.01) << to_string(b);
    EXPECT_LT((w.p_WoE_W(0) - p0).norm(), 2e-3) << to_string(b);
  }
}

TEST(Physics, MountCanBeReleased) {
  NEED_GEN3();
  WorldConfig c = test_world();
  c.base = BaseFidelity::Fixed;
  c.initial.contact_gap = 0.01;
  c.mount.active = true;
  World w(c, arm_chain);
  GravityCompensation g(arm_chain, mounts(c));
  g.f_E_P = {runtime::Vec3(-20, 0, 0), runtime::Vec3(-20, 0, 0)};  // pull
  auto control = [&](const robot::MeasuredState& s, robot::Command& cmd) { g.compute(s, cmd); };
  run(w, 200, control);
  const runtime::Vec3 p0 = w.p_WoE_W(0);
  w.set_mount_active(false);
  run(w, 200, control);
  EXPECT_LT(w.p_WoE_W(0).x(), p0.x() - 0.01);  // pulled away
}

}  // namespace
}  // namespace mospec::sim
