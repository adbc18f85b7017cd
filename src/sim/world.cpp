#include "sim/world.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>

#include "support/diagnostics.hpp"

namespace mospec::sim {
namespace {

using runtime::Mat3;
using runtime::Vec3;

int id_of(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) {
    throw Error("mujoco", "internal: the generated model has no object named '" + name + "'");
  }
  return id;
}

// A uniform draw in [-1, 1) from 53 random bits (the same on every platform,
// unlike std::uniform_real_distribution).
double symmetric_unit(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-52 - 1.0;
}

// splitmix64: a small, fully specified generator.
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
};

double yaw_of(const Mat3& R) {
  return std::atan2(R(1, 0), R(0, 0));
}

Mat3 mat3(const mjtNum* xmat) {
  Mat3 R;
  R << xmat[0], xmat[1], xmat[2], xmat[3], xmat[4], xmat[5], xmat[6], xmat[7], xmat[8];
  return R;
}

}  // namespace

namespace {
std::vector<int> joint_counts(const std::vector<runtime::Chain>& arms) {
  std::vector<int> n;
  for (const runtime::Chain& c : arms) n.push_back(c.size());
  return n;
}
}  // namespace

World::World(const WorldConfig& config, std::vector<runtime::Chain> arms)
    : config_(config),
      chains_(std::move(arms)),
      shape_(robot_shape(config, joint_counts(chains_))),
      layout_(layout_world(config, chains_)),
      mjcf_(world_mjcf(config, chains_, layout_)),
      kelo_(config.drives),
      kelo_data_(kelo_) {
  // Compile the generated text from memory: one virtual file.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "mospec-world.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf_.size())) != 0) {
    throw Error("mujoco", "cannot create the in-memory model file");
  }
  const int f = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[f], mjcf_.data(), mjcf_.size());
  char error[1024] = {0};
  m_ = mj_loadXML(name, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (m_ == nullptr) {
    throw Error("mujoco", std::string("the generated world does not compile: ") + error);
  }
  d_ = mj_makeData(m_);
  if (d_ == nullptr) {
    mj_deleteModel(m_);
    throw Error("mujoco", "cannot allocate the simulation data");
  }

  try {
    const auto n = static_cast<size_t>(kelo_.drives);
    if (!config.initial.pivot_q.empty() && config.initial.pivot_q.size() != n) {
      throw Error("invalid-world", "initial.pivot_q has " +
                                       std::to_string(config.initial.pivot_q.size()) +
                                       " angles, but the base has " + std::to_string(n) +
                                       " drives; give one per drive");
    }
    initial_pivot_q_ = config.initial.pivot_q.empty() ? std::vector<double>(n, 0.0)
                                                      : config.initial.pivot_q;
    planar_pivot_q_.assign(n, 0.0);
    planar_wheel_qd_.assign(2 * n, 0.0);
    pivot_buffer_.assign(n, 0.0);
    pivot_work_ = runtime::KeloPivotVector::Zero(kelo_.drives);
    drive_work_ = runtime::KeloDriveVector::Zero(2 * kelo_.drives);
    declare();
  } catch (...) {
    mj_deleteData(d_);
    mj_deleteModel(m_);
    throw;
  }
  limiter_ = robot::CommandLimiter(command_limits());
  faults_ = robot::FaultInjector(shape_);
  set_initial_state();
}

// The arms' limits are Kinova's published efforts (config.actuation), the
// hubs' the drive's torque limit (config.platform). The platform wrench is
// bounded by traction: the floor pushes the robot with at most μ m g in total
// (μ the wheel–floor friction coefficient, m the robot's mass), and turns it
// with at most that force at the wheel contact farthest from Po. Beyond it the
// wheels would only slip.
robot::CommandLimits World::command_limits() const {
  robot::CommandLimits l;
  for (size_t k = 0; k < chains_.size(); ++k) {
    l.arm_names.push_back(config_.arms[k].name);
    l.arm_effort.push_back(arm_actuation(config_, k).effort_limit);
    std::vector<bool> prismatic;
    for (int i = 0; i < chains_[k].size(); ++i) {
      prismatic.push_back(chains_[k].segment(i).type == runtime::JointType::Prismatic);
    }
    l.arm_prismatic.push_back(std::move(prismatic));
  }
  l.wheel_torque.assign(static_cast<size_t>(2 * kelo_.drives), config_.platform.wheel_torque_limit);
  const double g =
      std::sqrt(m_->opt.gravity[0] * m_->opt.gravity[0] + m_->opt.gravity[1] * m_->opt.gravity[1] +
                m_->opt.gravity[2] * m_->opt.gravity[2]);
  l.platform_force = config_.platform.wheel_friction * robot_mass() * g;
  const runtime::KeloGeometry& geo = config_.drives.geometry;
  const double contact = std::hypot(geo.castor_offset, geo.wheel_distance / 2);
  double reach = 0.0;
  for (const runtime::Vec2& p : geo.p_PoAi_P) reach = std::max(reach, p.norm() + contact);
  l.platform_moment = l.platform_force * reach;
  return l;
}

void World::declare() {
  // Look everything up once.
  const size_t arms = chains_.size();
  arm_qpos_.assign(arms, {});
  arm_dof_.assign(arms, {});
  arm_act_.assign(arms, {});
  ee_geom_.assign(arms, -1);
  ee_site_.assign(arms, -1);
  mount_eq_.assign(arms, -1);
  for (size_t ak = 0; ak < arms; ++ak) {
    const std::string& a = config_.arms[ak].name;
    const runtime::Chain& arm = chains_[ak];
    for (int i = 0; i < arm.size(); ++i) {
      const std::string j = a + "_" + arm.segment(i).joint;
      const int jid = id_of(m_, mjOBJ_JOINT, j);
      arm_qpos_[ak].push_back(m_->jnt_qposadr[jid]);
      arm_dof_[ak].push_back(m_->jnt_dofadr[jid]);
      arm_act_[ak].push_back(id_of(m_, mjOBJ_ACTUATOR, j));
    }
    ee_geom_[ak] = id_of(m_, mjOBJ_GEOM, a + "_ee");
    ee_site_[ak] = id_of(m_, mjOBJ_SITE, a + "_ee");
    mount_eq_[ak] = config_.table.present ? id_of(m_, mjOBJ_EQUALITY, a + "_mount") : -1;
  }
  platform_body_ = id_of(m_, mjOBJ_BODY, "platform");
  floor_geom_ = id_of(m_, mjOBJ_GEOM, "floor");
  if (config_.table.present) {
    table_geom_ = id_of(m_, mjOBJ_GEOM, "table");
    table_body_ = id_of(m_, mjOBJ_BODY, "table");
  }
  if (config_.base == BaseFidelity::Wheeled) {
    const int b = id_of(m_, mjOBJ_JOINT, "base");
    base_qpos_ = m_->jnt_qposadr[b];
    base_dof_ = m_->jnt_dofadr[b];
    for (int i = 0; i < kelo_.drives; ++i) {
      const std::string n = "drive" + std::to_string(i);
      const int p = id_of(m_, mjOBJ_JOINT, n + "_pivot");
      pivot_qpos_.push_back(m_->jnt_qposadr[p]);
      pivot_dof_.push_back(m_->jnt_dofadr[p]);
      for (int side = 0; side < 2; ++side) {
        const std::string w = n + (side == 0 ? "_left" : "_right");
        wheel_dof_.push_back(m_->jnt_dofadr[id_of(m_, mjOBJ_JOINT, w)]);
        wheel_act_.push_back(id_of(m_, mjOBJ_ACTUATOR, w));
      }
    }
  } else if (config_.base == BaseFidelity::Planar) {
    const int b = id_of(m_, mjOBJ_JOINT, "base_x");
    base_qpos_ = m_->jnt_qposadr[b];
    base_dof_ = m_->jnt_dofadr[b];
  }
}

World::~World() {
  if (d_ != nullptr) mj_deleteData(d_);
  if (m_ != nullptr) mj_deleteModel(m_);
}

void World::set_initial_state() {
  mj_resetData(m_, d_);
  // Draw every perturbation, always in this order, so that one amplitude
  // never shifts another's draws: base x, y, yaw; pivots 0-3; then each arm's
  // joints in order (right 0-6, left 0-6 on the default robot).
  SplitMix64 rng{config_.seed};
  const Perturbation& pert = config_.perturbation;
  const double x = layout_.base_x + pert.base_xy * symmetric_unit(rng.next());
  const double y = config_.initial.base_y + pert.base_xy * symmetric_unit(rng.next());
  const double yaw = config_.initial.base_yaw + pert.base_yaw * symmetric_unit(rng.next());
  std::vector<double> pivots = initial_pivot_q_;
  for (double& q : pivots) q += pert.pivot_q * symmetric_unit(rng.next());
  for (size_t ak = 0; ak < chains_.size(); ++ak) {
    const ArmActuation& act = arm_actuation(config_, ak);
    for (size_t ji = 0; ji < arm_qpos_[ak].size(); ++ji) {
      double q = config_.arms[ak].q0[ji] + pert.arm_q * symmetric_unit(rng.next());
      q = std::min(std::max(q, act.lower[ji]), act.upper[ji]);
      d_->qpos[arm_qpos_[ak][ji]] = q;
    }
  }
  switch (config_.base) {
    case BaseFidelity::Wheeled: {
      mjtNum* q = d_->qpos + base_qpos_;
      q[0] = x;
      q[1] = y;
      q[2] = config_.platform.deck_height;
      q[3] = std::cos(yaw / 2);
      q[4] = 0;
      q[5] = 0;
      q[6] = std::sin(yaw / 2);
      for (size_t i = 0; i < pivot_qpos_.size(); ++i) d_->qpos[pivot_qpos_[i]] = pivots[i];
      break;
    }
    case BaseFidelity::Planar:
      d_->qpos[base_qpos_] = x;
      d_->qpos[base_qpos_ + 1] = y;
      d_->qpos[base_qpos_ + 2] = yaw;
      planar_pivot_q_ = pivots;
      break;
    case BaseFidelity::Fixed:
      break;  // placed by the model (perturbations of the base do not apply)
  }
  mj_forward(m_, d_);
  if (config_.table.present) {
    anchor_mounts();
    mount_active_ = config_.mount.active;
    for (int eq : mount_eq_) m_->eq_active[eq] = mount_active_ ? 1 : 0;
    mj_forward(m_, d_);
  }
  tick_ = 0;
  current_ = previous_ = make_command();
}

// Re-anchors each mount at the end-effector's current position: the point's
// coordinates in body 2 (the table) are data[3..5] of a connect constraint.
void World::anchor_mounts() noexcept {
  if (table_body_ < 0) return;
  const Vec3 p_WoTo_W(d_->xpos[3 * table_body_], d_->xpos[3 * table_body_ + 1],
                      d_->xpos[3 * table_body_ + 2]);
  const Mat3 R_WT = mat3(d_->xmat + 9 * table_body_);
  for (size_t k = 0; k < mount_eq_.size(); ++k) {
    const Vec3 p_TE = R_WT.transpose() * (p_WoE_W(static_cast<int>(k)) - p_WoTo_W);
    mjtNum* data = m_->eq_data + mjNEQDATA * mount_eq_[k];
    data[3] = p_TE.x();
    data[4] = p_TE.y();
    data[5] = p_TE.z();
  }
}

void World::set_mount_active(bool active) noexcept {
  if (table_body_ < 0) return;
  if (active && !mount_active_) anchor_mounts();
  mount_active_ = active;
  for (int eq : mount_eq_) m_->eq_active[eq] = active ? 1 : 0;
}

double World::time() const noexcept {
  return static_cast<double>(tick_) * config_.control_period;
}

void World::read_true(robot::MeasuredState& s) const noexcept {
  s.clock.tick = tick_;
  s.clock.t = time();
  s.clock.dt = tick_ == 0 ? 0.0 : config_.control_period;
  for (size_t ak = 0; ak < arm_qpos_.size(); ++ak) {
    robot::ArmMeasurement& a = s.arm[ak];
    for (size_t ji = 0; ji < arm_qpos_[ak].size(); ++ji) {
      a.q[ji] = d_->qpos[arm_qpos_[ak][ji]];
      a.qd[ji] = d_->qvel[arm_dof_[ak][ji]];
      a.tau[ji] = d_->actuator_force[arm_act_[ak][ji]];
    }
  }
  switch (config_.base) {
    case BaseFidelity::Wheeled:
      for (size_t i = 0; i < pivot_qpos_.size(); ++i) s.pivot_q[i] = d_->qpos[pivot_qpos_[i]];
      for (size_t w = 0; w < wheel_dof_.size(); ++w) s.wheel_qd[w] = d_->qvel[wheel_dof_[w]];
      break;
    case BaseFidelity::Planar:
      std::copy(planar_pivot_q_.begin(), planar_pivot_q_.end(), s.pivot_q.begin());
      std::copy(planar_wheel_qd_.begin(), planar_wheel_qd_.end(), s.wheel_qd.begin());
      break;
    case BaseFidelity::Fixed:
      std::copy(initial_pivot_q_.begin(), initial_pivot_q_.end(), s.pivot_q.begin());
      std::fill(s.wheel_qd.begin(), s.wheel_qd.end(), 0.0);
      break;
  }
  const mjtNum* p = d_->xpos + 3 * platform_body_;
  const mjtNum* q = d_->xquat + 4 * platform_body_;
  s.truth.p_WoPo_W = {p[0], p[1], p[2]};
  s.truth.quat_WP = {q[0], q[1], q[2], q[3]};
  s.truth.yaw = yaw_of(mat3(d_->xmat + 9 * platform_body_));
}

void World::read(robot::MeasuredState& s) noexcept {
  read_true(s);
  faults_.corrupt(s);
}

void World::write(const robot::Command& command) noexcept {
  if (faults_.drops(tick_)) return;
  current_ = command;
  auto clean = [this](double& x) {
    if (!std::isfinite(x)) {
      x = 0.0;
      ++rejected_;
    }
  };
  for (auto& arm : current_.arm_tau) {
    for (double& t : arm) clean(t);
  }
  for (double& t : current_.wheel_tau) clean(t);
  limiter_.clamp(current_, tick_,
                 [this](std::span<const double> tau) noexcept { return platform_wrench(tau); });
  // Before the first tick there is no earlier command: the robot starts with
  // the first one (brakes released as the loop starts), not with zero torque.
  if (tick_ == 0) previous_ = current_;
}

void World::apply_command(const robot::Command& c) noexcept {
  for (size_t ak = 0; ak < arm_act_.size(); ++ak) {
    for (size_t i = 0; i < arm_act_[ak].size(); ++i) d_->ctrl[arm_act_[ak][i]] = c.arm_tau[ak][i];
  }
  if (config_.base == BaseFidelity::Wheeled) {
    for (size_t w = 0; w < wheel_act_.size(); ++w) d_->ctrl[wheel_act_[w]] = c.wheel_tau[w];
  }
}

// The planar base: wheel torques -> drive forces (massless drives rolling
// without slip, kelo.hpp) -> platform wrench G F_d, applied to the planar joints.
void World::planar_forces() noexcept {
  const robot::Command& c = config_.command_delay_ticks == 1 ? previous_ : current_;
  const double r = kelo_.wheel_radius, limit = config_.platform.wheel_torque_limit;
  runtime::KeloDriveVector& F_d = drive_work_;
  for (int i = 0; i < kelo_.drives; ++i) {
    const auto l = static_cast<size_t>(2 * i), rr = l + 1;
    const double f_l = std::clamp(c.wheel_tau[l], -limit, limit) / r;
    const double f_r = std::clamp(c.wheel_tau[rr], -limit, limit) / r;
    F_d[2 * i] = f_l + f_r;
    F_d[2 * i + 1] = kelo_.lateral_ratio * (f_r - f_l);
  }
  for (int i = 0; i < kelo_.drives; ++i) pivot_work_[i] = planar_pivot_q_[static_cast<size_t>(i)];
  runtime::kelo_set_pivots(kelo_, kelo_data_, pivot_work_);
  planar_F_p_.noalias() = kelo_data_.G * F_d;
  const double yaw = d_->qpos[base_qpos_ + 2];
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  d_->qfrc_applied[base_dof_] = cy * planar_F_p_[0] - sy * planar_F_p_[1];
  d_->qfrc_applied[base_dof_ + 1] = sy * planar_F_p_[0] + cy * planar_F_p_[1];
  d_->qfrc_applied[base_dof_ + 2] = planar_F_p_[2];
}

// The planar base's castors follow the platform's motion (no lateral slip).
void World::planar_drives_after_step() noexcept {
  const double yaw = d_->qpos[base_qpos_ + 2];
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const double vx = d_->qvel[base_dof_], vy = d_->qvel[base_dof_ + 1];
  const runtime::Vec3 xd_p(cy * vx + sy * vy, -sy * vx + cy * vy, d_->qvel[base_dof_ + 2]);
  for (int i = 0; i < kelo_.drives; ++i) pivot_work_[i] = planar_pivot_q_[static_cast<size_t>(i)];
  runtime::kelo_set_pivots(kelo_, kelo_data_, pivot_work_);
  runtime::kelo_wheel_rates(kelo_, kelo_data_, xd_p);
  const double h = m_->opt.timestep;
  for (int i = 0; i < kelo_.drives; ++i) {
    double& p = planar_pivot_q_[static_cast<size_t>(i)];
    p = std::remainder(p + h * kelo_data_.qd_pivot[i], 2 * std::numbers::pi);
  }
  for (int w = 0; w < 2 * kelo_.drives; ++w) {
    planar_wheel_qd_[static_cast<size_t>(w)] = kelo_data_.wheel_rates[w];
  }
}

void World::step() noexcept {
  apply_command(config_.command_delay_ticks == 1 ? previous_ : current_);
  for (int s = 0; s < config_.substeps; ++s) {
    if (config_.base == BaseFidelity::Planar) planar_forces();
    mj_step(m_, d_);
    if (config_.base == BaseFidelity::Planar) planar_drives_after_step();
  }
  // mj_step leaves the positions one physics step ahead of the poses derived
  // from them: update the poses (cheap) so that ground-truth poses match the
  // state read. Contacts and constraint forces stay those of the last physics
  // step: the forces that acted.
  mj_kinematics(m_, d_);
  previous_ = current_;
  ++tick_;
}

ArmContact World::contact(int arm) const noexcept {
  ArmContact out;
  const auto ak = static_cast<size_t>(arm);
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& c = d_->contact[i];
    const bool first = c.geom1 == ee_geom_[ak] && c.geom2 == table_geom_;
    const bool second = c.geom2 == ee_geom_[ak] && c.geom1 == table_geom_;
    if (!first && !second) continue;
    mjtNum f[6];
    mj_contactForce(m_, d_, i, f);
    // The contact frame's rows are its axes in W (normal first, from geom1
    // to geom2); f is what geom1 exerts on geom2.
    Vec3 f_W = Vec3::Zero();
    for (int r = 0; r < 3; ++r) {
      f_W += f[r] * Vec3(c.frame[3 * r], c.frame[3 * r + 1], c.frame[3 * r + 2]);
    }
    ++out.contacts;
    out.normal_force += f[0];
    out.f_E_W += second ? f_W : Vec3(-f_W);
  }
  if (mount_active_ && mount_eq_[ak] >= 0) {
    for (int r = 0; r < d_->nefc; ++r) {
      if (d_->efc_type[r] == mjCNSTR_EQUALITY && d_->efc_id[r] == mount_eq_[ak] &&
          r + 2 < d_->nefc) {
        // A connect constraint's three rows are the world-frame components of
        // the force on body 1 (the end-effector).
        out.f_mount_W = Vec3(d_->efc_force[r], d_->efc_force[r + 1], d_->efc_force[r + 2]);
        break;
      }
    }
  }
  return out;
}

Vec3 World::p_WoE_W(int arm) const noexcept {
  const mjtNum* p = d_->site_xpos + 3 * ee_site_[static_cast<size_t>(arm)];
  return {p[0], p[1], p[2]};
}

runtime::Pose World::X_WP() const noexcept {
  runtime::Pose X;
  X.R = mat3(d_->xmat + 9 * platform_body_);
  const mjtNum* p = d_->xpos + 3 * platform_body_;
  X.p = Vec3(p[0], p[1], p[2]);
  return X;
}

Vec3 World::ground_wrench_P() const noexcept {
  if (config_.base == BaseFidelity::Planar) return planar_F_p_;
  if (config_.base == BaseFidelity::Fixed) return Vec3::Zero();
  const runtime::Pose X = X_WP();
  Vec3 f_W = Vec3::Zero(), n_W = Vec3::Zero();
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& c = d_->contact[i];
    if (c.geom1 != floor_geom_ && c.geom2 != floor_geom_) continue;
    mjtNum f[6];
    mj_contactForce(m_, d_, i, f);
    Vec3 fc = Vec3::Zero();
    for (int r = 0; r < 3; ++r) {
      fc += f[r] * Vec3(c.frame[3 * r], c.frame[3 * r + 1], c.frame[3 * r + 2]);
    }
    if (c.geom2 == floor_geom_) fc = -fc;  // the force on the wheel (geom 2 is the robot)
    f_W += fc;
    n_W += (Vec3(c.pos[0], c.pos[1], c.pos[2]) - X.p).cross(fc);
  }
  const Vec3 f_P = X.R.transpose() * f_W, n_P = X.R.transpose() * n_W;
  return {f_P.x(), f_P.y(), n_P.z()};
}

robot::PlatformWrench hub_wrench(const runtime::KeloModel& model, std::span<const double> pivot_q,
                                 std::span<const double> wheel_tau) noexcept {
  // F_p = sum_i G_i(q_i) F_d,i with kelo.hpp's 3x2 block G_i.
  robot::PlatformWrench F_p{0.0, 0.0, 0.0};
  const double r = model.wheel_radius;
  for (int i = 0; i < model.drives; ++i) {
    const auto ii = static_cast<size_t>(i);
    const double f_l = wheel_tau[2 * ii] / r, f_r = wheel_tau[2 * ii + 1] / r;
    const double f_x = f_l + f_r, f_y = model.lateral_ratio * (f_r - f_l);
    const double c = std::cos(pivot_q[ii]), s = std::sin(pivot_q[ii]);
    const double x = model.config.geometry.p_PoAi_P[ii].x();
    const double y = model.config.geometry.p_PoAi_P[ii].y();
    F_p[0] += c * f_x - s * f_y;
    F_p[1] += s * f_x + c * f_y;
    F_p[2] += (x * s - y * c) * f_x + (x * c + y * s) * f_y;
  }
  return F_p;
}

robot::PlatformWrench World::platform_wrench(std::span<const double> wheel_tau) const noexcept {
  switch (config_.base) {
    case BaseFidelity::Wheeled:
      for (size_t i = 0; i < pivot_qpos_.size(); ++i) pivot_buffer_[i] = d_->qpos[pivot_qpos_[i]];
      return hub_wrench(kelo_, pivot_buffer_, wheel_tau);
    case BaseFidelity::Planar:
      return hub_wrench(kelo_, planar_pivot_q_, wheel_tau);
    case BaseFidelity::Fixed:
      break;
  }
  return hub_wrench(kelo_, initial_pivot_q_, wheel_tau);
}

int World::instabilities() const noexcept {
  int n = 0;
  for (int w :
       {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC, mjWARN_CONTACTFULL, mjWARN_CNSTRFULL}) {
    n += d_->warning[w].number;
  }
  return n;
}

double World::robot_mass() const noexcept {
  double m = 0.0;
  for (int b = 1; b < m_->nbody; ++b) {
    if (b != table_body_) m += m_->body_mass[b];
  }
  return m;
}

}  // namespace mospec::sim
