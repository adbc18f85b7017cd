// The kinematic chain model: a constant description of a serial chain, built
// once at setup (from a URDF, a JSON-LD model or by hand) and then read by the
// runtime's algorithms (src/runtime/model.hpp builds their constant data from it).
//
// Structure. A chain starts at a fixed root frame B (the root link) and has one
// Segment per moving child link. Segment i is
//   - a joint frame J_i, placed in the parent frame P (segment i-1's frame, or B
//     for i = 0) by the constant pose X_PJ exactly as a URDF joint's <origin>;
//   - a revolute or prismatic joint about/along the unit axis a_J (given in J,
//     as URDF's <axis>);
//   - the segment frame S_i (the child link's frame), which coincides with J_i
//     at q_i = 0: X_PS(q) = X_PJ · Rot(a_J, q) or X_PJ · Trans(a_J q);
//   - the link's rigid-body inertia expressed in S_i.
// Fixed joints are folded while building: a link attached by a fixed joint is
// merged into the current segment (its inertia re-expressed in S_i and added),
// and its offset is carried into the next segment's X_PJ or, after the last
// segment, into the tip pose X_NT (tip frame T in the last segment frame N).
// So every segment has one degree of freedom, q has size() entries, and there is
// never a fixed tail segment (on which KDL's ACHD divides by zero).
//
// Capacity is fixed at compile time (kMaxSegments) so the runtime's workspace
// can be fixed-size; exceeding it is a mospec::Error at build time.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/spatial.hpp"

namespace mospec::runtime {

inline constexpr int kMaxSegments = 8;
inline constexpr int kMaxJoints = kMaxSegments;  // one joint per segment

enum class JointType : unsigned char { Revolute, Prismatic };
std::string_view to_string(JointType);

// A rigid body's inertia in a frame S: mass [kg], centre of mass p_SoScm_S [m]
// and rotational inertia about the centre of mass, expressed in S [kg m^2].
struct RigidInertia {
  double mass = 0.0;
  Vec3 p_SoScm_S = Vec3::Zero();
  Mat3 I_Scm_S = Mat3::Zero();

  // The same body described in frame A, given X_AS.
  RigidInertia expressed_in(const Pose& X_AS) const;
  // The inertia of the union of two bodies described in the same frame.
  friend RigidInertia operator+(const RigidInertia& a, const RigidInertia& b);
  // The 6x6 spatial inertia about So (angular first).
  Mat6 spatial() const { return spatial_inertia(mass, p_SoScm_S, I_Scm_S); }
};

// Joint limits as the URDF's <limit>; unbounded entries are ±infinity
// (a URDF "continuous" joint has no position bounds).
struct JointLimits {
  double lower = -std::numeric_limits<double>::infinity();  // rad or m
  double upper = std::numeric_limits<double>::infinity();
  double velocity = std::numeric_limits<double>::infinity();  // rad/s or m/s
  double effort = std::numeric_limits<double>::infinity();    // N m or N
};

struct Segment {
  std::string link;   // the child link: names the segment frame S
  std::string joint;  // the joint that moves S
  JointType type = JointType::Revolute;
  Pose X_PJ;                    // joint frame J in the parent segment frame (or root B)
  Vec3 axis_J = Vec3::UnitZ();  // unit, in J (and in S: the motion leaves it fixed)
  RigidInertia inertia;         // of the link plus every link folded into it, in S
  JointLimits limits;
  double armature = 0.0;  // reflected rotor inertia added to the joint [kg m^2 or kg]
  std::vector<std::string> folded_links;  // links merged in via fixed joints, in order
};

class Chain {
 public:
  // An empty chain rooted at the frame of link `root`.
  explicit Chain(std::string root);

  // Appends a moving segment. `segment.X_PJ` is the joint origin relative to the
  // frame that the previous add_* call ended at (the previous link's frame);
  // offsets of folded fixed joints are composed in front of it here.
  // Throws mospec::Error when capacity is exceeded, the axis is not a unit
  // vector (within 1e-9), or the inertia is not physical.
  void add_segment(Segment segment);

  // Folds a link attached by a fixed joint at X_FL (the link's frame in the
  // frame the previous add_* call ended at). Its inertia joins the current
  // segment; before the first segment it is attached to the root and dropped
  // (the root does not move, so it cannot affect the dynamics).
  void add_fixed(std::string link, const Pose& X_FL, const RigidInertia& inertia);

  int size() const { return count_; }
  const Segment& segment(int i) const { return segments_[static_cast<std::size_t>(i)]; }
  const std::string& root() const { return root_; }
  // The tip link: the last link added (moving or folded).
  const std::string& tip() const { return tip_; }
  // Tip frame T in the last segment's frame N (identity if the tip is moving);
  // with no segments, T in the root frame B.
  const Pose& X_NT() const { return pending_; }
  // Links attached to the root by fixed joints before the first segment.
  const std::vector<std::string>& root_folded_links() const { return root_folded_; }

 private:
  std::string root_;
  std::string tip_;
  std::array<Segment, kMaxSegments> segments_{};
  int count_ = 0;
  Pose pending_;  // the frame reached by fixed joints since the last segment
  std::vector<std::string> root_folded_;
};

}  // namespace mospec::runtime
