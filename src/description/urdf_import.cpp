#include "description/urdf_import.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::description {

using namespace mospec::runtime;

namespace {

// Captures urdfdom's console_bridge messages during one parse so they end up
// in the thrown mospec::Error instead of on stderr.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      if (!messages.empty()) messages += "; ";
      messages += text;
    }
  }
  std::string messages;
};

Pose to_pose(const urdf::Pose& p) {
  Pose X;
  X.R = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
            .normalized()
            .toRotationMatrix();
  X.p = Vec3(p.position.x, p.position.y, p.position.z);
  return X;
}

// The link's inertia in its own frame L: URDF gives it about the CoM in the
// frame of <inertial><origin> (rotated by its rpy).
RigidInertia to_inertia(const urdf::Link& link) {
  RigidInertia I;
  if (!link.inertial) return I;
  const urdf::Inertial& in = *link.inertial;
  const Pose X_LC = to_pose(in.origin);
  Mat3 I_C;
  I_C << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  I.mass = in.mass;
  I.p_SoScm_S = X_LC.p;
  I.I_Scm_S = X_LC.R * I_C * X_LC.R.transpose();
  return I;
}

std::string link_list(const urdf::ModelInterface& model) {
  std::vector<std::string> names;
  for (const auto& [name, link] : model.links_) names.push_back(name);
  std::sort(names.begin(), names.end());
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

Chain chain_from_urdf(const std::string& urdf_xml, const std::string& root_link,
                      const std::string& tip_link, const std::string& source) {
  CapturingHandler handler;
  console_bridge::useOutputHandler(&handler);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  console_bridge::restorePreviousOutputHandler();
  if (!model) {
    throw Error("invalid-urdf",
                "cannot parse URDF" + (handler.messages.empty() ? "" : ": " + handler.messages),
                source);
  }
  const std::string root = root_link.empty() ? model->getRoot()->name : root_link;
  std::string tip = tip_link;
  if (tip.empty()) {
    std::vector<std::string> leaves;
    for (const auto& [name, link] : model->links_)
      if (link->child_links.empty()) leaves.push_back(name);
    std::sort(leaves.begin(), leaves.end());
    if (leaves.size() != 1) {
      std::string list;
      for (const auto& n : leaves) list.append(list.empty() ? "" : ", ").append(n);
      throw Error("invalid-urdf",
                  "robot '" + model->getName() + "' has " + std::to_string(leaves.size()) +
                      " leaf links (" + list + "); name the chain's tip link",
                  source);
    }
    tip = leaves.front();
  }
  const std::string* const names[] = {&root, &tip};
  for (const std::string* name : names) {
    if (!model->getLink(*name)) {
      throw Error("invalid-urdf",
                  "robot '" + model->getName() + "' has no link '" + *name +
                      "' (links: " + link_list(*model) + ")",
                  source);
    }
  }
  // Walk up from the tip; the joints on the path, tip first.
  std::vector<urdf::JointConstSharedPtr> path;
  for (urdf::LinkConstSharedPtr link = model->getLink(tip); link->name != root;) {
    if (!link->parent_joint) {
      throw Error("invalid-urdf",
                  "link '" + root + "' is not an ancestor of link '" + tip + "' (the path from '" +
                      tip + "' ends at the root link '" + link->name + "')",
                  source);
    }
    path.push_back(link->parent_joint);
    link = model->getLink(link->parent_joint->parent_link_name);
  }
  std::reverse(path.begin(), path.end());

  Chain chain(root);
  for (const auto& joint : path) try {
      const urdf::LinkConstSharedPtr child = model->getLink(joint->child_link_name);
      const Pose X_PJ = to_pose(joint->parent_to_joint_origin_transform);
      const RigidInertia inertia = to_inertia(*child);
      switch (joint->type) {
        case urdf::Joint::FIXED:
          chain.add_fixed(child->name, X_PJ, inertia);
          continue;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC:
          break;
        default:
          throw Error("invalid-urdf",
                      "joint '" + joint->name +
                          "': only revolute, continuous, prismatic and fixed joints can be in a "
                          "chain (floating and planar joints have more than one degree of freedom)",
                      source);
      }
      Segment s;
      s.link = child->name;
      s.joint = joint->name;
      s.type = joint->type == urdf::Joint::PRISMATIC ? JointType::Prismatic : JointType::Revolute;
      s.X_PJ = X_PJ;
      const Vec3 axis(joint->axis.x, joint->axis.y, joint->axis.z);
      if (!(axis.norm() > 1e-9)) {
        throw Error("invalid-urdf", "joint '" + joint->name + "': axis is zero", source);
      }
      s.axis_J = axis.normalized();
      s.inertia = inertia;
      if (joint->limits) {
        if (joint->type != urdf::Joint::CONTINUOUS) {
          s.limits.lower = joint->limits->lower;
          s.limits.upper = joint->limits->upper;
        }
        s.limits.velocity = joint->limits->velocity;
        s.limits.effort = joint->limits->effort;
      }
      chain.add_segment(std::move(s));
    } catch (const Error& e) {
      // Chain's own checks do not know the file: add it.
      if (!e.diagnostic().file.empty()) throw;
      throw Error(e.code(), e.diagnostic().message, source);
    }
  return chain;
}

Chain chain_from_urdf_file(const std::string& path, const std::string& root,
                           const std::string& tip) {
  return chain_from_urdf(read_file(path), root, tip, path);
}

}  // namespace mospec::description
