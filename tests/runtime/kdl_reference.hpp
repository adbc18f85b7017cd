// Test-only bridge to KDL, the oracle: a KDL::Tree built from urdfdom by hand
// (no kdl_parser), fixed-segment folding done with KDL's own algebra, and the
// layout conversions between mospec (angular first) and KDL (Twist = vel, rot;
// Wrench = force, torque; Jacobians and Vereshchagin's alpha linear first).
#pragma once

#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/tree.hpp>
#include <string>

#include "runtime/model.hpp"

namespace mospec::runtime::testing {

// The URDF under test; empty when ../shared is absent (tests then skip).
std::string gen3_urdf_path();
inline constexpr const char* kGen3Root = "base_link";
inline constexpr const char* kGen3Tip = "EndEffector_Link";

// Every link and joint of the URDF as a KDL::Tree, the way kdl_parser would
// build it: segment = joint + child link, tip frame = child link frame.
KDL::Tree kdl_tree_from_urdf_file(const std::string& path);
KDL::Chain kdl_chain(const KDL::Tree& tree, const std::string& root, const std::string& tip);
// The chain with every fixed segment merged into the one before it (KDL's ACHD
// divides by zero on a fixed segment).
KDL::Chain fold_fixed_segments(const KDL::Chain& chain);

KDL::JntArray to_kdl(const Eigen::VectorXd& v);
Eigen::VectorXd from_kdl(const KDL::JntArray& v);
KDL::Wrench to_kdl_wrench(const Vec6& F);  // [n; f] -> Wrench(f, n)
Vec6 from_kdl(const KDL::Twist& t);        // Twist(v, w) -> [w; v]
Vec6 from_kdl(const KDL::Wrench& w);       // Wrench(f, n) -> [n; f]
Pose from_kdl(const KDL::Frame& F);
// KDL Jacobian (linear rows first) -> angular rows first.
Eigen::MatrixXd from_kdl(const KDL::Jacobian& J);

}  // namespace mospec::runtime::testing
