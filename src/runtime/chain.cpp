#include "runtime/chain.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <utility>

#include "support/diagnostics.hpp"

namespace mospec::runtime {

std::string_view to_string(JointType t) {
  switch (t) {
    case JointType::Revolute:
      return "revolute";
    case JointType::Prismatic:
      return "prismatic";
  }
  return "revolute";
}

RigidInertia RigidInertia::expressed_in(const Pose& X_AS) const {
  RigidInertia out;
  out.mass = mass;
  out.p_SoScm_S = X_AS.apply(p_SoScm_S);
  out.I_Scm_S = X_AS.R * I_Scm_S * X_AS.R.transpose();
  return out;
}

RigidInertia operator+(const RigidInertia& a, const RigidInertia& b) {
  // Adding a massless body keeps the other's numbers bit for bit (what a URDF
  // states stays what the chain holds), rather than round-tripping m c / m.
  if (b.mass == 0.0) return {a.mass, a.p_SoScm_S, a.I_Scm_S + b.I_Scm_S};
  if (a.mass == 0.0) return {b.mass, b.p_SoScm_S, a.I_Scm_S + b.I_Scm_S};
  RigidInertia out;
  out.mass = a.mass + b.mass;
  // A massless body has no centre of mass: keep the other one's (or the origin).
  if (out.mass > 0.0) {
    out.p_SoScm_S = (a.mass * a.p_SoScm_S + b.mass * b.p_SoScm_S) / out.mass;
  }
  // Parallel-axis theorem: each body's inertia moved from its own CoM to the
  // common CoM, I + m (|d|^2 1 - d d^T) = I + m [d]x [d]x^T.
  const Mat3 da = skew(a.p_SoScm_S - out.p_SoScm_S);
  const Mat3 db = skew(b.p_SoScm_S - out.p_SoScm_S);
  out.I_Scm_S = a.I_Scm_S + a.mass * da * da.transpose() + b.I_Scm_S + b.mass * db * db.transpose();
  return out;
}

namespace {

// `what` names the body: "link 'l1'".
void check_inertia(const RigidInertia& I, const std::string& what) {
  if (!std::isfinite(I.mass) || I.mass < 0.0) {
    throw Error("invalid-chain",
                what + ": mass must be finite and >= 0, got " + exact_number(I.mass) + " kg");
  }
  if (!I.p_SoScm_S.allFinite() || !I.I_Scm_S.allFinite()) {
    throw Error("invalid-chain", what + ": inertia has non-finite entries");
  }
  const double scale = std::max(1.0, I.I_Scm_S.cwiseAbs().maxCoeff());
  if ((I.I_Scm_S - I.I_Scm_S.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
    throw Error("invalid-chain", what + ": rotational inertia is not symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(I.I_Scm_S, Eigen::EigenvaluesOnly);
  if (eig.eigenvalues().minCoeff() < -1e-12 * scale) {
    throw Error("invalid-chain", what +
                                     ": rotational inertia is not positive semi-definite "
                                     "(smallest principal moment " +
                                     exact_number(eig.eigenvalues().minCoeff()) + " kg m^2)");
  }
}

void check_pose(const Pose& X, const std::string& what) {
  if (!X.R.allFinite() || !X.p.allFinite() ||
      (X.R * X.R.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
      X.R.determinant() < 0.0) {
    throw Error("invalid-chain", what + ": origin is not a rigid transform (position " +
                                     exact_number(X.p.x()) + " " + exact_number(X.p.y()) + " " +
                                     exact_number(X.p.z()) + ")");
  }
}

}  // namespace

Chain::Chain(std::string root) : root_(std::move(root)), tip_(root_) {}

void Chain::add_segment(Segment segment) {
  if (count_ == kMaxSegments) {
    throw Error("invalid-chain", "joint '" + segment.joint + "' (child link '" + segment.link +
                                     "'): a chain holds at most " + std::to_string(kMaxSegments) +
                                     " moving joints");
  }
  const double norm = segment.axis_J.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-9) {
    throw Error("invalid-chain", "joint '" + segment.joint +
                                     "': axis must be a unit vector, got norm " +
                                     exact_number(norm));
  }
  check_pose(segment.X_PJ, "joint '" + segment.joint + "'");
  check_inertia(segment.inertia, "link '" + segment.link + "'");
  if (!(segment.armature >= 0.0) || !std::isfinite(segment.armature)) {
    throw Error("invalid-chain", "joint '" + segment.joint + "': armature must be finite and >= 0");
  }
  if (segment.limits.lower > segment.limits.upper) {
    throw Error("invalid-chain", "joint '" + segment.joint + "': lower limit " +
                                     exact_number(segment.limits.lower) + " exceeds upper " +
                                     exact_number(segment.limits.upper));
  }
  // Composing with the fixed joints before it can overflow what each stated.
  segment.X_PJ = pending_ * segment.X_PJ;
  check_pose(segment.X_PJ,
             "joint '" + segment.joint + "' (composed with the fixed joints before it)");
  pending_ = Pose::identity();
  tip_ = segment.link;
  segments_[static_cast<std::size_t>(count_)] = std::move(segment);
  ++count_;
}

void Chain::add_fixed(std::string link, const Pose& X_FL, const RigidInertia& inertia) {
  check_pose(X_FL, "fixed joint to link '" + link + "'");
  check_inertia(inertia, "link '" + link + "'");
  // The composed offset and the merged inertia can overflow what each part
  // stated (a 1e308 kg link folded into another): checked before they are kept.
  const Pose pending = pending_ * X_FL;
  check_pose(pending,
             "fixed joint to link '" + link + "' (composed with the fixed joints before it)");
  if (count_ == 0) {
    root_folded_.push_back(link);
  } else {
    Segment& s = segments_[static_cast<std::size_t>(count_ - 1)];
    const RigidInertia merged = s.inertia + inertia.expressed_in(pending);
    check_inertia(merged, "link '" + s.link + "' with link '" + link + "' folded in");
    s.inertia = merged;
    s.folded_links.push_back(link);
  }
  pending_ = pending;
  tip_ = std::move(link);
}

}  // namespace mospec::runtime
