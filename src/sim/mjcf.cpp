#include "sim/mjcf.hpp"

#include <charconv>
#include <cmath>
#include <initializer_list>

#include "runtime/kinematics.hpp"
#include "runtime/model.hpp"
#include "support/diagnostics.hpp"

namespace mospec::sim {
namespace {

using runtime::Mat3;
using runtime::Pose;
using runtime::Vec3;

// Shortest round-trip text: the same model gives the same bytes.
std::string num(double x) {
  if (x == 0.0) return "0";  // also folds -0
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  (void)ec;
  return std::string(buf, end);
}

std::string nums(std::initializer_list<double> xs) {
  std::string out;
  for (double x : xs) {
    if (!out.empty()) out += ' ';
    out += num(x);
  }
  return out;
}

std::string vec(const Vec3& v) {
  return nums({v.x(), v.y(), v.z()});
}

std::string quat(const Mat3& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return nums({q.w(), q.x(), q.y(), q.z()});
}

std::string yaw_quat(double yaw) {
  return nums({std::cos(yaw / 2), 0.0, 0.0, std::sin(yaw / 2)});
}

// Contact bits.
constexpr int kFloorBit = 1;
constexpr int kTableBit = 2;
const char* const kVisual = R"( contype="0" conaffinity="0" group="1")";

std::string inertial(double mass, const Vec3& com, const Mat3& I) {
  return R"(<inertial pos=")" + vec(com) + R"(" mass=")" + num(mass) + R"(" fullinertia=")" +
         nums({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}) + "\"/>\n";
}

std::string diag_inertial(double mass, const Vec3& com, const Vec3& d) {
  return R"(<inertial pos=")" + vec(com) + R"(" mass=")" + num(mass) + R"(" diaginertia=")" +
         vec(d) + "\"/>\n";
}

Vec3 box_inertia(double m, const std::array<double, 3>& s) {
  return {m / 12 * (s[1] * s[1] + s[2] * s[2]), m / 12 * (s[0] * s[0] + s[2] * s[2]),
          m / 12 * (s[0] * s[0] + s[1] * s[1])};
}

// One arm: its base on the platform, one body per chain segment.
void arm_bodies(std::string& x, const WorldConfig& c, const runtime::Chain& chain, int arm) {
  const ArmSetup& setup = c.arms[static_cast<size_t>(arm)];
  const ArmActuation& act = arm_actuation(c, static_cast<size_t>(arm));
  const std::string& a = setup.name;
  x += R"(<body name=")" + a + R"(_base" pos=")" + vec(setup.X_PB.p) + R"(" quat=")" +
       quat(setup.X_PB.R) + "\">\n";
  x += R"(<geom type="cylinder" size="0.045 0.05" pos="0 0 0.05" rgba="0.3 0.3 0.3 1")" +
       std::string(kVisual) + "/>\n";
  for (int i = 0; i < chain.size(); ++i) {
    const runtime::Segment& s = chain.segment(i);
    const auto j = static_cast<size_t>(i);
    x += R"(<body name=")" + a + "_" + s.link + R"(" pos=")" + vec(s.X_PJ.p) + R"(" quat=")" +
         quat(s.X_PJ.R) + "\">\n";
    // Every moving body needs mass; a massless segment gets a token 1 g.
    const double mass = s.inertia.mass > 1e-6 ? s.inertia.mass : 1e-3;
    Mat3 I = s.inertia.I_Scm_S;
    if (I.trace() < 1e-9) I = Mat3::Identity() * 1e-7;
    x += inertial(mass, s.inertia.p_SoScm_S, I);
    const bool limited = act.lower[j] > -1e8 || act.upper[j] < 1e8;
    const char* type = s.type == runtime::JointType::Prismatic ? "slide" : "hinge";
    x += R"(<joint name=")" + a + "_" + s.joint + R"(" type=")" + type + R"(" axis=")" +
         vec(s.axis_J) + R"(" damping=")" + num(act.damping) + R"(" armature=")" + num(s.armature) +
         "\"";
    if (limited) x += R"( limited="true" range=")" + nums({act.lower[j], act.upper[j]}) + "\"";
    x += "/>\n";
    // A capsule from this joint to the next (or to the tip).
    const Vec3 next = i + 1 < chain.size() ? chain.segment(i + 1).X_PJ.p : chain.X_NT().p;
    const double radius = i < 4 ? 0.04 : 0.032;
    if (next.norm() > 1e-3) {
      x += R"(<geom type="capsule" fromto="0 0 0 )" + vec(next) + R"(" size=")" + num(radius) +
           R"(" rgba="0.75 0.75 0.8 1")" + kVisual + "/>\n";
    } else {
      x += R"(<geom type="sphere" size=")" + num(radius) + R"(" rgba="0.75 0.75 0.8 1")" + kVisual +
           "/>\n";
    }
  }
  // The end-effector contact sphere at the tip frame, in the last segment.
  const Vec3& p_NT = chain.X_NT().p;
  x += R"(<site name=")" + a + R"(_ee" pos=")" + vec(p_NT) + "\"/>\n";
  x += R"(<geom name=")" + a + R"(_ee" type="sphere" size=")" + num(c.end_effector.radius) +
       R"(" pos=")" + vec(p_NT) + R"(" contype="0" conaffinity=")" + std::to_string(kTableBit) +
       R"(" condim="3" friction=")" + nums({c.end_effector.friction, 0.005, 0.0001}) +
       R"(" rgba="0.9 0.5 0.1 1"/>)" + "\n";
  for (int i = 0; i < chain.size(); ++i) x += "</body>\n";
  x += "</body>\n";
}

// The wheeled base's four castor drives (inside the platform body).
void drive_bodies(std::string& x, const WorldConfig& c) {
  const PlatformParameters& p = c.platform;
  const runtime::KeloGeometry& g = c.drives.geometry;
  const double r = g.wheel_radius, s = g.castor_offset, d = g.wheel_distance;
  const double hz = p.drive_mass * 0.1 * 0.1 / 6;  // a 10 cm cube
  const Vec3 wheel_I(p.wheel_mass * r * r / 4, p.wheel_mass * r * r / 2, p.wheel_mass * r * r / 4);
  for (size_t i = 0; i < g.p_PoAi_P.size(); ++i) {
    const std::string n = "drive" + std::to_string(i);
    const auto& a = g.p_PoAi_P[i];
    // The drive frame D_i sits on the pivot axis at wheel-axle height.
    x += R"(<body name=")" + n + R"(" pos=")" + nums({a.x(), a.y(), r - p.deck_height}) + "\">\n";
    x += R"(<joint name=")" + n + R"(_pivot" type="hinge" axis="0 0 1" damping=")" +
         num(p.pivot_damping) + "\"/>\n";
    x += diag_inertial(p.drive_mass, Vec3(-s, 0, 0.05), Vec3(hz, hz, hz));
    x += R"(<geom type="box" size="0.02 0.05 0.05" pos=")" + nums({-s, 0, 0.07}) +
         R"(" rgba="0.2 0.2 0.2 1")" + kVisual + "/>\n";
    for (int side = 0; side < 2; ++side) {
      const std::string w = n + (side == 0 ? "_left" : "_right");
      const double y = side == 0 ? d / 2 : -d / 2;
      x += R"(<body name=")" + w + R"(" pos=")" + nums({-s, y, 0}) + "\">\n";
      x += R"(<joint name=")" + w + R"(" type="hinge" axis="0 1 0" damping=")" +
           num(p.wheel_damping) + "\"/>\n";
      x += diag_inertial(p.wheel_mass, Vec3::Zero(), wheel_I);
      // Stiff contacts (5 ms time constant), so the load barely tilts the base.
      x += R"(<geom type="sphere" size=")" + num(r) + R"(" contype="0" conaffinity=")" +
           std::to_string(kFloorBit) + R"(" condim="3" solref="0.005 1" friction=")" +
           nums({p.wheel_friction, 0.005, 0.0001}) + R"(" rgba="0.1 0.1 0.1 1"/>)" + "\n";
      x += "</body>\n";
    }
    x += "</body>\n";
  }
}

}  // namespace

WorldLayout layout_world(const WorldConfig& c, std::span<const runtime::Chain> arms) {
  if (arms.size() != c.arms.size()) {
    throw Error("invalid-world", "internal: " + std::to_string(arms.size()) + " chains for " +
                                     std::to_string(c.arms.size()) + " arms");
  }
  WorldLayout l;
  for (size_t k = 0; k < arms.size(); ++k) {
    const runtime::Chain& arm = arms[k];
    const ArmSetup& s = c.arms[k];
    const ArmActuation& act = arm_actuation(c, k);
    const auto n = static_cast<size_t>(arm.size());
    const std::string chain = "the chain '" + arm.root() + "' -> '" + arm.tip() + "' of the " +
                              s.name + " arm has " + std::to_string(n) + " joints";
    const auto check = [&](size_t entries, const std::string& key, const std::string& in) {
      if (entries == n) return;
      // The Gen3's figures reach another arm only when neither the world file
      // nor the arm's robot description states its limits.
      const bool defaulted = !s.actuation && !c.actuation_stated && key != "arms." + s.name + ".q";
      throw Error("invalid-world",
                  chain + ", but " + in + key + " has " + std::to_string(entries) +
                      " entries; give one per joint" +
                      (defaulted ? " (the world file states no `actuation` and the arm's robot "
                                   "description no joint effort limits, so these are the Gen3's: "
                                   "state the arm's `actuation`, or import its description with "
                                   "`mospec import-urdf`, which keeps the URDF's <limit>)"
                                 : ""),
                  s.where.file, s.where.line, s.where.column);
    };
    const std::string in = s.actuation ? "arms." + s.name + "." : "the world's ";
    check(s.q0.size(), "arms." + s.name + ".q", "");
    check(act.effort_limit.size(), "actuation.effort_limit", in);
    check(act.lower.size(), "actuation.lower", in);
    check(act.upper.size(), "actuation.upper", in);
    for (size_t j = 0; j < n; ++j) {
      if (!(act.lower[j] < act.upper[j])) {
        throw Error("invalid-world",
                    in + "actuation: joint " + std::to_string(j) + " of the " + s.name +
                        " arm has lower limit " + num(act.lower[j]) + " >= upper limit " +
                        num(act.upper[j]),
                    s.where.file, s.where.line, s.where.column);
      }
    }
    const runtime::AchdModel model(arm);
    runtime::AchdData data(model);
    runtime::JointVector q(arm.size());
    for (size_t i = 0; i < n; ++i) q[static_cast<Eigen::Index>(i)] = s.q0[i];
    runtime::forward_kinematics(model, data, q);
    l.p_PoE_P.push_back(s.X_PB.apply(data.X_BT.p));
  }
  // The table's top at the mean end-effector height, its face where the
  // farthest end effector reaches.
  double mean_z = 0.0, reach = l.p_PoE_P.empty() ? 0.0 : l.p_PoE_P.front().x();
  for (const Vec3& p : l.p_PoE_P) {
    mean_z += p.z();
    reach = std::max(reach, p.x());
  }
  if (!l.p_PoE_P.empty()) mean_z /= static_cast<double>(l.p_PoE_P.size());
  l.table_height = c.platform.deck_height + mean_z + c.table.edge_height_offset;
  if (c.initial.base_x) {
    l.base_x = *c.initial.base_x;
  } else {
    l.base_x = c.table.x - (reach + c.end_effector.radius + c.initial.contact_gap);
  }
  return l;
}

std::string world_mjcf(const WorldConfig& c, std::span<const runtime::Chain> arms,
                       const WorldLayout& l) {
  const PlatformParameters& p = c.platform;
  std::string x;
  x.reserve(16384);
  x += "<mujoco model=\"mospec-world\">\n";
  x += R"(<compiler angle="radian" inertiafromgeom="false"/>)"
       "\n";
  x += R"(<option timestep=")" + num(c.control_period / c.substeps) +
       R"(" gravity="0 0 -9.81" integrator="Euler" cone="pyramidal" jacobian="dense">)"
       "\n";
  x += R"(<flag energy="disable"/>)"
       "\n</option>\n";
  x += R"(<size njmax="300" nconmax="60"/>)"
       "\n";
  x += "<worldbody>\n";
  x += R"(<geom name="floor" type="plane" size="0 0 1" contype=")" + std::to_string(kFloorBit) +
       R"(" conaffinity="0" friction=")" + nums({p.wheel_friction, 0.005, 0.0001}) +
       R"(" rgba="0.8 0.8 0.8 1"/>)"
       "\n";
  if (c.table.present) {
    const double h = l.table_height;
    x += R"(<body name="table" pos=")" + nums({c.table.x, c.table.y, 0}) + R"(" quat=")" +
         yaw_quat(c.table.yaw) + "\">\n";
    x += R"(<geom name="table" type="box" size=")" +
         nums({c.table.depth / 2, c.table.width / 2, h / 2}) + R"(" pos=")" +
         nums({c.table.depth / 2, 0, h / 2}) + R"(" contype=")" + std::to_string(kTableBit) +
         R"(" conaffinity="0" condim="3" friction=")" + nums({c.table.friction, 0.005, 0.0001}) +
         R"(" rgba="0.6 0.45 0.3 1"/>)"
         "\n</body>\n";
  }

  // The platform body. Its initial pose is the state's business (World sets
  // qpos); the body itself sits at the origin at deck height, except for the
  // fixed base, which has no joints and so is placed here.
  const double yaw = c.initial.base_yaw;
  if (c.base == BaseFidelity::Fixed) {
    x += R"(<body name="platform" pos=")" + nums({l.base_x, c.initial.base_y, p.deck_height}) +
         R"(" quat=")" + yaw_quat(yaw) + "\">\n";
  } else {
    x += R"(<body name="platform" pos=")" + nums({0, 0, p.deck_height}) + "\">\n";
  }
  const Vec3 chassis_com(0, 0, -p.size[2] / 2);
  if (c.base == BaseFidelity::Wheeled) {
    x += "<freejoint name=\"base\"/>\n";
    x += diag_inertial(p.mass, chassis_com, box_inertia(p.mass, p.size));
  } else {
    if (c.base == BaseFidelity::Planar) {
      x += R"(<joint name="base_x" type="slide" axis="1 0 0"/>)"
           "\n";
      x += R"(<joint name="base_y" type="slide" axis="0 1 0"/>)"
           "\n";
      x += R"(<joint name="base_yaw" type="hinge" axis="0 0 1"/>)"
           "\n";
    }
    // The drives are not bodies here: lump their masses at the pivots so both
    // fidelities carry the same mass and yaw inertia.
    const double md = p.drive_mass + 2 * p.wheel_mass;
    const double drives = static_cast<double>(c.drives.geometry.p_PoAi_P.size());
    const double mt = p.mass + drives * md;
    const double zd = c.drives.geometry.wheel_radius - p.deck_height;
    const Vec3 com = (p.mass * chassis_com + drives * md * Vec3(0, 0, zd)) / mt;
    Vec3 I = box_inertia(p.mass, p.size);
    const double dzc = chassis_com.z() - com.z();
    I += p.mass * Vec3(dzc * dzc, dzc * dzc, 0);
    for (const auto& a : c.drives.geometry.p_PoAi_P) {
      const double dz = zd - com.z();
      I += md *
           Vec3(a.y() * a.y() + dz * dz, a.x() * a.x() + dz * dz, a.x() * a.x() + a.y() * a.y());
    }
    x += diag_inertial(mt, com, I);
  }
  x += R"(<geom type="box" size=")" + nums({p.size[0] / 2, p.size[1] / 2, p.size[2] / 2}) +
       R"(" pos=")" + vec(chassis_com) + R"(" rgba="0.25 0.35 0.6 1")" + kVisual + "/>\n";
  if (c.base == BaseFidelity::Wheeled) drive_bodies(x, c);
  for (size_t k = 0; k < arms.size(); ++k) arm_bodies(x, c, arms[k], static_cast<int>(k));
  x += "</body>\n</worldbody>\n";

  if (c.table.present) {
    x += "<equality>\n";
    for (size_t k = 0; k < arms.size(); ++k) {
      const runtime::Chain& arm = arms[k];
      const std::string& a = c.arms[k].name;
      x += R"(<connect name=")" + a + R"(_mount" body1=")" + a + "_" +
           arm.segment(arm.size() - 1).link + R"(" body2="table" anchor=")" + vec(arm.X_NT().p) +
           R"(" active=")" + (c.mount.active ? "true" : "false") + R"(" solref=")" +
           nums({c.mount.time_constant, 1}) + "\"/>\n";
    }
    x += "</equality>\n";
  }

  x += "<actuator>\n";
  for (size_t k = 0; k < arms.size(); ++k) {
    const runtime::Chain& arm = arms[k];
    const std::string& a = c.arms[k].name;
    for (int i = 0; i < arm.size(); ++i) {
      const double e = arm_actuation(c, k).effort_limit[static_cast<size_t>(i)];
      const std::string j = a + "_" + arm.segment(i).joint;
      x += R"(<motor name=")" + j + R"(" joint=")" + j + R"(" gear="1" ctrllimited="true" )" +
           R"(ctrlrange=")" + nums({-e, e}) + "\"/>\n";
    }
  }
  if (c.base == BaseFidelity::Wheeled) {
    const double e = p.wheel_torque_limit;
    for (size_t i = 0; i < c.drives.geometry.p_PoAi_P.size(); ++i) {
      for (const char* side : {"_left", "_right"}) {
        const std::string w = "drive" + std::to_string(i) + side;
        x += R"(<motor name=")" + w + R"(" joint=")" + w + R"(" gear="1" ctrllimited="true" )" +
             R"(ctrlrange=")" + nums({-e, e}) + "\"/>\n";
      }
    }
  }
  x += "</actuator>\n</mujoco>\n";
  return x;
}

}  // namespace mospec::sim
