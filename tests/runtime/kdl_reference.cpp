#include "kdl_reference.hpp"

#include <urdf_parser/urdf_parser.h>

#include <filesystem>
#include <stdexcept>

namespace mospec::runtime::testing {

std::string gen3_urdf_path() {
  const std::string path = std::string(MOSPEC_SHARED_DIR) + "/upstream/kinova/GEN3_URDF_V12.urdf";
  return std::filesystem::exists(path) ? path : std::string();
}

namespace {

KDL::Frame to_kdl(const urdf::Pose& p) {
  return KDL::Frame(
      KDL::Rotation::Quaternion(p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w),
      KDL::Vector(p.position.x, p.position.y, p.position.z));
}

KDL::RigidBodyInertia to_kdl(const urdf::InertialSharedPtr& in) {
  if (!in) return KDL::RigidBodyInertia::Zero();
  const KDL::Frame X_LC = to_kdl(in->origin);
  // Rotate the CoM inertia from the inertial frame into the link frame with
  // KDL's own algebra: a massless body carries just the rotational part.
  const KDL::RotationalInertia I_C(in->ixx, in->iyy, in->izz, in->ixy, in->ixz, in->iyz);
  const KDL::RigidBodyInertia rotated =
      X_LC.M * KDL::RigidBodyInertia(0.0, KDL::Vector::Zero(), I_C);
  return KDL::RigidBodyInertia(in->mass, X_LC.p, rotated.getRotationalInertia());
}

KDL::Joint to_kdl(const urdf::Joint& j) {
  const KDL::Frame X_PJ = to_kdl(j.parent_to_joint_origin_transform);
  const KDL::Vector axis_P = X_PJ.M * KDL::Vector(j.axis.x, j.axis.y, j.axis.z);
  switch (j.type) {
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
      return KDL::Joint(j.name, X_PJ.p, axis_P, KDL::Joint::RotAxis);
    case urdf::Joint::PRISMATIC:
      return KDL::Joint(j.name, X_PJ.p, axis_P, KDL::Joint::TransAxis);
    case urdf::Joint::FIXED:
      return KDL::Joint(j.name, KDL::Joint::Fixed);
    default:
      throw std::runtime_error("test KDL builder: unsupported joint " + j.name);
  }
}

void add_children(const urdf::Link& parent, KDL::Tree& tree) {
  for (const auto& child : parent.child_links) {
    const urdf::Joint& j = *child->parent_joint;
    const KDL::Segment segment(child->name, to_kdl(j), to_kdl(j.parent_to_joint_origin_transform),
                               to_kdl(child->inertial));
    if (!tree.addSegment(segment, parent.name)) {
      throw std::runtime_error("test KDL builder: cannot add " + child->name);
    }
    add_children(*child, tree);
  }
}

}  // namespace

KDL::Tree kdl_tree_from_urdf_file(const std::string& path) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(path);
  if (!model) throw std::runtime_error("test KDL builder: cannot parse " + path);
  KDL::Tree tree(model->getRoot()->name);
  add_children(*model->getRoot(), tree);
  return tree;
}

KDL::Chain kdl_chain(const KDL::Tree& tree, const std::string& root, const std::string& tip) {
  KDL::Chain chain;
  if (!tree.getChain(root, tip, chain)) throw std::runtime_error("test KDL builder: no chain");
  return chain;
}

KDL::Chain fold_fixed_segments(const KDL::Chain& chain) {
  std::vector<KDL::Segment> out;
  KDL::Frame X_BF = KDL::Frame::Identity();  // fixed segments before the first moving one
  for (unsigned i = 0; i < chain.getNrOfSegments(); ++i) {
    const KDL::Segment& s = chain.getSegment(i);
    const bool fixed = s.getJoint().getType() == KDL::Joint::Fixed;
    if (out.empty()) {
      if (fixed) {
        X_BF = X_BF * s.getFrameToTip();  // its inertia is on the root: irrelevant
        continue;
      }
      // Move the joint (origin and axis are in the parent frame) and the tip
      // in front of the root offset.
      const KDL::Joint& j = s.getJoint();
      const KDL::Joint moved(j.getName(), X_BF * j.JointOrigin(), X_BF.M * j.JointAxis(),
                             j.getType());
      out.emplace_back(s.getName(), moved, X_BF * s.getFrameToTip(), s.getInertia());
      continue;
    }
    if (!fixed) {
      out.push_back(s);
      continue;
    }
    // Merge s into the previous segment, whose tip moves to s's tip; the
    // previous inertia is re-expressed there (X_TP * I_P).
    const KDL::Segment& p = out.back();
    const KDL::Frame X_PT = s.getFrameToTip();
    const KDL::RigidBodyInertia I = X_PT.Inverse() * p.getInertia() + s.getInertia();
    out.back() = KDL::Segment(p.getName(), p.getJoint(), p.getFrameToTip() * X_PT, I);
  }
  KDL::Chain folded;
  for (const auto& s : out) folded.addSegment(s);
  return folded;
}

KDL::JntArray to_kdl(const Eigen::VectorXd& v) {
  KDL::JntArray a(static_cast<unsigned>(v.size()));
  a.data = v;
  return a;
}
Eigen::VectorXd from_kdl(const KDL::JntArray& v) {
  return v.data;
}

KDL::Wrench to_kdl_wrench(const Vec6& F) {
  return KDL::Wrench(KDL::Vector(F[3], F[4], F[5]), KDL::Vector(F[0], F[1], F[2]));
}
Vec6 from_kdl(const KDL::Twist& t) {
  Vec6 v;
  v << t.rot.x(), t.rot.y(), t.rot.z(), t.vel.x(), t.vel.y(), t.vel.z();
  return v;
}
Vec6 from_kdl(const KDL::Wrench& w) {
  Vec6 v;
  v << w.torque.x(), w.torque.y(), w.torque.z(), w.force.x(), w.force.y(), w.force.z();
  return v;
}
Pose from_kdl(const KDL::Frame& F) {
  Pose X;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.R(r, c) = F.M(r, c);
    X.p[r] = F.p[r];
  }
  return X;
}
Eigen::MatrixXd from_kdl(const KDL::Jacobian& J) {
  Eigen::MatrixXd out(6, J.columns());
  out.topRows(3) = J.data.bottomRows(3);
  out.bottomRows(3) = J.data.topRows(3);
  return out;
}

}  // namespace mospec::runtime::testing
